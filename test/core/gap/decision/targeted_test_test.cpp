// A steering-loop delay tested on its own fit (targeted_test.h, issue 47 kind 3): where the replays' omnibus
// test does not tell a margin delay's log from its noise-only draws, the delay's fit removes held-out excess
// that the same fit on every draw does not, and is named on it; on the same set-up with nothing wrong it is not.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/common/brief_number.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/decision/targeted_test.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/evaluation.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

GapReport diagnosed(const std::string& id, bool targeted) {
  const BenchmarkCase c = independentCase(id);
  DiagnosisOptions options;
  options.targeted_delay_test = targeted;
  options.closed_loop = false;  // the verdict's wiring and the test, not how far
  return diagnoseGap(benchmarkCaseNominal(c), {generateBenchmarkLog(c, SensorNoise{}, c.log_rate)}, {}, options);
}

std::string targetedNote(const GapReport& r) {
  for (const auto& n : r.notes) {
    if (n.rfind("targeted test of actuation_delay", 0) == 0) return n;
  }
  return "";
}

TEST(TargetedTest, AMarginDelayTheReplaysTestMissesIsNamedOnItsOwnFit) {
  // +1.4 ms on the margin set-up (p = 2000), a sinusoid logged at 100 Hz: the loop's 113 Hz mode is aliased to
  // 13 Hz among the manoeuvre's own content, and the replays' total excess is a typical draw (p = 0.1).
  const std::string id = "actuation_delay-margin-1.4ms-p2000-sinusoid-100Hz";
  const GapReport without = diagnosed(id, false);
  std::printf("[ measured ] without the targeted test: %s: %s\n", without.verdict.effect.c_str(),
              without.verdict.reason.c_str());
  EXPECT_EQ(without.verdict.effect, "unexplained");
  EXPECT_FALSE(without.detection.heldout.detected);
  EXPECT_TRUE(targetedNote(without).empty());

  const GapReport with = diagnosed(id, true);
  std::printf("[ measured ] %s (%s): %s\n", with.verdict.effect.c_str(), with.verdict.basis.c_str(),
              with.verdict.reason.c_str());
  EXPECT_EQ(with.verdict.effect, "actuation_delay") << with.verdict.reason;
  EXPECT_EQ(with.verdict.basis, "targeted");
  EXPECT_DOUBLE_EQ(with.verdict.confidence, 0.5);
  ASSERT_EQ(with.verdict.effects.size(), 1u);
  // A delay of the order of the truth's (the replays step 10 ms at 100 Hz).
  const double delay = with.verdict.effects[0].params.at("extra_delay");
  EXPECT_GT(delay, 0.0004);
  EXPECT_LT(delay, 0.0025);
  EXPECT_EQ(with.verdict.effects[0].config.count("delays.torque_to_plant"), 1u);
  // It removes part of the steering replay's held-out excess, gross of the noise reference.
  EXPECT_GT(with.verdict.gap_before, with.verdict.gap_after);
  EXPECT_GT(with.verdict.shrink, 0.05);
  EXPECT_NE(targetedNote(with).find(": named"), std::string::npos) << targetedNote(with);
}

TEST(TargetedTest, AFitBeyondTheMarginIsNamedAtItsFitUnderTheLoggedBounds) {
  // +1.6 ms on the margin set-up at 200 Hz: the least-squares delay, 2.06 ms, lies beyond the loop's margin and its
  // closed loop diverges, so the how-far replay contradicted it ("unexplained"). Fitted again under the logged
  // bounds it is named, at a delay whose closed loop stays bounded.
  const BenchmarkCase c = independentCase("actuation_delay-margin2-1.6ms-p2000-sinusoid-200Hz");
  const GapReport r =
      diagnoseGap(benchmarkCaseNominal(c), {generateBenchmarkLog(c, SensorNoise{}, c.log_rate)}, {}, DiagnosisOptions{});
  const std::string note = targetedNote(r);
  std::printf("[ measured ] %s (%s); %s; how far net %.4g -> %.4g\n", r.verdict.effect.c_str(), r.verdict.basis.c_str(),
              note.c_str(), r.how_far.net_before, r.how_far.net_after);
  ASSERT_EQ(r.verdict.effect, "actuation_delay") << r.verdict.reason;
  EXPECT_EQ(r.verdict.basis, "targeted");
  EXPECT_NE(note.find("its closed loop leaves the logged bounds at"), std::string::npos) << note;
  EXPECT_NE(note.find("fitted again under them"), std::string::npos) << note;
  const double named = r.verdict.effects.at(0).params.at("extra_delay");
  EXPECT_GT(named, 0.0008);
  EXPECT_LT(named, 0.00205);  // below the unconstrained 2.06 ms
  // The note gives the least-squares fit's held-out gap and then the refit's, each its own (the refit's is the
  // verdict's gap after).
  const std::string refit = "fitted again under them: ";
  const std::size_t at = note.find(refit);
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(note.find(" -> " + briefNumber(r.verdict.gap_after), at), std::string::npos) << note;
  const std::size_t first = note.find("(gross gap ");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(note.find(" -> " + briefNumber(r.verdict.gap_after) + ")", first), std::string::npos)
      << "the least-squares fit's gap is the refit's: " << note;
  // Its closed loop does not drive farther from the log than the nominal's.
  EXPECT_LE(r.how_far.net_after, r.how_far.net_before * 1.05);
}

TEST(TargetedTest, NoMarginSetUpWithNothingWrongIsNamed) {
  // Every no-effect log of the margin groups below 500 Hz (the same set-ups as the delays': p = 1500-3000,
  // 50-300 Hz): the test runs on each (the replays see nothing) and names nothing. The fit mostly stays at nil
  // delay; where it does not, what it removes in training the held-out half does not share.
  int ran = 0;
  for (const BenchmarkCase& c : independentCases()) {
    if (c.truth != "none" || c.id.find("margin") == std::string::npos || c.log_rate >= 500.0) continue;
    const GapReport r = diagnosed(c.id, true);
    const std::string note = targetedNote(r);
    std::printf("[ measured ] %s: %s; %s\n", c.id.c_str(), r.verdict.effect.c_str(), note.c_str());
    EXPECT_EQ(r.verdict.effect, "unexplained") << c.id << ": " << r.verdict.reason;
    EXPECT_NE(r.verdict.basis, "targeted") << c.id;
    if (!note.empty()) {
      ++ran;
      EXPECT_NE(note.find(": not named"), std::string::npos) << note;
    }
  }
  EXPECT_GE(ran, 8);  // 10 such logs; the test must have run on nearly all of them to mean anything
}

TEST(TargetedTest, EachDrawIsDrawnAgainAsItWas) {
  // The draws the test fits on are the detection's own: draw k made again holds the same data.
  const BenchmarkCase c = independentCase("none-margin3-p2000-bend-100Hz");
  DiagnosisOptions options;
  const GapLog log = generateBenchmarkLog(c, SensorNoise{}, c.log_rate);
  GapRun run;
  run.log = log;
  run.config = benchmarkCaseNominal(c);
  const DataSplit split = splitData(prepareRuns({run}), {}, options);
  const NoiseNull null = noiseNull(split.train, split.held, {"steering"}, options.replay, 19, 2);
  ASSERT_TRUE(static_cast<bool>(null.redraw));
  ASSERT_EQ(null.draws(), 19);
  for (int k : {0, 7, 18}) {
    const NoiseDraw draw = null.redraw(k);
    ASSERT_TRUE(draw.ok) << draw.note;
    const Evaluation held = evaluate(nullptr, draw.held, {"steering"}, options.replay);
    EXPECT_DOUBLE_EQ(held.scores.at("steering").excess, null.held[k].at("steering").excess) << "draw " << k;
  }
  EXPECT_NE(null.redraw(0).held.front().log->at(LogSignals::kTorque, 1.0),
            null.redraw(1).held.front().log->at(LogSignals::kTorque, 1.0));
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
