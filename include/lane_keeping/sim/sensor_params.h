#pragma once
/// What the car's sensors report (all exact by default). A real car's log records the same
/// localisation and steering-angle sensors its controllers use, so these change what the tracker and
/// the actuator sense *and* what the log records (the log's x, y, psi, yaw_rate, delta, delta_rate, ay):
///  * a localisation bias: reported y + b_y, psi + b_psi (map frame; x as is), optionally varying along
///    the road with the factor (1 + a sin(2 pi x / wavelength));
///  * a localisation latency: the pose (and the velocities of G) reported at t is the pose at t - L;
///  * a steering-angle sensor: reported angle = scale * angle(t - L) + bias (rate = scale * rate(t - L));
///    the scale is a steering ratio that differs from the one the log was converted with;
///  * a yaw-rate sensor (gyro): reported rate = scale * yaw rate(t - L) + bias;
///  * a lateral accelerometer: reported a_y = a_y(t - L) + bias (a road bank's gravity not sensed:
///    DisturbanceParams::kind);
/// Every real log carries some of these (a mounting offset, a gyro's bias, a channel logged late), and
/// the gap diagnosis fits each as a sensor-error candidate (gap/fit/candidate_effects.h) before it blames
/// the physics. Latencies are of the sensor: the controller that reads the sensor sees it late too.
/// Contrast: tracker.pose_bias_* is a bias only the tracker sees, delays.pose_to_tracker a delay only
/// the tracker sees (the log records the true pose at its time).
#include <cmath>
#include <string>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct SensorParams {
  double pose_bias_y = 0.0;            ///< [m]
  double pose_bias_psi = 0.0;          ///< [rad]
  double pose_bias_variation = 0.0;    ///< the bias scales with (1 + a sin(2 pi x / pose_bias_wavelength))
  double pose_bias_wavelength = 200.0; ///< [m]
  double pose_latency = 0.0;           ///< [s]
  double steering_angle_latency = 0.0; ///< [s]
  double steering_angle_bias = 0.0;    ///< [rad]
  double steering_angle_scale = 1.0;   ///< reported / true
  double yaw_rate_bias = 0.0;          ///< [rad/s]
  double yaw_rate_scale = 1.0;         ///< reported / true
  double yaw_rate_latency = 0.0;       ///< [s]
  double lateral_acceleration_bias = 0.0;     ///< [m/s^2]
  double lateral_acceleration_latency = 0.0;  ///< [s]

  bool poseBiased() const { return pose_bias_y != 0.0 || pose_bias_psi != 0.0; }
  /// The steering-angle sensor reports the angle unchanged but for its latency.
  bool steeringAngleAffine() const { return steering_angle_bias != 0.0 || steering_angle_scale != 1.0; }
  /// The reported steering angle of a true one (before the latency), and the true one of a reported one.
  double reportedSteeringAngle(double delta) const { return steering_angle_scale * delta + steering_angle_bias; }
  double trueSteeringAngle(double reported) const { return (reported - steering_angle_bias) / steering_angle_scale; }
  /// The reported yaw rate of a true one (before the latency), and the true one of a reported one.
  double reportedYawRate(double r) const { return yaw_rate_scale * r + yaw_rate_bias; }
  double trueYawRate(double reported) const { return (reported - yaw_rate_bias) / yaw_rate_scale; }
  /// The factor of the localisation bias at the reported x.
  double poseBiasScale(double x) const {
    return pose_bias_variation == 0.0 ? 1.0 : 1.0 + pose_bias_variation * std::sin(2.0 * M_PI * x / pose_bias_wavelength);
  }
  bool exact() const {
    return !poseBiased() && pose_latency == 0.0 && steering_angle_latency == 0.0 && !steeringAngleAffine() &&
           yaw_rate_bias == 0.0 && yaw_rate_scale == 1.0 && yaw_rate_latency == 0.0 &&
           lateral_acceleration_bias == 0.0 && lateral_acceleration_latency == 0.0;
  }

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "pose_bias_y", pose_bias_y, "m", Range::closed(-10.0, 10.0),
             "localisation bias in y that the tracker and the log both see (map frame); 0 = none");
    v.number(prefix + "pose_bias_psi", pose_bias_psi, "rad", Range::closed(-0.5, 0.5),
             "localisation bias in the yaw angle that the tracker and the log both see; 0 = none");
    v.number(prefix + "pose_bias_variation", pose_bias_variation, "", Range::closed(0.0, 1.0),
             "localisation bias varying along the road: scaled by (1 + a sin(2 pi x / pose_bias_wavelength))");
    v.number(prefix + "pose_bias_wavelength", pose_bias_wavelength, "m", Range::positive(),
             "wavelength of the localisation bias variation");
    v.number(prefix + "pose_latency", pose_latency, "s", Range::closed(0.0, 2.0),
             "localisation latency: the pose reported (to the tracker and the log) at t is the pose at t - latency");
    v.number(prefix + "steering_angle_latency", steering_angle_latency, "s", Range::closed(0.0, 0.5),
             "steering-angle sensor latency: the angle and rate reported (to the actuator and the log) lag by it");
    v.number(prefix + "steering_angle_bias", steering_angle_bias, "rad", Range::closed(-0.2, 0.2),
             "steering-angle sensor offset (the actuator's and the log's road-wheel angle); 0 = none");
    v.number(prefix + "steering_angle_scale", steering_angle_scale, "", Range::closed(0.5, 2.0),
             "steering-angle sensor gain, reported / true (a steering ratio other than the log's conversion); 1 = exact");
    v.number(prefix + "yaw_rate_bias", yaw_rate_bias, "rad/s", Range::closed(-1.0, 1.0),
             "yaw-rate sensor bias (the log's yaw rate and the tracker's); 0 = none");
    v.number(prefix + "yaw_rate_scale", yaw_rate_scale, "", Range::closed(0.5, 2.0),
             "yaw-rate sensor gain, reported / true; 1 = exact");
    v.number(prefix + "yaw_rate_latency", yaw_rate_latency, "s", Range::closed(0.0, 2.0),
             "yaw-rate sensor latency: the rate reported (to the tracker and the log) at t is the rate at t - latency");
    v.number(prefix + "lateral_acceleration_bias", lateral_acceleration_bias, "m/s^2", Range::closed(-5.0, 5.0),
             "lateral accelerometer offset (the log's ay; a mounting tilt reads g sin(tilt)); 0 = none");
    v.number(prefix + "lateral_acceleration_latency", lateral_acceleration_latency, "s", Range::closed(0.0, 2.0),
             "lateral accelerometer latency: the ay logged at t is the one at t - latency");
  }
};

}  // namespace lane_keeping
