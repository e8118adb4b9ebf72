#pragma once
/// Parameters of the single-track model, Beregi Table 1 (SI units).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"  // formatNumber
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
  /// [[t, V], ...]: V [m/s] in time t [s] from the run's start (speed_profile.h: a monotone cubic through
  /// the points, held before the first and after the last); empty = `speed` (and speed_variation).
  PointList speed_profile;

  /// Points of a speed profile closer than this in time [s] make its slopes overflow (as the waypoints'
  /// kMinWaypointSpacing); a log thinned to 10 Hz has them 0.1 s apart.
  static constexpr double kMinProfileSpacing = 1e-3;

  /// The fastest speed of a run [m/s]: the profile's fastest point, or V (1 + speed_variation). (The
  /// monotone cubic of speed_profile.h never passes its points' speeds.)
  double fastestSpeed() const {
    if (speed_profile.empty()) return speed * (1.0 + speed_variation);
    double fastest = 0.0;
    for (const Point2& p : speed_profile) fastest = std::max(fastest, p[1]);
    return fastest;
  }

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
             "V, wheel-direction speed of the front axle (non-holonomic constraint, eq 1; the logs' v is G's speed)");
    v.number(prefix + "gravity", gravity, "m/s^2", Range::positive(), "g, for the static axle loads");
    v.number(prefix + "speed_variation", speed_variation, "", Range::closed(0.0, 0.5),
             "speed varying along the road: V(x) = V (1 + a sin(2 pi x / speed_wavelength)); 0 = constant");
    v.number(prefix + "speed_wavelength", speed_wavelength, "m", Range::positive(), "wavelength of the speed variation");
    v.points(prefix + "speed_profile", speed_profile, "s, m/s",
             "speed in time instead: [[t, V], ...] (t from the run's start, increasing; V > 0 as `speed`) or a CSV file "
             "of t,V lines (relative to this file); a monotone cubic through the points, held beyond; [] = off");
  }

  /// Cross-field rules (ranges are checked by RangeChecker through visit()).
  void validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
    if (cg_to_rear_axle >= wheelbase) {
      problems.push_back({prefix + "cg_to_rear_axle", "",
                          "= " + std::to_string(cg_to_rear_axle) + " m, must be smaller than " + prefix +
                              "wheelbase (" + std::to_string(wheelbase) + " m): G lies between the axles"});
    }
    validateSpeedProfile(prefix, problems);
  }

  /// A speed profile's rules: speeds > 0, times strictly increasing (at least kMinProfileSpacing apart),
  /// and not together with a speed varying along the road. (That every value is finite is RangeChecker's.)
  void validateSpeedProfile(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
    if (speed_profile.empty()) return;
    const std::string key = prefix + "speed_profile";
    if (speed_variation != 0.0) {
      problems.push_back({key, "", "is set together with " + prefix + "speed_variation = " +
                                       formatNumber(speed_variation) +
                                       ": a speed in time and a speed along the road exclude one another; set one"});
    }
    for (std::size_t i = 0; i < speed_profile.size(); ++i) {
      const double v = speed_profile[i][1];
      if (std::isfinite(v) && !(v > 0.0)) {
        problems.push_back({key, "", "[" + std::to_string(i) + "]: V = " + formatNumber(v) + " m/s, must be > 0 m/s"});
      }
    }
    for (std::size_t i = 1; i < speed_profile.size(); ++i) {
      const double t0 = speed_profile[i - 1][0], t1 = speed_profile[i][0];
      if (!std::isfinite(t0) || !std::isfinite(t1)) continue;
      if (!(t1 > t0)) {
        problems.push_back({key, "", "[" + std::to_string(i) + "]: t = " + formatNumber(t1) +
                                         " s, must be after t[" + std::to_string(i - 1) + "] = " + formatNumber(t0) +
                                         " s (times strictly increasing)"});
      } else if (t1 - t0 < kMinProfileSpacing) {
        problems.push_back({key, "", "[" + std::to_string(i) + "]: t = " + formatNumber(t1) + " s is only " +
                                         formatNumber(t1 - t0) + " s after t[" + std::to_string(i - 1) +
                                         "]; points must be at least 0.001 s apart"});
      }
    }
  }
};

}  // namespace lane_keeping
