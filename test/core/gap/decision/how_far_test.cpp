// "How far" in closed loop (how_far.h, issue 47 kind 7): a verdict the replays name but whose corrected closed
// loop closes much less of its gap, net of the logs' noise, than the replays do is said to still miss.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "lane_keeping/gap/decision/how_far.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// The kingpin case: the tanh friction removes 95 % of the held-out replays' gap; its closed loop
/// goes from `net_before` to `net_after` net of noise.
GapReport frictionReport(double net_before, double net_after) {
  GapReport r;
  r.verdict.effect = "steering_friction";
  r.verdict.shrink = 0.95;
  r.how_far.noise_floor = 0.02;
  r.how_far.net_before = net_before;
  r.how_far.net_after = net_after;
  return r;
}

TEST(HowFar, AClosedLoopThatClosesLessThanHalfWhatTheReplaysCloseStillMisses) {
  const std::string note = closedLoopStillMisses(frictionReport(0.1, 0.084));  // 16 % against 95 %
  EXPECT_NE(note.find("still misses"), std::string::npos) << note;
  EXPECT_NE(note.find("from 0.1 to 0.084 (16 %)"), std::string::npos) << note;
  EXPECT_NE(note.find("shrinks by 95 %"), std::string::npos) << note;
  // Closing more than half of what the replays close: no note (0.1 -> 0.05 is 50 % against 47.5 %).
  EXPECT_EQ(closedLoopStillMisses(frictionReport(0.1, 0.05)), "");
  // Several effects: their combined shrink is what the closed loop is held to.
  GapReport several = frictionReport(0.1, 0.07);  // 30 %
  several.verdict.effects.resize(2);
  several.verdict.combined_shrink = 0.7;  // half of it 35 %
  EXPECT_NE(closedLoopStillMisses(several), "");
  several.verdict.combined_shrink = 0.58;  // 29 %
  EXPECT_EQ(closedLoopStillMisses(several), "");
}

TEST(HowFar, NoNoteWithoutAVerdictByTheReplaysOrAGapNetOfNoise) {
  GapReport r = frictionReport(0.1, 0.09);
  r.verdict.effect = "unexplained";
  EXPECT_EQ(closedLoopStillMisses(r), "");
  r = frictionReport(0.1, 0.09);
  r.verdict.basis = "modal";  // the replays do not weigh it: nothing to compare
  EXPECT_EQ(closedLoopStillMisses(r), "");
  EXPECT_EQ(closedLoopStillMisses(frictionReport(0.0, 0.0)), "");  // all of it noise
  EXPECT_EQ(closedLoopStillMisses(frictionReport(0.009, 0.009)), "");  // below half the floor (0.02): unseen
  EXPECT_NE(closedLoopStillMisses(frictionReport(0.011, 0.011)), "");
  EXPECT_NE(closedLoopStillMisses(frictionReport(0.008, 4.9)), "");  // unseen, but the corrected loop diverges
  r = frictionReport(0.1, 0.09);
  r.verdict.effects.resize(1);
  r.verdict.effects[0].sensor = true;  // a sensor error need not move y, yaw rate or delta
  EXPECT_EQ(closedLoopStillMisses(r), "");
  EXPECT_EQ(closedLoopStillMisses(frictionReport(std::numeric_limits<double>::quiet_NaN(), 0.05)), "");
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
