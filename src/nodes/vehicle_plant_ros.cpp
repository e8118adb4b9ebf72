#include "vehicle_plant_ros.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include <rosgraph_msgs/Clock.h>

#include "lane_keeping/RunStatus.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/log_row.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/run_summary.h"
#include "ros_config.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

std::string percentiles(std::vector<double> values) {
  if (values.empty()) return "no samples";
  std::sort(values.begin(), values.end());
  auto at = [&](double q) { return values[static_cast<std::size_t>(q * (values.size() - 1))] * 1e6; };
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "p50 %.0f us, p99 %.0f us, max %.0f us (%zu samples)", at(0.5), at(0.99),
                values.back() * 1e6, values.size());
  return buffer;
}

}  // namespace

VehiclePlantRos::VehiclePlantRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name)
    : nh_(nh), pnh_(pnh), name_(std::move(name)), created_(ros::WallTime::now()) {
  NodeParamReader params(pnh_);
  const std::string config_ns = params.text("config_namespace", "config");
  realtime_ = params.choice("time_mode", "lockstep", {"lockstep", "realtime"}) == "realtime";
  exit_when_done_ = params.flag("exit_when_done", true);
  log_file_ = params.text("log_file", "");
  input_timeout_ = params.number("input_timeout", 5.0, 0.01, 3600.0, "s");
  startup_timeout_ = params.number("startup_timeout", 30.0, 0.1, 3600.0, "s");
  startup_settle_ = params.number("startup_settle", 0.5, 0.0, 60.0, "s");
  min_state_subscribers_ = static_cast<int>(params.number("min_state_subscribers", 1, 1, 100, "subscribers"));
  const double clock_period = params.number("clock_period", 0.01, 0.0, 10.0, "s");
  publish_clock_ = params.flag("publish_clock", true);
  const double max_state_batch = params.number("max_state_batch", 0.01, 0.0, 1.0, "s");
  const double tick = params.number("realtime_tick", 1e-3, 1e-5, 1.0, "s");
  lag_warning_ = params.number("lag_warning", 0.1, 1e-4, 3600.0, "s");
  lag_warning_period_ = params.number("lag_warning_period", 2.0, 0.0, 3600.0, "s");
  VisualizationOptions vis;
  vis.rate = params.number("visualization_rate", 50.0, 0.0, 1e4, "Hz");
  vis.trail_spacing = params.number("trail_spacing", 0.1, 0.0, 100.0, "s");
  vis.force_scale = params.number("force_scale", 200.0, 1e-3, 1e9, "N/m");
  params.throwIfProblems();
  clock_period_ = secondsToNanoseconds(clock_period);

  config_ = loadSimConfigFromParams(nh_, config_ns);
  checkLockstepFeasible(config_);  // a schedule that cannot advance fails here, naming the delays
  // ~changes: every entry checked (all nodes read the same list), the plant's own keys applied here.
  changes_ = std::make_unique<NodeChanges>(nh_, pnh_, config_, LoopRole::kPlant, name_);
  const LoopSchedule schedule = loopScheduleOf(changes_->start());
  max_state_batch_ = secondsToNanoseconds(max_state_batch);
  state_batch_span_ = stateBatchSpan();
  session_ = std::make_unique<PlantSession>(changes_->start(), schedule, schedule.duration);
  session_->scheduleChanges(changes_->schedule(), 1);
  if (vis.rate > 0) visualizer_ = std::make_unique<LaneVisualizer>(nh_, config_, session_->path(), vis);

  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  status_pub_ = nh_.advertise<RunStatus>(topics::kRunStatus, 1, true);
  measured_pub_.advertise(nh_, topics::kMeasuredSteering);
  state_pub_.advertise(nh_, topics::kVehicleState);
  torque_sub_ = nh_.subscribe(topics::kSteeringTorque, kLoopQueueSize, &VehiclePlantRos::onTorque, this,
                              loopTransportHints());
  desired_sub_ = nh_.subscribe(topics::kDesiredSteering, kLoopQueueSize, &VehiclePlantRos::onDesired, this,
                               loopTransportHints());
  changes_sub_ = nh_.subscribe(topics::kParameterChanges, 1000, &VehiclePlantRos::onParameterChange, this);
  watchdog_timer_ = nh_.createWallTimer(ros::WallDuration(0.05), [this](const ros::WallTimerEvent&) { onWatchdog(); });
  if (realtime_) {
    pace_timer_ = nh_.createWallTimer(ros::WallDuration(tick), [this](const ros::WallTimerEvent&) { advance(); },
                                      false, false);
  }
  std::ostringstream effective;
  config_.print(effective);
  ROS_INFO("%s: scenario '%s', %s mode, plant step %s, %g s; node parameters:\n%seffective configuration:\n%s",
           name_.c_str(), config_.simulation.name.c_str(), realtime_ ? "realtime" : "lockstep",
           formatSeconds(config_.simulation.step).c_str(), config_.simulation.duration, params.effective().c_str(),
           effective.str().c_str());
}

Nanoseconds VehiclePlantRos::stateBatchSpan() const {
  // The tracker needs the state at t only for its output at t + tau1, which the actuator needs at
  // t + tau1 + tau2 and the plant one actuator sample later: the state may wait up to tau1 + tau2
  // less two periods of every grid as margin (with a small tau1 it goes out every cycle). Batching
  // never changes a value, only how many messages carry them. With delays that change during the run
  // the smallest of each counts, as soon as it is known (a shorter delay announced mid-run shrinks
  // the span before it takes effect: the announcement precedes the change).
  const SimConfig& start = changes_->start();
  double tau1 = start.delays.pose_to_tracker, tau2 = start.delays.desired_steering_to_actuator;
  for (const auto& entry : changes_->schedule().entries()) {
    tau1 = std::min(tau1, entry.after->delays.pose_to_tracker);
    tau2 = std::min(tau2, entry.after->delays.desired_steering_to_actuator);
  }
  for (const ScheduledChange& change : heard_) {
    const double value = std::strtod(change.new_value.c_str(), nullptr);
    if (change.key == "delays.pose_to_tracker") tau1 = std::min(tau1, value);
    if (change.key == "delays.desired_steering_to_actuator") tau2 = std::min(tau2, value);
  }
  const LoopSchedule grids = loopScheduleOf(start);
  const Nanoseconds slack = secondsToNanoseconds(tau1) + secondsToNanoseconds(tau2) -
                            2 * (grids.tracker_period + grids.actuator_period + grids.plant_step);
  return std::max<Nanoseconds>(0, std::min(slack, max_state_batch_));
}

void VehiclePlantRos::flushStateIfDue() {
  // The tracker holds the state up to the last flush: it may wait while that is within the span.
  if (state_pub_.pendingSamples() > 0 && (session_->stopped() || state_flushed_until_ < 0 ||
                                          session_->plant().time() - state_flushed_until_ >= state_batch_span_)) {
    if (state_pub_.flush()) state_flushed_until_ = session_->plant().time();
  }
}

void VehiclePlantRos::onParameterChange(const ParameterChange::ConstPtr& msg) {
  ScheduledChange change;
  try {
    change = fromParameterChangeMsg(*msg);
  } catch (const LaneKeepingError& e) {
    ROS_WARN("%s: ignored a message on %s from %s: %s", name_.c_str(), changes_sub_.getTopic().c_str(),
             msg->node.c_str(), e.what());
    return;
  }
  for (const ScheduledChange& known : heard_) {
    if (known.stamp == change.stamp && known.key == change.key && known.new_value == change.new_value) return;
  }
  heard_.push_back(change);
  if (change.key.rfind("delays.", 0) != 0 || phase_ == Phase::kEnded) return;
  const Nanoseconds span = stateBatchSpan();
  if (span < state_batch_span_) {
    state_batch_span_ = span;
    if (phase_ == Phase::kRunning) flushStateIfDue();
  }
}

std::vector<ScheduledChange> VehiclePlantRos::changesUpTo(Nanoseconds reached) const {
  std::vector<ScheduledChange> out;
  auto add = [&](const ScheduledChange& change) {
    if (change.stamp > reached) return;
    for (const ScheduledChange& known : out) {
      if (known.stamp == change.stamp && known.key == change.key && known.new_value == change.new_value) return;
    }
    out.push_back(change);
  };
  for (const ScheduledChange& change : changes_->schedule().changes()) add(change);
  for (const ScheduledChange& change : heard_) add(change);
  return out;
}

Nanoseconds VehiclePlantRos::wallElapsed() const {
  return (ros::WallTime::now() - wall_start_).toNSec();
}

std::string VehiclePlantRos::connectionProblem() const {
  std::string problem;
  // Each controller is seen through its two connections with the plant; name the node and both.
  auto check = [&](const std::string& role, bool listens, const std::string& input, bool talks,
                   const std::string& output) {
    if (listens && talks) return;
    std::string missing;
    if (!listens) missing = "no subscriber on " + input;
    if (!talks) missing += (missing.empty() ? "" : ", ") + std::string("no publisher on ") + output;
    problem += (problem.empty() ? "" : "; ") + role + " (subscribes " + input + ", publishes " + output +
               ") is missing: " + missing;
  };
  if (phase_ == Phase::kConnecting && state_pub_.subscribers() < min_state_subscribers_) {
    problem += std::string(problem.empty() ? "" : "; ") + "waiting for " + std::to_string(min_state_subscribers_) +
               " subscribers on " + state_pub_.topic() + " (min_state_subscribers, e.g. rosbag record), have " +
               std::to_string(state_pub_.subscribers());
  }
  check("path_tracking", state_pub_.connected(), state_pub_.topic(), desired_sub_.getNumPublishers() > 0,
        desired_sub_.getTopic());
  check("steering_actuator", measured_pub_.connected(), measured_pub_.topic(), torque_sub_.getNumPublishers() > 0,
        torque_sub_.getTopic());
  return problem;
}

std::string VehiclePlantRos::stallDescription() const {
  const VehiclePlant& plant = session_->plant();
  if (session_->waitingForTorque()) {
    return "no steering torque on " + torque_sub_.getTopic() + ": the step from t = " +
           formatSeconds(nanosecondsToSeconds(plant.time())) + " needs it up to t = " +
           formatSeconds(nanosecondsToSeconds(plant.torqueNeededUntil() - session_->schedule().torque_delay)) +
           ", the latest sample is stamped " +
           formatSeconds(nanosecondsToSeconds(plant.torqueLine().latestStamp()));
  }
  return session_->pendingReason();
}

void VehiclePlantRos::onWatchdog() {
  const ros::WallTime now = ros::WallTime::now();
  if (phase_ == Phase::kConnecting) {
    const std::string problem = connectionProblem();
    if (problem.empty()) {
      if (!connected_) {
        connected_ = true;
        connected_since_ = now;
      }
      if ((now - connected_since_).toSec() >= startup_settle_) start();
    } else {
      connected_ = false;
      if ((now - created_).toSec() > startup_timeout_) {
        fail("the loop did not connect within startup_timeout = " + formatSeconds(startup_timeout_) + ": " + problem);
      }
    }
    return;
  }
  if (phase_ != Phase::kRunning) return;
  const std::string problem = connectionProblem();
  if (!problem.empty()) {
    fail("a loop node is gone: " + problem + ". " + stallDescription());
    return;
  }
  if ((now - last_progress_).toSec() > input_timeout_) {
    fail("no progress for input_timeout = " + formatSeconds(input_timeout_) + " (wall clock): " + stallDescription());
  }
}

void VehiclePlantRos::start() {
  phase_ = Phase::kRunning;
  wall_start_ = last_progress_ = ros::WallTime::now();
  ROS_INFO("%s: loop connected, running", name_.c_str());
  if (visualizer_) visualizer_->publishLane();
  RunStatus status;
  status.state = RunStatus::RUNNING;
  status.wall_start = wall_start_.toSec();
  status_pub_.publish(status);
  if (realtime_) pace_timer_.start();
  changes_->announceConfigured();
  advance();
}

void VehiclePlantRos::advance() {
  if (phase_ != Phase::kRunning) return;
  bool visual_due = false;
  Nanoseconds visual_t = 0;
  VehicleStateSample visual_state;
  const auto on_sample = [&](const VehiclePlant& plant) {
    const Nanoseconds t = plant.time();
    measured_pub_.add(toMeasuredSteeringMsg(t, plant.measurement()));
    const VehicleStateSample state = plant.sample();
    state_pub_.add(toVehicleStateMsg(t, state, frames::kMap));
    if (visualizer_ && visualizer_->due(t)) {
      visual_due = true;
      visual_t = t;
      visual_state = state;
    }
  };
  const long steps = session_->advance(on_sample, realtime_ ? wallElapsed() : PlantSession::kNoLimit);
  // The actuator is on the critical path of the next cycle: its input goes out first.
  measured_pub_.flush();
  flushStateIfDue();
  publishClock(false);
  changes_->takeEffective(session_->plant().time());
  if (visual_due) visualizer_->publish(visual_t, visual_state);
  const std::size_t rows = session_->result().rows.size();
  if (steps > 0 || rows != rows_seen_) {
    last_progress_ = ros::WallTime::now();
    rows_seen_ = rows;
  }
  if (realtime_ && steps > 0) {
    const double lag = nanosecondsToSeconds(wallElapsed() - session_->plant().time());
    lag_.push_back(lag);
    if (lag > max_lag_) {
      max_lag_ = lag;
      max_lag_at_ = session_->plant().time();
    }
    warnIfBehind(lag);
  }
  if (session_->done()) finish();
}

void VehiclePlantRos::warnIfBehind(double lag) {
  // The plant steps up to the wall clock on every tick; a lag that grows means the loop (the plant's
  // steps plus a message round trip per actuator cycle) is slower than real time. Said while it
  // happens, throttled on the wall clock (sim time is what lags), and counted for the summary.
  if (lag <= lag_warning_) return;
  const ros::WallTime now = ros::WallTime::now();
  if (lag_warnings_ > 0 && (now - last_lag_warning_).toSec() < lag_warning_period_) return;
  ++lag_warnings_;
  last_lag_warning_ = now;
  const double t = nanosecondsToSeconds(session_->plant().time());
  const double wall = (now - wall_start_).toSec();
  ROS_WARN("%s: realtime run %.3f s behind the wall clock at t = %.2f s (%.2fx real time so far; lag_warning = %g s): "
           "the loop cannot keep up (an input later than its delay allows, or steps slower than real time%s)",
           name_.c_str(), lag, t, wall > 0 ? t / wall : 0.0, lag_warning_,
           config_.actuator.rate > 2000.0 ? "; with a fast actuator over three processes: try nodelets:=true" : "");
}

void VehiclePlantRos::publishClock(bool force) {
  if (!publish_clock_) return;
  const Nanoseconds t = session_->plant().time();
  if (!force && last_clock_ >= 0 && t - last_clock_ < clock_period_) return;
  if (t == last_clock_) return;
  rosgraph_msgs::Clock clock;
  clock.clock = toRosTime(t);
  clock_pub_.publish(clock);
  last_clock_ = t;
}

void VehiclePlantRos::onTorque(const SteeringTorqueArray::ConstPtr& msg) {
  ++torque_messages_;
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    torque_rejects_.reject(name_, torque_sub_.getTopic(), bad);
    return;
  }
  pushSamples(*msg, name_, torque_sub_.getTopic(), torque_rejects_, [this](Nanoseconds stamp, const SteeringTorque& s) {
    session_->pushTorque(stamp, fromSteeringTorqueMsg(s).torque);  // throws (and skips the next line) on old stamps
    session_->pushIntegral(stamp, s.integral);
  });
  advance();
}

void VehiclePlantRos::onDesired(const DesiredSteeringArray::ConstPtr& msg) {
  ++desired_messages_;
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    desired_rejects_.reject(name_, desired_sub_.getTopic(), bad);
    return;
  }
  pushSamples(*msg, name_, desired_sub_.getTopic(), desired_rejects_, [this](Nanoseconds stamp, const DesiredSteering& s) {
    session_->pushCommand(stamp, fromDesiredSteeringMsg(s));
  });
  if (phase_ == Phase::kRunning && session_->done()) finish();
}

void VehiclePlantRos::finish() {
  const double wall = (ros::WallTime::now() - wall_start_).toSec();
  const RunResult& result = session_->result();
  std::ostringstream text;
  RunSummary summary = summarizeRun(config_, result);
  summary.changes = describeChanges(changesUpTo(session_->plant().time()));
  text << formatSummary(summary);
  text << "wall time:              " << wall << " s (" << result.end_time / wall << "x real time, "
       << result.plant_steps << " plant steps, " << (realtime_ ? "realtime" : "lockstep") << " over ROS)\n";
  if (realtime_) {
    text << "realtime lag:           " << percentiles(lag_) << " behind the wall clock\n";
    char verdict[240];
    if (max_lag_ > lag_warning_) {
      std::snprintf(verdict, sizeof(verdict),
                    "FELL BEHIND the wall clock: up to %.3f s (at t = %.2f s), %.2fx real time over the run; %zu "
                    "warning(s)", max_lag_, nanosecondsToSeconds(max_lag_at_), result.end_time / wall, lag_warnings_);
    } else {
      std::snprintf(verdict, sizeof(verdict), "kept up (lag at most %.3f s, lag_warning = %g s)", max_lag_, lag_warning_);
    }
    text << "realtime:               " << verdict << "\n";
  }
  text << "loop messages:          " << measured_pub_.messages() << " measured_steering, " << state_pub_.messages()
       << " vehicle_state sent; " << torque_messages_ << " steering_torque, " << desired_messages_
       << " desired_steering received\n";
  if (torque_rejects_.count() + desired_rejects_.count() > 0) {
    text << "rejected inputs:        " << torque_rejects_.count() << " on " << torque_sub_.getTopic() << ", "
         << desired_rejects_.count() << " on " << desired_sub_.getTopic() << "\n";
  }
  text << writeLog();
  std::cout << text.str() << std::flush;
  end(result.diverged() ? 3 : 0, result.diverged() ? RunStatus::DIVERGED : RunStatus::COMPLETED, result.message,
      text.str());
}

std::string VehiclePlantRos::writeLog() {
  // The rows recorded so far, at the end of a run and at a fault alike: a run stopped by a dead node
  // keeps its log up to the stop. A log that cannot be written (no such folder, the disk full) is an
  // error naming the file, and the summary says the log is missing.
  if (log_file_.empty()) return "";
  const std::vector<LogRow>& rows = session_->result().rows;
  try {
    writeLogCsv(log_file_, rows);
    std::ofstream config_out(log_file_ + ".config.yaml");
    config_out << "# effective configuration of " << log_file_ << "\n";
    std::vector<ScheduledChange> changes = changesUpTo(session_->plant().time());
    sortForSummary(changes);
    for (const auto& change : changes) {
      config_out << "# changed during the run (--change " << change.argument() << "): " << change.describe() << "\n";
    }
    config_.print(config_out);
    return "log:                    " + log_file_ + " (" + std::to_string(rows.size()) + " rows)\n";
  } catch (const LaneKeepingError& e) {
    ROS_ERROR("%s: %s", name_.c_str(), e.what());
    return std::string("log:                    NOT WRITTEN: ") + e.what() + "\n";
  }
}

void VehiclePlantRos::fail(const std::string& message) {
  const double t = nanosecondsToSeconds(session_->plant().time());
  const std::string text = name_ + ": run stopped at t = " + formatSeconds(t) + ": " + message;
  ROS_ERROR("%s", text.c_str());
  std::cout << text << std::endl;
  const std::string log = writeLog();
  if (!log.empty()) std::cout << log << std::flush;
  end(1, RunStatus::FAILED, message, log);
}

void VehiclePlantRos::end(int exit_code, std::uint8_t state, const std::string& message, const std::string& summary) {
  const Phase previous = phase_;
  phase_ = Phase::kEnded;
  exit_code_ = exit_code;
  watchdog_timer_.stop();
  pace_timer_.stop();
  publishClock(true);
  RunStatus status;
  status.header.stamp = toRosTime(session_->plant().time());
  status.state = state;
  status.message = message;
  status.simulated_time = nanosecondsToSeconds(session_->plant().time());
  if (previous == Phase::kRunning) {
    status.wall_start = wall_start_.toSec();
    status.wall_time = (ros::WallTime::now() - wall_start_).toSec();
    status.real_time_factor = status.wall_time > 0 ? status.simulated_time / status.wall_time : 0.0;
  }
  status.plant_steps = static_cast<std::uint64_t>(session_->result().plant_steps);
  status.log_rows = static_cast<std::uint32_t>(session_->result().rows.size());
  status.summary = summary;
  status_pub_.publish(status);
  if (exit_when_done_) {
    // Give the last messages (status, clock, log rows in a bag) a moment to reach their subscribers.
    shutdown_timer_ = nh_.createWallTimer(ros::WallDuration(0.3), [](const ros::WallTimerEvent&) {
      ros::requestShutdown();
    }, true);
  }
}

}  // namespace lane_keeping
