#pragma once
/// ROS interface of the live gap monitor (core gap_monitor.h), shared by the gap_monitor node and
/// nodelet. It watches the loop's topics — or a real car's, remapped — and never takes part in it:
///  * subscribes to vehicle_state, desired_steering and steering_torque (each optional: a stream that
///    never arrives leaves the replays that need it out); the callbacks only append samples to the
///    window, so a slow evaluation never holds a message of the loop;
///  * evaluates on the stamps k * period (gap_monitor.h) in its own thread, from snapshots of the
///    window taken in the callback thread — the same data give the same statuses live and from a bag;
///    if the thread falls behind, the oldest waiting snapshots are dropped and counted;
///  * publishes per subsystem a diagnostic_msgs/DiagnosticStatus through diagnostic_updater
///    (/diagnostics: rosdiagnostic, diagnostic_aggregator, rqt_robot_monitor), a lane_keeping/GapStatus
///    on `gap_status`, and a text marker above the car on `gap_marker` for rviz;
///  * serves `~diagnose` (lane_keeping/Diagnose): the full diagnosis (lk_gap's code) of the current
///    window, in a thread of its own, so the monitor goes on while it runs.
/// dynamic_reconfigure (cfg/GapMonitor.cfg): warn_excess, error_excess, max_floor, period, reference_draws.
/// Private parameters: the GapMonitorOptions keys (window, period, sample_period, warn_excess, ...),
/// config_namespace (the nominal configuration, default "config"), diagnose_sample_period, queue.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <boost/thread/recursive_mutex.hpp>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/Diagnose.h"
#include "lane_keeping/GapMonitorConfig.h"
#include "lane_keeping/SteeringTorqueArray.h"
#include "lane_keeping/VehicleStateArray.h"
#include "lane_keeping/gap/monitor/gap_monitor.h"
#include "loop_io.h"

namespace lane_keeping {

class GapMonitorRos {
 public:
  /// Throws ConfigError naming every bad parameter.
  GapMonitorRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);
  ~GapMonitorRos();

 private:
  void onState(const VehicleStateArray::ConstPtr& msg);
  void onDesired(const DesiredSteeringArray::ConstPtr& msg);
  void onTorque(const SteeringTorqueArray::ConstPtr& msg);
  /// Under window_mutex_: queues a snapshot for every evaluation stamp the streams now cover.
  void queueDueSnapshots();
  void evaluationLoop();
  void publish(const MonitorStatus& status);
  bool onDiagnose(Diagnose::Request& request, Diagnose::Response& response);
  /// dynamic_reconfigure: thresholds and reference checked by GapMonitorOptions::validate; a refused
  /// request is logged with the reason and the server's values put back.
  void onReconfigure(GapMonitorConfig& request, uint32_t level);

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  std::unique_ptr<GapMonitor> monitor_;
  double diagnose_sample_period_ = 0.01;
  std::size_t max_queued_ = 5;

  std::mutex window_mutex_;  // the monitor's window: callbacks, snapshots, ~diagnose
  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;
  std::deque<MonitorSnapshot> queue_;
  bool stopping_ = false;
  std::uint64_t dropped_snapshots_ = 0, evaluations_ = 0;

  std::mutex status_mutex_;  // last_status_: written by the evaluation thread, read by the diagnostics tasks
  MonitorStatus last_status_;
  bool have_status_ = false;

  static constexpr std::chrono::milliseconds kInputPeriod{20};
  ros::CallbackQueue input_queue_;
  ros::Subscriber state_sub_, desired_sub_, torque_sub_;
  RejectLog state_rejects_, desired_rejects_, torque_rejects_;
  ros::Publisher status_pub_, marker_pub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;

  ros::CallbackQueue diagnose_queue_;
  std::unique_ptr<ros::AsyncSpinner> diagnose_spinner_;
  ros::ServiceServer diagnose_srv_;
  std::atomic<bool> diagnosing_{false};

  std::atomic<bool> input_stopping_{false};
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<GapMonitorConfig>> reconfigure_;
  std::thread worker_;       // last: joined first
  std::thread input_thread_;
};

}  // namespace lane_keeping
