#pragma once
/// A speed profile in time: V(t), the front axle's wheel-direction speed of Beregi eq 1, through the
/// points [t, V] of `vehicle.speed_profile` (t [s] from the run's start, V [m/s]), with its rate dV/dt.
///
/// Interpolation: a monotone cubic (Fritsch & Carlson, "Monotone piecewise cubic interpolation", SIAM J.
/// Numer. Anal. 17(2), 1980; slopes by the weighted harmonic mean of Fritsch & Butland 1984, as Moler's
/// pchip), not straight lines and not a natural spline:
///  * dV/dt enters the equations of motion (the rheonomic terms of a varying speed, SingleTrackModel::
///    bodyForces), so it should be continuous, as a real car's acceleration is: straight lines make it
///    jump at every point (ten times a second for a profile taken from a log);
///  * a natural cubic spline overshoots between points (a ramp into a hold rings past the held speed, and
///    points close together can drive V towards 0); the monotone cubic stays within the speeds of each
///    interval's ends, so V > 0 whenever every point's speed is;
///  * before the first point and after the last the speed holds (dV/dt = 0), and the end slopes are 0 so
///    that the profile joins those holds smoothly: dV/dt is continuous for every t. Two points give the
///    smooth step V0 + (V1 - V0)(3 s^2 - 2 s^3) (peak rate 1.5 times the mean); points on a line give
///    that line between the end intervals.
#include <cstddef>
#include <vector>

#include "lane_keeping/config/point_list.h"

namespace lane_keeping {

class SpeedProfile {
 public:
  struct Sample {
    double speed;  ///< V [m/s]
    double rate;   ///< dV/dt [m/s^2]
  };

  /// @param points [t, V] with t strictly increasing (VehicleParams::validate checks it); at least one.
  explicit SpeedProfile(const std::vector<Point2>& points);

  /// V and dV/dt at time t [s] from the run's start.
  Sample at(double t) const;

  std::size_t size() const { return t_.size(); }

 private:
  std::vector<double> t_, v_, slope_;  ///< the points and dV/dt at each
};

}  // namespace lane_keeping
