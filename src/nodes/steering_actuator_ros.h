#pragma once
/// ROS interface of the steering actuator (Beregi eqs 12-16): subscribes to the desired and the
/// measured steering angle, feeds the core SteeringActuatorStage (which applies tau2 on the stamps
/// and samples at actuator.rate), and publishes every torque its inputs cover. Shared by the
/// steering_actuator node and nodelet.
///
/// Runtime tuning (docs/ros.md): the changes of ~changes it owns, and a dynamic_reconfigure server
/// (cfg/SteeringActuator.cfg: p, tau2 = both input delays, apply_at) whose requests the core checks
/// and schedules (node_changes.h); each change is announced on parameter_changes.
#include <memory>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/MeasuredSteeringArray.h"
#include "lane_keeping/SteeringActuatorConfig.h"
#include "lane_keeping/SteeringTorqueArray.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/control_stages.h"
#include "clock_jump.h"
#include "loop_io.h"
#include "node_changes.h"

namespace lane_keeping {

class SteeringActuatorRos {
 public:
  /// Throws ConfigError naming every bad parameter.
  SteeringActuatorRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);

 private:
  void onDesired(const DesiredSteeringArray::ConstPtr& msg);
  void onMeasured(const MeasuredSteeringArray::ConstPtr& msg);
  /// Push the samples into the stage (a stale one is rejected by the core) and compute what they cover.
  void takeDesired(const DesiredSteeringArray::ConstPtr& msg);
  void takeMeasured(const MeasuredSteeringArray::ConstPtr& msg);
  void createStage();
  void produceAndFlush();
  /// The run has started (first input): announce the configured changes.
  void started();
  /// dynamic_reconfigure: each changed value goes through the core's checks; a refused one is put back.
  void onReconfigure(SteeringActuatorConfig& request, uint32_t level);

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  SimConfig config_;
  std::unique_ptr<NodeChanges> changes_;
  std::unique_ptr<SteeringActuatorStage> stage_;
  ros::Subscriber desired_sub_, measured_sub_;
  BatchPublisher<SteeringTorqueArray> torque_pub_;
  ros::WallTimer flush_timer_;
  RejectLog desired_rejects_, measured_rejects_;
  bool started_ = false;
  ClockJumpGuard jumps_;  // restarts the node from its initial state when the ROS clock jumps back
  Nanoseconds latest_desired_ = ClockJumpGuard::kNone, latest_measured_ = ClockJumpGuard::kNone;  // since the (re)start
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<SteeringActuatorConfig>> reconfigure_;
  SteeringActuatorConfig shown_;  // what the server shows: values in force, or accepted and scheduled
};

}  // namespace lane_keeping
