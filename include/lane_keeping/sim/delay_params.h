#pragma once
/// Transport delay of every hop, in seconds (DESIGN §4). Beregi's tau1 is pose -> tracker; his
/// tau2 applies to both inputs of the actuator; the torque reaches the plant undelayed.
#include <string>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct DelayParams {
  /// Largest delay a configuration may set [s]. A delay line that may be changed during a run without
  /// notice (dynamic_reconfigure) keeps this much input history, so that a longer delay can still
  /// read its past (delay_line.h).
  static constexpr double kMaxDelay = 10.0;

  double pose_to_tracker = 0.2;                ///< tau1 [s]
  double desired_steering_to_actuator = 1e-4;  ///< tau2 [s] (delta_des, its rate)
  double steering_angle_to_actuator = 1e-4;    ///< tau2 [s] (measured delta, its rate)
  double torque_to_plant = 0.0;                ///< [s]
  std::string hold = "linear";                 ///< linear | zoh: value between two samples

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "pose_to_tracker", pose_to_tracker, "s", Range::closed(0.0, kMaxDelay),
             "tau1: vehicle pose -> path tracker (Beregi eq 11)");
    v.number(prefix + "desired_steering_to_actuator", desired_steering_to_actuator, "s", Range::closed(0.0, kMaxDelay),
             "tau2 on the desired steering angle -> actuator (Beregi eq 12)");
    v.number(prefix + "steering_angle_to_actuator", steering_angle_to_actuator, "s", Range::closed(0.0, kMaxDelay),
             "tau2 on the measured steering angle -> actuator (Beregi eq 12)");
    v.number(prefix + "torque_to_plant", torque_to_plant, "s", Range::closed(0.0, kMaxDelay),
             "steering torque -> vehicle plant");
    v.choice(prefix + "hold", hold, {"linear", "zoh"},
             "value between samples: linear interpolation (continuous-time DDE) or zero-order hold (digital)");
  }
};

}  // namespace lane_keeping
