#include "path_tracking_ros.h"

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/sim/delay_params.h"
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
  changes_ = std::make_unique<NodeChanges>(nh_, pnh_, config_, LoopRole::kTracker, name_);
  const SimConfig& start = changes_->start();
  jumps_.onRestart(name_, "the path tracker", "delay lines empty, runtime changes scheduled again",
                   [this] { flush(); }, [this] { createStage(); });
  createStage();

  command_pub_.advertise(nh_, topics::kDesiredSteering);
  state_sub_ = nh_.subscribe(topics::kVehicleState, kLoopQueueSize, &PathTrackingRos::onVehicleState, this,
                             loopTransportHints());
  flush_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) {
    flush();
    jumps_.onTimer();
  });

  // The server starts from the loaded configuration, not from the .cfg's defaults.
  shown_.k_psi = start.tracker.k_psi;
  shown_.k_y = start.tracker.k_y;
  shown_.tau1 = start.delays.pose_to_tracker;
  shown_.apply_at = 0.0;
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<PathTrackingConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(shown_);
  reconfigure_->setCallback([this](PathTrackingConfig& request, uint32_t level) { onReconfigure(request, level); });
  ROS_INFO("%s: path tracker k_psi = %g, k_y = %g 1/m at %g Hz, delay %s (pose -> tracker, on stamps); %zu "
           "runtime change(s) in ~changes\n%s",
           name_.c_str(), start.tracker.k_psi, start.tracker.k_y, start.tracker.rate,
           formatSeconds(start.delays.pose_to_tracker).c_str(), changes_->configured().size(),
           params.effective().c_str());
}

void PathTrackingRos::onVehicleState(const VehicleStateArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    rejects_.reject(name_, state_sub_.getTopic(), bad);
    return;
  }
  if (jumps_.heldOrDropped(msg, latest_input_, state_sub_.getTopic(), rejects_, [this, msg] { take(msg); })) return;
  take(msg);
}

void PathTrackingRos::take(const VehicleStateArray::ConstPtr& msg) {
  if (!started_) {  // the plant has started the run: everyone listens now
    started_ = true;
    changes_->announceConfigured();
  }
  pushSamples(*msg, name_, state_sub_.getTopic(), rejects_, [this](Nanoseconds stamp, const VehicleState& s) {
    stage_->pushPose(stamp, PoseSample::of(fromVehicleStateMsg(s)));
    latest_input_ = std::max(latest_input_, stamp);
  });
  produceAndFlush();
}

void PathTrackingRos::createStage() {
  const SimConfig& start = changes_->start();
  stage_ = std::make_unique<PathTrackingStage>(createPathTrackingStage(start, loopScheduleOf(start)));
  scheduleChanges(*stage_, changes_->schedule(), 1);
  // A live request may lengthen tau1 up to the largest delay allowed: keep that much pose history.
  stage_->retainInputFor(secondsToNanoseconds(DelayParams::kMaxDelay));
  latest_input_ = ClockJumpGuard::kNone;
}

void PathTrackingRos::produceAndFlush() {
  while (stage_->ready()) {
    const Stamped<SteeringCommand> command = stage_->produce();
    command_pub_.add(toDesiredSteeringMsg(command.stamp, command.value));
  }
  flush();
  // Changes that took effect with the samples just computed: the server shows the values in force.
  const auto effective = changes_->takeEffective(stage_->nextTime() - 1);
  if (effective.empty()) return;
  for (const ScheduledChange& change : effective) {
    const SimConfig& now = changes_->schedule().configFor(LoopRole::kTracker, change.stamp);
    if (change.key == "tracker.k_psi") shown_.k_psi = now.tracker.k_psi;
    if (change.key == "tracker.k_y") shown_.k_y = now.tracker.k_y;
    if (change.key == "delays.pose_to_tracker") shown_.tau1 = now.delays.pose_to_tracker;
  }
  reconfigure_->updateConfig(shown_);
}

void PathTrackingRos::flush() { command_pub_.flush(); }

void PathTrackingRos::onReconfigure(PathTrackingConfig& request, uint32_t /*level*/) {
  const double apply_at = request.apply_at;
  request.apply_at = 0.0;  // one request at a time: the next one means "now" unless it says otherwise
  bool scheduled = false;
  auto consider = [&](const char* key, double& requested, double& shown) {
    if (requested == shown) return;  // unchanged (a NaN request never equals: it is checked and refused)
    try {
      changes_->request(apply_at, {{key, yamlNumber(requested)}}, stage_->nextTime());
      shown = requested;
      scheduled = true;
    } catch (const ConfigError& e) {
      ROS_ERROR("%s: dynamic_reconfigure: refused %s = %s, which stays %s: %s", name_.c_str(), key,
                yamlNumber(requested).c_str(), formatNumber(shown).c_str(), e.what());
      requested = shown;  // the server keeps (and reports) the value in force
    }
  };
  consider("tracker.k_psi", request.k_psi, shown_.k_psi);
  consider("tracker.k_y", request.k_y, shown_.k_y);
  consider("delays.pose_to_tracker", request.tau1, shown_.tau1);
  if (scheduled) {
    scheduleChanges(*stage_, changes_->schedule(), stage_->nextTime());
    // A longer delay may make the next sample computable now, with no new input to prompt it.
    produceAndFlush();
  }
  request = shown_;  // what the server keeps and answers with
}

}  // namespace lane_keeping
