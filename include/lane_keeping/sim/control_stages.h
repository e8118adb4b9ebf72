#pragma once
/// The two controllers as lockstep components: each owns its input delay lines and produces its
/// output on its own sample grid (t_k = k * period) as soon as every input line covers t_k. The
/// in-process runner and the ROS nodes/nodelets drive these same classes, which is what makes a
/// lockstep ROS run reproduce the in-process trajectory.
#include <memory>

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
    const PoseSample delayed = pose_line_.at(next_);
    Stamped<SteeringCommand> out{next_, tracker_.command(delayed, nanosecondsToSeconds(next_), &last_errors_)};
    pose_line_.discardBefore(next_);
    next_ += period_;
    return out;
  }

  /// e_y, e_psi the last command was computed from (of the delayed state).
  const PathErrors& lastErrors() const { return last_errors_; }
  const PathTracker& tracker() const { return tracker_; }
  const DelayLine<PoseSample>& inputLine() const { return pose_line_; }

 private:
  PathTracker tracker_;
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
    const SteeringCommand desired = desired_line_.at(next_);
    const SteeringMeasurement measured = measured_line_.at(next_);
    Stamped<TorqueCommand> out{next_, TorqueCommand{actuator_.update(nanosecondsToSeconds(next_), desired, measured)}};
    desired_line_.discardBefore(next_);
    measured_line_.discardBefore(next_);
    next_ += period_;
    return out;
  }

  const SteeringActuator& actuator() const { return actuator_; }
  const DelayLine<SteeringCommand>& desiredLine() const { return desired_line_; }
  const DelayLine<SteeringMeasurement>& measuredLine() const { return measured_line_; }

 private:
  SteeringActuator actuator_;
  Nanoseconds period_;
  Nanoseconds next_ = 0;
  DelayLine<SteeringCommand> desired_line_;
  DelayLine<SteeringMeasurement> measured_line_;
};

}  // namespace lane_keeping
