// The open-loop steering replay (gap/subsystem_replay.h) under the configuration that made a
// noise-free log reproduces the logged steering angle — also for compliant columns, whose fast
// modes set the integration step.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/gap/benchmark_cases.h"
#include "lane_keeping/gap/log_signals.h"
#include "lane_keeping/gap/noise_reference.h"
#include "lane_keeping/gap/subsystem_replay.h"

namespace lane_keeping {
namespace {

/// RMS of the normalised residual of the replay's delta trace, over all shooting intervals.
double steeringMismatch(const std::vector<std::string>& column) {
  BenchmarkCase c;
  c.id = "column-replay";
  c.manoeuvre = "lane_change";
  c.truth_overlay = column;
  c.truth_overlay.push_back("simulation.duration=8");
  const SensorNoise none{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const LogSignals log(generateBenchmarkLog(c, none, 500.0));
  SimConfig config = benchmarkNominal("lane_change");
  for (const auto& assignment : column) {
    const auto eq = assignment.find('=');
    const std::string key = assignment.substr(assignment.find('.') + 1, eq - assignment.find('.') - 1);
    const double value = std::stod(assignment.substr(eq + 1));
    if (key == "column_stiffness") config.steering.column_stiffness = value;
    if (key == "column_damping") config.steering.column_damping = value;
    if (key == "column_inertia") config.steering.column_inertia = value;
    if (key == "column_stiffening_angle") config.steering.column_stiffening_angle = value;
  }
  const SubsystemReplay replay = replaySteering(config, log, {{0.6, 8.0}});
  EXPECT_EQ(replay.diverged_intervals, 0);
  const std::vector<double> r = replay.traces.at(0).residual();
  double s = 0.0;
  for (double x : r) s += x * x;
  return std::sqrt(s / std::max<std::size_t>(1, r.size()));
}

TEST(SteeringReplay, RigidColumnReproducesTheLog) {
  // (The logged torque is interpolated between 500 Hz samples of a 10 kHz PD loop: not zero.)
  EXPECT_LT(steeringMismatch({}), 0.01);
}

TEST(SteeringReplay, WellDampedColumnReproducesTheLog) {
  // c (1/J_c + 1/J_F) = 40 * 54 = 2160 1/s: with the 2 ms step sized by the column's frequency alone
  // (1 / 402 rad/s) RK4 was past its stability limit (2.8) and the replay blew up.
  EXPECT_LT(steeringMismatch({"steering.column_stiffness=3000", "steering.column_damping=40",
                              "steering.column_inertia=0.02"}),
            0.01);
}

TEST(SteeringReplay, ProgressiveColumnReproducesTheLog) {
  // The benchmark's large compliance truth: each interval starts from the column's static twist
  // under the logged torque (the root of the cubic spring law).
  EXPECT_LT(steeringMismatch({"steering.column_stiffness=1500", "steering.column_damping=15",
                              "steering.column_inertia=0.05", "steering.column_stiffening_angle=0.03"}),
            0.01);
}

}  // namespace
}  // namespace lane_keeping
