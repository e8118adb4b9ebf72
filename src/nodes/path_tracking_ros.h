#pragma once
/// ROS interface of the path tracker (Beregi eq 11): subscribes to the vehicle state, feeds the
/// core PathTrackingStage (which applies tau1 on the stamps and samples at tracker.rate), and
/// publishes every command its input covers. Shared by the path_tracking node and nodelet.
#include <memory>
#include <string>

#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/VehicleStateArray.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/control_stages.h"
#include "loop_io.h"

namespace lane_keeping {

class PathTrackingRos {
 public:
  /// Reads the configuration and the private parameters, subscribes and advertises.
  /// Throws ConfigError naming every bad parameter.
  PathTrackingRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);

 private:
  void onVehicleState(const VehicleStateArray::ConstPtr& msg);
  void flush();

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  SimConfig config_;
  std::unique_ptr<PathTrackingStage> stage_;
  ros::Subscriber state_sub_;
  BatchPublisher<DesiredSteeringArray> command_pub_;
  ros::WallTimer flush_timer_;  // retries a flush that waited for a subscriber
  RejectLog rejects_;  // vehicle_state
};

}  // namespace lane_keeping
