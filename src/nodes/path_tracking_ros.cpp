#include "path_tracking_ros.h"

#include "lane_keeping/sim/loop_components.h"
#include "ros_config.h"
#include "topic_names.h"

namespace lane_keeping {

PathTrackingRos::PathTrackingRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name)
    : nh_(nh), pnh_(pnh), name_(std::move(name)) {
  NodeParamReader params(pnh_);
  const std::string config_ns = params.text("config_namespace", "config");
  params.throwIfProblems();
  config_ = loadSimConfigFromParams(nh_, config_ns);
  stage_ = std::make_unique<PathTrackingStage>(createPathTrackingStage(config_, loopScheduleOf(config_)));

  command_pub_.advertise(nh_, topics::kDesiredSteering);
  state_sub_ = nh_.subscribe(topics::kVehicleState, kLoopQueueSize, &PathTrackingRos::onVehicleState, this,
                             loopTransportHints());
  flush_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) { flush(); });
  ROS_INFO("%s: path tracker k_psi = %g, k_y = %g 1/m at %g Hz, delay %s (pose -> tracker, on stamps)\n%s",
           name_.c_str(), config_.tracker.k_psi, config_.tracker.k_y, config_.tracker.rate,
           formatSeconds(config_.delays.pose_to_tracker).c_str(), params.effective().c_str());
}

void PathTrackingRos::onVehicleState(const VehicleStateArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    rejects_.reject(name_, state_sub_.getTopic(), bad);
    return;
  }
  pushSamples(*msg, name_, state_sub_.getTopic(), rejects_, [this](Nanoseconds stamp, const VehicleState& s) {
    stage_->pushPose(stamp, PoseSample::of(fromVehicleStateMsg(s)));
  });
  while (stage_->ready()) {
    const Stamped<SteeringCommand> command = stage_->produce();
    command_pub_.add(toDesiredSteeringMsg(command.stamp, command.value));
  }
  flush();
}

void PathTrackingRos::flush() { command_pub_.flush(); }

}  // namespace lane_keeping
