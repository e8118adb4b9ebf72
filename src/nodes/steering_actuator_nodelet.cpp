// The steering_actuator nodelet: the SteeringActuatorRos role inside a nodelet manager.
#include <pluginlib/class_list_macros.hpp>

#include "node_shell.h"
#include "steering_actuator_ros.h"

namespace lane_keeping {
using SteeringActuatorNodelet = NodeletShell<SteeringActuatorRos>;
}  // namespace lane_keeping

PLUGINLIB_EXPORT_CLASS(lane_keeping::SteeringActuatorNodelet, nodelet::Nodelet)
