#pragma once
/// Which component of the loop applies a configuration key that changes during a run, and which
/// keys cannot change mid-run (and why). The key names are the configuration's (config/default.yaml).
///
///   path_tracking      tracker.* (gains, pose bias, excitation; not tracker.rate), delays.pose_to_tracker
///   steering_actuator  actuator.* (not actuator.rate), delays.desired_steering_to_actuator,
///                      delays.steering_angle_to_actuator
///   vehicle_plant      vehicle.*, steering.* (not steering.angle_sensor), disturbance.*, tire.*,
///                      delays.torque_to_plant — as long as the model's state layout stays
///                      (checked by the schedule, change_schedule.h)
/// Fixed for a run: the sample grids (simulation.step, tracker.rate, actuator.rate), delays.hold, the
/// rest of simulation.* (duration, log, initial state, divergence limits), path.* (the lane both the
/// tracker and the log measure against), sensors.* and steering.angle_sensor (the sensor model keeps a
/// history shaped by them).
#include <string>

namespace lane_keeping {

enum class LoopRole { kTracker, kActuator, kPlant };

/// The ROS node (and nodelet) name of a role: "path_tracking", "steering_actuator", "vehicle_plant".
const char* roleName(LoopRole role);

/// The component that applies a change of `key` during a run. Throws ConfigError naming the key and
/// why it cannot change during a run.
LoopRole changeOwner(const std::string& key);

}  // namespace lane_keeping
