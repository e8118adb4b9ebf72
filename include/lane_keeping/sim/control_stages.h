#pragma once
/// The two controllers as lockstep components: each owns its input delay lines and produces its
/// output on its own sample grid (t_k = k * period) as soon as every input line covers t_k. The
/// in-process runner and the ROS nodes/nodelets drive these same classes, which is what makes a
/// lockstep ROS run reproduce the in-process trajectory.
///
/// Runtime changes (change_schedule.h): a stage takes a change of its parameters and input delays
/// for a stamp; its samples stamped at or after the stamp use the new values (the delays through
/// the delay lines' tau(t), delay_line.h), earlier ones the old.
#include <algorithm>
#include <memory>
#include <vector>

#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/control/steering_actuator.h"
#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

class PathTrackingStage {
 public:
  /// @param pose_delay tau1 [ns]; @param plant_period the plant step [ns] (for zoh coverage).
  PathTrackingStage(PathTracker tracker, Nanoseconds period, Nanoseconds pose_delay, Hold hold,
                    Nanoseconds plant_period)
      : tracker_(std::move(tracker)), period_(period), pose_line_("vehicle state -> tracker", pose_delay, hold, plant_period) {}

  void pushPose(Nanoseconds stamp, const PoseSample& pose) { pose_line_.push(stamp, pose); }
  bool ready() const { return pose_line_.covers(next_); }
  Nanoseconds nextTime() const { return next_; }

  /// The command for nextTime() from the state delayed by tau1; advances to the next grid time.
  Stamped<SteeringCommand> produce() {
    while (!pending_.empty() && pending_.front().stamp <= next_) {
      tracker_.setParams(pending_.front().params);
      pending_.erase(pending_.begin());
    }
    const PoseSample delayed = pose_line_.at(next_);
    Stamped<SteeringCommand> out{next_, tracker_.command(delayed, nanosecondsToSeconds(next_), &last_errors_)};
    pose_line_.discardBefore(next_);
    next_ += period_;
    return out;
  }

  /// From its first sample stamped >= `stamp` [ns] (not before nextTime()) the tracker uses
  /// `params` and reads the pose `pose_delay` [ns] back. Changes for one stamp apply in call order.
  void scheduleChange(Nanoseconds stamp, const TrackerParams& params, Nanoseconds pose_delay) {
    if (stamp < next_) throw ScheduleError("path tracker: a change for a sample already computed");
    pose_line_.scheduleDelay(stamp, pose_delay);
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), stamp,
                                     [](Nanoseconds t, const Pending& p) { return t < p.stamp; });
    pending_.insert(at, Pending{stamp, params});
  }
  /// Forgets the changes scheduled at `from` [ns] or later (before the schedule is handed over again).
  void clearChangesFrom(Nanoseconds from) {
    pose_line_.clearDelaysFrom(from);
    pending_.erase(std::remove_if(pending_.begin(), pending_.end(), [from](const Pending& p) { return p.stamp >= from; }),
                   pending_.end());
  }
  /// Keeps the pose history a delay up to `max_delay` [ns] needs (changes not known in advance).
  void retainInputFor(Nanoseconds max_delay) { pose_line_.retainFor(max_delay); }

  /// e_y, e_psi the last command was computed from (of the delayed state).
  const PathErrors& lastErrors() const { return last_errors_; }
  const PathTracker& tracker() const { return tracker_; }
  const DelayLine<PoseSample>& inputLine() const { return pose_line_; }

 private:
  struct Pending {
    Nanoseconds stamp;
    TrackerParams params;
  };
  PathTracker tracker_;
  std::vector<Pending> pending_;  // by stamp
  Nanoseconds period_;
  Nanoseconds next_ = 0;
  DelayLine<PoseSample> pose_line_;
  PathErrors last_errors_;
};

class SteeringActuatorStage {
 public:
  SteeringActuatorStage(SteeringActuator actuator, Nanoseconds period, Nanoseconds desired_delay,
                        Nanoseconds measured_delay, Hold hold, Nanoseconds tracker_period, Nanoseconds plant_period)
      : actuator_(std::move(actuator)),
        period_(period),
        desired_line_("desired steering -> actuator", desired_delay, hold, tracker_period),
        measured_line_("steering angle -> actuator", measured_delay, hold, plant_period) {}

  void pushDesired(Nanoseconds stamp, const SteeringCommand& command) { desired_line_.push(stamp, command); }
  void pushMeasurement(Nanoseconds stamp, const SteeringMeasurement& measurement) {
    measured_line_.push(stamp, measurement);
  }
  bool ready() const { return desired_line_.covers(next_) && measured_line_.covers(next_); }
  Nanoseconds nextTime() const { return next_; }

  /// M_S for nextTime() from both inputs delayed by tau2 (eq 12); advances the integral and the grid.
  Stamped<TorqueCommand> produce() {
    while (!pending_.empty() && pending_.front().stamp <= next_) {
      actuator_.setParams(pending_.front().params);
      pending_.erase(pending_.begin());
    }
    const SteeringCommand desired = desired_line_.at(next_);
    const SteeringMeasurement measured = measured_line_.at(next_);
    Stamped<TorqueCommand> out{next_, TorqueCommand{actuator_.update(nanosecondsToSeconds(next_), desired, measured)}};
    desired_line_.discardBefore(next_);
    measured_line_.discardBefore(next_);
    next_ += period_;
    return out;
  }

  /// From its first sample stamped >= `stamp` [ns] (not before nextTime()) the actuator uses
  /// `params` and reads its inputs `desired_delay` and `measured_delay` [ns] back (Beregi's tau2).
  void scheduleChange(Nanoseconds stamp, const ActuatorParams& params, Nanoseconds desired_delay,
                      Nanoseconds measured_delay) {
    if (stamp < next_) throw ScheduleError("steering actuator: a change for a sample already computed");
    desired_line_.scheduleDelay(stamp, desired_delay);
    measured_line_.scheduleDelay(stamp, measured_delay);
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), stamp,
                                     [](Nanoseconds t, const Pending& p) { return t < p.stamp; });
    pending_.insert(at, Pending{stamp, params});
  }
  /// Forgets the changes scheduled at `from` [ns] or later (before the schedule is handed over again).
  void clearChangesFrom(Nanoseconds from) {
    desired_line_.clearDelaysFrom(from);
    measured_line_.clearDelaysFrom(from);
    pending_.erase(std::remove_if(pending_.begin(), pending_.end(), [from](const Pending& p) { return p.stamp >= from; }),
                   pending_.end());
  }
  /// Keeps the input history delays up to `max_delay` [ns] need (changes not known in advance).
  void retainInputsFor(Nanoseconds max_delay) {
    desired_line_.retainFor(max_delay);
    measured_line_.retainFor(max_delay);
  }

  const SteeringActuator& actuator() const { return actuator_; }
  const DelayLine<SteeringCommand>& desiredLine() const { return desired_line_; }
  const DelayLine<SteeringMeasurement>& measuredLine() const { return measured_line_; }

 private:
  struct Pending {
    Nanoseconds stamp;
    ActuatorParams params;
  };
  SteeringActuator actuator_;
  std::vector<Pending> pending_;  // by stamp
  Nanoseconds period_;
  Nanoseconds next_ = 0;
  DelayLine<SteeringCommand> desired_line_;
  DelayLine<SteeringMeasurement> measured_line_;
};

}  // namespace lane_keeping
