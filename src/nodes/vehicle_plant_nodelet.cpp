// The vehicle_plant nodelet: the VehiclePlantRos role inside a nodelet manager.
#include <pluginlib/class_list_macros.hpp>

#include "node_shell.h"
#include "vehicle_plant_ros.h"

namespace lane_keeping {
using VehiclePlantNodelet = NodeletShell<VehiclePlantRos>;
}  // namespace lane_keeping

PLUGINLIB_EXPORT_CLASS(lane_keeping::VehiclePlantNodelet, nodelet::Nodelet)
