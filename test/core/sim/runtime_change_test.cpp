// Runtime changes in the closed loop (change_schedule.h): a change at t leaves everything before t as it
// was and acts from t on; a change at 0 is the same run as the configuration set that way; a change
// scheduled while the loop runs (the way a node schedules a dynamic_reconfigure request) gives, bit
// for bit, the run whose schedule held it from the start (the way lk_simulate --change reproduces it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/plant_session.h"
#include "lane_keeping/sim/run_summary.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

std::vector<TimedChange> parseAll(const std::vector<std::string>& texts) {
  std::vector<TimedChange> out;
  for (const auto& text : texts) out.push_back(parseTimedChange(text));
  return out;
}

RunResult run(const SimConfig& c, const std::vector<std::string>& changes = {}) {
  return ClosedLoop(c, parseAll(changes)).run();
}

void expectBitIdentical(const RunResult& a, const RunResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.plant_steps, b.plant_steps);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) ASSERT_EQ(logValues(a.rows[i]), logValues(b.rows[i])) << "row " << i;
}

/// Index of the first row that differs (rows.size() if none), and the largest |difference| of delta
/// after `t` [s].
std::pair<std::size_t, double> compare(const RunResult& a, const RunResult& b, double t) {
  std::size_t first = a.rows.size();
  double worst_delta = 0.0;
  for (std::size_t i = 0; i < std::min(a.rows.size(), b.rows.size()); ++i) {
    if (first == a.rows.size() && logValues(a.rows[i]) != logValues(b.rows[i])) first = i;
    if (a.rows[i].t > t) worst_delta = std::max(worst_delta, std::fabs(a.rows[i].state.delta - b.rows[i].state.delta));
  }
  return {first, worst_delta};
}

TEST(RuntimeChange, KingpinFrictionOnAtTChangesNothingBeforeT) {
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=3"});
  const RunResult before = run(c);
  const RunResult after = run(c, {"1.5:steering.coulomb_friction=3", "1.5:steering.viscous_friction=0.5"});
  ASSERT_EQ(after.rows.size(), before.rows.size());
  const auto [first, worst] = compare(after, before, 1.5);
  // Rows at t < 1.5 s are the same bits; the row at 1.5 s has the same state, and its accelerations
  // (a_y) already come from the new model; after it the friction bends the steering angle.
  ASSERT_EQ(first, 1500u);
  EXPECT_EQ(after.rows[1500].t, 1.5);
  EXPECT_EQ(after.rows[1500].state.delta, before.rows[1500].state.delta);
  EXPECT_EQ(after.rows[1500].state.y, before.rows[1500].state.y);
  EXPECT_NE(after.rows[1500].state.lateral_acceleration, before.rows[1500].state.lateral_acceleration);
  EXPECT_GT(worst, 1e-5);  // rad: 3 N m against k_p = 16 000 N m/rad is ~2e-4 rad of steering error
  EXPECT_NE(after.rows.back().state.y, before.rows.back().state.y);
  ASSERT_EQ(after.changes.size(), 2u);
  EXPECT_EQ(after.changes[0].describe(), "t = 1.5 s: steering.coulomb_friction 0 -> 3 (vehicle_plant)");
  const std::string summary = formatSummary(summarizeRun(c, after));
  EXPECT_NE(summary.find("changes:                t = 1.5 s: steering.coulomb_friction 0 -> 3 (vehicle_plant)\n"
                         "                        t = 1.5 s: steering.viscous_friction 0 -> 0.5 (vehicle_plant)\n"),
            std::string::npos) << summary;
}

TEST(RuntimeChange, AChangeAtZeroIsTheRunOfTheConfigurationSetThatWay) {
  // Fig 6 (1 m initial offset, so every key below matters from the first step), lumped LuGre tires.
  const std::vector<std::string> common = {"simulation.duration=0.6", "tire.front.model=lugre_lumped",
                                           "tire.rear.model=lugre_lumped"};
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, common);
  const RunResult base = run(c);
  const std::vector<std::vector<std::string>> cases = {
      {"steering.coulomb_friction=2", "steering.viscous_friction=0.3"},           // plant: kingpin friction
      {"tire.front.mu=0.8", "delays.torque_to_plant=3e-4"},                        // plant: tires, torque delay
      {"tracker.k_psi=1.1", "tracker.k_y=0.08", "delays.pose_to_tracker=0.05"},     // tracker
      {"actuator.p=1500", "delays.desired_steering_to_actuator=2e-4", "delays.steering_angle_to_actuator=3e-4"}};
  for (const auto& sets : cases) {
    SCOPED_TRACE(sets.front());
    std::vector<std::string> changes, all = common;
    for (const auto& s : sets) {
      changes.push_back("0:" + s);
      all.push_back(s);
    }
    const RunResult changed = run(c, changes);
    expectBitIdentical(changed, run(loadSimConfig({scenario("fig6.yaml")}, all)));
    EXPECT_LT(compare(changed, base, 0.0).first, 10u);  // and it is not the unchanged run
  }
}

TEST(RuntimeChange, AChangeAfterTheEndIsRefusedNamingIt) {
  // It would never take effect: it used to be dropped without a word (issue 48), now it is refused by name.
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=0.5"});
  try {
    run(c, {"0.6:tracker.k_psi=2"});
    FAIL() << "a change at 0.6 s of a 0.5 s run was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tracker.k_psi at t = 0.6 s is after the run's end"), std::string::npos)
        << e.what();
  }
  // At the end itself it is still inside the run (the last row is logged at t = duration).
  EXPECT_NO_THROW(run(c, {"0.5:tracker.k_psi=2"}));
}

TEST(RuntimeChange, DelaysThatShrinkAndGrowMidRunKeepTheLoopGoing) {
  // tau1 0.2 -> 0.05 s at 0.4 s; tau2 0.1 -> 1.5 ms at 0.5 s and back to 0.1 ms at 0.7 s (three
  // processes' worth of lookahead changes; the lockstep schedule must advance through each).
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=1"});
  const RunResult base = run(c);
  const RunResult changed = run(c, {"0.4:delays.pose_to_tracker=0.05", "0.5:delays.desired_steering_to_actuator=1.5e-3",
                                    "0.5:delays.steering_angle_to_actuator=1.5e-3",
                                    "0.7:delays.desired_steering_to_actuator=1e-4",
                                    "0.7:delays.steering_angle_to_actuator=1e-4"});
  EXPECT_FALSE(changed.diverged());
  ASSERT_EQ(changed.rows.size(), base.rows.size());
  const auto [first, worst] = compare(changed, base, 0.4);
  // The row at 0.4 s logs the tracker's command at 0.4 s, the first one read 0.05 s back.
  EXPECT_EQ(first, 400u);
  EXPECT_GT(worst, 1e-6);
  EXPECT_EQ(changed.changes.size(), 5u);
}

/// The lockstep loop driven by hand (as closed_loop.cpp does), with `hook` called after every round:
/// it may add changes to `schedule` and hand them to the components, as a node does with a live
/// request. Returns the result with the schedule's changes up to the end.
RunResult runWithLiveChanges(ChangeSchedule& schedule,
                             const std::function<void(ChangeSchedule&, PathTrackingStage&, SteeringActuatorStage&)>& hook) {
  const SimConfig& c = schedule.start();
  const LoopSchedule s = loopScheduleOf(c);
  PlantSession plant(c, s, s.duration);
  PathTrackingStage tracker = createPathTrackingStage(c, s);
  SteeringActuatorStage actuator = createSteeringActuatorStage(c, s);
  // Live changes may come with any delay: keep the history the longest one needs.
  tracker.retainInputFor(secondsToNanoseconds(DelayParams::kMaxDelay));
  actuator.retainInputsFor(secondsToNanoseconds(DelayParams::kMaxDelay));
  const PlantSession::SampleCallback feed = [&](const VehiclePlant& p) {
    tracker.pushPose(p.time(), p.pose());
    actuator.pushMeasurement(p.time(), p.measurement());
  };
  while (!plant.done()) {
    const long steps = plant.advance(feed);
    bool produced = false;
    while (tracker.ready()) {
      const auto command = tracker.produce();
      actuator.pushDesired(command.stamp, command.value);
      plant.pushCommand(command.stamp, command.value);
      produced = true;
    }
    while (actuator.ready()) {
      const auto torque = actuator.produce();
      plant.pushTorque(torque.stamp, torque.value.torque);
      plant.pushIntegral(torque.stamp, actuator.actuator().integral());
      produced = true;
    }
    hook(schedule, tracker, actuator);
    if (steps == 0 && !produced && !plant.done()) ADD_FAILURE() << "stalled at " << plant.plant().time();
    if (steps == 0 && !produced) break;
  }
  const Nanoseconds end = plant.plant().time();
  RunResult result = plant.takeResult();
  for (const auto& change : schedule.changes()) {
    if (change.stamp <= end) result.changes.push_back(change);
  }
  return result;
}

TEST(RuntimeChange, ALiveChangeIsReproducedBitForBitByItsRecord) {
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=1.2"});
  ChangeSchedule schedule(c);
  bool tracker_done = false, actuator_done = false;
  const RunResult live = runWithLiveChanges(schedule, [&](ChangeSchedule& sch, PathTrackingStage& tracker,
                                                          SteeringActuatorStage& actuator) {
    // Requests with apply_at = 0 ("the next sample"), the moment each component has passed some time:
    // their stamps depend on how far the loop ran, which the records then say.
    if (!tracker_done && tracker.nextTime() > 430'000'000) {
      tracker_done = true;
      const Nanoseconds next = tracker.nextTime();
      sch.add(0.0, {{"tracker.k_psi", "1.2"}}, "reconfigure", next);
      sch.add(0.0, {{"delays.pose_to_tracker", "0.35"}}, "reconfigure", next);  // longer: re-reads 0.15 s of poses
      scheduleChanges(tracker, sch, next);
    }
    if (!actuator_done && actuator.nextTime() > 610'000'000) {
      actuator_done = true;
      const Nanoseconds next = actuator.nextTime();
      sch.add(0.0, {{"actuator.p", "2600"}}, "reconfigure", next);
      sch.add(0.0, {{"delays.desired_steering_to_actuator", "4e-4"}, {"delays.steering_angle_to_actuator", "4e-4"}},
              "reconfigure", next);
      scheduleChanges(actuator, sch, next);
    }
  });
  ASSERT_TRUE(tracker_done && actuator_done);
  ASSERT_EQ(live.changes.size(), 5u);
  std::vector<std::string> arguments;
  for (const auto& change : live.changes) arguments.push_back(change.argument());
  const RunResult replayed = run(c, arguments);
  expectBitIdentical(live, replayed);
  ASSERT_EQ(replayed.changes.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(replayed.changes[i].describe(), live.changes[i].describe());
  // And the changes did something.
  EXPECT_LT(compare(live, run(c), 0.43).first, live.rows.size());
}

}  // namespace
}  // namespace lane_keeping
