#pragma once
/// The plant side of one closed-loop run: the vehicle plant, the divergence monitor, the end of the
/// run and the assembly of the log rows. The in-process runner (closed_loop.cpp) and the ROS
/// vehicle_plant node drive this same object, so both stop at the same step, for the same reason,
/// with the same log.
///
/// A log row at time t holds the plant's state at t, the errors of that state from the path, the
/// tracker's output at t (undelayed; read with the configured hold) and the actuator's integral z
/// after its latest sample <= t. The plant learns the last two from the controllers' outputs,
/// which may arrive after the plant has passed t (over ROS they always may), so rows wait in a
/// queue until their inputs are in; the queue keeps them in time order. The rows, the stop time
/// and the stop reason do not depend on when the inputs arrive.
#include <cstddef>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/divergence_monitor.h"
#include "lane_keeping/sim/log_row.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/vehicle_plant.h"

namespace lane_keeping {

/// The actuator's integral z after one of its samples (for the log).
struct ActuatorIntegral {
  double value = 0.0;  ///< [rad s]
  static ActuatorIntegral interpolate(const ActuatorIntegral& a, const ActuatorIntegral& b, double w) {
    return {a.value + w * (b.value - a.value)};
  }
};

class PlantSession {
 public:
  static constexpr Nanoseconds kNoLimit = std::numeric_limits<Nanoseconds>::max();
  /// Called with the plant after every step (and once for t = 0, on the first advance()).
  using SampleCallback = std::function<void(const VehiclePlant&)>;

  /// @param end simulated time to stop at [ns]; @param record_rows false: keep no log (feasibility probes).
  PlantSession(const SimConfig& config, const LoopSchedule& schedule, Nanoseconds end, bool record_rows = true);

  /// Hands the plant the changes of its keys (vehicle, steering, disturbance, tires, torque delay)
  /// stamped at `from` [ns] or later (change_schedule.h); the session must have been built from
  /// changes.start().
  void scheduleChanges(const ChangeSchedule& changes, Nanoseconds from) { lane_keeping::scheduleChanges(plant_, changes, from); }

  /// Steps the plant while the torque covers the next step, the run has not stopped, and the step
  /// ends no later than `until` [ns] (wall-clock pacing). At every log time and at the end it checks
  /// for divergence (DivergenceMonitor::check), after every step the cheap check (checkStep).
  /// Returns the number of steps taken. `on_sample` is a SampleCallback (may be empty) or any callable
  /// taking the plant (the in-process runner's, inlined: it runs after every step).
  template <typename OnSample>
  long advance(const OnSample& on_sample, Nanoseconds until = kNoLimit);
  /// No callback.
  long advance(std::nullptr_t, Nanoseconds until = kNoLimit) { return advance(SampleCallback(), until); }

  /// Steering torque M_S stamped `stamp` (the actuator's output); throws InputError if not newer than the last.
  void pushTorque(Nanoseconds stamp, double torque) {
    plant_.pushTorque(stamp, torque);
    command_.push(stamp, TorqueCommand{torque});
    completeRows();
  }
  /// The tracker's output (for the log's delta_des columns); throws InputError if not newer than the last.
  void pushCommand(Nanoseconds stamp, const SteeringCommand& command);
  /// The actuator's integral z after its sample at `stamp`; throws InputError if not newer than the last.
  void pushIntegral(Nanoseconds stamp, double integral);

  /// The run has ended (end reached or diverged): no more steps.
  bool stopped() const { return stopped_; }
  /// Stopped, and every log row is complete: result() is final.
  bool done() const { return stopped_ && pending_.empty(); }
  /// Not stopped, and the next step needs torque that has not arrived.
  bool waitingForTorque() const { return !stopped_ && !plant_.readyToStep(); }
  std::size_t pendingRows() const { return pending_.size(); }
  /// What the oldest incomplete log row waits for ("" if none), for error messages.
  std::string pendingReason() const;

  /// Status, message, end time, plant steps, and the log rows completed so far.
  const RunResult& result() const { return result_; }
  RunResult takeResult() { return std::move(result_); }
  const VehiclePlant& plant() const { return plant_; }
  const Path& path() const { return *path_; }
  const LoopSchedule& schedule() const { return schedule_; }

 private:
  struct PendingRow {
    Nanoseconds stamp = 0;  ///< row.t in ns
    LogRow row;
    bool needs_inputs = true;  ///< false: complete as it is (the row of a diverged step)
  };
  void stop(RunResult::Status status, const std::string& message);
  void completeRows();
  /// The checks at plant_.time() (log row, divergence, end), once per time; false if the run stopped.
  /// Between log times and before the end there is nothing to do (inline: every step passes here).
  bool checkCurrent() {
    checked_current_ = true;
    if (plant_.time() < next_log_ && plant_.time() < end_) return true;
    return checkLogTimeOrEnd();
  }
  bool checkLogTimeOrEnd();
  /// The cheap check after a step; false (and the run stopped, its last row recorded) if it failed.
  bool checkStepped() {
    const auto reason = monitor_.checkStep(plant_.state());
    if (!reason) return true;
    stopAfterStep(*reason);
    return false;
  }
  void stopAfterStep(const std::string& reason);
  static bool callable(const SampleCallback& f) { return static_cast<bool>(f); }
  template <typename F>
  static bool callable(const F&) { return true; }

  LoopSchedule schedule_;
  Nanoseconds end_;
  bool record_rows_;
  VehiclePlant plant_;
  std::shared_ptr<const Path> path_;
  DivergenceMonitor monitor_;
  DelayLine<SteeringCommand> desired_;     // tracker output, undelayed
  DelayLine<TorqueCommand> command_;       // actuator output (the torque command), undelayed
  DelayLine<ActuatorIntegral> integral_;   // actuator integral, latest sample <= t (zero-order hold)
  std::deque<PendingRow> pending_;
  RunResult result_;
  Nanoseconds next_log_ = 0;
  bool started_ = false;
  bool checked_current_ = false;  // the log/divergence/end checks ran for plant_.time()
  bool stopped_ = false;
};

template <typename OnSample>
long PlantSession::advance(const OnSample& on_sample, Nanoseconds until) {
  if (!started_) {
    started_ = true;
    if (callable(on_sample)) on_sample(plant_);
  }
  long steps = 0;
  while (!stopped_) {
    if (!checked_current_ && !checkCurrent()) break;
    if (plant_.time() + plant_.stepSize() > until || !plant_.readyToStep()) break;
    plant_.step();
    ++steps;
    ++result_.plant_steps;
    checked_current_ = false;
    if (!checkStepped()) break;
    if (callable(on_sample)) on_sample(plant_);
  }
  completeRows();
  return steps;
}

}  // namespace lane_keeping
