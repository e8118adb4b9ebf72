// The verdict on hand-made rankings and tests: the calibrated detection decides whether there is
// anything to explain, a training-only gap is said to be one, a pinned fit inside the noise-only
// spread never wins, and half an explanation is named as such, not as the cause.
#include <gtest/gtest.h>

#include "lane_keeping/gap/decision/verdict.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

RankedEffect candidate(const std::string& effect, double shrink, double score, int parameters = 1) {
  RankedEffect r;
  r.effect = effect;
  r.shrink = shrink;
  r.score = score;
  r.heldout_gap_before = 0.01;
  r.heldout_gap_after = 0.01 * (1.0 - shrink);
  for (int i = 0; i < parameters; ++i) r.params["p" + std::to_string(i)] = 1.0;
  return r;
}

DetectionTest detectionTest(double value, double p, bool detected) {
  DetectionTest t;
  t.value = value;
  t.p_value = p;
  t.detected = detected;
  return t;
}

struct Fixture {
  GapWhere where;
  VerdictContext context;
  Fixture(bool held_detected, bool train_detected) {
    where.subsystem = "steering";
    where.subsystems.push_back({"steering", 0.58, 0.10, {"delta"}});
    context.where = &where;
    context.gap_before = 0.01;
    context.detection.draws = 19;
    context.detection.heldout = detectionTest(1e-4, held_detected ? 0.05 : 0.6, held_detected);
    context.detection.training = detectionTest(0.3, train_detected ? 0.05 : 0.7, train_detected);
  }
};

TEST(Verdict, AGapOnlyInTheTrainingDataIsSaidToBeOneNeverNothingToExplain) {
  Fixture f(false, true);
  const GapVerdict v = decideVerdict({candidate("torque_limit", 0.9, 1e4)}, f.context, DiagnosisOptions{});
  EXPECT_EQ(v.effect, "unexplained");
  EXPECT_NE(v.reason.find("the training data carry a gap that the held-out data do not confirm"), std::string::npos)
      << v.reason;
  EXPECT_NE(v.reason.find("nrmse 0.58 against a noise floor of 0.1"), std::string::npos) << v.reason;
  EXPECT_EQ(v.reason.find("nothing to explain"), std::string::npos) << v.reason;
}

TEST(Verdict, NothingToExplainOnlyWhenNeitherSideShowsAGap) {
  Fixture f(false, false);
  const GapVerdict v = decideVerdict({candidate("torque_limit", 0.9, 1e4)}, f.context, DiagnosisOptions{});
  EXPECT_EQ(v.effect, "unexplained");
  EXPECT_NE(v.reason.find("nothing to explain"), std::string::npos) << v.reason;
  EXPECT_NE(v.reason.find("among 19 noise-only draws"), std::string::npos) << v.reason;
}

TEST(Verdict, ADetectedGapGoesToTheBestQualifyingCandidate) {
  Fixture f(true, true);
  const GapVerdict v = decideVerdict({candidate("torque_limit", 0.9, 1e4), candidate("inertia", 0.4, 1e4)}, f.context,
                                     DiagnosisOptions{});
  EXPECT_EQ(v.effect, "torque_limit") << v.reason;
  EXPECT_NEAR(v.shrink, 0.9, 1e-12);
}

TEST(Verdict, APinnedFitInsideTheNoiseOnlySpreadNeverWins) {
  Fixture f(true, true);
  f.context.pinned = {"steering_compliance"};
  const std::vector<RankedEffect> ranking{candidate("steering_compliance", 1.0, 1e4, 3)};
  EXPECT_EQ(decideVerdict(ranking, f.context, DiagnosisOptions{}).effect, "steering_compliance");
  f.context.pinned_within_noise = {"steering_compliance"};
  const GapVerdict v = decideVerdict(ranking, f.context, DiagnosisOptions{});
  EXPECT_EQ(v.effect, "unexplained");
  EXPECT_NE(v.reason.find("less than the noise-only spread"), std::string::npos) << v.reason;
}

// A fit pinned on some of its parameters may win where nothing unpinned qualifies (the data may fix only a
// combination of them); one pinned on every parameter is placed by the data nowhere, and never wins (the race
// car's lap 6: inertia at cg_forward 0.3, mass_scale 0.5, yaw_scale 5, the ends of all three ranges, and a
// steering scale at 2, the end of its range, were named with confidence 0.19).
TEST(Verdict, AFitPinnedOnEveryParameterNeverWins) {
  Fixture f(true, true);
  f.context.pinned = {"inertia", "sensor_scale (steering_angle)"};
  RankedEffect scale = candidate("sensor_scale", 0.52, 5e5);
  scale.form = "steering_angle";
  const std::vector<RankedEffect> ranking{candidate("inertia", 0.57, 5e5, 3), scale};
  EXPECT_EQ(decideVerdict(ranking, f.context, DiagnosisOptions{}).effect, "inertia");  // pinned on some: may win
  f.context.pinned_everywhere = {{"inertia", "p0 0.3, p1 0.5, p2 5"}};
  EXPECT_EQ(decideVerdict(ranking, f.context, DiagnosisOptions{}).effect, "sensor_scale");
  f.context.pinned_everywhere["sensor_scale (steering_angle)"] = "scale 2";
  const GapVerdict v = decideVerdict(ranking, f.context, DiagnosisOptions{});
  EXPECT_EQ(v.effect, "unexplained");
  EXPECT_NE(v.reason.find("the best candidate that changes it, inertia, removes 57 %"), std::string::npos) << v.reason;
  EXPECT_NE(v.reason.find("its fit runs to a bound of the range of every parameter it fits (p0 0.3, p1 0.5, p2 5)"),
            std::string::npos)
      << v.reason;
}

TEST(Verdict, HalfAnExplanationIsNamedAsSuchNotAsTheCause) {
  Fixture f(true, true);
  f.context.partial_of = [](const RankedEffect& r) {
    PartialExplanation p;
    p.effect = r.effect;
    p.share = r.shrink;
    p.untouched_share = 0.4;
    return p;
  };
  const GapVerdict v = decideVerdict({candidate("steering_friction", 0.47, 1e4, 2)}, f.context, DiagnosisOptions{});
  EXPECT_EQ(v.effect, "unexplained");
  EXPECT_EQ(v.partial.effect, "steering_friction");
  EXPECT_NE(v.reason.find("steering_friction explains only in part"), std::string::npos) << v.reason;
  EXPECT_NE(v.reason.find("40 % of the gap lies in subsystems it does not change"), std::string::npos) << v.reason;
}

TEST(Verdict, PinnedWithinNoiseComparesTheImprovementWithTheSpreadOfTheDraws) {
  NoiseNull null;
  for (int k = 0; k < 19; ++k) {
    std::map<std::string, SubsystemScore> draw;
    draw["steering"].excess = 0.001 * k;  // T = 1e-6 k^2: median 81e-6, 95 % quantile ~ 300e-6
    null.held.push_back(draw);
  }
  const double spread = heldSpread(null);
  EXPECT_GT(spread, 2e-4);
  EXPECT_LT(spread, 3e-4);
  RankedEffect small = candidate("a", 0.0, 1e4), large = candidate("b", 0.0, 1e4);
  small.heldout_gap_after = std::sqrt(0.02 * 0.02 - 0.5 * spread);  // improves gap^2 by half the spread
  large.heldout_gap_after = std::sqrt(0.02 * 0.02 - 2.0 * spread);
  const auto within = pinnedWithinNoise({small, large}, {"a", "b"}, null, 0.02);
  EXPECT_EQ(within.count("a"), 1u);
  EXPECT_EQ(within.count("b"), 0u);
}

TEST(RankFits, AFitWhoseSearchSpentItsBudgetIsRankedByItsGapAndTheNotesSaySo) {
  // A search held back by its evaluation budget (evaluation_budget.h) keeps the best point it had: a
  // fit like any other, ranked by its held-out gap, with its note among the report's notes.
  const CandidateEffect* friction = nullptr;
  const CandidateEffect* limit = nullptr;
  for (const auto& e : candidateEffects()) {
    if (e.name == "steering_friction") friction = &e;
    if (e.name == "torque_limit") limit = &e;
  }
  ASSERT_TRUE(friction && limit);
  std::vector<CandidateFit> fits(2);
  fits[0].effect = limit;
  fits[0].theta = {40.0};
  fits[0].heldout_after = 0.008;
  fits[1].effect = friction;
  fits[1].theta = {2.0, 0.5};
  fits[1].heldout_after = 0.004;
  fits[1].note = "its search stopped at its evaluation budget (122 replays) and kept the best point it had found";
  for (auto& fit : fits) {
    fit.ok = true;
    fit.loop_checked = true;
    fit.heldout_before = 0.01;
  }
  std::vector<std::string> notes;
  const std::vector<RankedEffect> ranking = rankFits(fits, SimConfig{}, 0.01, &notes);
  ASSERT_EQ(ranking.size(), 2u);
  EXPECT_EQ(ranking[0].effect, "steering_friction");
  EXPECT_NEAR(ranking[0].shrink, 0.6, 1e-12);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "steering_friction: " + fits[1].note);
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
