#include "lane_keeping/sim/sensor_model.h"

#include <algorithm>
#include <initializer_list>
#include <cmath>

namespace lane_keeping {

SensorModel::SensorModel(const SensorParams& params, bool column_sensor)
    : p_(params),
      column_sensor_(column_sensor),
      pass_through_(params.exact() && !column_sensor),
      pose_latency_(secondsToNanoseconds(params.pose_latency)),
      steering_latency_(secondsToNanoseconds(params.steering_angle_latency)),
      yaw_rate_latency_(secondsToNanoseconds(params.yaw_rate_latency)),
      ay_latency_(secondsToNanoseconds(params.lateral_acceleration_latency)),
      keep_(std::max({pose_latency_, steering_latency_, yaw_rate_latency_, ay_latency_})) {}

void SensorModel::record(Nanoseconds t, const PoseSample& pose, const SteeringMeasurement& wheel,
                         const SteeringMeasurement& column, double sensed_lateral_acceleration) {
  if (keep_ == 0) {  // no latency: only the latest record is read
    history_.clear();
  }
  history_.push_back({t, pose, wheel, column, sensed_lateral_acceleration});
  // Keep one record at or before t - keep_ (the interpolation's left end).
  while (history_.size() > 2 && history_[1].t <= t - keep_) history_.pop_front();
}

SensorModel::Record SensorModel::at(Nanoseconds t) const {
  if (history_.empty()) return {};
  if (t <= history_.front().t) return history_.front();
  if (t >= history_.back().t) return history_.back();
  const auto it = std::upper_bound(history_.begin(), history_.end(), t,
                                   [](Nanoseconds value, const Record& r) { return value < r.t; });
  const Record& b = *it;
  const Record& a = *(it - 1);
  const double w = static_cast<double>(t - a.t) / static_cast<double>(b.t - a.t);
  return {t, PoseSample::interpolate(a.pose, b.pose, w), SteeringMeasurement::interpolate(a.wheel, b.wheel, w),
          SteeringMeasurement::interpolate(a.column, b.column, w),
          a.lateral_acceleration + w * (b.lateral_acceleration - a.lateral_acceleration)};
}

PoseSample SensorModel::pose(Nanoseconds t, const PoseSample& truth) const {
  if (pass_through_) return truth;
  PoseSample out = pose_latency_ > 0 ? at(t - pose_latency_).pose : truth;
  // A gyro, not the localisation: its own latency, gain and bias.
  out.yaw_rate = p_.reportedYawRate(yaw_rate_latency_ > 0 ? at(t - yaw_rate_latency_).pose.yaw_rate : truth.yaw_rate);
  if (p_.poseBiased()) {
    const double scale = p_.poseBiasScale(out.x);
    out.y += scale * p_.pose_bias_y;
    out.psi += scale * p_.pose_bias_psi;
  }
  return out;
}

SteeringMeasurement SensorModel::reported(SteeringMeasurement m) const {
  if (!p_.steeringAngleAffine()) return m;
  m.delta = p_.reportedSteeringAngle(m.delta);
  m.delta_rate *= p_.steering_angle_scale;
  return m;
}

SteeringMeasurement SensorModel::actuatorAngle(Nanoseconds t, const SteeringMeasurement& wheel,
                                               const SteeringMeasurement& column) const {
  if (pass_through_) return wheel;
  if (steering_latency_ > 0) {
    const Record r = at(t - steering_latency_);
    return reported(column_sensor_ ? r.column : r.wheel);
  }
  return reported(column_sensor_ ? column : wheel);
}

VehicleStateSample SensorModel::sample(Nanoseconds t, const VehicleStateSample& truth, double unsensed_force,
                                       double mass) const {
  VehicleStateSample out = truth;
  out.lateral_acceleration -= unsensed_force / mass;
  if (pass_through_) return out;
  const PoseSample pose = this->pose(t, PoseSample::of(truth));
  out.x = pose.x;
  out.y = pose.y;
  out.psi = pose.psi;
  out.x_dot = pose.x_dot;
  out.y_dot = pose.y_dot;
  out.sigma2 = pose.yaw_rate;
  if (!column_sensor_) {  // the log's angle is the actuator's sensor at the wheel (at the column: the wheel's, exact)
    const SteeringMeasurement wheel =
        reported(steering_latency_ > 0 ? at(t - steering_latency_).wheel : SteeringMeasurement{truth.delta, truth.sigma3});
    out.delta = wheel.delta;
    out.sigma3 = wheel.delta_rate;
  }
  if (ay_latency_ > 0) out.lateral_acceleration = at(t - ay_latency_).lateral_acceleration;
  out.lateral_acceleration += p_.lateral_acceleration_bias;
  return out;
}

}  // namespace lane_keeping
