#pragma once
/// The vehicle model of a configuration, with everything the configuration switches on (steering
/// system, disturbance, tire relaxation). Every runner (in-process, ROS plant, gap replay) builds its
/// model here.
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

inline SingleTrackModel createVehicleModel(const SimConfig& config) {
  return createVehicleModel(config.vehicle, config.steering, config.disturbance, config.tire_front, config.tire_rear);
}

}  // namespace lane_keeping
