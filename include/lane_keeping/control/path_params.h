#pragma once
/// The reference path (lane centre) as a graph y = f(x) in the map frame.
#include <cmath>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"  // formatNumber
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct PathParams {
  std::string type = "straight";  ///< straight | lane_change | sinusoid | waypoints
  double lane_width = 3.5;        ///< [m] for lane boundaries (rviz) and the departure flag in the summary
  // lane_change: quintic (C2) shift of `offset` between x = start and x = start + length.
  double lane_change_start = 30.0;   ///< [m]
  double lane_change_length = 60.0;  ///< [m]
  double lane_change_offset = 3.5;   ///< [m], left positive
  // sinusoid: y = A w(x) sin(2 pi (x - start) / wavelength), w fades in over the first wavelength.
  double sinusoid_amplitude = 1.0;    ///< A [m]
  double sinusoid_wavelength = 150.0; ///< [m]
  double sinusoid_start = 30.0;       ///< [m]
  // waypoints: natural cubic spline through the points (x strictly increasing), straight beyond.
  PointList waypoints{{0.0, 0.0}, {50.0, 0.0}, {100.0, 2.0}, {150.0, 2.0}};

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.choice(prefix + "type", type, {"straight", "lane_change", "sinusoid", "waypoints"},
             "lane centre: straight (x axis), lane_change, sinusoid, or waypoints");
    v.number(prefix + "lane_width", lane_width, "m", Range::positive(), "lane width (boundaries, departure flag)");
    v.number(prefix + "lane_change.start", lane_change_start, "m", Range::any(), "x where the lane change begins");
    v.number(prefix + "lane_change.length", lane_change_length, "m", Range::positive(),
             "longitudinal length of the quintic lane change");
    v.number(prefix + "lane_change.offset", lane_change_offset, "m", Range::any(), "lateral shift, left positive");
    v.number(prefix + "sinusoid.amplitude", sinusoid_amplitude, "m", Range::any(), "amplitude A");
    v.number(prefix + "sinusoid.wavelength", sinusoid_wavelength, "m", Range::positive(), "wavelength");
    v.number(prefix + "sinusoid.start", sinusoid_start, "m", Range::any(),
             "x where the sinusoid starts (amplitude fades in over one wavelength)");
    v.points(prefix + "waypoints", waypoints, "m", "[[x, y], ...] with strictly increasing x (waypoints type), or the name of a CSV file of x,y lines "
             "(relative to this file; a lane from a map)");
  }

  /// Waypoints farther than this from the map origin [m] (a map frame spanning a continent, as the gap
  /// logs' x and y) are a unit error; the spline's arithmetic stays finite within it.
  static constexpr double kMaxWaypointCoordinate = 1e8;
  /// Waypoints closer than this in x [m] make the spline's slopes (y difference / x difference) overflow:
  /// found by fuzzing (x = 0 and 3.5e-310 gave a NaN lane). A map's points are centimetres apart or more.
  static constexpr double kMinWaypointSpacing = 1e-3;

  /// Cross-field and shape rules; that every value is finite is RangeChecker's (param_readers.h). The
  /// lane's bends against the car's turning radius are checked with the vehicle (SimConfig::problems).
  void validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
    // The shapes' lengths within the map's extent, as the waypoints' coordinates below.
    const std::pair<const char*, double> lengths[] = {
        {"lane_change.start", lane_change_start},   {"lane_change.length", lane_change_length},
        {"lane_change.offset", lane_change_offset}, {"sinusoid.amplitude", sinusoid_amplitude},
        {"sinusoid.wavelength", sinusoid_wavelength}, {"sinusoid.start", sinusoid_start}};
    const bool shape = type == "lane_change" || type == "sinusoid";
    for (const auto& [key, value] : lengths) {
      if (shape && std::string(key).rfind(type, 0) == 0 && std::isfinite(value) &&
          std::fabs(value) > kMaxWaypointCoordinate) {
        problems.push_back({prefix + key, "", "= " + formatNumber(value) + " m is beyond 1e8 m; check the unit"});
      }
    }
    // A shape's length divides its slope: below a millimetre (3.5e-310 m was accepted as positive) the lane
    // is NaN even without an offset (found by fuzzing, fuzz/regressions/path/lane_change_denormal_length.bin).
    const std::pair<const char*, double> divisors[] = {{"lane_change.length", lane_change_length},
                                                       {"sinusoid.wavelength", sinusoid_wavelength}};
    for (const auto& [key, value] : divisors) {
      if (shape && std::string(key).rfind(type, 0) == 0 && std::isfinite(value) && value > 0.0 &&
          value < kMinWaypointSpacing) {
        problems.push_back({prefix + key, "", "= " + formatNumber(value) + " m is shorter than 0.001 m"});
      }
    }
    if (type != "waypoints") return;
    if (waypoints.size() < 2) {
      problems.push_back({prefix + "waypoints", "", "needs at least 2 points, got " + std::to_string(waypoints.size())});
      return;
    }
    for (std::size_t i = 0; i < waypoints.size(); ++i) {
      for (int c = 0; c < 2; ++c) {
        const double v = waypoints[i][c];
        if (std::isfinite(v) && std::fabs(v) > kMaxWaypointCoordinate) {
          problems.push_back({prefix + "waypoints", "",
                              "[" + std::to_string(i) + "]: " + (c == 0 ? "x" : "y") + " = " + formatNumber(v) +
                                  " m is beyond 1e8 m from the map origin; check the unit"});
        }
      }
    }
    for (std::size_t i = 1; i < waypoints.size(); ++i) {
      if (!(waypoints[i][0] > waypoints[i - 1][0])) {
        problems.push_back({prefix + "waypoints", "",
                            "[" + std::to_string(i) + "]: x must increase strictly along the lane (x[" +
                                std::to_string(i) + "] <= x[" + std::to_string(i - 1) + "])"});
      } else if (waypoints[i][0] - waypoints[i - 1][0] < kMinWaypointSpacing) {
        problems.push_back({prefix + "waypoints", "",
                            "[" + std::to_string(i) + "]: x = " + formatNumber(waypoints[i][0]) + " m is only " +
                                formatNumber(waypoints[i][0] - waypoints[i - 1][0]) + " m after x[" +
                                std::to_string(i - 1) + "]; waypoints must be at least 0.001 m apart in x"});
      }
    }
  }
};

}  // namespace lane_keeping
