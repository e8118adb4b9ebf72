// The gap_monitor nodelet: the GapMonitorRos role inside a nodelet manager (zero-copy input beside the
// loop's nodelets). It takes no part in the loop, so by default it does not share the loop's thread.
#include <pluginlib/class_list_macros.hpp>

#include "gap_monitor_ros.h"
#include "node_shell.h"

namespace lane_keeping {
template <>
struct SharedThreadDefault<GapMonitorRos> : std::false_type {};
using GapMonitorNodelet = NodeletShell<GapMonitorRos>;
}  // namespace lane_keeping

PLUGINLIB_EXPORT_CLASS(lane_keeping::GapMonitorNodelet, nodelet::Nodelet)
