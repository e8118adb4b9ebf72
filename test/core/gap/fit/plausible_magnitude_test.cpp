// A fitted side force beyond what a road's bank or a storm's crosswind makes cannot be the cause
// (fit/plausible_magnitude.h), however much of the gap it removes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/decision/winner_selection.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/plausible_magnitude.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

TEST(PlausibleMagnitude, ASideForceBeyondATenthOfTheCarsWeightIsImplausible) {
  const CandidateEffect& side = candidateEffect("lateral_disturbance");
  SimConfig car;
  car.vehicle.mass = 485.0;  // the race car: 0.1 g is 475.6 N
  EXPECT_EQ(implausibleMagnitude(side, {-470.0, 0.0}, car, 0.1), "");
  const std::string why = implausibleMagnitude(side, {-3195.0, -31.7}, car, 0.1);
  EXPECT_NE(why.find("3195 N is 0.67 g on this car (485 kg)"), std::string::npos) << why;
  // The bound is the option's, and 0 lifts it; other effects are not judged here.
  EXPECT_EQ(implausibleMagnitude(side, {-3195.0, 0.0}, car, 0.7), "");
  EXPECT_EQ(implausibleMagnitude(side, {-3195.0, 0.0}, car, 0.0), "");
  EXPECT_EQ(implausibleMagnitude(candidateEffect("cornering_stiffness"), {4.0, 4.0}, car, 0.1), "");
  car.vehicle.mass = 1791.6;  // the RAV4: its 2.4 kN side force is 0.14 g
  EXPECT_NE(implausibleMagnitude(side, {-2427.0, 36.4}, car, 0.1), "");
}

TEST(PlausibleMagnitude, AnImplausibleFitCannotWinHoweverMuchItRemoves) {
  RankedEffect side, offset;
  side.effect = "lateral_disturbance";
  side.form = "aerodynamic";
  side.params = {{"force", -3195.0}, {"moment", -31.7}};
  side.shrink = 0.9;
  side.score = 1e6;
  side.implausible = "a side force of 3195 N is 0.67 g on this car";
  offset.effect = "sensor_offset";
  offset.form = "steering_angle";
  offset.params = {{"bias", 0.005}};
  offset.shrink = 0.4;
  offset.score = 1e5;
  const auto changes = [](const RankedEffect&) { return true; };
  std::vector<RankedEffect> ranking{side, offset};  // (the selection points into it)
  WinnerSelection pick = selectWinner(ranking, changes, {}, 0.3, 50.0);
  ASSERT_NE(pick.winner, nullptr);
  EXPECT_EQ(pick.winner->effect, "sensor_offset");
  // Plausible, the same fit would have won (it beats the sensor error by far more than 50 per parameter).
  ranking[0].implausible.clear();
  pick = selectWinner(ranking, changes, {}, 0.3, 50.0);
  ASSERT_NE(pick.winner, nullptr);
  EXPECT_EQ(pick.winner->effect, "lateral_disturbance");
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
