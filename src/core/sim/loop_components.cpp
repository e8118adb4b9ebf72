#include "lane_keeping/sim/loop_components.h"

#include <algorithm>

#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {

LoopSchedule loopScheduleOf(const SimConfig& c) {
  LoopSchedule s;
  s.plant_step = secondsToNanoseconds(c.simulation.step);
  s.tracker_period = periodFromRate(c.tracker.rate);
  s.actuator_period = periodFromRate(c.actuator.rate);
  s.log_period = periodFromRate(c.simulation.log_rate);
  s.duration = secondsToNanoseconds(c.simulation.duration);
  s.pose_delay = secondsToNanoseconds(c.delays.pose_to_tracker);
  s.desired_delay = secondsToNanoseconds(c.delays.desired_steering_to_actuator);
  s.measured_delay = secondsToNanoseconds(c.delays.steering_angle_to_actuator);
  s.torque_delay = secondsToNanoseconds(c.delays.torque_to_plant);
  s.hold = holdFromName(c.delays.hold);
  return s;
}

VehiclePlant createVehiclePlant(const SimConfig& c, const LoopSchedule& s) {
  return VehiclePlant(createVehicleModel(c), c.simulation.initial, s.plant_step, s.torque_delay, s.hold,
                      s.actuator_period, c.sensors);
}

PathTrackingStage createPathTrackingStage(const SimConfig& c, const LoopSchedule& s) {
  return PathTrackingStage(PathTracker(c.tracker, createPath(c.path)), s.tracker_period, s.pose_delay, s.hold,
                           s.plant_step);
}

SteeringActuatorStage createSteeringActuatorStage(const SimConfig& c, const LoopSchedule& s) {
  return SteeringActuatorStage(SteeringActuator(c.actuator), s.actuator_period, s.desired_delay, s.measured_delay,
                               s.hold, s.tracker_period, s.plant_step);
}

namespace {

/// The distinct stamps of `role`'s changes at `from` or later, in order.
std::vector<Nanoseconds> stampsOf(const ChangeSchedule& changes, LoopRole role, Nanoseconds from) {
  std::vector<Nanoseconds> stamps;
  for (const auto& e : changes.entries()) {
    if (e.change.owner == role && e.change.stamp >= from) stamps.push_back(e.change.stamp);
  }
  std::sort(stamps.begin(), stamps.end());
  stamps.erase(std::unique(stamps.begin(), stamps.end()), stamps.end());
  return stamps;
}

}  // namespace

void scheduleChanges(PathTrackingStage& stage, const ChangeSchedule& changes, Nanoseconds from) {
  stage.clearChangesFrom(from);
  for (const Nanoseconds stamp : stampsOf(changes, LoopRole::kTracker, from)) {
    const SimConfig& c = changes.configFor(LoopRole::kTracker, stamp);
    stage.scheduleChange(stamp, c.tracker, secondsToNanoseconds(c.delays.pose_to_tracker));
  }
}

void scheduleChanges(SteeringActuatorStage& stage, const ChangeSchedule& changes, Nanoseconds from) {
  stage.clearChangesFrom(from);
  for (const Nanoseconds stamp : stampsOf(changes, LoopRole::kActuator, from)) {
    const SimConfig& c = changes.configFor(LoopRole::kActuator, stamp);
    stage.scheduleChange(stamp, c.actuator, secondsToNanoseconds(c.delays.desired_steering_to_actuator),
                         secondsToNanoseconds(c.delays.steering_angle_to_actuator));
  }
}

void scheduleChanges(VehiclePlant& plant, const ChangeSchedule& changes, Nanoseconds from) {
  plant.clearChangesFrom(from);
  for (const Nanoseconds stamp : stampsOf(changes, LoopRole::kPlant, from)) {
    const SimConfig& c = changes.configFor(LoopRole::kPlant, stamp);
    plant.scheduleChange(stamp, createVehicleModel(c), secondsToNanoseconds(c.delays.torque_to_plant));
  }
}

}  // namespace lane_keeping
