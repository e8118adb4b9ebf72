// The closed loop simulated from a log's first sample (gap/replay/closed_loop_replay.h): it reproduces the
// run that made the log, and it tells a configuration whose loop diverges on the log from one whose
// loop stays bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/closed_loop_replay.h"

namespace lane_keeping {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A noise-free 10 s lane-change log of the benchmark's nominal loop, at 500 Hz.
LogSignals nominalLog() {
  BenchmarkCase c;
  c.id = "none-replay";
  c.manoeuvre = "lane_change";
  c.truth_overlay = {"simulation.duration=10"};
  const SensorNoise none{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  return LogSignals(generateBenchmarkLog(c, none, 500.0));
}

SimConfig nominal() {
  SimConfig c = benchmarkNominal("lane_change");
  c.simulation.duration = 10.0;
  return c;
}

TEST(ClosedLoopReplay, ReproducesTheRunThatMadeTheLog) {
  const LogSignals log = nominalLog();
  const ClosedLoopReplay replay = closedLoopReplay(nominal(), log, kNaN);
  EXPECT_TRUE(replay.note.empty()) << replay.note;
  ASSERT_EQ(replay.t.size(), log.times().size());
  // Same loop, same start: what remains is the initial sigma1 read from differentiated positions
  // and the interpolation of the 500 Hz rows (measured 3.9e-4).
  EXPECT_LT(replay.gap, 2e-3);
  // A different loop is told apart: a tracker with half the heading gain.
  SimConfig other = nominal();
  other.tracker.k_psi *= 0.5;
  EXPECT_GT(closedLoopReplay(other, log, kNaN).gap, 20.0 * replay.gap);
}

TEST(ClosedLoopReplay, NetOfTheLogsNoiseAPerfectModelLeavesLittle) {
  // Issue 47, kind 7: the log's own noise is a floor no model goes below. The noise-free log with the
  // benchmark's white noise added to its record (0.01 m, 2e-3 rad/s, 2e-4 rad): the right model's gap is
  // that noise; net of the floor estimated from the noisy log alone it is what it was without noise.
  const LogSignals clean = nominalLog();
  GapLog noisy_log = clean.log();
  addSensorNoise(noisy_log, SensorNoise{}, 11);
  const LogSignals noisy(noisy_log);
  const ClosedLoopReplay exact = closedLoopReplay(nominal(), clean, kNaN);
  const ClosedLoopReplay right = closedLoopReplay(nominal(), noisy, kNaN);
  const SensorNoise estimated = estimatedNoise(noisy);
  const auto floor = closedLoopNoiseFloor(noisy, {estimated.position, estimated.yaw_rate, estimated.steering});
  const double raw = right.gap;
  const double net = netClosedLoopGap(right, floor);
  std::printf("[ measured ] noise-free %.3g, with noise %.3g (y %.3g, r %.3g, delta %.3g), floor %.3g %.3g %.3g, net %.3g\n",
              exact.gap, raw, right.channel_gaps[0], right.channel_gaps[1], right.channel_gaps[2], floor[0], floor[1],
              floor[2], net);
  EXPECT_GT(raw, 3.0 * exact.gap);  // the noise dominates the right model's raw gap
  // Net of it, most of that is gone (measured 0.0052 of 0.0136: what remains is the replay's start, taken
  // from the first noisy sample, and sigma1 from noisy positions: a floor this closed form does not count).
  EXPECT_LT(net, 0.5 * raw);
  // The floor closed form: sigma over the channel's spread, each channel.
  EXPECT_NEAR(closedLoopNoiseFloor(noisy, {0.01, 0.0, 0.0})[0],
              0.01 / std::sqrt([&] {
                const auto& y = noisy.samples(LogSignals::kY);
                double m = 0.0, s = 0.0;
                for (double v : y) m += v;
                m /= y.size();
                for (double v : y) s += (v - m) * (v - m);
                return s / y.size();
              }()),
              1e-12);
  // A wrong model's gap is not taken for noise: its net gap stays within a few per cent of its raw one.
  SimConfig other = nominal();
  other.tracker.k_psi *= 0.5;
  const ClosedLoopReplay wrong = closedLoopReplay(other, noisy, kNaN);
  EXPECT_GT(netClosedLoopGap(wrong, floor), 0.95 * wrong.gap);
  // No gap, no net gap.
  EXPECT_TRUE(std::isnan(netClosedLoopGap(ClosedLoopReplay{}, floor)));
}

TEST(ClosedLoopReplay, TellsADivergingConfigurationFromABoundedOne) {
  const LogSignals log = nominalLog();
  EXPECT_FALSE(closedLoopDivergence(nominal(), log, kNaN, 10.0).diverged);
  // A compliant column with little damping under the actuator's stiff PD loop (k_p = 8000 N m/rad):
  // the column mode goes unstable within a tenth of a second; with 15 N m s/rad it is damped.
  SimConfig column = nominal();
  column.steering.column_stiffness = 3000.0;
  column.steering.column_damping = 0.8;
  const LoopDivergence d = closedLoopDivergence(column, log, kNaN, 10.0);
  EXPECT_TRUE(d.diverged);
  EXPECT_LT(d.time, 0.5);
  EXPECT_NE(d.message.find("steering angle"), std::string::npos) << d.message;
  column.steering.column_damping = 15.0;
  EXPECT_FALSE(closedLoopDivergence(column, log, kNaN, 10.0).diverged);
  // The horizon bounds the check: a run cut before the divergence is bounded.
  column.steering.column_damping = 0.8;
  EXPECT_FALSE(closedLoopDivergence(column, log, kNaN, 0.02).diverged);
}

TEST(ClosedLoopReplay, ATorqueBoundCountsAsDivergence) {
  // The diagnosis bounds the torque of a fitted loop by the logged range: a column at the edge of
  // stability can oscillate at its 69 Hz mode for many seconds under the monitor's 1.2 rad while its
  // torque command reaches hundreds of N m.
  const LogSignals log = nominalLog();
  double logged = 0.0;
  for (double m : log.samples(LogSignals::kTorque)) logged = std::max(logged, std::fabs(m));
  ASSERT_GT(logged, 10.0);
  EXPECT_FALSE(closedLoopDivergence(nominal(), log, kNaN, 10.0, 1.2 * logged).diverged);
  const LoopDivergence d = closedLoopDivergence(nominal(), log, kNaN, 10.0, 0.5 * logged);
  EXPECT_TRUE(d.diverged);
  EXPECT_GT(d.time, 0.0);
  EXPECT_NE(d.message.find("steering torque"), std::string::npos) << d.message;
}

TEST(ClosedLoopReplay, AConfigurationThatCannotRunCountsAsDivergedAtTheStart) {
  const LogSignals log = nominalLog();
  SimConfig bad = nominal();
  bad.vehicle.mass = -1.0;
  const LoopDivergence d = closedLoopDivergence(bad, log, kNaN, 10.0);
  EXPECT_TRUE(d.diverged);
  EXPECT_EQ(d.time, 0.0);
  EXPECT_NE(d.message.find("mass"), std::string::npos) << d.message;
  EXPECT_FALSE(closedLoopReplay(bad, log, kNaN).note.empty());
}

// How far's onset timing (how_far.cpp) gives the replay the effect as changes at the onset. A change a running
// loop can take holds from its time: the loop matches the nominal's before it and leaves it after. One that
// would add a state (a compliant column on a rigid one) is refused: no gap, a note — where how far falls back
// to the effect from the log's start. (LuGre kingpin friction is taken: its bristle state is always there.)
TEST(ClosedLoopReplay, ChangesMidRunHoldFromTheirTimeOrAreRefusedWithANote) {
  const LogSignals log = nominalLog();
  const ClosedLoopReplay plain = closedLoopReplay(nominal(), log, kNaN);
  const ClosedLoopReplay gust = closedLoopReplay(nominal(), log, kNaN, {{5.0, "disturbance.lateral_force", "800"}});
  EXPECT_TRUE(gust.note.empty()) << gust.note;
  ASSERT_EQ(gust.y.size(), plain.y.size());
  double before = 0.0, after = 0.0;
  for (std::size_t i = 0; i < gust.t.size(); ++i) {
    const double d = std::fabs(gust.y[i] - plain.y[i]);
    (gust.t[i] - log.start() < 5.0 ? before : after) = std::max(gust.t[i] - log.start() < 5.0 ? before : after, d);
  }
  EXPECT_EQ(before, 0.0);
  EXPECT_GT(after, 0.01);
  EXPECT_GT(gust.gap, plain.gap);
  const ClosedLoopReplay column = closedLoopReplay(nominal(), log, kNaN, {{5.0, "steering.column_stiffness", "2000"}});
  EXPECT_FALSE(std::isfinite(column.gap));
  EXPECT_NE(column.note.find("closed-loop replay failed"), std::string::npos) << column.note;
  EXPECT_NE(column.note.find("changes the plant model's state"), std::string::npos) << column.note;
  const ClosedLoopReplay lugre = closedLoopReplay(nominal(), log, kNaN, {{5.0, "steering.friction_model", "lugre"}});
  EXPECT_TRUE(std::isfinite(lugre.gap)) << lugre.note;
}

}  // namespace
}  // namespace lane_keeping
