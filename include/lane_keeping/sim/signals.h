#pragma once
/// The quantities that flow between the three components (and over ROS topics), each with the
/// interpolation a delay line applies between two samples.
#include "lane_keeping/common/time.h"

namespace lane_keeping {

/// Plant -> tracker: everything about the vehicle at one instant (stamp = that instant).
struct VehicleStateSample {
  double x = 0.0, y = 0.0, psi = 0.0, delta = 0.0;         ///< pose of G [m, m, rad], steering angle [rad]
  double sigma1 = 0.0, sigma2 = 0.0, sigma3 = 0.0;         ///< lateral velocity [m/s], yaw rate, steering rate [rad/s]
  double x_dot = 0.0, y_dot = 0.0;                         ///< velocity of G in map (Beregi eq 2) [m/s]
  double speed = 0.0;                                      ///< |velocity of G| [m/s]
  double lateral_acceleration = 0.0;                       ///< a_y at G, body frame [m/s^2]
  double slip_angle_front = 0.0, slip_angle_rear = 0.0;    ///< alpha_F, alpha_R (Beregi eq 8) [rad]
  double force_front = 0.0, force_rear = 0.0;              ///< F_F, F_R [N]
  double moment_front = 0.0, moment_rear = 0.0;            ///< M_F, M_R [N m]
  double torque = 0.0;                                     ///< steering torque acting at this instant [N m]

  static VehicleStateSample interpolate(const VehicleStateSample& a, const VehicleStateSample& b, double w);
};

/// What the tracker needs of the vehicle state (a subset of VehicleStateSample).
struct PoseSample {
  double x = 0.0, y = 0.0, psi = 0.0;    ///< pose of G [m, m, rad]
  double x_dot = 0.0, y_dot = 0.0;       ///< velocity of G in map [m/s]
  double yaw_rate = 0.0;                 ///< [rad/s]
  static PoseSample of(const VehicleStateSample& s) { return {s.x, s.y, s.psi, s.x_dot, s.y_dot, s.sigma2}; }
  static PoseSample interpolate(const PoseSample& a, const PoseSample& b, double w) {
    return {a.x + w * (b.x - a.x),         a.y + w * (b.y - a.y),         a.psi + w * (b.psi - a.psi),
            a.x_dot + w * (b.x_dot - a.x_dot), a.y_dot + w * (b.y_dot - a.y_dot), a.yaw_rate + w * (b.yaw_rate - a.yaw_rate)};
  }
};

/// Plant -> actuator: the measured steering angle and rate.
struct SteeringMeasurement {
  double delta = 0.0;       ///< [rad]
  double delta_rate = 0.0;  ///< [rad/s]
  static SteeringMeasurement interpolate(const SteeringMeasurement& a, const SteeringMeasurement& b, double w) {
    return {a.delta + w * (b.delta - a.delta), a.delta_rate + w * (b.delta_rate - a.delta_rate)};
  }
};

/// Tracker -> actuator: desired steering angle (Beregi eq 11) and its exact rate.
struct SteeringCommand {
  double delta_des = 0.0;       ///< [rad]
  double delta_des_rate = 0.0;  ///< [rad/s]
  static SteeringCommand interpolate(const SteeringCommand& a, const SteeringCommand& b, double w) {
    return {a.delta_des + w * (b.delta_des - a.delta_des), a.delta_des_rate + w * (b.delta_des_rate - a.delta_des_rate)};
  }
};

/// Actuator -> plant: steering torque M_S (Beregi eq 12).
struct TorqueCommand {
  double torque = 0.0;  ///< [N m]
  static TorqueCommand interpolate(const TorqueCommand& a, const TorqueCommand& b, double w) {
    return {a.torque + w * (b.torque - a.torque)};
  }
};

template <typename S>
struct Stamped {
  Nanoseconds stamp = 0;
  S value;
};

}  // namespace lane_keeping
