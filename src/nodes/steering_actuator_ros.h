#pragma once
/// ROS interface of the steering actuator (Beregi eqs 12-16): subscribes to the desired and the
/// measured steering angle, feeds the core SteeringActuatorStage (which applies tau2 on the stamps
/// and samples at actuator.rate), and publishes every torque its inputs cover. Shared by the
/// steering_actuator node and nodelet.
#include <memory>
#include <string>

#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/MeasuredSteeringArray.h"
#include "lane_keeping/SteeringTorqueArray.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/control_stages.h"
#include "loop_io.h"

namespace lane_keeping {

class SteeringActuatorRos {
 public:
  /// Throws ConfigError naming every bad parameter.
  SteeringActuatorRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);

 private:
  void onDesired(const DesiredSteeringArray::ConstPtr& msg);
  void onMeasured(const MeasuredSteeringArray::ConstPtr& msg);
  void produceAndFlush();

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  SimConfig config_;
  std::unique_ptr<SteeringActuatorStage> stage_;
  ros::Subscriber desired_sub_, measured_sub_;
  BatchPublisher<SteeringTorqueArray> torque_pub_;
  ros::WallTimer flush_timer_;
  RejectLog desired_rejects_, measured_rejects_;
};

}  // namespace lane_keeping
