#include "lane_keeping/sim/closed_loop.h"

#include <sstream>

#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/control_stages.h"
#include "lane_keeping/sim/divergence_monitor.h"
#include "lane_keeping/sim/model_factory.h"
#include "lane_keeping/sim/vehicle_plant.h"

namespace lane_keeping {
namespace {

struct Schedule {
  Nanoseconds plant_step, tracker_period, actuator_period, log_period, duration;
  Nanoseconds pose_delay, desired_delay, measured_delay, torque_delay;
  Hold hold;
};

Schedule scheduleOf(const SimConfig& c) {
  Schedule s;
  s.plant_step = secondsToNanoseconds(c.simulation.step);
  s.tracker_period = periodFromRate(c.tracker.rate);
  s.actuator_period = periodFromRate(c.actuator.rate);
  s.log_period = periodFromRate(c.simulation.log_rate);
  s.duration = secondsToNanoseconds(c.simulation.duration);
  s.pose_delay = secondsToNanoseconds(c.delays.pose_to_tracker);
  s.desired_delay = secondsToNanoseconds(c.delays.desired_steering_to_actuator);
  s.measured_delay = secondsToNanoseconds(c.delays.steering_angle_to_actuator);
  s.torque_delay = secondsToNanoseconds(c.delays.torque_to_plant);
  s.hold = holdFromName(c.delays.hold);
  return s;
}

std::string deadlockMessage(const SimConfig& c, const VehiclePlant& plant, const SteeringActuatorStage& actuator) {
  std::ostringstream out;
  out << "lockstep schedule cannot advance at t = " << formatSeconds(nanosecondsToSeconds(plant.time()))
      << ": the plant needs the steering torque up to t = "
      << formatSeconds(nanosecondsToSeconds(plant.torqueNeededUntil()))
      << ", but the actuator's next sample (t = " << formatSeconds(nanosecondsToSeconds(actuator.nextTime()))
      << ") needs the steering angle at t = "
      << formatSeconds(nanosecondsToSeconds(actuator.nextTime()) - c.delays.steering_angle_to_actuator)
      << ", which the plant has not reached. The loop delay delays.steering_angle_to_actuator + "
         "delays.torque_to_plant = "
      << formatSeconds(c.delays.steering_angle_to_actuator + c.delays.torque_to_plant)
      << " gives too little lookahead for simulation.step = " << formatSeconds(c.simulation.step)
      << " and actuator.rate = " << c.actuator.rate << " Hz with delays.hold = " << c.delays.hold
      << ". Raise that delay, use delays.hold: zoh, or raise actuator.rate.";
  return out.str();
}

/// The lockstep loop. Returns the result; throws ScheduleError on deadlock.
RunResult runLoop(const SimConfig& c, Nanoseconds end, const std::function<void(const LogRow&)>& on_row,
                  bool record_rows) {
  const Schedule s = scheduleOf(c);
  const auto path = createPath(c.path);
  VehiclePlant plant(createVehicleModel(c), c.simulation.initial, s.plant_step,
                     s.torque_delay, s.hold, s.actuator_period);
  PathTrackingStage tracker(PathTracker(c.tracker, path), s.tracker_period, s.pose_delay, s.hold, s.plant_step);
  SteeringActuatorStage actuator(SteeringActuator(c.actuator), s.actuator_period, s.desired_delay, s.measured_delay,
                                 s.hold, s.tracker_period, s.plant_step);
  // The tracker's output undelayed, for the log's delta_des column.
  DelayLine<SteeringCommand> desired_log("desired steering (log)", 0, s.hold, s.tracker_period);
  const DivergenceMonitor monitor(c.simulation.divergence);

  RunResult result;
  if (record_rows) result.rows.reserve(static_cast<std::size_t>(end / s.log_period) + 2);
  tracker.pushPose(0, plant.pose());
  actuator.pushMeasurement(0, plant.measurement());
  Nanoseconds next_log = 0;
  double integral_at_last_torque = 0.0;

  while (true) {
    while (tracker.ready()) {
      const Stamped<SteeringCommand> command = tracker.produce();
      actuator.pushDesired(command.stamp, command.value);
      desired_log.push(command.stamp, command.value);
    }
    while (actuator.ready()) {
      const Stamped<TorqueCommand> torque = actuator.produce();
      plant.pushTorque(torque.stamp, torque.value.torque);
      integral_at_last_torque = actuator.actuator().integral();
    }

    const Nanoseconds t = plant.time();
    const bool log_due = t >= next_log;
    const bool at_end = t >= end;
    if (log_due || at_end) {
      const VehicleStateSample state = plant.sample();
      const PathErrors errors =
          path->errors(state.x, state.y, state.psi, state.x_dot, state.y_dot, state.sigma2);
      if (log_due) {
        LogRow row;
        row.t = nanosecondsToSeconds(t);
        row.state = state;
        const SteeringCommand desired = desired_log.at(t);
        desired_log.discardBefore(t);
        row.delta_des = desired.delta_des;
        row.delta_des_rate = desired.delta_des_rate;
        row.e_y = errors.lateral;
        row.e_psi = errors.heading;
        row.integral = integral_at_last_torque;
        if (on_row) on_row(row);
        if (record_rows) result.rows.push_back(row);
        while (next_log <= t) next_log += s.log_period;
      }
      if (auto reason = monitor.check(state, errors)) {
        result.status = RunResult::Status::kDiverged;
        result.message = "diverged at t = " + formatSeconds(nanosecondsToSeconds(t)) + ": " + *reason;
        break;
      }
    }
    if (at_end) break;
    if (!plant.readyToStep()) throw ScheduleError(deadlockMessage(c, plant, actuator));
    plant.step();
    ++result.plant_steps;
    if (auto reason = monitor.checkStep(plant.state())) {
      // Record the offending state so the log shows how it ended, then stop.
      LogRow row;
      row.t = nanosecondsToSeconds(plant.time());
      row.state = plant.sample();
      if (record_rows) result.rows.push_back(row);
      result.status = RunResult::Status::kDiverged;
      result.message = "diverged at t = " + formatSeconds(row.t) + ": " + *reason;
      break;
    }
    tracker.pushPose(plant.time(), plant.pose());
    actuator.pushMeasurement(plant.time(), plant.measurement());
  }
  result.end_time = nanosecondsToSeconds(plant.time());
  return result;
}

}  // namespace

void checkLockstepFeasible(const SimConfig& config) {
  const Schedule s = scheduleOf(config);
  // A deadlock shows within a few actuator periods; run that long without logging.
  const Nanoseconds probe = std::min<Nanoseconds>(s.duration, 4 * (s.actuator_period + s.tracker_period) + 20 * s.plant_step);
  runLoop(config, probe, nullptr, false);
}

ClosedLoop::ClosedLoop(SimConfig config) : config_(std::move(config)) {
  config_.validate();
  checkLockstepFeasible(config_);
}

RunResult ClosedLoop::run(const std::function<void(const LogRow&)>& on_row) const {
  return runLoop(config_, scheduleOf(config_).duration, on_row, true);
}

}  // namespace lane_keeping
