// The linear predictions against the nonlinear closed loop (lane_keeping::ClosedLoop, the simulator
// lk_simulate runs): on both sides of the lower-level (tau2) and the higher-level (k_y, k_psi)
// boundaries a small perturbation decays or grows as the rightmost root says, at its frequency.
//
// The simulator is not the continuous DDE: the actuator samples at 10 kHz (linear torque hold), the
// tracker at 1 kHz, RK4 at 0.1 ms, brush curves are nonlinear. Points sit 5-15 % from the boundary
// (the lower-level frequency moves ~-45 Hz per ms of tau2, so farther points leave the 5 % band
// around the crossing frequency) and the analysis stops before the amplitude leaves the linear range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/sim/oscillation.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/sim/closed_loop.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

struct Check {
  std::string key;     ///< parameter moved across the boundary
  double value;        ///< where the simulation runs
  Crossing boundary;   ///< the boundary it is compared with
};

/// Dominant oscillation of `signal` over a run, up to the first sample beyond `linear_limit`.
OscillationEstimate simulate(const SimConfig& c, const std::function<double(const LogRow&)>& signal, double linear_limit) {
  const RunResult run = ClosedLoop(c).run();
  std::vector<double> values;
  for (const LogRow& row : run.rows) {
    const double v = signal(row);
    if (std::fabs(v) > linear_limit) break;
    values.push_back(v);
  }
  return analyzeOscillation(values, 1.0 / c.simulation.log_rate);
}

/// Runs the simulation at `value` of `key` and compares with the linear prediction there: the crossing
/// root continued by Newton to `value`.
void expectAsPredicted(const SimConfig& base, const std::string& key, double value, const Crossing& boundary,
                       const std::function<double(const LogRow&)>& signal, double linear_limit) {
  SimConfig c = base;
  setConfigNumber(c, key, value);
  Complex mode = boundary.root;
  // Continue the crossing root in small steps from the boundary to `value`.
  const SystemFamily family = configFamily(base, key);
  for (int step = 1; step <= 8; ++step) {
    ASSERT_TRUE(refineRoot(family(boundary.parameter + (value - boundary.parameter) * step / 8.0), &mode));
  }
  const Spectrum spectrum = computeSpectrum(family(value));
  const bool predicted_stable = spectrum.abscissa() < 0.0;
  const OscillationEstimate sim = simulate(c, signal, linear_limit);
  const double f_mode = std::fabs(mode.imag()) / (2 * M_PI), f_cross = boundary.frequencyHz();
  std::printf("  %s = %.6g (boundary %.6g): DDE %s, mode %+.3f 1/s %.3f Hz (crossing %.3f Hz) | simulation %+.3f 1/s %.3f Hz, %d cycles\n",
              key.c_str(), value, boundary.parameter, predicted_stable ? "stable" : "unstable", mode.real(), f_mode, f_cross,
              sim.growth_rate, sim.frequency_hz, sim.cycles);
  ASSERT_TRUE(sim.valid);
  EXPECT_TRUE(sim.regular) << "no regular oscillation";
  EXPECT_GE(sim.cycles, 4);
  EXPECT_EQ(predicted_stable, mode.real() < 0.0) << "the continued mode is the one that decides";
  if (predicted_stable) {
    EXPECT_LT(sim.growth_rate, 0.0);
  } else {
    EXPECT_GT(sim.growth_rate, 0.0);
  }
  // Growth rates agree to ~15 % (sampled actuator and tracker, RK4, nonlinear tires).
  EXPECT_NEAR(sim.growth_rate, mode.real(), 0.2 * std::fabs(mode.real()) + 0.02);
  EXPECT_NEAR(sim.frequency_hz / f_cross, 1.0, 0.05) << "simulated vs crossing frequency";
  EXPECT_NEAR(sim.frequency_hz / f_mode, 1.0, 0.03) << "simulated vs predicted frequency at this point";
}

double steeringError(const LogRow& row) { return row.state.delta - row.delta_des; }
/// Yaw rate: the derivative weights the 0.5-1 Hz lateral mode ~5 rad/s against the slow real roots
/// (-0.06 to -0.2 1/s) that dominate e_y itself near the k_psi boundary.
double yawRate(const LogRow& row) { return row.state.sigma2; }

Crossing boundaryAlong(const SimConfig& c, const std::string& key, double from, double to, bool geometric) {
  ScanOptions scan;
  scan.start = from;
  scan.end = to;
  scan.steps = 60;
  scan.geometric = geometric;
  scan.spectrum.degree = 16;
  const Crossing b = findFirstCrossing(configFamily(c, key), scan);
  EXPECT_TRUE(b.found) << b.reason;
  return b;
}

TEST(StabilityNonlinear, LowerLevelBoundaryInTau2) {
  for (const std::string case_name : {"brush p=2000", "brush p=1000", "lugre_lumped p=2000"}) {
    // Fig 9 set-up; perturb the steering rate only (y = 0) and look at delta - delta_des.
    const std::string tire = case_name.substr(0, case_name.find(' '));
    SimConfig c = loadSimConfig({scenario("fig9.yaml")}, {"simulation.initial.y=0", "simulation.initial.sigma3=0.01",
                                                           "simulation.duration=1.0", "simulation.log_rate=10000",
                                                           "tire.front.model=" + tire, "tire.rear.model=" + tire});
    c.actuator.p = case_name.find("1000") != std::string::npos ? 1000.0 : 2000.0;
    std::printf("  %s\n", case_name.c_str());
    const Crossing b = boundaryAlong(c, "tau2", 0.5e-3, 10e-3, true);
    ASSERT_TRUE(b.found);
    expectAsPredicted(c, "tau2", 0.94 * b.parameter, b, steeringError, 0.02);
    expectAsPredicted(c, "tau2", 1.055 * b.parameter, b, steeringError, 0.02);
  }
}

TEST(StabilityNonlinear, HigherLevelBoundaryInKy) {
  // Fig 6 set-up (tau2 = 0.1 ms): k_y boundary 0.1405 1/m at 0.517 Hz; 1 cm initial offset.
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.initial.y=0.01", "simulation.duration=40",
                                                              "simulation.log_rate=200"});
  const Crossing b = boundaryAlong(c, "tracker.k_y", 0.01, 0.5, true);
  ASSERT_TRUE(b.found);
  expectAsPredicted(c, "tracker.k_y", 0.85 * b.parameter, b, yawRate, 0.2);
  expectAsPredicted(c, "tracker.k_y", 1.15 * b.parameter, b, yawRate, 0.2);
}

TEST(StabilityNonlinear, HigherLevelBoundaryInKpsi) {
  // k_psi boundary 1.4355 at 0.81 Hz (k_y = 0.01 1/m).
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.initial.y=0.01", "simulation.duration=40",
                                                              "simulation.log_rate=200"});
  const Crossing b = boundaryAlong(c, "tracker.k_psi", 0.8, 3.0, false);
  ASSERT_TRUE(b.found);
  expectAsPredicted(c, "tracker.k_psi", 0.9 * b.parameter, b, yawRate, 0.2);
  expectAsPredicted(c, "tracker.k_psi", 1.1 * b.parameter, b, yawRate, 0.2);
}

}  // namespace
}  // namespace lane_keeping
