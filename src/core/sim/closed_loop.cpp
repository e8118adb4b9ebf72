#include "lane_keeping/sim/closed_loop.h"

#include <sstream>

#include "lane_keeping/sim/control_stages.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/plant_session.h"

namespace lane_keeping {
namespace {

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

/// The lockstep loop: the plant side (PlantSession) steps while its torque is in; the tracker and
/// the actuator produce every sample their inputs cover. Returns the result; throws ScheduleError
/// on deadlock.
RunResult runLoop(const ChangeSchedule& changes, Nanoseconds end, const std::function<void(const LogRow&)>& on_row,
                  bool record_rows) {
  // Components start from the configuration with the changes at t = 0 and take the later ones.
  const SimConfig& c = changes.start();
  const LoopSchedule s = loopScheduleOf(c);
  PlantSession plant(c, s, end, record_rows);
  PathTrackingStage tracker = createPathTrackingStage(c, s);
  SteeringActuatorStage actuator = createSteeringActuatorStage(c, s);
  plant.scheduleChanges(changes, 1);
  scheduleChanges(tracker, changes, 1);
  scheduleChanges(actuator, changes, 1);
  const auto feed = [&](const VehiclePlant& p) {  // a lambda, not a SampleCallback: inlined into advance()
    tracker.pushPose(p.time(), p.pose());
    actuator.pushMeasurement(p.time(), p.measurement());
  };
  std::size_t forwarded = 0;
  while (true) {
    const long steps = plant.advance(feed);
    bool produced = false;
    while (tracker.ready()) {
      const Stamped<SteeringCommand> command = tracker.produce();
      actuator.pushDesired(command.stamp, command.value);
      plant.pushCommand(command.stamp, command.value);
      produced = true;
    }
    while (actuator.ready()) {
      const Stamped<TorqueCommand> torque = actuator.produce();
      plant.pushTorque(torque.stamp, torque.value.torque);
      plant.pushIntegral(torque.stamp, actuator.actuator().integral());
      produced = true;
    }
    if (on_row) {
      for (; forwarded < plant.result().rows.size(); ++forwarded) on_row(plant.result().rows[forwarded]);
    }
    if (plant.done()) break;
    if (steps == 0 && !produced) {
      if (plant.stopped()) throw ScheduleError("run stopped but " + plant.pendingReason());
      throw ScheduleError(deadlockMessage(c, plant.plant(), actuator));
    }
  }
  const Nanoseconds reached = plant.plant().time();
  RunResult result = plant.takeResult();
  for (const ScheduledChange& change : changes.changes()) {
    if (change.stamp <= reached) result.changes.push_back(change);
  }
  return result;
}

}  // namespace

void checkLockstepFeasible(const SimConfig& config) {
  const LoopSchedule s = loopScheduleOf(config);
  // A deadlock shows within a few actuator periods; run that long without logging.
  const Nanoseconds probe = std::min<Nanoseconds>(s.duration, 4 * (s.actuator_period + s.tracker_period) + 20 * s.plant_step);
  runLoop(ChangeSchedule(config), probe, nullptr, false);
}

ClosedLoop::ClosedLoop(SimConfig config) : ClosedLoop(std::move(config), {}) {}

ClosedLoop::ClosedLoop(SimConfig config, const std::vector<TimedChange>& changes)
    : config_(std::move(config)), changes_(config_) {
  config_.validate();
  checkLockstepFeasible(config_);
  changes_.addAll(changes, "--change");
}

RunResult ClosedLoop::run(const std::function<void(const LogRow&)>& on_row) const {
  return runLoop(changes_, loopScheduleOf(config_).duration, on_row, true);
}

}  // namespace lane_keeping
