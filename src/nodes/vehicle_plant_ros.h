#pragma once
/// ROS interface of the vehicle plant: drives the core PlantSession (single-track model, RK4,
/// torque delay line, divergence monitor, log), publishes the state and the measured steering
/// angle, owns /clock, and reports the run (summary, CSV, RunStatus). Shared by the vehicle_plant
/// node and nodelet.
///
/// Lockstep protocol (time_mode = lockstep):
///  1. Start: wait until the loop topics are connected both ways, then a settle time; publish t = 0.
///  2. Whenever a torque message arrives: step while the torque covers the next step, collecting
///     every step's state and steering angle.
///  3. When blocked (the next step needs torque not yet in): publish the collected samples as one
///     message per topic, then /clock (at most every clock_period of simulated time). The
///     vehicle state, which the tracker needs only tau1 later, may collect for a few ms first.
///  4. The controllers do the same with their inputs: compute every sample their delayed inputs
///     cover, publish them as one message. Nothing advances before its inputs are in, and batch
///     boundaries never change a value: the run is bit-identical to the in-process one.
///  5. End (duration or divergence): once the last log rows have their inputs, print the summary,
///     write the log, publish RunStatus. A stall (an input silent for input_timeout, or a
///     publisher gone) stops the run with a message naming the topic.
/// time_mode = realtime: the same, but the plant never runs ahead of the wall clock.
///
/// Runtime tuning (docs/ros.md): the plant applies the changes of ~changes it owns (vehicle, steering,
/// disturbance, tires, torque delay) at their stamps, without resetting its state; it hears every
/// node's changes on parameter_changes, lists them in the summary, and keeps the vehicle_state batches
/// short enough for the shortest tau1 + tau2 it knows of.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "lane_keeping/DesiredSteeringArray.h"
#include "lane_keeping/MeasuredSteeringArray.h"
#include "lane_keeping/ParameterChange.h"
#include "lane_keeping/SteeringTorqueArray.h"
#include "lane_keeping/VehicleStateArray.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/plant_session.h"
#include "loop_io.h"
#include "node_changes.h"
#include "visualization.h"

namespace lane_keeping {

class VehiclePlantRos {
 public:
  /// Throws ConfigError naming every bad parameter.
  VehiclePlantRos(ros::NodeHandle nh, ros::NodeHandle pnh, std::string name);
  /// 0 completed, 3 diverged, 1 failed (an input stopped), as lk_simulate; -1 while running.
  int exitCode() const { return exit_code_; }

 private:
  enum class Phase { kConnecting, kRunning, kEnded };

  void onTorque(const SteeringTorqueArray::ConstPtr& msg);
  void onDesired(const DesiredSteeringArray::ConstPtr& msg);
  void onParameterChange(const ParameterChange::ConstPtr& msg);
  /// How long vehicle_state samples may wait before they go out (see the constructor) for the
  /// shortest tau1 + tau2 known: the configuration, ~changes, and every change heard.
  Nanoseconds stateBatchSpan() const;
  /// Publishes the collected vehicle_state samples once the oldest has waited the span (or the run stopped).
  void flushStateIfDue();
  /// Every change known to have taken effect by `reached` [ns]: ~changes and those heard.
  std::vector<ScheduledChange> changesUpTo(Nanoseconds reached) const;
  void onWatchdog();
  void start();
  /// Steps as far as the inputs (and in realtime the wall clock) allow, publishes, ends if done.
  void advance();
  void publishClock(bool force);
  void finish();
  void fail(const std::string& message);
  void end(int exit_code, std::uint8_t state, const std::string& message, const std::string& summary);
  std::string connectionProblem() const;
  std::string stallDescription() const;
  Nanoseconds wallElapsed() const;
  void warnIfBehind(double lag);
  std::string writeLog();  // the log so far (if log_file is set); a line for the summary

  ros::NodeHandle nh_, pnh_;
  std::string name_;
  SimConfig config_;
  std::unique_ptr<NodeChanges> changes_;
  std::vector<ScheduledChange> heard_;  // changes announced on parameter_changes (own ones included)
  std::unique_ptr<PlantSession> session_;
  std::unique_ptr<LaneVisualizer> visualizer_;

  // options
  bool realtime_ = false;
  bool exit_when_done_ = true;
  std::string log_file_;
  double input_timeout_ = 5.0, startup_timeout_ = 30.0, startup_settle_ = 0.5;
  int min_state_subscribers_ = 1;
  Nanoseconds clock_period_ = 0;
  bool publish_clock_ = true;
  Nanoseconds state_batch_span_ = 0;  // vehicle_state samples may wait this long (see the constructor)
  Nanoseconds max_state_batch_ = 0;   // the parameter max_state_batch

  BatchPublisher<VehicleStateArray> state_pub_;
  BatchPublisher<MeasuredSteeringArray> measured_pub_;
  ros::Publisher clock_pub_, status_pub_;
  ros::Subscriber torque_sub_, desired_sub_, changes_sub_;
  ros::WallTimer watchdog_timer_, pace_timer_, shutdown_timer_;
  RejectLog torque_rejects_, desired_rejects_;

  Phase phase_ = Phase::kConnecting;
  int exit_code_ = -1;
  ros::WallTime created_, connected_since_, wall_start_, last_progress_;
  bool connected_ = false;
  Nanoseconds last_clock_ = -1;
  Nanoseconds state_flushed_until_ = -1;  // stamp of the last vehicle_state sample sent
  std::size_t rows_seen_ = 0;
  std::uint64_t torque_messages_ = 0, desired_messages_ = 0;
  std::vector<double> lag_;  // realtime: wall lag of the plant behind wall_start + t after each advance [s]
  // realtime: a lag above lag_warning_ is warned about while the run goes on (at most every
  // lag_warning_period_ of wall time) and the summary says the run fell behind.
  double lag_warning_ = 0.1, lag_warning_period_ = 2.0;
  double max_lag_ = 0.0;
  Nanoseconds max_lag_at_ = 0;
  std::size_t lag_warnings_ = 0;
  ros::WallTime last_lag_warning_;
};

}  // namespace lane_keeping
