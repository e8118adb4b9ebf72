// The verdict rule of the gap diagnosis on hand-made rankings: which candidate is named the cause.
#include <gtest/gtest.h>

#include "lane_keeping/gap/decision/winner_selection.h"

namespace lane_keeping {
namespace {

RankedEffect candidate(const std::string& effect, double shrink, double score, int parameters = 1) {
  RankedEffect r;
  r.effect = effect;
  r.shrink = shrink;
  r.score = score;
  for (int i = 0; i < parameters; ++i) r.params["p" + std::to_string(i)] = 1.0;
  return r;
}

const auto kAll = [](const RankedEffect&) { return true; };
constexpr double kShrink = 0.3, kEvidence = 50.0;

TEST(WinnerSelection, BestQualifyingCandidateWins) {
  const std::vector<RankedEffect> ranking{candidate("a", 0.8, 1000), candidate("b", 0.5, 1000)};
  const WinnerSelection s = selectWinner(ranking, kAll, {}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->effect, "a");
  EXPECT_EQ(s.runner_up->effect, "b");
  EXPECT_FALSE(s.winner_pinned);
}

TEST(WinnerSelection, BothBarsMustBeCleared) {
  // Shrink below the bar; evidence below 50 per parameter (2 parameters need 100).
  const std::vector<RankedEffect> ranking{candidate("a", 0.29, 1e6), candidate("b", 0.9, 99, 2)};
  const WinnerSelection s = selectWinner(ranking, kAll, {}, kShrink, kEvidence);
  EXPECT_EQ(s.winner, nullptr);
  EXPECT_EQ(s.top->effect, "a");
}

TEST(WinnerSelection, OnlyCandidatesThatChangeTheGapSubsystem) {
  const std::vector<RankedEffect> ranking{candidate("steering_only", 0.9, 1e4), candidate("chassis", 0.4, 1e4)};
  const auto changes = [](const RankedEffect& r) { return r.effect == "chassis"; };
  const WinnerSelection s = selectWinner(ranking, changes, {}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->effect, "chassis");
  EXPECT_EQ(s.top->effect, "chassis");
  EXPECT_EQ(s.runner_up, nullptr);
}

TEST(WinnerSelection, PinnedFitRanksBelowEveryQualifyingUnpinnedOne) {
  const std::vector<RankedEffect> ranking{candidate("pinned", 0.45, 1e4), candidate("free", 0.41, 1e4)};
  const WinnerSelection s = selectWinner(ranking, kAll, {"pinned"}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->effect, "free");
  EXPECT_FALSE(s.winner_pinned);
  EXPECT_EQ(s.runner_up->effect, "pinned");
}

TEST(WinnerSelection, PinnedFitWinsWhenNothingElseQualifies) {
  const std::vector<RankedEffect> ranking{candidate("pinned", 0.74, 1e4, 2), candidate("free", 0.05, 10)};
  const WinnerSelection s = selectWinner(ranking, kAll, {"pinned"}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->effect, "pinned");
  EXPECT_TRUE(s.winner_pinned);
  EXPECT_EQ(s.runner_up->effect, "free");
}

TEST(WinnerSelection, AFitWhoseClosedLoopLeavesTheLoggedBoundsIsNeverPicked) {
  RankedEffect unbounded = candidate("unbounded", 0.9, 1e4);
  unbounded.closed_loop_bounded = false;
  const std::vector<RankedEffect> ranking{unbounded, candidate("bounded", 0.5, 1e4)};
  const WinnerSelection s = selectWinner(ranking, kAll, {}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->effect, "bounded");
  EXPECT_EQ(s.top->effect, "bounded");
  EXPECT_EQ(s.runner_up, nullptr);
  // Alone, it leaves the gap unexplained.
  const WinnerSelection alone = selectWinner({unbounded}, kAll, {}, kShrink, kEvidence);
  EXPECT_EQ(alone.winner, nullptr);
  EXPECT_EQ(alone.top, nullptr);
}

RankedEffect sensorError(const std::string& channel, double shrink, double score) {
  RankedEffect r = candidate("sensor_offset", shrink, score);
  r.form = channel;
  return r;
}

TEST(WinnerSelection, APhysicalEffectMustBeatTheSensorErrorsByItsEvidence) {
  // A side force (2 parameters) that ranks first by 2 points of shrink, but whose held-out evidence is
  // only 60 above a heading offset's: it needs 50 per parameter, 100. The sensor error is named.
  const std::vector<RankedEffect> close{candidate("lateral_disturbance", 0.74, 1060, 2), sensorError("heading", 0.72, 1000)};
  const WinnerSelection s = selectWinner(close, kAll, {}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->label(), "sensor_offset (heading)");
  ASSERT_NE(s.sensor_over, nullptr);
  EXPECT_EQ(s.sensor_over->effect, "lateral_disturbance");
  // With 101 more it keeps the verdict.
  const std::vector<RankedEffect> clear{candidate("lateral_disturbance", 0.74, 1101, 2), sensorError("heading", 0.72, 1000)};
  const WinnerSelection t = selectWinner(clear, kAll, {}, kShrink, kEvidence);
  EXPECT_EQ(t.winner->effect, "lateral_disturbance");
  EXPECT_EQ(t.sensor_over, nullptr);
}

TEST(WinnerSelection, ASensorErrorThatDoesNotQualifyDoesNotOverruleAPhysicalEffect) {
  // The sensor error removes too little of the gap (20 % < 30 %): no explanation to prefer.
  const std::vector<RankedEffect> ranking{candidate("cornering_stiffness", 0.8, 2000, 2), sensorError("yaw_rate", 0.2, 1990)};
  const WinnerSelection s = selectWinner(ranking, kAll, {}, kShrink, kEvidence);
  EXPECT_EQ(s.winner->effect, "cornering_stiffness");
}

TEST(WinnerSelection, PinnedFitsAreKeyedByTheirForm) {
  // A pinned heading offset does not pin the gyro's: each sensor error is its own explanation.
  const std::vector<RankedEffect> ranking{sensorError("heading", 0.8, 1000), sensorError("yaw_rate", 0.6, 900)};
  const WinnerSelection s = selectWinner(ranking, kAll, {"sensor_offset (heading)"}, kShrink, kEvidence);
  ASSERT_NE(s.winner, nullptr);
  EXPECT_EQ(s.winner->label(), "sensor_offset (yaw_rate)");
  EXPECT_FALSE(s.winner_pinned);
}

}  // namespace
}  // namespace lane_keeping
