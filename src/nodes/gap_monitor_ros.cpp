#include "gap_monitor_ros.h"

#include <chrono>
#include <cstdio>

#include <visualization_msgs/Marker.h>

#include "lane_keeping/GapStatus.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/gap_report.h"
#include "ros_config.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

constexpr char kGapStatusTopic[] = "gap_status";
constexpr char kGapMarkerTopic[] = "gap_marker";

/// Reads the private parameters a struct visits (key, unit and range from its visit()), so that the
/// node's parameters and their checks cannot drift from the core's.
class NodeParamVisitor : public ParamVisitor {
 public:
  explicit NodeParamVisitor(NodeParamReader& reader) : reader_(reader) {}
  void number(const std::string& key, double& value, const char* unit, const Range& range, const char*) override {
    value = reader_.number(key, value, range.min, range.max, unit);
  }
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range& range,
                      const char*) override {
    if (value) value = reader_.number(key, *value, range.min, range.max, unit);
  }
  void integer(const std::string& key, int& value, const Range& range, const char*) override {
    value = static_cast<int>(reader_.number(key, value, range.min, range.max, ""));
  }
  void flag(const std::string& key, bool& value, const char*) override { value = reader_.flag(key, value); }
  void choice(const std::string& key, std::string& value, const std::vector<std::string>& allowed, const char*) override {
    value = allowed.empty() ? reader_.text(key, value) : reader_.choice(key, value, allowed);
  }
  void points(const std::string&, PointList&, const char*, const char*) override {}

 private:
  NodeParamReader& reader_;
};

MonitorStateSample stateSample(const VehicleState& s) {
  MonitorStateSample m;
  m.t = s.header.stamp.toSec();
  m.x = s.x;
  m.y = s.y;
  m.psi = s.psi;
  m.yaw_rate = s.yaw_rate;
  m.delta = s.delta;
  m.delta_rate = s.steering_rate;
  m.speed = s.speed;
  m.lateral_acceleration = s.lateral_acceleration;
  m.torque_applied = s.steering_torque;
  return m;
}

/// Every k-th row, k chosen so that the rows are about `period` apart (the full diagnosis fits every
/// candidate: at the monitor's 500 Hz it would take minutes for a 10 s window).
GapLog thinned(const GapLog& log, double period) {
  const double step = log.medianStep();
  const std::size_t k = step > 0.0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(period / step))) : 1;
  if (k == 1) return log;
  GapLog out = log;
  for (auto* column : {&out.t, &out.x, &out.y, &out.psi, &out.yaw_rate, &out.delta, &out.delta_des, &out.torque, &out.v,
                       &out.ay, &out.delta_rate}) {
    if (column->empty()) continue;
    std::vector<double> kept;
    for (std::size_t i = 0; i < column->size(); i += k) kept.push_back((*column)[i]);
    *column = std::move(kept);
  }
  return out;
}

std::uint8_t diagnosticLevel(MonitorLevel level) {
  switch (level) {
    case MonitorLevel::kOk: return diagnostic_msgs::DiagnosticStatus::OK;
    case MonitorLevel::kWarn: return diagnostic_msgs::DiagnosticStatus::WARN;
    case MonitorLevel::kError: return diagnostic_msgs::DiagnosticStatus::ERROR;
    case MonitorLevel::kStale: return diagnostic_msgs::DiagnosticStatus::STALE;
  }
  return diagnostic_msgs::DiagnosticStatus::STALE;
}

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

}  // namespace

GapMonitorRos::GapMonitorRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name)
    : nh_(nh), pnh_(pnh), name_(std::move(name)) {
  NodeParamReader params(pnh_);
  const std::string config_ns = params.text("config_namespace", "config");
  GapMonitorOptions options;
  NodeParamVisitor visitor(params);
  options.visit(visitor, "");
  diagnose_sample_period_ = params.number("diagnose_sample_period", 0.01, 1e-4, 0.1, "s");
  max_queued_ = static_cast<std::size_t>(params.number("max_queued_evaluations", 5, 1, 1000, ""));
  params.throwIfProblems();
  options.validate();
  monitor_ = std::make_unique<GapMonitor>(loadSimConfigFromParams(nh_, config_ns), options);

  // Subscriber queues hold a few seconds of a 1 kHz loop: the callbacks are short, but a loaded
  // machine may still delay them, and a dropped message would only cost the monitor a gap.
  // The input goes to a callback queue of its own, drained every kInputPeriod by a thread of its own:
  // one wake-up per batch instead of one per message (at 3 x 1 kHz, a wake-up per message cost the
  // nodelet 15-23 % of a core; the monitor needs no low latency). Without TCP_NODELAY, unlike the
  // loop's subscribers, for the same reason. Queues hold a few seconds of a 10 kHz loop.
  ros::NodeHandle input_nh(nh_);
  input_nh.setCallbackQueue(&input_queue_);
  const std::uint32_t queue = 50000;
  state_sub_ = input_nh.subscribe(topics::kVehicleState, queue, &GapMonitorRos::onState, this);
  desired_sub_ = input_nh.subscribe(topics::kDesiredSteering, queue, &GapMonitorRos::onDesired, this);
  torque_sub_ = input_nh.subscribe(topics::kSteeringTorque, queue, &GapMonitorRos::onTorque, this);
  status_pub_ = nh_.advertise<GapStatus>(kGapStatusTopic, 10);
  marker_pub_ = nh_.advertise<visualization_msgs::Marker>(kGapMarkerTopic, 1, true);

  updater_ = std::make_unique<diagnostic_updater::Updater>(nh_, pnh_, name_);
  updater_->setHardwareID("lane_keeping gap monitor (" + nh_.getNamespace() + ")");
  for (const std::string& subsystem : subsystemNames()) {
    updater_->add("gap " + subsystem, [this, subsystem](diagnostic_updater::DiagnosticStatusWrapper& out) {
      std::lock_guard<std::mutex> lock(status_mutex_);
      if (!have_status_) {
        out.summary(diagnostic_msgs::DiagnosticStatus::STALE, "no evaluation yet (waiting for min_span of data)");
        return;
      }
      for (const MonitorSubsystem& s : last_status_.subsystems) {
        if (s.name != subsystem) continue;
        out.summary(diagnosticLevel(s.level), s.message);
        out.add("stamp [s]", last_status_.stamp);
        out.add("window [s]", format("%.2f", last_status_.window_start) + " - " + format("%.2f", last_status_.window_end));
        out.add("judged", s.judged);
        std::string outputs;
        for (const auto& o : s.outputs) outputs += (outputs.empty() ? "" : ", ") + o;
        out.add("outputs", outputs);
        out.add("nrmse", s.nrmse);
        out.add("noise floor", s.floor);
        out.add("excess", s.excess);
        out.add("noise-only reference", s.reference);
        out.add("net excess", s.net);
        out.add("warn_excess", monitor_->options().warn_excess);
        out.add("error_excess", monitor_->options().error_excess);
        if (last_status_.leading == subsystem) {
          out.add("leading time window [s]", format("%.2f", last_status_.leading_t0) + " - " +
                                                 format("%.2f", last_status_.leading_t1));
          out.add("leading band [Hz]", format("%g", last_status_.band_f0) + " - " + format("%g", last_status_.band_f1));
        }
        out.add("dropped evaluations", dropped_snapshots_);
      }
    });
  }

  // ~diagnose runs in a thread of its own: a diagnosis takes seconds to minutes.
  ros::AdvertiseServiceOptions service;
  service.init<Diagnose::Request, Diagnose::Response>(
      "diagnose", [this](Diagnose::Request& rq, Diagnose::Response& rs) { return onDiagnose(rq, rs); });
  service.callback_queue = &diagnose_queue_;
  diagnose_srv_ = pnh_.advertiseService(service);
  diagnose_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &diagnose_queue_);
  diagnose_spinner_->start();

  GapMonitorConfig shown;
  shown.warn_excess = options.warn_excess;
  shown.error_excess = options.error_excess;
  shown.max_floor = options.max_floor;
  shown.period = options.period;
  shown.reference_draws = options.reference_draws;
  reconfigure_ = std::make_unique<dynamic_reconfigure::Server<GapMonitorConfig>>(reconfigure_mutex_, pnh_);
  reconfigure_->updateConfig(shown);
  reconfigure_->setCallback([this](GapMonitorConfig& request, uint32_t level) { onReconfigure(request, level); });

  worker_ = std::thread([this] { evaluationLoop(); });
  input_thread_ = std::thread([this] {
    while (!input_stopping_ && ros::ok()) {
      std::this_thread::sleep_for(kInputPeriod);
      input_queue_.callAvailable();
    }
  });
  ROS_INFO("%s: gap monitor on %s, %s, %s: window %g s every %g s at %g Hz, warn at net excess %g, error at %g\n%s",
           name_.c_str(), state_sub_.getTopic().c_str(), desired_sub_.getTopic().c_str(), torque_sub_.getTopic().c_str(),
           options.window, options.period, 1.0 / options.sample_period, options.warn_excess, options.error_excess,
           params.effective().c_str());
}

GapMonitorRos::~GapMonitorRos() {
  input_stopping_ = true;
  if (input_thread_.joinable()) input_thread_.join();
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_cv_.notify_all();
  if (worker_.joinable()) worker_.join();
  if (diagnose_spinner_) diagnose_spinner_->stop();
}

void GapMonitorRos::onState(const VehicleStateArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    state_rejects_.reject(name_, state_sub_.getTopic(), bad);
    return;
  }
  std::lock_guard<std::mutex> lock(window_mutex_);
  for (const VehicleState& s : msg->samples) {
    if (monitor_->window().addState(stateSample(s)) == MonitorWindow::Added::kRestarted) {
      ROS_WARN("%s: the clock jumped back to %.3f s (a bag played in a loop, a restarted run): the window starts again",
               name_.c_str(), s.header.stamp.toSec());
    }
  }
  queueDueSnapshots();
}

void GapMonitorRos::onDesired(const DesiredSteeringArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    desired_rejects_.reject(name_, desired_sub_.getTopic(), bad);
    return;
  }
  std::lock_guard<std::mutex> lock(window_mutex_);
  for (const DesiredSteering& s : msg->samples) monitor_->window().addDesired(s.header.stamp.toSec(), s.delta_des);
  queueDueSnapshots();
}

void GapMonitorRos::onTorque(const SteeringTorqueArray::ConstPtr& msg) {
  const std::string bad = nonFiniteSample(*msg);
  if (!bad.empty()) {
    torque_rejects_.reject(name_, torque_sub_.getTopic(), bad);
    return;
  }
  std::lock_guard<std::mutex> lock(window_mutex_);
  for (const SteeringTorque& s : msg->samples) monitor_->window().addTorque(s.header.stamp.toSec(), s.torque);
  queueDueSnapshots();
}

void GapMonitorRos::queueDueSnapshots() {
  while (monitor_->due()) {
    MonitorSnapshot snapshot = monitor_->snapshot();
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_back(std::move(snapshot));
    while (queue_.size() > max_queued_) {
      queue_.pop_front();  // behind: the newest windows matter most
      ++dropped_snapshots_;
    }
    queue_cv_.notify_one();
  }
}

void GapMonitorRos::evaluationLoop() {
  for (;;) {
    MonitorSnapshot snapshot;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      queue_cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      snapshot = std::move(queue_.front());
      queue_.pop_front();
    }
    const MonitorStatus status = monitor_->evaluate(snapshot);
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      last_status_ = status;
      have_status_ = true;
      ++evaluations_;
    }
    publish(status);
  }
}

void GapMonitorRos::publish(const MonitorStatus& status) {
  GapStatus msg;
  msg.header.stamp = ros::Time(std::max(0.0, status.stamp));
  msg.level = static_cast<std::uint8_t>(status.level);
  msg.window_start = status.window_start;
  msg.window_end = status.window_end;
  msg.samples = static_cast<std::uint32_t>(status.samples);
  msg.leading = status.leading;
  msg.leading_window_start = status.leading_t0;
  msg.leading_window_end = status.leading_t1;
  msg.leading_window_share = status.leading_share;
  msg.leading_band_low = status.band_f0;
  msg.leading_band_high = status.band_f1;
  msg.leading_band_share = status.band_share;
  msg.evaluation_seconds = status.evaluation_seconds;
  msg.evaluation_cpu_seconds = status.evaluation_cpu_seconds;
  msg.notes = status.notes;
  std::string worst;
  for (const MonitorSubsystem& s : status.subsystems) {
    SubsystemGapStatus out;
    out.name = s.name;
    out.level = static_cast<std::uint8_t>(s.level);
    out.message = s.message;
    out.judged = s.judged;
    out.outputs = s.outputs;
    out.nrmse = s.nrmse;
    out.floor = s.floor;
    out.excess = s.excess;
    out.reference = s.reference;
    out.net_excess = s.net;
    msg.subsystems.push_back(out);
    if (s.judged && s.level != MonitorLevel::kOk) {
      worst += std::string(worst.empty() ? "" : ", ") + s.name + " " + monitorLevelName(s.level) + " " + format("%.3f", s.net);
    }
  }
  status_pub_.publish(msg);
  updater_->force_update();

  visualization_msgs::Marker marker;
  marker.header.frame_id = frames::kBaseLink;
  // Stamp 0: drawn at the car's latest pose (the evaluation's stamp lies a period or more behind it).
  marker.header.stamp = ros::Time(0);
  marker.ns = "gap_monitor";
  marker.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
  marker.action = visualization_msgs::Marker::ADD;
  // Below the lane in rviz's top-down view (the plant's own text sits above it), centred where the
  // default view centres (6 m ahead of G).
  marker.pose.position.x = 6.0;
  marker.pose.position.y = -3.5;
  marker.pose.position.z = 1.0;
  marker.pose.orientation.w = 1.0;
  marker.scale.z = 0.5;
  marker.color.a = 1.0;
  switch (status.level) {
    case MonitorLevel::kOk: marker.color.g = 0.9; break;
    case MonitorLevel::kWarn: marker.color.r = 1.0; marker.color.g = 0.8; break;
    case MonitorLevel::kError: marker.color.r = 1.0; break;
    case MonitorLevel::kStale: marker.color.r = marker.color.g = marker.color.b = 0.7; break;
  }
  marker.text = std::string("gap ") + monitorLevelName(status.level) + (worst.empty() ? "" : ": " + worst);
  if (!status.leading.empty() && status.level != MonitorLevel::kOk && status.level != MonitorLevel::kStale) {
    marker.text += format(" | %.1f", status.leading_t0) + format("-%.1f s", status.leading_t1) +
                   format(", %g", status.band_f0) + format("-%g Hz", status.band_f1);
  }
  marker_pub_.publish(marker);
}

void GapMonitorRos::onReconfigure(GapMonitorConfig& request, uint32_t) {
  GapMonitorOptions options = monitor_->options();
  const GapMonitorOptions before = options;
  options.warn_excess = request.warn_excess;
  options.error_excess = request.error_excess;
  options.max_floor = request.max_floor;
  options.period = request.period;
  options.reference_draws = request.reference_draws;
  try {
    monitor_->setOptions(options);
    if (options.warn_excess != before.warn_excess || options.error_excess != before.error_excess ||
        options.max_floor != before.max_floor || options.period != before.period ||
        options.reference_draws != before.reference_draws) {
      ROS_INFO("%s: dynamic_reconfigure: warn_excess %g, error_excess %g, max_floor %g, period %g s, reference_draws %d "
               "(from the next evaluation)",
               name_.c_str(), options.warn_excess, options.error_excess, options.max_floor, options.period,
               options.reference_draws);
    }
  } catch (const ConfigError& e) {
    ROS_ERROR("%s: dynamic_reconfigure: refused (the values stay as they were): %s", name_.c_str(), e.what());
    request.warn_excess = before.warn_excess;
    request.error_excess = before.error_excess;
    request.max_floor = before.max_floor;
    request.period = before.period;
    request.reference_draws = before.reference_draws;
  }
}

bool GapMonitorRos::onDiagnose(Diagnose::Request&, Diagnose::Response& response) {
  if (diagnosing_.exchange(true)) {
    response.success = false;
    response.message = "a diagnosis is already running";
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  try {
    GapRun run;
    {
      std::lock_guard<std::mutex> lock(window_mutex_);
      run.log = monitor_->windowLog();
    }
    run.log = thinned(run.log, diagnose_sample_period_);
    run.log.source = name_ + " window";
    run.config = monitor_->nominal();
    run.initial_from_log = true;
    if (run.log.size() < 20) throw InputError("only " + std::to_string(run.log.size()) + " samples in the window");
    response.window_start = run.log.t.front();
    response.window_end = run.log.t.back();
    ROS_INFO("%s: ~diagnose: diagnosing %.2f - %.2f s (%zu rows)", name_.c_str(), response.window_start,
             response.window_end, run.log.size());
    DiagnosisOptions options;
    options.threads = 1;  // beside the loop and the monitor: one core at most
    const GapReport report = diagnoseGap(monitor_->nominal(), std::vector<GapRun>{run}, {}, options);
    response.success = true;
    response.effect = report.verdict.effect;
    response.where = report.where.subsystem;
    response.shrink = report.verdict.shrink;
    response.report_json = gapReportJson(report);
    response.message = report.verdict.effect + " (" + report.verdict.reason + ")";
  } catch (const LaneKeepingError& e) {
    response.success = false;
    response.message = e.what();
  }
  response.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ROS_INFO("%s: ~diagnose: %s in %.1f s", name_.c_str(), response.message.c_str(), response.wall_seconds);
  diagnosing_ = false;
  return true;
}

}  // namespace lane_keeping
