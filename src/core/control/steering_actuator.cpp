#include "lane_keeping/control/steering_actuator.h"

namespace lane_keeping {

double SteeringActuator::update(double t, const SteeringCommand& desired, const SteeringMeasurement& measured) {
  const double error = desired.delta_des - measured.delta;
  const double error_rate = desired.delta_des_rate - measured.delta_rate;
  if (has_previous_) integral_ += 0.5 * (t - previous_time_) * (previous_error_ + error);  // eq 13, trapezoid
  has_previous_ = true;
  previous_time_ = t;
  previous_error_ = error;
  return torque(params_, error, error_rate, integral_);  // eq 12
}

}  // namespace lane_keeping
