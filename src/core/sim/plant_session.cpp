#include "lane_keeping/sim/plant_session.h"

namespace lane_keeping {

PlantSession::PlantSession(const SimConfig& config, const LoopSchedule& schedule, Nanoseconds end, bool record_rows)
    : schedule_(schedule),
      end_(end),
      record_rows_(record_rows),
      plant_(createVehiclePlant(config, schedule)),
      path_(createPath(config.path)),
      monitor_(config.simulation.divergence),
      desired_("desired steering (log)", 0, schedule.hold, schedule.tracker_period),
      command_("steering torque command (log)", 0, schedule.hold, schedule.actuator_period),
      integral_("actuator integral (log)", 0, Hold::kZeroOrder, schedule.actuator_period) {
  if (record_rows_) result_.rows.reserve(static_cast<std::size_t>(end / schedule.log_period) + 2);
}

void PlantSession::pushCommand(Nanoseconds stamp, const SteeringCommand& command) {
  desired_.push(stamp, command);
  completeRows();
}

void PlantSession::pushIntegral(Nanoseconds stamp, double integral) {
  integral_.push(stamp, ActuatorIntegral{integral});
  completeRows();
}

void PlantSession::stop(RunResult::Status status, const std::string& message) {
  stopped_ = true;
  result_.status = status;
  result_.message = message;
  result_.end_time = nanosecondsToSeconds(plant_.time());
}

bool PlantSession::checkLogTimeOrEnd() {
  const Nanoseconds t = plant_.time();
  const bool log_due = t >= next_log_;
  const bool at_end = t >= end_;
  if (log_due || at_end) {
    // The errors from the lane and the divergence monitor see the true motion; the log records what
    // the sensors report (sensor_model.h), with the true pose in its *_true columns.
    const VehicleStateSample truth = plant_.truth();
    const PathErrors errors = path_->errors(truth.x, truth.y, truth.psi, truth.x_dot, truth.y_dot, truth.sigma2);
    if (log_due) {
      if (record_rows_) {
        PendingRow pending;
        pending.stamp = t;
        pending.row.t = nanosecondsToSeconds(t);
        pending.row.state = plant_.sample();
        pending.row.x_true = truth.x;
        pending.row.y_true = truth.y;
        pending.row.psi_true = truth.psi;
        pending.row.e_y = errors.lateral;
        pending.row.e_psi = errors.heading;
        pending_.push_back(pending);
      }
      while (next_log_ <= t) next_log_ += schedule_.log_period;
    }
    if (auto reason = monitor_.check(truth, errors)) {
      stop(RunResult::Status::kDiverged, "diverged at t = " + formatSeconds(nanosecondsToSeconds(t)) + ": " + *reason);
      return false;
    }
  }
  if (at_end) {
    stop(RunResult::Status::kCompleted, "");
    return false;
  }
  return true;
}

void PlantSession::stopAfterStep(const std::string& reason) {
  // Record the offending state so the log shows how it ended, then stop.
  PendingRow pending;
  pending.stamp = plant_.time();
  pending.row.t = nanosecondsToSeconds(plant_.time());
  pending.row.state = plant_.sample();
  const VehicleStateSample truth = plant_.truth();
  pending.row.x_true = truth.x;
  pending.row.y_true = truth.y;
  pending.row.psi_true = truth.psi;
  pending.needs_inputs = false;
  if (record_rows_) pending_.push_back(pending);
  stop(RunResult::Status::kDiverged, "diverged at t = " + formatSeconds(pending.row.t) + ": " + reason);
}

void PlantSession::completeRows() {
  while (!pending_.empty()) {
    PendingRow& front = pending_.front();
    if (front.needs_inputs) {
      const Nanoseconds t = front.stamp;
      if (!desired_.covers(t) || !integral_.covers(t) || !command_.covers(t)) return;
      const SteeringCommand desired = desired_.at(t);
      desired_.discardBefore(t);
      front.row.torque_command = command_.at(t).torque;
      command_.discardBefore(t);
      front.row.delta_des = desired.delta_des;
      front.row.delta_des_rate = desired.delta_des_rate;
      front.row.integral = integral_.at(t).value;
      integral_.discardBefore(t);
    }
    result_.rows.push_back(front.row);
    pending_.pop_front();
  }
}

std::string PlantSession::pendingReason() const {
  if (pending_.empty()) return "";
  const Nanoseconds t = pending_.front().stamp;
  std::string reason = "the log row at t = " + formatSeconds(pending_.front().row.t) + " waits for";
  if (!desired_.covers(t)) {
    reason += " the desired steering angle (tracker output; latest stamp " +
              formatSeconds(nanosecondsToSeconds(desired_.latestStamp())) + ")";
  }
  if (!integral_.covers(t) || !command_.covers(t)) {
    reason += " the steering torque (actuator output; latest stamp " +
              formatSeconds(nanosecondsToSeconds(integral_.latestStamp())) + ")";
  }
  return reason;
}

}  // namespace lane_keeping
