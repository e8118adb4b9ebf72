#pragma once
/// The steering system between the actuator's torque command M_S and the front axle (all off by
/// default, i.e. Beregi's rigid, frictionless steering with f3 = M_F + M_S).
///  * torque_limit / dead_band: the applied torque is M = sat(M_S) with |M| <= torque_limit, and zero
///    inside |M_S| < dead_band (the command is shifted by the band outside it).
///  * friction at the kingpin: tanh model  T_f = T_c tanh(delta_dot / v_f) + b delta_dot, or the
///    LuGre point model (Deur eqs 6, 9) with one internal state z:
///      dz/dt = w - sigma0 |w| z / g(w),  g(w) = T_c + (T_s - T_c) exp(-(w / w_s)^2),
///      T_f = sigma0 z + sigma1 dz/dt + b w,   w = delta_dot.
///  * compliance: the torque acts on a column of inertia J_c and angle theta (relative to the body),
///    coupled to the wheel by a torsional spring k_c and damper c_c:
///      J_c theta'' = M - k_c (theta - delta) - c_c (theta' - delta'),  f3 = M_F + k_c (theta - delta)
///      + c_c (theta' - delta') - T_f.   (column yaw coupling with the body neglected: J_c << J_G)
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct SteeringParams {
  double torque_limit = 0.0;        ///< [N m]; 0 = unlimited
  std::string saturation = "hard";  ///< hard: clamp; soft: M / (1 + (M / limit)^4)^(1/4)
  double dead_band = 0.0;           ///< [N m]; 0 = none
  std::string friction_model = "tanh";  ///< tanh | lugre
  double coulomb_friction = 0.0;    ///< T_c [N m]
  double breakaway_friction = 0.0;  ///< T_s [N m] (lugre; <= T_c means no Stribeck peak)
  double viscous_friction = 0.0;    ///< b [N m s/rad]
  double friction_velocity = 0.01;  ///< v_f of tanh, or w_s (Stribeck) of lugre [rad/s]
  double friction_stiffness = 1e3;  ///< sigma0 of lugre [N m/rad]: presliding g/sigma0 ~ 1 mrad; the state's
                                    ///< decay rate sigma0 |w| / g must stay within RK4's limit (~2.8 / step)
  double friction_damping = 0.0;    ///< sigma1 of lugre [N m s/rad]
  double column_stiffness = 0.0;    ///< k_c [N m/rad]; 0 = rigid column
  double column_damping = 0.0;      ///< c_c [N m s/rad]
  double column_inertia = 0.02;     ///< J_c [kg m^2]
  double column_stiffening_angle = 0.0;  ///< twist [rad] at which a progressive column is twice as stiff
                                        ///< (secant k (1 + (twist / angle)^2)); 0 = linear
  /// Where the actuator's angle sensor sits: at the road wheel, or on the motor side of a compliant
  /// column (the PID then closes on the column's angle and rate; the log's delta stays the road wheel's).
  std::string angle_sensor = "wheel";

  bool softSaturation() const { return saturation == "soft"; }
  bool hasFriction() const { return coulomb_friction > 0.0 || breakaway_friction > 0.0 || viscous_friction > 0.0; }
  bool lugreFriction() const { return friction_model == "lugre" && (coulomb_friction > 0.0 || breakaway_friction > 0.0); }
  bool compliant() const { return column_stiffness > 0.0; }
  /// The LuGre sliding level g(w) = T_c + (T_s - T_c) exp(-(w / w_s)^2) at the steering rate w (Deur eq 6; T_s
  /// taken at least T_c): the model, and the replays that step its bristle state, read it from here.
  template <typename T>
  T lugreLevel(const T& rate) const {
    using std::exp;
    const double tc = coulomb_friction, ts = std::max(breakaway_friction, coulomb_friction);
    const T ratio = rate / friction_velocity;
    return tc + (ts - tc) * exp(-ratio * ratio);
  }
  bool columnSensor() const { return angle_sensor == "column"; }
  /// Extra states: column angle and rate (compliant), LuGre friction state.
  int stateSize() const { return (compliant() ? 2 : 0) + (lugreFriction() ? 1 : 0); }

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "torque_limit", torque_limit, "N m", Range::nonNegative(),
             "saturation of the applied steering torque; 0 = unlimited");
    v.choice(prefix + "saturation", saturation, {"hard", "soft"},
             "torque limit shape: hard clamp, or soft (M / (1 + (M / limit)^4)^(1/4))");
    v.number(prefix + "dead_band", dead_band, "N m", Range::nonNegative(), "torque dead band; 0 = none");
    v.choice(prefix + "friction_model", friction_model, {"tanh", "lugre"},
             "kingpin friction: tanh (Coulomb smoothed + viscous) or lugre (Deur eq 9, one state)");
    v.number(prefix + "coulomb_friction", coulomb_friction, "N m", Range::nonNegative(), "T_c, Coulomb friction torque");
    v.number(prefix + "breakaway_friction", breakaway_friction, "N m", Range::nonNegative(),
             "T_s, breakaway (static) friction torque of the lugre model");
    v.number(prefix + "viscous_friction", viscous_friction, "N m s/rad", Range::nonNegative(), "b, viscous friction");
    v.number(prefix + "friction_velocity", friction_velocity, "rad/s", Range::positive(),
             "tanh smoothing velocity, or Stribeck velocity of the lugre model");
    v.number(prefix + "friction_stiffness", friction_stiffness, "N m/rad", Range::positive(),
             "sigma0 of the lugre friction model");
    v.number(prefix + "friction_damping", friction_damping, "N m s/rad", Range::nonNegative(),
             "sigma1 of the lugre friction model");
    v.number(prefix + "column_stiffness", column_stiffness, "N m/rad", Range::nonNegative(),
             "k_c, torsional stiffness between actuator and wheel; 0 = rigid");
    v.number(prefix + "column_damping", column_damping, "N m s/rad", Range::nonNegative(), "c_c, column damping");
    v.number(prefix + "column_inertia", column_inertia, "kg m^2", Range::positive(), "J_c, actuator-side inertia");
    v.choice(prefix + "angle_sensor", angle_sensor, {"wheel", "column"},
             "the actuator's angle sensor: at the road wheel, or on the motor side of a compliant column");
    v.number(prefix + "column_stiffening_angle", column_stiffening_angle, "rad", Range::nonNegative(),
             "progressive column: twist at which the secant stiffness doubles, k (1 + (twist / angle)^2); 0 = linear");
  }
};

/// External loads on the car body (wind, road bank): a lateral force at G and a yaw moment.
struct DisturbanceParams {
  double lateral_force = 0.0;   ///< [N], body y at G, left positive
  double yaw_moment = 0.0;      ///< [N m], counter-clockwise positive
  double gust_amplitude = 0.0;  ///< fraction: both scale with (1 + a sin(2 pi x / gust_wavelength))
  double gust_wavelength = 120.0;  ///< [m]
  /// aerodynamic: a force on the body, which the lateral accelerometer senses (a real acceleration);
  /// road_bank: the lateral component of gravity on a banked road, which moves the car the same way but
  /// which an accelerometer does not sense (it measures specific force): the reported a_y lacks F / m.
  std::string kind = "aerodynamic";
  /// [m] x from which the loads act, ramped in over kOnsetRamp (a crosswind past a cutting, an exposed
  /// bridge, a banked section): an effect that sets in mid-run. 0 = from the start.
  double onset_x = 0.0;
  static constexpr double kOnsetRamp = 10.0;  ///< [m]

  bool active() const { return lateral_force != 0.0 || yaw_moment != 0.0; }
  /// The onset's factor at x: 0 before onset_x, a smoothstep over kOnsetRamp, then 1. Templated for the
  /// model's Jets (the comparisons read the value part).
  template <typename T>
  T onsetScale(const T& x) const {
    if (onset_x == 0.0) return T(1.0);
    const T u = (x - onset_x) / kOnsetRamp;
    if (u <= 0.0) return T(0.0);
    if (u >= 1.0) return T(1.0);
    return u * u * (3.0 - 2.0 * u);
  }
  bool sensedByAccelerometer() const { return kind != "road_bank"; }
  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "lateral_force", lateral_force, "N", Range::any(),
             "lateral force at G in the body frame (crosswind, road bank), left positive");
    v.number(prefix + "yaw_moment", yaw_moment, "N m", Range::any(), "yaw moment on the body");
    v.number(prefix + "gust_amplitude", gust_amplitude, "", Range::closed(0.0, 1.0),
             "gusts along the road: force and moment scale with (1 + a sin(2 pi x / gust_wavelength))");
    v.number(prefix + "gust_wavelength", gust_wavelength, "m", Range::positive(), "wavelength of the gusts");
    v.choice(prefix + "kind", kind, {"aerodynamic", "road_bank"},
             "aerodynamic (the accelerometer senses it) or road_bank (gravity: the logged a_y does not)");
    v.number(prefix + "onset_x", onset_x, "m", Range::any(),
             "x from which the loads act, ramped in over 10 m (an effect that sets in mid-run); 0 = from the start");
  }
};

}  // namespace lane_keeping
