// A log seen through the inverse of its sensors (gap/log/sensor_correction.h): the channels the physics
// replays compare with are the true motion again, and a log of the suite's own loop recorded through
// wrong sensors replays as exactly under those sensors as a log through exact ones.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"
#include "lane_keeping/gap/log/sensor_correction.h"

namespace lane_keeping {
namespace {

const SensorNoise kNoNoise{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

double trueDelta(double t) { return 0.01 * std::sin(1.3 * t); }
double trueYawRate(double t) { return 0.1 * std::sin(0.7 * t) + 0.02; }
double trueAy(double t) { return 1.5 * std::cos(0.7 * t); }

/// A 100 Hz log of smooth signals recorded through `s`: reported(t) = scale * truth(t - L) + bias.
GapLog recorded(const SensorParams& s, double duration = 20.0) {
  GapLog g;
  g.source = "synthetic";
  for (double t = 0.0; t <= duration + 1e-9; t += 0.01) {
    g.t.push_back(t);
    g.x.push_back(15.0 * (t - s.pose_latency));
    g.y.push_back(0.5 * std::sin(0.2 * (t - s.pose_latency)));
    g.psi.push_back(0.1 * std::cos(0.2 * (t - s.pose_latency)) + s.pose_bias_psi);
    g.delta.push_back(s.reportedSteeringAngle(trueDelta(t - s.steering_angle_latency)));
    g.yaw_rate.push_back(s.reportedYawRate(trueYawRate(t - s.yaw_rate_latency)));
    g.ay.push_back(trueAy(t - s.lateral_acceleration_latency) + s.lateral_acceleration_bias);
  }
  return g;
}

TEST(SensorCorrection, ExactSensorsGiveTheSameLog) {
  auto log = std::make_shared<const LogSignals>(recorded({}));
  EXPECT_EQ(correctedForSensors(log, SensorParams{}).get(), log.get());
  EXPECT_FALSE(sensorsChangeTheLog(SensorParams{}));
}

TEST(SensorCorrection, OffsetsGainsAndLatenciesAreUndoneOnEveryChannel) {
  SensorParams s;
  s.steering_angle_bias = 0.003;
  s.steering_angle_scale = 1.12;
  s.steering_angle_latency = 0.03;
  s.yaw_rate_bias = -0.007;
  s.yaw_rate_scale = 0.85;
  s.yaw_rate_latency = 0.2;
  s.lateral_acceleration_bias = 0.12;
  s.lateral_acceleration_latency = 0.05;
  s.pose_bias_psi = 0.0155;
  auto log = std::make_shared<const LogSignals>(recorded(s));
  const auto truth = correctedForSensors(log, s);
  ASSERT_NE(truth.get(), log.get());
  // The log's end is cut by the longest latency (its last samples would read past it).
  EXPECT_NEAR(truth->end(), log->end() - 0.2, 1e-9);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < truth->times().size(); i += 7) {
    const double t = truth->times()[i];
    if (t < 0.1 || t > truth->end() - 0.1) continue;  // the smoothing's edges
    ASSERT_NEAR(truth->samples(LogSignals::kDelta)[i], trueDelta(t), 1e-7) << "t = " << t;
    ASSERT_NEAR(truth->samples(LogSignals::kYawRate)[i], trueYawRate(t), 1e-7) << "t = " << t;
    ASSERT_NEAR(truth->samples(LogSignals::kLateralAcceleration)[i], trueAy(t), 1e-6) << "t = " << t;
    ASSERT_NEAR(truth->samples(LogSignals::kPsi)[i], 0.1 * std::cos(0.2 * t), 1e-12) << "t = " << t;
    // Derived channels follow: the rates of the true signals.
    ASSERT_NEAR(truth->samples(LogSignals::kDeltaRate)[i], 0.013 * std::cos(1.3 * t), 2e-5) << "t = " << t;
    ASSERT_NEAR(truth->samples(LogSignals::kYawAcceleration)[i], 0.07 * std::cos(0.7 * t), 2e-5) << "t = " << t;
    ++checked;
  }
  EXPECT_GT(checked, 200u);
  // Noise levels scale with the gains (what the replays weigh residuals by).
  EXPECT_NEAR(truth->noise(LogSignals::kYawRate), log->noise(LogSignals::kYawRate) / 0.85, 1e-15);
}

TEST(SensorCorrection, ALatencyKeepsEachSampleOneWhiteNoiseSample) {
  // White noise on the gyro: read 0.123 s later along the smoothed curve, the noise stays white at its
  // level (the replays' floor, from second differences, must hold); interpolating would shrink it.
  SensorParams s;
  s.yaw_rate_latency = 0.123;
  GapLog g = recorded({});
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (double& r : g.yaw_rate) r += noise(rng);
  auto log = std::make_shared<const LogSignals>(g);
  const auto truth = correctedForSensors(log, s);
  EXPECT_NEAR(fourthDifferenceNoise(truth->samples(LogSignals::kYawRate)), 0.002, 0.0002);
}

/// The chassis replay's excess on a noise-free log of the suite's loop recorded through `truth_sensors`,
/// replayed believing `believed`.
double chassisExcess(const std::vector<std::string>& truth_sensors, const std::vector<std::string>& believed) {
  BenchmarkCase c;
  c.id = "sensors";
  c.manoeuvre = "sinusoid";
  c.truth_overlay = truth_sensors;
  c.truth_overlay.push_back("simulation.duration=12");
  const GapLog g = generateBenchmarkLog(c, kNoNoise, 100.0);
  BenchmarkCase replayed = c;
  replayed.truth_overlay = believed;
  replayed.truth_overlay.push_back("simulation.duration=12");
  const SimConfig config = benchmarkTruth(replayed);
  const diagnosis::Dataset set{std::make_shared<const LogSignals>(g), std::make_shared<const SimConfig>(config), {{0.6, 12.0}}};
  const diagnosis::Evaluation ev = diagnosis::evaluate(nullptr, {set}, {"chassis"}, ReplayOptions{});
  return ev.scores.at("chassis").excess;
}

TEST(SensorCorrection, TheChassisReplayOfALogThroughWrongSensorsMatchesUnderThem) {
  const std::vector<std::string> sensors{"sensors.yaw_rate_bias=-0.007", "sensors.yaw_rate_scale=0.85",
                                         "sensors.steering_angle_bias=0.002", "sensors.pose_bias_psi=0.0155",
                                         "sensors.lateral_acceleration_bias=0.1"};
  const double believed_exact = chassisExcess(sensors, {});
  const double believed_right = chassisExcess(sensors, sensors);
  EXPECT_GT(believed_exact, 0.1);
  EXPECT_LT(believed_right, 0.01) << "exact sensors believed: " << believed_exact;
}

TEST(SensorCorrection, AYawRateLoggedLateReplaysUnderItsLatency) {
  const std::vector<std::string> late{"sensors.yaw_rate_latency=0.2"};
  const double believed_exact = chassisExcess(late, {});
  const double believed_right = chassisExcess(late, late);
  EXPECT_GT(believed_exact, 0.05);
  EXPECT_LT(believed_right, 0.01) << "exact sensors believed: " << believed_exact;
}

}  // namespace
}  // namespace lane_keeping
