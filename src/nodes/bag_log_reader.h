#pragma once
/// Reads a rosbag recorded from the suite's own topics (launch/closed_loop.launch record:=true) into a
/// GapLog for the gap diagnosis (DESIGN §5): the vehicle_state topic gives the pose, yaw rate, speed,
/// lateral acceleration, steering angle and rate at every plant step; desired_steering gives
/// delta_des; steering_torque (if recorded) gives the torque command M_S — otherwise the torque acting
/// on the wheel, recorded in vehicle_state, stands in for it (the same unless an actuation delay is
/// configured) and the log says so.
#include <string>

#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

/// Topics are found by name suffix in any namespace. Samples are thinned to at most `max_rate` Hz.
/// Throws InputError naming the bag and the missing topic (with the topics the bag holds).
GapLog readBagLog(const std::string& path, double max_rate = 1000.0);

}  // namespace lane_keeping
