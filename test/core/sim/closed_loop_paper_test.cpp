// The paper's reference points (Beregi et al., brush tires, k_psi = 0.8, tau1 = 0.2 s), run through the
// nonlinear closed loop exactly as lk_simulate runs them.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/run_summary.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

RunSummary run(const SimConfig& config, RunResult* out = nullptr) {
  const RunResult result = ClosedLoop(config).run();
  if (out) *out = result;
  return summarizeRun(config, result);
}

TEST(ClosedLoopPaper, Fig6Converges) {
  RunResult result;
  const RunSummary s = run(loadSimConfig({scenario("fig6.yaml")}), &result);
  EXPECT_FALSE(s.diverged);
  EXPECT_LT(std::fabs(s.final_lateral_offset), 0.03);  // from 1 m in 20 s
  EXPECT_LT(s.peak_steering_angle, 0.02);
  // The slow closed-loop pole: kinematic estimate s^2 + k_psi (V/l) s + k_y V^2/l = 0 -> -0.20 1/s.
  EXPECT_LT(s.lateral.growth_rate, -0.15);
  EXPECT_GT(s.lateral.growth_rate, -0.26);
  EXPECT_EQ(s.steering.trend(), "decays");
  for (const auto& row : result.rows) ASSERT_TRUE(std::isfinite(row.state.delta));
}

TEST(ClosedLoopPaper, Fig7LateralOscillationGrowsAndTheCarSpinsOut) {
  // The paper (Figs 7-8) shows a stable limit cycle. The printed equations with mu = mu0 = 1 give a
  // growing low-frequency oscillation that saturates the rear tire and ends in a spin (docs/findings.md).
  RunResult result;
  const RunSummary s = run(loadSimConfig({scenario("fig7.yaml")}), &result);
  ASSERT_TRUE(s.diverged);
  EXPECT_NE(s.stop_message.find("spinning out"), std::string::npos) << s.stop_message;
  EXPECT_GT(result.end_time, 2.5);
  EXPECT_LT(result.end_time, 5.0);
  // Successive |e_y| extrema grow: ~1.0 m, then ~1.25 m, then beyond 2.5 m.
  double first_half_peak = 0.0, second_half_peak = 0.0;
  for (const auto& row : result.rows) {
    (row.t < result.end_time / 2 ? first_half_peak : second_half_peak) =
        std::max(row.t < result.end_time / 2 ? first_half_peak : second_half_peak, std::fabs(row.e_y));
  }
  EXPECT_GT(second_half_peak, 2.0 * first_half_peak);
  EXPECT_GT(s.lateral.growth_rate, 0.1);
  EXPECT_GT(s.lateral.frequency_hz, 0.3);
  EXPECT_LT(s.lateral.frequency_hz, 0.8);
  // The rear tire went past full sliding: tan(alpha_crit,R) = 3 mu0 F_zR / (2 a^2 k) = 0.324.
  EXPECT_GT(s.peak_slip_angle, std::atan(0.324));
}

TEST(ClosedLoopPaper, Fig9SteeringOscillationGrowsAt100To150Hz) {
  RunResult result;
  const RunSummary s = run(loadSimConfig({scenario("fig9.yaml")}), &result);
  EXPECT_EQ(s.steering.trend(), "grows");
  EXPECT_TRUE(s.steering.regular);
  EXPECT_GT(s.steering.frequency_hz, 100.0);
  EXPECT_LT(s.steering.frequency_hz, 150.0);
  EXPECT_GT(s.steering.growth_rate, 5.0);
  // It grows until the steering angle leaves the model's domain: detected, not integrated on.
  EXPECT_TRUE(s.diverged);
  EXPECT_NE(s.stop_message.find("steering angle"), std::string::npos) << s.stop_message;
  EXPECT_LT(result.end_time, 2.0);
}

TEST(ClosedLoopPaper, LowerLevelDelayOf1p5msDecays) {
  const RunSummary s = run(loadSimConfig({scenario("fig9_stable.yaml")}));
  EXPECT_FALSE(s.diverged);
  EXPECT_EQ(s.steering.trend(), "decays");
  EXPECT_LT(s.steering.growth_rate, -0.5);
  EXPECT_LT(s.peak_steering_angle, 0.02);
}

TEST(ClosedLoop, DivergenceStopsTheRunWithoutNaN) {
  SimConfig c = loadSimConfig({scenario("fig9.yaml")});
  c.simulation.duration = 30.0;
  RunResult result;
  const RunSummary s = run(c, &result);
  ASSERT_TRUE(s.diverged);
  EXPECT_LT(result.end_time, 1.0);  // stopped promptly, not integrated on for 30 s
  for (const auto& row : result.rows) {
    for (double v : logValues(row)) ASSERT_TRUE(std::isfinite(v));
  }
}

TEST(ClosedLoop, TwoRunsAreBitIdentical) {
  const SimConfig c = loadSimConfig({scenario("lane_change.yaml")}, {"simulation.duration=3"});
  const RunResult a = ClosedLoop(c).run(), b = ClosedLoop(c).run();
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) ASSERT_EQ(logValues(a.rows[i]), logValues(b.rows[i])) << i;
}

TEST(ClosedLoop, DelayShorterThanTheLoopLookaheadIsAScheduleError) {
  // With a linear torque hold the plant needs the torque at t + h before stepping from t, which the
  // actuator can only produce if the steering angle reaches it at least one step late.
  SimConfig c;
  c.delays.steering_angle_to_actuator = 0.0;
  try {
    ClosedLoop loop(c);
    FAIL() << "expected a ScheduleError";
  } catch (const ScheduleError& e) {
    EXPECT_NE(std::string(e.what()).find("delays.steering_angle_to_actuator"), std::string::npos) << e.what();
  }
  // A zero-order hold needs no lookahead.
  c.delays.hold = "zoh";
  EXPECT_NO_THROW(ClosedLoop{c});
}

TEST(ClosedLoop, StepAndDelaysAreSecondsNotTicks) {
  // Halving the plant step must not change the (continuous-time) response beyond integration error:
  // the delays are applied in seconds.
  SimConfig a = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=4"});
  SimConfig b = a;
  b.simulation.step = 5e-5;
  b.actuator.rate = 20000;
  const RunResult ra = ClosedLoop(a).run(), rb = ClosedLoop(b).run();
  ASSERT_EQ(ra.rows.size(), rb.rows.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < ra.rows.size(); ++i) worst = std::max(worst, std::fabs(ra.rows[i].e_y - rb.rows[i].e_y));
  EXPECT_LT(worst, 1e-4);
}

TEST(Oscillation, RecoversFrequencyAndGrowthOfADampedSine) {
  std::vector<double> v;
  const double dt = 1e-3;
  for (int i = 0; i < 3000; ++i) v.push_back(std::exp(-1.5 * i * dt) * std::sin(2 * M_PI * 12.0 * i * dt + 0.3));
  const OscillationEstimate o = analyzeOscillation(v, dt);
  EXPECT_TRUE(o.regular);
  EXPECT_NEAR(o.frequency_hz, 12.0, 0.05);
  EXPECT_NEAR(o.growth_rate, -1.5, 0.05);
  EXPECT_EQ(o.trend(), "decays");
  std::vector<double> w;
  for (int i = 0; i < 3000; ++i) w.push_back(std::exp(0.8 * i * dt) * std::cos(2 * M_PI * 120.0 * i * dt));
  const OscillationEstimate g = analyzeOscillation(w, dt / 10);
  EXPECT_NEAR(g.frequency_hz, 1200.0, 5.0);
}

}  // namespace
}  // namespace lane_keeping
