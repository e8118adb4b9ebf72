#include "lane_keeping/sim/loop_components.h"

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

}  // namespace lane_keeping
