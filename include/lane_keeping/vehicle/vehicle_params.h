#pragma once
/// Parameters of the single-track model, Beregi Table 1 (SI units).
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct VehicleParams {
  double wheelbase = 2.57;           ///< l [m]
  double cg_to_rear_axle = 1.54;     ///< d [m], distance from G to the rear axle R
  double mass = 1100.0;              ///< m [kg]
  double yaw_inertia = 1343.0;       ///< J_G [kg m^2]
  double steering_mass = 10.0;       ///< m_F [kg], steered front axle incl. wheel
  double steering_inertia = 0.25;    ///< J_F [kg m^2], about F
  double speed = 15.0;               ///< V [m/s], wheel-direction speed of F (constraint of eq 1)
  double gravity = 9.81;             ///< g [m/s^2]
  double speed_variation = 0.0;      ///< fraction: V(x) = V (1 + a sin(2 pi x / wavelength)); 0 = constant V
  double speed_wavelength = 150.0;   ///< [m] of the speed variation

  /// Distance G -> front axle F, (l - d) [m].
  double cgToFrontAxle() const { return wheelbase - cg_to_rear_axle; }
  /// Static axle loads (DESIGN §3): F_zF = m g d / l, F_zR = m g (l - d) / l [N].
  double frontAxleLoad() const { return mass * gravity * cg_to_rear_axle / wheelbase; }
  double rearAxleLoad() const { return mass * gravity * cgToFrontAxle() / wheelbase; }

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "wheelbase", wheelbase, "m", Range::positive(), "l, wheelbase (Beregi Table 1)");
    v.number(prefix + "cg_to_rear_axle", cg_to_rear_axle, "m", Range::positive(),
             "d, centre of gravity G to rear axle R");
    v.number(prefix + "mass", mass, "kg", Range::positive(), "m, vehicle mass");
    v.number(prefix + "yaw_inertia", yaw_inertia, "kg m^2", Range::positive(), "J_G, yaw inertia about G");
    v.number(prefix + "steering_mass", steering_mass, "kg", Range::nonNegative(),
             "m_F, mass of the steered front axle and wheel");
    v.number(prefix + "steering_inertia", steering_inertia, "kg m^2", Range::positive(),
             "J_F, inertia of the steered front axle about F");
    v.number(prefix + "speed", speed, "m/s", Range::positive(),
             "V, constant wheel-direction speed of the front axle (non-holonomic constraint, eq 1)");
    v.number(prefix + "gravity", gravity, "m/s^2", Range::positive(), "g, for the static axle loads");
    v.number(prefix + "speed_variation", speed_variation, "", Range::closed(0.0, 0.5),
             "speed varying along the road: V(x) = V (1 + a sin(2 pi x / speed_wavelength)); 0 = constant");
    v.number(prefix + "speed_wavelength", speed_wavelength, "m", Range::positive(), "wavelength of the speed variation");
  }

  /// Cross-field rules (ranges are checked by RangeChecker through visit()).
  void validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
    if (cg_to_rear_axle >= wheelbase) {
      problems.push_back({prefix + "cg_to_rear_axle", "",
                          "= " + std::to_string(cg_to_rear_axle) + " m, must be smaller than " + prefix +
                              "wheelbase (" + std::to_string(wheelbase) + " m): G lies between the axles"});
    }
  }
};

}  // namespace lane_keeping
