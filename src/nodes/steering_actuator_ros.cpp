#include "steering_actuator_ros.h"

#include "lane_keeping/sim/loop_components.h"
#include "ros_config.h"
#include "topic_names.h"

namespace lane_keeping {

SteeringActuatorRos::SteeringActuatorRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name)
    : nh_(nh), pnh_(pnh), name_(std::move(name)) {
  NodeParamReader params(pnh_);
  const std::string config_ns = params.text("config_namespace", "config");
  params.throwIfProblems();
  config_ = loadSimConfigFromParams(nh_, config_ns);
  stage_ = std::make_unique<SteeringActuatorStage>(createSteeringActuatorStage(config_, loopScheduleOf(config_)));

  torque_pub_.advertise(nh_, topics::kSteeringTorque);
  desired_sub_ = nh_.subscribe(topics::kDesiredSteering, kLoopQueueSize, &SteeringActuatorRos::onDesired, this,
                               loopTransportHints());
  measured_sub_ = nh_.subscribe(topics::kMeasuredSteering, kLoopQueueSize, &SteeringActuatorRos::onMeasured, this,
                                loopTransportHints());
  flush_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) { torque_pub_.flush(); });
  ROS_INFO("%s: steering actuator p = %g (k_p = %g, k_d = %g, k_i = %g) at %g Hz, delays %s (desired) and %s "
           "(measured), hold %s\n%s",
           name_.c_str(), config_.actuator.p, config_.actuator.kp(), config_.actuator.kd(), config_.actuator.ki(),
           config_.actuator.rate, formatSeconds(config_.delays.desired_steering_to_actuator).c_str(),
           formatSeconds(config_.delays.steering_angle_to_actuator).c_str(), config_.delays.hold.c_str(),
           params.effective().c_str());
}

void SteeringActuatorRos::onDesired(const DesiredSteeringArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    desired_rejects_.reject(name_, desired_sub_.getTopic(), bad);
    return;
  }
  pushSamples(*msg, name_, desired_sub_.getTopic(), desired_rejects_, [this](Nanoseconds stamp, const DesiredSteering& s) {
    stage_->pushDesired(stamp, fromDesiredSteeringMsg(s));
  });
  produceAndFlush();
}

void SteeringActuatorRos::onMeasured(const MeasuredSteeringArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    measured_rejects_.reject(name_, measured_sub_.getTopic(), bad);
    return;
  }
  pushSamples(*msg, name_, measured_sub_.getTopic(), measured_rejects_, [this](Nanoseconds stamp, const MeasuredSteering& s) {
    stage_->pushMeasurement(stamp, fromMeasuredSteeringMsg(s));
  });
  produceAndFlush();
}

void SteeringActuatorRos::produceAndFlush() {
  while (stage_->ready()) {
    const Stamped<TorqueCommand> torque = stage_->produce();
    torque_pub_.add(toSteeringTorqueMsg(torque.stamp, torque.value, stage_->actuator().integral()));
  }
  torque_pub_.flush();
}

}  // namespace lane_keeping
