// PlantSession and the lockstep components: the log, the stop time and the stop reason do not depend
// on how the samples are batched or when they arrive (the property a lockstep ROS run relies on to
// reproduce the in-process run bit for bit).
#include <gtest/gtest.h>

#include <deque>
#include <random>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/plant_session.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

/// The three components with queues between them, delivered in random batches (seeded): like topics
/// whose messages carry several samples and arrive whenever the scheduler gets to them.
RunResult runWithRandomDelivery(const SimConfig& c, unsigned seed) {
  const LoopSchedule s = loopScheduleOf(c);
  PlantSession plant(c, s, s.duration);
  PathTrackingStage tracker = createPathTrackingStage(c, s);
  SteeringActuatorStage actuator = createSteeringActuatorStage(c, s);
  std::deque<std::pair<Nanoseconds, PoseSample>> poses;
  std::deque<std::pair<Nanoseconds, SteeringMeasurement>> measurements;
  std::deque<Stamped<SteeringCommand>> commands_to_actuator, commands_to_plant;
  std::deque<std::pair<Stamped<TorqueCommand>, double>> torques;
  std::mt19937 random(seed);
  auto some = [&](std::size_t available) {
    return available == 0 ? std::size_t{0} : std::uniform_int_distribution<std::size_t>(1, available)(random);
  };
  const PlantSession::SampleCallback feed = [&](const VehiclePlant& p) {
    poses.emplace_back(p.time(), p.pose());
    measurements.emplace_back(p.time(), p.measurement());
  };
  for (int round = 0; round < 10000000 && !plant.done(); ++round) {
    switch (random() % 4) {
      case 0:
        plant.advance(feed);
        break;
      case 1:
        for (std::size_t n = some(poses.size()); n > 0; --n, poses.pop_front()) {
          tracker.pushPose(poses.front().first, poses.front().second);
        }
        while (tracker.ready()) {
          const auto command = tracker.produce();
          commands_to_actuator.push_back(command);
          commands_to_plant.push_back(command);
        }
        break;
      case 2:
        for (std::size_t n = some(measurements.size()); n > 0; --n, measurements.pop_front()) {
          actuator.pushMeasurement(measurements.front().first, measurements.front().second);
        }
        for (std::size_t n = some(commands_to_actuator.size()); n > 0; --n, commands_to_actuator.pop_front()) {
          actuator.pushDesired(commands_to_actuator.front().stamp, commands_to_actuator.front().value);
        }
        while (actuator.ready()) {
          const auto torque = actuator.produce();
          torques.emplace_back(torque, actuator.actuator().integral());
        }
        break;
      default:
        for (std::size_t n = some(torques.size()); n > 0; --n, torques.pop_front()) {
          plant.pushTorque(torques.front().first.stamp, torques.front().first.value.torque);
          plant.pushIntegral(torques.front().first.stamp, torques.front().second);
        }
        for (std::size_t n = some(commands_to_plant.size()); n > 0; --n, commands_to_plant.pop_front()) {
          plant.pushCommand(commands_to_plant.front().stamp, commands_to_plant.front().value);
        }
        break;
    }
  }
  EXPECT_TRUE(plant.done());
  return plant.takeResult();
}

void expectSameRun(const RunResult& a, const RunResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.end_time, b.end_time);
  EXPECT_EQ(a.plant_steps, b.plant_steps);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) ASSERT_EQ(logValues(a.rows[i]), logValues(b.rows[i])) << "row " << i;
}

TEST(PlantSession, RandomBatchingAndArrivalGiveTheInProcessRunBitForBit) {
  const SimConfig c = loadSimConfig({scenario("lane_change.yaml")}, {"simulation.duration=0.3"});
  const RunResult reference = ClosedLoop(c).run();
  for (unsigned seed : {1u, 2u, 3u}) expectSameRun(runWithRandomDelivery(c, seed), reference);
}

TEST(PlantSession, ZeroOrderHoldAndTorqueDelayToo) {
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")},
                                    {"simulation.duration=0.3", "actuator.rate=2000", "delays.hold=zoh",
                                     "delays.torque_to_plant=3.3e-4", "delays.pose_to_tracker=0.01"});
  expectSameRun(runWithRandomDelivery(c, 7u), ClosedLoop(c).run());
}

TEST(PlantSession, DivergedRunStopsAtTheSameStepWithTheSameReason) {
  const SimConfig c = loadSimConfig({scenario("fig9.yaml")});
  const RunResult reference = ClosedLoop(c).run();
  ASSERT_TRUE(reference.diverged());
  expectSameRun(runWithRandomDelivery(c, 11u), reference);
}

TEST(PlantSession, LogRowsWaitForTheControllersOutputs) {
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=0.01"});
  const LoopSchedule s = loopScheduleOf(c);
  PlantSession plant(c, s, s.duration);
  plant.advance(nullptr);  // t = 0: logged, but without the tracker's command and the actuator's outputs
  EXPECT_EQ(plant.result().rows.size(), 0u);
  EXPECT_EQ(plant.pendingRows(), 1u);
  EXPECT_NE(plant.pendingReason().find("desired steering"), std::string::npos) << plant.pendingReason();
  EXPECT_TRUE(plant.waitingForTorque());
  plant.pushCommand(0, SteeringCommand{0.01, 0.0});
  plant.pushIntegral(0, 0.0);
  EXPECT_EQ(plant.result().rows.size(), 0u);  // still waits for the torque command at t = 0
  EXPECT_NE(plant.pendingReason().find("steering torque"), std::string::npos) << plant.pendingReason();
  plant.pushTorque(0, 12.5);
  plant.pushTorque(100000, 12.5);
  EXPECT_EQ(plant.result().rows.size(), 1u);
  EXPECT_EQ(plant.result().rows[0].delta_des, 0.01);
  EXPECT_EQ(plant.result().rows[0].torque_command, 12.5);
}

TEST(PlantSession, PacingLimitStopsBeforeTheWallClock) {
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")}, {"simulation.duration=0.01", "delays.hold=zoh"});
  const LoopSchedule s = loopScheduleOf(c);
  PlantSession plant(c, s, s.duration);
  plant.pushTorque(0, 0.0);
  plant.pushTorque(100000000, 0.0);  // covers the whole run
  EXPECT_EQ(plant.advance(nullptr, 5 * s.plant_step), 5);  // realtime: not beyond 0.5 ms
  EXPECT_EQ(plant.plant().time(), 5 * s.plant_step);
}

}  // namespace
}  // namespace lane_keeping
