#include "steering_actuator_ros.h"

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/sim/delay_params.h"
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
  changes_ = std::make_unique<NodeChanges>(nh_, pnh_, config_, LoopRole::kActuator, name_);
  const SimConfig& start = changes_->start();
  jumps_.onRestart(name_, "the steering actuator", "delay lines empty, integrator zero, runtime changes scheduled again",
                   [this] { torque_pub_.flush(); }, [this] { createStage(); });
  createStage();

  torque_pub_.advertise(nh_, topics::kSteeringTorque);
  desired_sub_ = nh_.subscribe(topics::kDesiredSteering, kLoopQueueSize, &SteeringActuatorRos::onDesired, this,
                               loopTransportHints());
  measured_sub_ = nh_.subscribe(topics::kMeasuredSteering, kLoopQueueSize, &SteeringActuatorRos::onMeasured, this,
                                loopTransportHints());
  flush_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
    torque_pub_.flush();
    jumps_.onTimer();
  });

  // The server starts from the loaded configuration, not from the .cfg's defaults. tau2 shows the
  // steering-angle delay (the two may differ in a configuration; a request sets both).
  shown_.p = start.actuator.p;
  shown_.tau2 = start.delays.steering_angle_to_actuator;
  shown_.apply_at = 0.0;
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<SteeringActuatorConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(shown_);
  reconfigure_->setCallback([this](SteeringActuatorConfig& request, uint32_t level) { onReconfigure(request, level); });
  ROS_INFO("%s: steering actuator p = %g (k_p = %g, k_d = %g, k_i = %g) at %g Hz, delays %s (desired) and %s "
           "(measured), hold %s; %zu runtime change(s) in ~changes\n%s",
           name_.c_str(), start.actuator.p, start.actuator.kp(), start.actuator.kd(), start.actuator.ki(),
           start.actuator.rate, formatSeconds(start.delays.desired_steering_to_actuator).c_str(),
           formatSeconds(start.delays.steering_angle_to_actuator).c_str(), start.delays.hold.c_str(),
           changes_->configured().size(), params.effective().c_str());
}

void SteeringActuatorRos::started() {
  if (started_) return;
  started_ = true;  // the plant has started the run: everyone listens now
  changes_->announceConfigured();
}

void SteeringActuatorRos::onDesired(const DesiredSteeringArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    desired_rejects_.reject(name_, desired_sub_.getTopic(), bad);
    return;
  }
  if (jumps_.heldOrDropped(msg, latest_desired_, desired_sub_.getTopic(), desired_rejects_, [this, msg] { takeDesired(msg); })) {
    return;
  }
  takeDesired(msg);
}

void SteeringActuatorRos::takeDesired(const DesiredSteeringArray::ConstPtr& msg) {
  started();
  pushSamples(*msg, name_, desired_sub_.getTopic(), desired_rejects_, [this](Nanoseconds stamp, const DesiredSteering& s) {
    stage_->pushDesired(stamp, fromDesiredSteeringMsg(s));
    latest_desired_ = std::max(latest_desired_, stamp);
  });
  produceAndFlush();
}

void SteeringActuatorRos::onMeasured(const MeasuredSteeringArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    measured_rejects_.reject(name_, measured_sub_.getTopic(), bad);
    return;
  }
  if (jumps_.heldOrDropped(msg, latest_measured_, measured_sub_.getTopic(), measured_rejects_, [this, msg] { takeMeasured(msg); })) {
    return;
  }
  takeMeasured(msg);
}

void SteeringActuatorRos::takeMeasured(const MeasuredSteeringArray::ConstPtr& msg) {
  started();
  pushSamples(*msg, name_, measured_sub_.getTopic(), measured_rejects_, [this](Nanoseconds stamp, const MeasuredSteering& s) {
    stage_->pushMeasurement(stamp, fromMeasuredSteeringMsg(s));
    latest_measured_ = std::max(latest_measured_, stamp);
  });
  produceAndFlush();
}

void SteeringActuatorRos::createStage() {
  const SimConfig& start = changes_->start();
  stage_ = std::make_unique<SteeringActuatorStage>(createSteeringActuatorStage(start, loopScheduleOf(start)));
  scheduleChanges(*stage_, changes_->schedule(), 1);
  // A live request may lengthen tau2 up to the largest delay allowed: keep that much input history.
  stage_->retainInputsFor(secondsToNanoseconds(DelayParams::kMaxDelay));
  latest_desired_ = latest_measured_ = ClockJumpGuard::kNone;
}

void SteeringActuatorRos::produceAndFlush() {
  while (stage_->ready()) {
    const Stamped<TorqueCommand> torque = stage_->produce();
    torque_pub_.add(toSteeringTorqueMsg(torque.stamp, torque.value, stage_->actuator().integral()));
  }
  torque_pub_.flush();
  // Changes that took effect with the samples just computed: the server shows the values in force.
  const auto effective = changes_->takeEffective(stage_->nextTime() - 1);
  if (effective.empty()) return;
  for (const ScheduledChange& change : effective) {
    const SimConfig& now = changes_->schedule().configFor(LoopRole::kActuator, change.stamp);
    if (change.key == "actuator.p") shown_.p = now.actuator.p;
    if (change.key == "delays.steering_angle_to_actuator") shown_.tau2 = now.delays.steering_angle_to_actuator;
  }
  reconfigure_->updateConfig(shown_);
}

void SteeringActuatorRos::onReconfigure(SteeringActuatorConfig& request, uint32_t /*level*/) {
  const double apply_at = request.apply_at;
  request.apply_at = 0.0;  // one request at a time: the next one means "now" unless it says otherwise
  bool scheduled = false;
  // Each value on its own (a refused one does not hold back the other); tau2 sets both input delays
  // together, checked together (one at a time could stall the lockstep schedule in between).
  auto consider = [&](const char* name, double& requested, double& shown, std::vector<std::string> keys) {
    if (requested == shown) return;  // unchanged (a NaN request never equals: it is checked and refused)
    std::vector<std::pair<std::string, std::string>> assignments;
    for (const auto& key : keys) assignments.emplace_back(key, yamlNumber(requested));
    try {
      changes_->request(apply_at, assignments, stage_->nextTime());
      shown = requested;
      scheduled = true;
    } catch (const ConfigError& e) {
      ROS_ERROR("%s: dynamic_reconfigure: refused %s = %s, which stays %s: %s", name_.c_str(), name,
                yamlNumber(requested).c_str(), formatNumber(shown).c_str(), e.what());
      requested = shown;  // the server keeps (and reports) the value in force
    }
  };
  consider("p (actuator.p)", request.p, shown_.p, {"actuator.p"});
  consider("tau2 (delays.desired_steering_to_actuator, delays.steering_angle_to_actuator)", request.tau2, shown_.tau2,
           {"delays.desired_steering_to_actuator", "delays.steering_angle_to_actuator"});
  if (scheduled) {
    scheduleChanges(*stage_, changes_->schedule(), stage_->nextTime());
    // A longer delay may make the next sample computable now, with no new input to prompt it.
    produceAndFlush();
  }
  request = shown_;  // what the server keeps and answers with
}

}  // namespace lane_keeping
