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

const auto kAll = [](const std::string&) { return true; };
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
  const auto changes = [](const std::string& e) { return e == "chassis"; };
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

}  // namespace
}  // namespace lane_keeping
