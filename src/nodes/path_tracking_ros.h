#pragma once
/// ROS interface of the path tracker (Beregi eq 11): subscribes to the vehicle state, feeds the
/// core PathTrackingStage (which applies tau1 on the stamps and samples at tracker.rate), and
/// publishes every command its input covers. Shared by the path_tracking node and nodelet.
///
/// Runtime tuning (docs/ros.md): the changes of ~changes it owns, and a dynamic_reconfigure server
/// (cfg/PathTracking.cfg: k_psi, k_y, tau1, apply_at) whose requests the core checks and schedules
/// (node_changes.h); each change is announced on parameter_changes.
#include <memory>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/PathTrackingConfig.h"
#include "lane_keeping/VehicleStateArray.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/control_stages.h"
#include "clock_jump.h"
#include "loop_io.h"
#include "node_changes.h"

namespace lane_keeping {

class PathTrackingRos {
 public:
  /// Reads the configuration and the private parameters, subscribes and advertises.
  /// Throws ConfigError naming every bad parameter.
  PathTrackingRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);

 private:
  void onVehicleState(const VehicleStateArray::ConstPtr& msg);
  /// Pushes the samples into the stage (a stale one is rejected by the core) and computes what they cover.
  void take(const VehicleStateArray::ConstPtr& msg);
  void createStage();
  void produceAndFlush();
  void flush();
  /// dynamic_reconfigure: each changed value goes through the core's checks; a refused one is put back.
  void onReconfigure(PathTrackingConfig& request, uint32_t level);

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  SimConfig config_;
  std::unique_ptr<NodeChanges> changes_;
  std::unique_ptr<PathTrackingStage> stage_;
  ros::Subscriber state_sub_;
  BatchPublisher<DesiredSteeringArray> command_pub_;
  ros::WallTimer flush_timer_;  // retries a flush that waited for a subscriber
  RejectLog rejects_;  // vehicle_state
  bool started_ = false;  // the first input arrived: the run is on
  ClockJumpGuard jumps_;  // restarts the node from its initial state when the ROS clock jumps back
  Nanoseconds latest_input_ = ClockJumpGuard::kNone;  // latest pose stamp taken since the (re)start
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<PathTrackingConfig>> reconfigure_;
  PathTrackingConfig shown_;  // what the server shows: values in force, or accepted and scheduled
};

}  // namespace lane_keeping
