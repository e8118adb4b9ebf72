// The schedule of runtime changes (change_schedule.h): which component owns a key, the stamps on the
// owners' grids, the records (old -> new), and the refusals — each naming the key and the reason: the
// configuration's own rules (a negative friction, a delay beyond its limit, a NaN gain), keys fixed for
// a run, a plant change of the model's state layout, a delay change that stalls the lockstep schedule.
#include <gtest/gtest.h>

#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/change_schedule.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

SimConfig fig6() { return loadSimConfig({scenario("fig6.yaml")}); }

std::string refusal(ChangeSchedule& schedule, double t, const std::vector<std::pair<std::string, std::string>>& kv,
                    Nanoseconds earliest = 0) {
  try {
    schedule.add(t, kv, "test", earliest);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted " << kv.front().first << " = " << kv.front().second;
  return "";
}

std::string refusal(const std::string& text) {
  ChangeSchedule schedule(fig6());
  try {
    schedule.addAll({parseTimedChange(text)}, "--change");
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted " << text;
  return "";
}

TEST(ChangeSchedule, OwnersOfTheKeys) {
  EXPECT_EQ(changeOwner("tracker.k_psi"), LoopRole::kTracker);
  EXPECT_EQ(changeOwner("tracker.pose_bias_y"), LoopRole::kTracker);
  EXPECT_EQ(changeOwner("delays.pose_to_tracker"), LoopRole::kTracker);
  EXPECT_EQ(changeOwner("actuator.p"), LoopRole::kActuator);
  EXPECT_EQ(changeOwner("delays.desired_steering_to_actuator"), LoopRole::kActuator);
  EXPECT_EQ(changeOwner("delays.steering_angle_to_actuator"), LoopRole::kActuator);
  EXPECT_EQ(changeOwner("steering.coulomb_friction"), LoopRole::kPlant);
  EXPECT_EQ(changeOwner("tire.front.mu"), LoopRole::kPlant);
  EXPECT_EQ(changeOwner("delays.torque_to_plant"), LoopRole::kPlant);
  for (const char* fixed : {"tracker.rate", "actuator.rate", "simulation.step", "simulation.duration", "delays.hold",
                            "path.type", "sensors.pose_latency", "steering.angle_sensor"}) {
    EXPECT_THROW(changeOwner(fixed), ConfigError) << fixed;
  }
  EXPECT_STREQ(roleName(LoopRole::kPlant), "vehicle_plant");
}

TEST(ChangeSchedule, StampsOnTheOwnersGridsAndRecordsOldAndNew) {
  ChangeSchedule schedule(fig6());  // tracker 1 kHz, actuator 10 kHz, plant step 0.1 ms
  schedule.addAll({parseTimedChange("10.00005:tracker.k_psi=1"), parseTimedChange("10.00005:actuator.p=3000"),
                   parseTimedChange("10.00005:steering.coulomb_friction=3"), parseTimedChange("2:tracker.k_y=0.05")},
                  "--change");
  const auto changes = schedule.changes();
  ASSERT_EQ(changes.size(), 4u);
  EXPECT_EQ(changes[0].key, "tracker.k_y");  // in time order
  EXPECT_EQ(changes[0].stamp, 2'000'000'000);
  EXPECT_EQ(changes[0].old_value, "0.01");
  EXPECT_EQ(changes[0].new_value, "0.05");
  EXPECT_EQ(changes[1].stamp, 10'001'000'000);  // the tracker's next 1 ms sample
  EXPECT_EQ(changes[1].owner, LoopRole::kTracker);
  EXPECT_EQ(changes[2].stamp, 10'000'100'000);  // the actuator's next 0.1 ms sample
  EXPECT_EQ(changes[3].stamp, 10'000'100'000);  // the plant's next step
  EXPECT_EQ(changes[3].owner, LoopRole::kPlant);
  EXPECT_EQ(changes[3].describe(), "t = 10.0001 s: steering.coulomb_friction 0 -> 3 (vehicle_plant)");
  EXPECT_EQ(changes[3].argument(), "10.0001:steering.coulomb_friction=3");
  EXPECT_EQ(changes[1].argument(), "10.001:tracker.k_psi=1");
  // The configuration in force for each role.
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 10'000'999'999).tracker.k_psi, 0.8);
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 10'001'000'000).tracker.k_psi, 1.0);
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 10'001'000'000).tracker.k_y, 0.05);
  EXPECT_EQ(schedule.configFor(LoopRole::kPlant, 10'000'000'000).steering.coulomb_friction, 0.0);
  EXPECT_EQ(schedule.configFor(LoopRole::kPlant, 10'000'100'000).steering.coulomb_friction, 3.0);
  // A change re-created from its record lands on the same stamp.
  ChangeSchedule again(fig6());
  again.addAll({parseTimedChange(changes[1].argument())}, "--change");
  EXPECT_EQ(again.changes()[0].stamp, changes[1].stamp);
}

TEST(ChangeSchedule, ChangesAtZeroFormTheStartingConfiguration) {
  ChangeSchedule schedule(fig6());
  schedule.addAll({parseTimedChange("0:tracker.k_psi=1.1"), parseTimedChange("0:steering.friction_model=lugre"),
                   parseTimedChange("0:steering.coulomb_friction=2"), parseTimedChange("3:tracker.k_psi=1.2")},
                  "--change");
  EXPECT_EQ(schedule.start().tracker.k_psi, 1.1);
  EXPECT_EQ(schedule.start().steering.friction_model, "lugre");  // a new state layout is fine at t = 0
  EXPECT_EQ(schedule.initial().tracker.k_psi, 0.8);
}

TEST(ChangeSchedule, TheConfigurationsRulesRefuseNamingTheKey) {
  std::string error = refusal("10:steering.coulomb_friction=-3");
  EXPECT_NE(error.find("--change '10:steering.coulomb_friction=-3': steering.coulomb_friction = -3 N m, must be >= 0 N m"),
            std::string::npos) << error;
  error = refusal("1:delays.pose_to_tracker=12");
  EXPECT_NE(error.find("delays.pose_to_tracker = 12 s, must be in [0, 10] s"), std::string::npos) << error;
  error = refusal("1:tracker.k_psi=.nan");
  EXPECT_NE(error.find("tracker.k_psi = nan"), std::string::npos) << error;
  error = refusal("1:actuator.p=-5");
  EXPECT_NE(error.find("actuator.p = -5, must be >= 0"), std::string::npos) << error;
  error = refusal("1:tracker.k_yy=0.1");
  EXPECT_NE(error.find("tracker.k_yy is not a known parameter"), std::string::npos) << error;
}

TEST(ChangeSchedule, KeysFixedForARunAreRefusedWithTheReason) {
  std::string error = refusal("1:simulation.step=1e-5");
  EXPECT_NE(error.find("--change '1:simulation.step=1e-5': simulation.step cannot change during a run: it sets a sample grid"),
            std::string::npos) << error;
  error = refusal("1:tracker.rate=500");
  EXPECT_NE(error.find("tracker.rate cannot change during a run"), std::string::npos) << error;
  error = refusal("1:path.type=sinusoid");
  EXPECT_NE(error.find("path.type cannot change during a run: the lane"), std::string::npos) << error;
  error = refusal("1:delays.hold=zoh");
  EXPECT_NE(error.find("delays.hold cannot change during a run"), std::string::npos) << error;
}

TEST(ChangeSchedule, APlantChangeMustKeepTheStateLayout) {
  // LuGre kingpin friction adds a state: not after t = 0 (the state carries over a change).
  const std::string error = refusal("1:steering.column_stiffness=5000");
  EXPECT_NE(error.find("steering.column_stiffness = 5000 changes the plant model's state (7 states"), std::string::npos)
      << error;
  EXPECT_NE(error.find("-> 9 states: 7 rigid, 2 compliant column"), std::string::npos) << error;
  ChangeSchedule schedule(fig6());
  const std::string both = refusal(schedule, 1.0, {{"steering.friction_model", "lugre"}, {"steering.coulomb_friction", "2"}});
  EXPECT_NE(both.find("steering.friction_model = lugre (with steering.coulomb_friction = 2) changes the plant model's "
                      "state"), std::string::npos) << both;
  // The tanh friction has no state: on at any time.
  EXPECT_NO_THROW(schedule.add(1.0, {{"steering.coulomb_friction", "2"}, {"steering.viscous_friction", "0.5"}}, "test"));
}

TEST(ChangeSchedule, ADelayThatStallsTheLockstepScheduleIsRefused) {
  // Linear torque hold needs the torque one step ahead: tau2 = 0 on the steering angle gives none.
  const std::string error = refusal("1:delays.steering_angle_to_actuator=0");
  EXPECT_NE(error.find("delays.steering_angle_to_actuator = 0 s leaves a loop that cannot run in lockstep"),
            std::string::npos) << error;
  // Both tau2 delays at once are checked together.
  ChangeSchedule schedule(fig6());
  const auto records = schedule.add(1.0, {{"delays.desired_steering_to_actuator", "0.0015"},
                                          {"delays.steering_angle_to_actuator", "0.0015"}}, "reconfigure");
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].old_value, "0.0001");
  EXPECT_EQ(records[1].new_value, "0.0015");
}

TEST(ChangeSchedule, LiveChangesComeNoEarlierThanTheNextSampleAndKeepTheRecordsTrue) {
  ChangeSchedule schedule(fig6());
  schedule.addAll({parseTimedChange("5:tracker.k_psi=1")}, "~changes");
  // apply_at = 0 while the tracker is at 2.0005 s: its next sample.
  const auto live = schedule.add(0.0, {{"tracker.k_y", "0.02"}}, "reconfigure", 2'000'500'000);
  EXPECT_EQ(live[0].stamp, 2'001'000'000);
  // k_psi has a change at 5 s whose record says 0.8 -> 1: one before it would falsify that record.
  const std::string error = refusal(schedule, 3.0, {{"tracker.k_psi", "0.9"}});
  EXPECT_NE(error.find("tracker.k_psi has a change scheduled later, at t = 5 s"), std::string::npos) << error;
  // After it, fine; the configurations after each change follow the new order.
  schedule.add(6.0, {{"tracker.k_psi", "0.9"}}, "reconfigure");
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 5'500'000'000).tracker.k_psi, 1.0);
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 5'500'000'000).tracker.k_y, 0.02);
  EXPECT_EQ(schedule.configFor(LoopRole::kTracker, 6'000'000'000).tracker.k_psi, 0.9);
  // A refused change leaves the schedule as it was.
  EXPECT_EQ(schedule.changes().size(), 3u);
}

}  // namespace
}  // namespace lane_keeping
