// The noise-only reference of the gap diagnosis (gap/evaluation/noise_reference.h): it must reproduce a log's
// noise levels and span, and account for the excess that noise alone leaves in the replays, so that
// the gap of a log without any effect is (nearly) all reference.
#include <gtest/gtest.h>

#include <cmath>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"

namespace lane_keeping {
namespace {

BenchmarkCase shortCase(const std::string& id, double duration) {
  for (BenchmarkCase c : benchmarkCases()) {
    if (c.id != id) continue;
    c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
    return c;
  }
  throw std::runtime_error("no case " + id);
}

TEST(NoiseReference, EstimatesTheLogsNoiseAndCoversItsSpan) {
  const SensorNoise truth;  // the benchmark's noise levels
  const GapLog log = generateBenchmarkLog(shortCase("none-1-lane_change", 12.0), truth, 200.0);
  const LogSignals signals(log);
  const SensorNoise estimated = estimatedNoise(signals);
  EXPECT_NEAR(estimated.position, truth.position, 0.1 * truth.position);
  EXPECT_NEAR(estimated.heading, truth.heading, 0.1 * truth.heading);
  EXPECT_NEAR(estimated.yaw_rate, truth.yaw_rate, 0.1 * truth.yaw_rate);
  EXPECT_NEAR(estimated.steering, truth.steering, 0.1 * truth.steering);
  EXPECT_NEAR(estimated.torque, truth.torque, 0.1 * truth.torque);

  SimConfig nominal = benchmarkNominal("lane_change");
  const GapLog reference = noiseReferenceLog(nominal, signals, 5);
  EXPECT_NEAR(reference.t.front(), log.t.front(), 1e-9);
  EXPECT_GE(reference.t.back(), log.t.back() - 1e-9);
  EXPECT_NEAR(reference.medianStep(), log.medianStep(), 1e-9);
  EXPECT_EQ(reference.hasSteeringRate(), log.hasSteeringRate());
  // Its own noise, estimated the same way, is the log's.
  const SensorNoise again = estimatedNoise(LogSignals(reference));
  EXPECT_NEAR(again.steering, estimated.steering, 0.1 * estimated.steering);
  EXPECT_NEAR(again.torque, estimated.torque, 0.1 * estimated.torque);

  // A log without the optional columns gets a reference without them.
  GapLog bare = log;
  bare.v.clear();
  bare.ay.clear();
  bare.delta_rate.clear();
  const GapLog bare_reference = noiseReferenceLog(nominal, LogSignals(bare), 5);
  EXPECT_FALSE(bare_reference.hasSpeed() || bare_reference.hasLateralAcceleration() || bare_reference.hasSteeringRate());
}

TEST(NoiseReference, AccountsForTheSteeringExcessOfANoEffectLog) {
  // Noise on the logged torque and yaw rate drives the steering replay: a log with no effect shows a
  // steering excess that the reference (the largest of its noise draws) must cover — here 0.0048
  // against 0.0102 — so that the net gap is much smaller than the raw one.
  const GapLog log = generateBenchmarkLog(shortCase("none-2-sinusoid", 16.0), SensorNoise{}, 200.0);
  SimConfig nominal = benchmarkNominal("sinusoid");
  nominal.simulation.duration = 16.0;
  DiagnosisOptions options;
  options.effects = {"actuation_delay"};
  options.closed_loop = false;
  const GapReport with_reference = diagnoseGap(nominal, {log}, {}, options);
  const double steering = with_reference.how_far.subsystems_before.at("steering");
  const double reference = with_reference.how_far.subsystems_noise_reference.at("steering");
  ASSERT_GT(steering, 0.0);
  EXPECT_GT(reference, steering);
  EXPECT_LT(reference, 3.0 * steering);
  double raw2 = 0.0;
  for (const auto& [name, excess] : with_reference.how_far.subsystems_before) raw2 += excess * excess;
  // The net gap drops the steering's excess and part of the others' (here 0.0151 against a raw 0.0213;
  // the raw figure was 0.0285 while the actuator's interpolated inputs coloured its noise).
  const double gap2 = with_reference.verdict.gap_before * with_reference.verdict.gap_before;
  EXPECT_LT(gap2, raw2 - steering * steering);
  EXPECT_LT(with_reference.verdict.gap_before, 0.8 * std::sqrt(raw2));
  EXPECT_EQ(with_reference.verdict.effect, "unexplained") << with_reference.verdict.reason;

  options.noise_reference_draws = 0;  // the raw excess
  const GapReport raw = diagnoseGap(nominal, {log}, {}, options);
  EXPECT_NEAR(raw.verdict.gap_before, std::sqrt(raw2), 1e-12);
  for (const auto& [name, value] : raw.how_far.subsystems_noise_reference) EXPECT_EQ(value, 0.0) << name;
}

TEST(NoiseReference, TheTruthModelRemovesTheGapOfAHiddenActuationDelayOnAlmostEveryNoiseDraw) {
  // The gap is what the model misses beyond noise, so the truth model (the best a candidate could be)
  // must remove all of it - up to the held-out noise realisations beyond every draw of the null, which
  // no model removes. Subtracting the draws' RMS (before 5152318) left the larger draws' excess as gap:
  // the truth model removed 78.4 % of the held-out gap of the benchmark's small actuation-delay sinusoid.
  // Net of the largest of 19 draws, a held-out set beyond them in the chassis or the steering happens
  // on about one log in ten (that benchmark log is one, at 36 %); here six noise seeds.
  BenchmarkCase c;
  for (const auto& candidate : benchmarkCases()) {
    if (candidate.id == "actuation_delay-large-sinusoid") c = candidate;
  }
  c.truth_overlay.push_back("simulation.duration=16");
  SimConfig nominal = benchmarkNominal("sinusoid");
  nominal.simulation.duration = 16.0;
  int logs = 0, removed = 0;
  for (unsigned seed = 301; seed <= 306; ++seed) {
    c.seed = seed;
    const GapLog log = generateBenchmarkLog(c, SensorNoise{}, 500.0);
    const std::vector<double> gaps =
        heldoutGaps(sharedConfigurationRuns(nominal, {log}), {}, {assignmentsChange(c.truth_overlay)});
    ASSERT_EQ(gaps.size(), 2u);
    if (gaps[0] < 1e-3) continue;
    ++logs;
    if (gaps[1] < 0.05 * gaps[0]) ++removed;
    std::printf("seed %u: gap %.4f, truth model %.4f\n", seed, gaps[0], gaps[1]);
  }
  EXPECT_GE(logs, 5);
  EXPECT_GE(removed, logs - 1);
}

}  // namespace
}  // namespace lane_keeping
