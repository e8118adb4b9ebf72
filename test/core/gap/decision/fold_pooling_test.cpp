// Every side held out once (fold_pooling.h, issue 47 kind 1): the pooled detection test of both sides, the
// second fold's swapped split, and a verdict that stands only where both folds name the same effect.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/decision/fold_pooling.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// One subsystem's scores with total excess^2 `t` (no noise reference: the net gap is sqrt(t)).
std::map<std::string, SubsystemScore> scoresOf(double t) {
  SubsystemScore s;
  s.name = "steering";
  s.excess = std::sqrt(t);
  return {{"steering", s}};
}

/// 19 draws whose held-out totals are 0..18 and whose training totals are `train(i)`.
template <typename F>
NoiseNull nullOf(F train) {
  NoiseNull null;
  for (int i = 0; i < 19; ++i) {
    null.held.push_back(scoresOf(i));
    null.train.push_back(scoresOf(train(i)));
  }
  return null;
}

TEST(FoldPooling, ThePooledTestSumsEachDrawsTwoSides) {
  // The log's sides at 17 each: each side alone has two draws at least as large (p = 3/20 = 0.15), both
  // together 34. Draws whose sides move against each other (18 - i, i) sum to 18 each: the log is beyond
  // all of them, p = 1/20. Draws whose sides move together (i, i) sum to 2i: two reach 34, p = 0.15. A test
  // that pooled the sides' marginals instead of each draw's sum would give both the same p.
  const DiagnosisOptions options;
  const GapDetection opposed = detectGap(scoresOf(17), scoresOf(17), nullOf([](int i) { return 18.0 - i; }), options);
  EXPECT_NEAR(opposed.heldout.p_value, 0.15, 1e-12);
  EXPECT_NEAR(opposed.training.p_value, 0.15, 1e-12);  // training draws 18..0: two at least 17
  EXPECT_FALSE(opposed.heldout.detected);
  EXPECT_DOUBLE_EQ(opposed.pooled.value, 34.0);
  EXPECT_NEAR(opposed.pooled.p_value, 0.05, 1e-12);
  EXPECT_TRUE(opposed.pooled.detected);
  const GapDetection together = detectGap(scoresOf(17), scoresOf(17), nullOf([](int i) { return 1.0 * i; }), options);
  EXPECT_NEAR(together.pooled.p_value, 0.15, 1e-12);
  EXPECT_FALSE(together.pooled.detected);
  // Below the detection threshold's net gap nothing is detected, however rare.
  DiagnosisOptions strict;
  strict.detection_gap = 10.0;
  EXPECT_FALSE(detectGap(scoresOf(17), scoresOf(17), nullOf([](int i) { return 18.0 - i; }), strict).pooled.detected);
}

TEST(FoldPooling, DecidesOnThePooledTestOnlyWhereTheHeldOutTestAloneMisses) {
  GapDetection d;
  d.draws = 19;
  d.pooled.detected = true;
  d.pooled.p_value = 0.05;
  d.heldout.p_value = 0.1;
  DiagnosisOptions options;
  EXPECT_TRUE(decidesOnPooledTest(d, options));
  EXPECT_TRUE(decisiveDetection(d, options).heldout.detected);  // the pooled test in the held-out test's place
  EXPECT_DOUBLE_EQ(decisiveDetection(d, options).heldout.p_value, 0.05);
  d.heldout.detected = true;  // one fold is enough
  EXPECT_FALSE(decidesOnPooledTest(d, options));
  EXPECT_DOUBLE_EQ(decisiveDetection(d, options).heldout.p_value, 0.1);  // its own test stands
  d.heldout.detected = false;
  options.two_folds = false;
  EXPECT_FALSE(decidesOnPooledTest(d, options));
  options.two_folds = true;
  d.draws = 0;  // no calibrated test
  EXPECT_FALSE(decidesOnPooledTest(d, options));
  d.draws = 19;
  d.pooled.detected = false;
  EXPECT_FALSE(decidesOnPooledTest(d, options));
}

GapFold foldNaming(const std::string& effect, double before, double after) {
  GapFold f;
  f.effect = effect;
  f.gap_before = before;
  f.gap_after = after;
  return f;
}

GapVerdict named(const std::string& effect) {
  GapVerdict v;
  v.effect = effect;
  v.gap_before = 0.02;
  v.gap_after = 0.005;
  v.shrink = 0.75;
  v.confidence = 0.7;
  v.reason = "its own reason";
  VerdictEffect e;
  e.effect = effect;
  v.effects = {e};
  return v;
}

TEST(FoldPooling, AnEffectStandsOnlyWhereBothFoldsNameIt) {
  GapDetection d;
  d.draws = 19;
  d.heldout.p_value = 0.1;
  d.training.p_value = 0.05;
  d.pooled.p_value = 0.05;
  GapVerdict agree = named("cornering_stiffness");
  poolFolds(&agree, d, {foldNaming("cornering_stiffness", 0.02, 0.005), foldNaming("cornering_stiffness", 0.03, 0.004)});
  EXPECT_EQ(agree.effect, "cornering_stiffness");
  EXPECT_DOUBLE_EQ(agree.shrink, 0.75);
  EXPECT_NE(agree.reason.find("Both folds name it"), std::string::npos) << agree.reason;
  EXPECT_NE(agree.reason.find("its own reason"), std::string::npos) << agree.reason;

  for (const auto& [first, second] : std::vector<std::pair<std::string, std::string>>{
           {"cornering_stiffness", "inertia"}, {"cornering_stiffness", "unexplained"}, {"unexplained", "inertia"},
           {"unexplained", "unexplained"}}) {
    GapVerdict v = named(first);
    if (first == "unexplained") v = GapVerdict{};
    v.gap_before = 0.02;
    poolFolds(&v, d, {foldNaming(first, 0.02, 0.005), foldNaming(second, 0.03, 0.004)});
    EXPECT_EQ(v.effect, "unexplained") << first << " / " << second;
    EXPECT_DOUBLE_EQ(v.gap_after, v.gap_before);
    EXPECT_DOUBLE_EQ(v.shrink, 0.0);
    EXPECT_TRUE(v.effects.empty());
    EXPECT_NE(v.reason.find("do not agree"), std::string::npos) << v.reason;
    EXPECT_NE(v.reason.find("fold 2 (sides swapped) " + second), std::string::npos) << v.reason;
  }
  // The same effect in another form is another explanation.
  GapVerdict forms = named("steering_friction");
  GapFold tanh = foldNaming("steering_friction", 0.02, 0.005), lugre = tanh;
  lugre.form = "lugre";
  poolFolds(&forms, d, {tanh, lugre});
  EXPECT_EQ(forms.effect, "unexplained");
}

TEST(FoldPooling, TheSecondFoldHoldsOutWhatTheFirstTrainedOn) {
  const BenchmarkCase c = independentCase("sensor-yaw_rate_offset-lane_change");
  const SimConfig nominal = benchmarkCaseNominal(c);
  const std::vector<RunData> runs = prepareRuns({gapRun(generateBenchmarkLog(c, SensorNoise{}, 500.0), nominal)});
  DiagnosisOptions second;
  second.fold = 1;
  const DataSplit a = splitData(runs, {}, DiagnosisOptions{});
  const DataSplit b = splitData(runs, {}, second);
  ASSERT_EQ(a.train.size(), b.held.size());
  ASSERT_EQ(a.held.size(), b.train.size());
  for (std::size_t k = 0; k < a.train.size(); ++k) {
    ASSERT_EQ(a.train[k].segments.size(), b.held[k].segments.size());
    for (std::size_t s = 0; s < a.train[k].segments.size(); ++s) {
      EXPECT_EQ(a.train[k].segments[s].t0, b.held[k].segments[s].t0);
      EXPECT_EQ(a.train[k].segments[s].t1, b.held[k].segments[s].t1);
    }
  }
  EXPECT_EQ(a.train_blocks, b.held_blocks);
  EXPECT_EQ(a.held_blocks, b.train_blocks);
  EXPECT_NE(a.held_blocks.at(0).find("odd ones"), std::string::npos);
  EXPECT_NE(b.held_blocks.at(0).find("even ones"), std::string::npos);
}

TEST(FoldPooling, AYawRateOffsetTheHeldOutSideAloneMissesIsNamedByBothFolds) {
  // The independent family's yaw-rate offset on a lane change (0.004 rad/s): its odd blocks alone are not
  // significant (p = 0.1), its even ones are (p = 0.05) but with a net gap below the detection threshold
  // once held out; both sides together are (p = 0.05). One fold said "nothing to explain"; both folds fit a
  // bias near 0.004 rad/s on one side that removes the other side's gap. Three candidates, no closed loop:
  // the folds' wiring is tested, not the ranking.
  const BenchmarkCase c = independentCase("sensor-yaw_rate_offset-lane_change");
  const GapLog log = generateBenchmarkLog(c, SensorNoise{}, 500.0);
  DiagnosisOptions options;
  options.effects = {"sensor_offset", "cornering_stiffness", "inertia"};
  options.closed_loop = false;
  // The gyro's drift measured before any model would be corrected first and leave no gap for the folds
  // (heading_agreement.h): read as logged, the folds' own finding is tested.
  options.correct_measured_sensor_errors = false;
  const GapReport two = diagnoseGap(benchmarkCaseNominal(c), {log}, {}, options);
  std::printf("[ measured ] two folds: %s (%s): %s\n", two.verdict.effect.c_str(), two.verdict.form.c_str(),
              two.verdict.reason.c_str());
  EXPECT_FALSE(two.detection.heldout.detected);
  EXPECT_TRUE(two.detection.pooled.detected);
  EXPECT_EQ(two.verdict.effect, "sensor_offset") << two.verdict.reason;
  EXPECT_EQ(two.verdict.form, "yaw_rate");
  ASSERT_EQ(two.folds.size(), 2u);
  for (const GapFold& f : two.folds) {
    EXPECT_EQ(f.effect, "sensor_offset");
    ASSERT_EQ(f.params.count("bias"), 1u);
    EXPECT_NEAR(f.params.at("bias"), 0.004, 0.0006);
  }
  EXPECT_EQ(two.folds[0].heldout, two.folds[1].training);
  // The folds in report.json and back.
  const GapReport back = [&] {
    const std::string path = ::testing::TempDir() + "/fold_pooling_report.json";
    writeGapReportJson(path, two);
    return readGapReportJson(path);
  }();
  ASSERT_EQ(back.folds.size(), 2u);
  EXPECT_EQ(back.folds[1].training, two.folds[1].training);
  EXPECT_DOUBLE_EQ(back.folds[1].params.at("bias"), two.folds[1].params.at("bias"));
  EXPECT_DOUBLE_EQ(back.detection.pooled.p_value, two.detection.pooled.p_value);
  EXPECT_EQ(back.detection.pooled.detected, two.detection.pooled.detected);

  options.two_folds = false;  // one fold: the held-out side's test alone decides
  const GapReport one = diagnoseGap(benchmarkCaseNominal(c), {log}, {}, options);
  EXPECT_EQ(one.verdict.effect, "unexplained") << one.verdict.reason;
  EXPECT_TRUE(one.folds.empty());
}

RankedEffect ranked(const std::string& effect, const std::string& form, double before, double after, double score,
                    bool bounded = true) {
  RankedEffect r;
  r.effect = effect;
  r.form = form;
  r.heldout_gap_before = before;
  r.heldout_gap_after = after;
  r.shrink = 1.0 - after / before;
  r.score = score;
  r.closed_loop_bounded = bounded;
  r.params = {{"p", before}};
  return r;
}

TEST(FoldPooling, TheRunsFoldsPoolEachCandidatesEvidenceAndGaps) {
  // Three folds, each holding out one run: a candidate's evidence summed, its gaps summed in squares; the
  // parameters those of the split as made; a candidate one fold did not rank left out; sorted by the
  // pooled gap after, bounded first.
  const std::vector<RankedEffect> first = {ranked("sensor_offset", "yaw_rate", 3.0, 0.0, -2864.0),
                                           ranked("inertia", "", 3.0, 2.9, 10.0),
                                           ranked("cornering_stiffness", "", 3.0, 2.0, 50.0)};
  const std::vector<std::vector<RankedEffect>> folds = {
      first,
      {ranked("sensor_offset", "yaw_rate", 4.0, 0.0, 16490.0), ranked("inertia", "", 4.0, 4.0, 5.0),
       ranked("cornering_stiffness", "", 4.0, 1.0, 40.0, false)},
      {ranked("sensor_offset", "yaw_rate", 12.0, 0.0, 6000.0), ranked("inertia", "", 12.0, 12.0, -20.0)}};
  std::vector<std::string> notes;
  const std::vector<RankedEffect> pooled = pooledRanking(first, folds, &notes);
  ASSERT_EQ(pooled.size(), 2u);
  EXPECT_EQ(pooled[0].label(), "sensor_offset (yaw_rate)");
  EXPECT_DOUBLE_EQ(pooled[0].score, -2864.0 + 16490.0 + 6000.0);
  EXPECT_DOUBLE_EQ(pooled[0].heldout_gap_before, 13.0);  // sqrt(9 + 16 + 144)
  EXPECT_DOUBLE_EQ(pooled[0].heldout_gap_after, 0.0);
  EXPECT_DOUBLE_EQ(pooled[0].shrink, 1.0);
  EXPECT_DOUBLE_EQ(pooled[0].params.at("p"), 3.0);
  EXPECT_EQ(pooled[1].effect, "inertia");
  EXPECT_DOUBLE_EQ(pooled[1].heldout_gap_after, std::sqrt(2.9 * 2.9 + 16.0 + 144.0));
  EXPECT_DOUBLE_EQ(pooled[1].score, -5.0);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("cornering_stiffness: not ranked in every fold"), std::string::npos) << notes[0];
  // Bounded only where bounded in every fold: unbounded ranks last whatever its gap.
  std::vector<std::vector<RankedEffect>> two = {folds[0], folds[1]};
  const std::vector<RankedEffect> with_cs = pooledRanking(first, two, nullptr);
  ASSERT_EQ(with_cs.size(), 3u);
  EXPECT_EQ(with_cs.back().effect, "cornering_stiffness");
  EXPECT_FALSE(with_cs.back().closed_loop_bounded);
}

TEST(FoldPooling, TheUntouchedShareSumsEveryRunsOtherSubsystems) {
  // A delay changes the steering replay; two folds' held-out chassis excess 0.003 and 0.001, steering 0.01
  // and 0.02: untouched (0.003^2 + 0.001^2) / 0.05^2 = 0.4 %.
  const std::vector<std::map<std::string, double>> excess = {{{"chassis", 0.003}, {"steering", 0.01}},
                                                             {{"chassis", 0.001}, {"steering", 0.02}}};
  EXPECT_NEAR(pooledUntouchedShare({"steering"}, excess, 0.05), 1e-5 / 2.5e-3, 1e-12);
  EXPECT_DOUBLE_EQ(pooledUntouchedShare({"steering", "chassis"}, excess, 0.05), 0.0);
  EXPECT_DOUBLE_EQ(pooledUntouchedShare({"steering"}, excess, 0.0), 0.0);  // no gap: nothing to share
}

TEST(FoldPooling, TheRunsFoldsSayWhichTestMadeThemRun) {
  std::vector<GapFold> folds(3, foldNaming("inertia", 0.02, 0.01));
  for (std::size_t k = 0; k < 3; ++k) folds[k].heldout = {"run" + std::to_string(k + 1) + ".csv"};
  GapDetection d;
  d.draws = 19;
  d.heldout.p_value = 0.3;
  d.training.p_value = 0.05;
  d.training.detected = true;
  d.pooled.p_value = 0.1;
  GapVerdict v = named("inertia");
  describeRunFolds(&v, d, folds);  // the training side alone
  EXPECT_NE(v.reason.find("the training data alone show a gap"), std::string::npos) << v.reason;
  EXPECT_EQ(v.reason.find("both sides together do"), std::string::npos) << v.reason;
  EXPECT_NE(v.reason.find("fold 3 (run3.csv held out) inertia"), std::string::npos) << v.reason;
  d.pooled.detected = true;
  GapVerdict pooled = named("inertia");
  describeRunFolds(&pooled, d, folds);
  EXPECT_NE(pooled.reason.find("both sides together do"), std::string::npos) << pooled.reason;
  d.heldout.detected = true;
  GapVerdict held = named("inertia");
  describeRunFolds(&held, d, folds);
  EXPECT_NE(held.reason.find("the held-out data alone detect the gap"), std::string::npos) << held.reason;
  EXPECT_NE(held.reason.find("each of the 3 runs was held out in turn"), std::string::npos) << held.reason;
}

TEST(FoldPooling, ThreeRunsOfAGyroBiasAreEachHeldOutAndNamedOnTheirSummedEvidence) {
  // Three runs of the same lane change, each with its own noise, a gyro reading 0.0025 rad/s high. The
  // split as made (whole runs: the first and third train, the second is held out) fits the bias at
  // 0.0025 rad/s and removes 100 % of the second run's gap, yet with evidence below zero: in a second of
  // its steering reversal the chassis replay's lateral-velocity estimate lies 0.015 m/s further off with
  // the correction and the steering replay's residual doubles. Alone, that run made the verdict
  // `unexplained`; each run held out in turn, the evidence summed over the three is the bias's.
  BenchmarkCase c = independentCase("sensor-yaw_rate_offset-lane_change");
  for (auto& o : c.truth_overlay) {
    if (o.rfind("sensors.yaw_rate_bias=", 0) == 0) o = "sensors.yaw_rate_bias=0.0025";
  }
  std::vector<GapLog> logs;
  for (unsigned seed = 1; seed <= 3; ++seed) {
    c.seed = seed;
    logs.push_back(generateBenchmarkLog(c));
    logs.back().source = "run" + std::to_string(seed) + ".csv";
  }
  DiagnosisOptions options;
  options.effects = {"sensor_offset", "cornering_stiffness", "inertia"};
  options.closed_loop = false;
  options.correct_measured_sensor_errors = false;  // (as above: the folds' own finding is tested)
  const GapReport three = diagnoseGap(benchmarkCaseNominal(c), logs, {}, options);
  std::printf("[ measured ] three runs: %s (%s): %s\n", three.verdict.effect.c_str(), three.verdict.form.c_str(),
              three.verdict.reason.c_str());
  EXPECT_EQ(three.verdict.effect, "sensor_offset") << three.verdict.reason;
  EXPECT_EQ(three.verdict.form, "yaw_rate");
  ASSERT_EQ(three.folds.size(), 3u);
  int naming = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string run = "run" + std::to_string(k + 1) + ".csv";
    ASSERT_EQ(three.folds[k].heldout.size(), 1u);
    EXPECT_EQ(three.folds[k].heldout[0].rfind(run, 0), 0u) << three.folds[k].heldout[0];  // each run held out once
    for (const std::string& t : three.folds[k].training) EXPECT_EQ(t.find(run), std::string::npos) << t;
    naming += three.folds[k].effect == "sensor_offset" ? 1 : 0;
  }
  EXPECT_LT(naming, 3) << "every fold names it alone: the test no longer shows a run outvoted";
  ASSERT_FALSE(three.ranking.empty());
  EXPECT_EQ(three.ranking.front().label(), "sensor_offset (yaw_rate)");
  EXPECT_GT(three.ranking.front().score, 50.0);
  EXPECT_NEAR(three.ranking.front().params.at("bias"), 0.0025, 0.0003);

  options.two_folds = false;  // the split as made alone
  const GapReport one = diagnoseGap(benchmarkCaseNominal(c), logs, {}, options);
  EXPECT_EQ(one.verdict.effect, "unexplained") << one.verdict.reason;
  EXPECT_TRUE(one.folds.empty());
  ASSERT_FALSE(one.ranking.empty());
  EXPECT_LT(one.ranking.front().score, 0.0);  // the bias, with the held-out run's evidence below zero
}

TEST(FoldPooling, WhatACandidateLeavesIsPooledOverTheRunsToo) {
  // The independent family's three-run set with +1 ms of actuation delay (a sinusoid, a lane change and a
  // bend). The split as made holds out the lane change, where 41.5 % of a small gap lies in subsystems the
  // delay does not change: "a partial explanation". Each run held out in turn, the delay removes 83 % of the
  // three runs' gap, and the untouched part, summed over the three runs' held-out data, is a few per cent of
  // theirs: named. (Found on that set, so not an untuned figure.) Three candidates, no closed loop.
  const BenchmarkCase c = independentCase("actuation_delay-three_small-sinusoid-lane_change-bend");
  FlatParams nominal;
  {
    std::ostringstream yaml;
    benchmarkCaseNominal(c).print(yaml);
    nominal.overlayText(yaml.str(), "the case's nominal");
  }
  std::vector<GapRun> runs{gapRun(generateBenchmarkLog(c), nominal, FlatParams{}, "")};
  for (std::size_t k = 0; k < c.more_runs.size(); ++k) {
    const BenchmarkCase r = moreRunOf(c, k);
    FlatParams scenario;
    scenario.overlayText(benchmarkScenarioYaml(r), r.id + ".yaml");
    GapLog log = generateBenchmarkLog(r);
    log.source = r.id + ".csv";
    runs.push_back(gapRun(std::move(log), nominal, scenario, r.id + ".yaml"));
  }
  DiagnosisOptions options;
  options.effects = {"actuation_delay", "sensor_latency", "inertia"};
  options.closed_loop = false;
  const SimConfig shared = benchmarkCaseNominal(c);
  const GapReport three = diagnoseGap(shared, runs, {}, options);
  std::printf("[ measured ] three runs: %s: %s\n", three.verdict.effect.c_str(), three.verdict.reason.c_str());
  EXPECT_EQ(three.verdict.effect, "actuation_delay") << three.verdict.reason;
  ASSERT_EQ(three.folds.size(), 3u);
  options.two_folds = false;
  const GapReport one = diagnoseGap(shared, runs, {}, options);
  EXPECT_EQ(one.verdict.effect, "unexplained") << one.verdict.reason;
  EXPECT_NE(one.verdict.reason.find("subsystems it does not change"), std::string::npos) << one.verdict.reason;
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
