// The path_tracking nodelet: the PathTrackingRos role inside a nodelet manager.
#include <pluginlib/class_list_macros.hpp>

#include "node_shell.h"
#include "path_tracking_ros.h"

namespace lane_keeping {
using PathTrackingNodelet = NodeletShell<PathTrackingRos>;
}  // namespace lane_keeping

PLUGINLIB_EXPORT_CLASS(lane_keeping::PathTrackingNodelet, nodelet::Nodelet)
