// The steering angle at which the car goes straight (straight_line_steering.h).
#include "lane_keeping/gap/log/straight_line_steering.h"

#include <algorithm>
#include <cmath>

#include "lane_keeping/common/effective_samples.h"
#include "lane_keeping/common/printf_string.h"
#include "lane_keeping/gap/log/time_holes.h"

namespace lane_keeping {
namespace {

constexpr double kMinSpeed = 5.0;          ///< [m/s] below it l r / V is the gyro's noise over a small V
/// [m/s^2] the path's centripetal acceleration V r, RMS over kClassifyWindow, below it: straight (0.05 g; a driver's
/// corrections on a race car's straight at 50 m/s stay within it, a lane change's swing does not); and the mean
/// a_y over the window below kStraightMeanAy (no steady cornering, whatever the gyro)
constexpr double kStraightRms = 0.5;
constexpr double kStraightMeanAy = 0.3;  ///< [m/s^2]
constexpr double kMinStraight = 2.0;        ///< [s] shorter straights are a corner's exit, not a straight line
constexpr double kClassifyWindow = 2.0;    ///< [s] the window the classification averages over (noise, corrections)
constexpr double kDegrees = 180.0 / M_PI;

/// Centred moving average over `window` seconds (by samples at the median step).
std::vector<double> averaged(const std::vector<double>& v, double step, double window) {
  const auto half = static_cast<std::size_t>(std::max(0.0, std::round(0.5 * window / step)));
  std::vector<double> prefix(v.size() + 1, 0.0);
  for (std::size_t i = 0; i < v.size(); ++i) prefix[i + 1] = prefix[i] + v[i];
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::size_t a = i >= half ? i - half : 0, b = std::min(v.size(), i + half + 1);
    out[i] = (prefix[b] - prefix[a]) / static_cast<double>(b - a);
  }
  return out;
}

}  // namespace

StraightLineSteering straightLineSteering(const GapLog& log, double wheelbase, double yaw_rate_bias) {
  StraightLineSteering out;
  if (log.size() < 20 || !log.has("delta", true) || !log.has("yaw_rate", true) || !log.hasSpeed()) return out;
  const double step = log.medianStep();
  if (!(step > 0.0)) return out;
  const std::size_t n = log.size();
  std::vector<double> r(n), lateral(n), centripetal_sq(n);
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = log.yaw_rate[i] - yaw_rate_bias;
    lateral[i] = log.hasLateralAcceleration() ? log.ay[i] : 0.0;
    centripetal_sq[i] = std::pow(log.v[i] * r[i], 2);
  }
  const std::vector<double> rms_sq = averaged(centripetal_sq, step, kClassifyWindow);
  const std::vector<double> ay_avg = averaged(lateral, step, kClassifyWindow);
  auto straight = [&](std::size_t i) {
    return std::fabs(log.v[i]) >= kMinSpeed && std::sqrt(rms_sq[i]) < kStraightRms && std::fabs(ay_avg[i]) < kStraightMeanAy;
  };
  auto close = [&](std::size_t a, std::size_t b) {  // [a, b)
    if (b <= a + 2 || log.t[b - 1] - log.t[a] < kMinStraight) return;
    StraightStretch s;
    s.t0 = log.t[a];
    s.t1 = log.t[b - 1];
    std::vector<double> u;
    double course = 0.0;
    for (std::size_t i = a; i < b; ++i) {
      // The road-wheel angle less the kinematic steer of the path's slight curvature.
      u.push_back(log.delta[i] - wheelbase * r[i] / std::fabs(log.v[i]));
      course += log.has("psi", true) ? log.psi[i] : 0.0;
    }
    const double m = static_cast<double>(u.size());
    double mean = 0.0;
    for (double x : u) mean += x / m;
    double see = 0.0;
    for (double& x : u) {
      x -= mean;  // the deviations from the stretch's mean
      see += x * x;
    }
    const double effective = effectiveSampleCount(u);
    s.offset = mean;
    s.sigma = std::sqrt(see / std::max(1.0, m - 1.0) / effective);
    s.course = course / m;
    out.stretches.push_back(s);
  };
  // A straight ends at a hole in the time axis (time_holes.h) as it ends where the car turns.
  std::vector<char> after_hole(n, 0);
  for (const auto& [begin, end] : holeFreeStretches(log.t)) {
    if (begin > 0) after_hole[begin] = 1;
  }
  std::size_t first = 0;
  bool in = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (in && (after_hole[i] || !straight(i))) {
      close(first, i);
      in = false;
    }
    if (!in && straight(i)) {
      first = i;
      in = true;
    }
  }
  if (in) close(first, n);
  if (out.stretches.empty()) return out;
  double sum = 0.0, weight = 0.0;
  for (const StraightStretch& s : out.stretches) {
    const double sigma = std::max(s.sigma, 1e-6);  // a stretch of exactly constant samples
    sum += s.offset / (sigma * sigma);
    weight += 1.0 / (sigma * sigma);
  }
  out.offset = sum / weight;
  out.sigma = 1.0 / std::sqrt(weight);
  bool contradicted = false;
  for (const StraightStretch& s : out.stretches) {
    if (std::fabs(s.offset - out.offset) > 3.0 * std::hypot(s.sigma, out.sigma) + kSteeringZeroTolerance) contradicted = true;
  }
  out.found = !contradicted && std::fabs(out.offset) > std::max(3.0 * out.sigma, kSteeringZeroTolerance);
  return out;
}

std::vector<InputCheck> straightLineSteeringChecks(const GapLog& log, double wheelbase, double yaw_rate_bias) {
  const StraightLineSteering s = straightLineSteering(log, wheelbase, yaw_rate_bias);
  if (!s.found) return {};
  std::string detail = printfString(
      "the car goes straight with the road wheels at %+.2f +- %.2f mrad (%+.2f deg) over %zu straight%s of %.1f s and "
      "more (its course, psi,",
      1e3 * s.offset, 1e3 * s.sigma, s.offset * kDegrees, s.stretches.size(), s.stretches.size() == 1 ? "" : "s",
      kMinStraight);
  for (std::size_t k = 0; k < s.stretches.size(); ++k) {
    const StraightStretch& t = s.stretches[k];
    // The course as a compass reads it would need the map's north; the log's psi is what there is.
    detail += printfString("%s %.0f deg (%.1f-%.1f s: %+.2f mrad)", k == 0 ? "" : ",",
                           std::round(std::remainder(t.course, 2.0 * M_PI) * kDegrees) + 0.0, t.t0 - log.t.front(),
                           t.t1 - log.t.front(), 1e3 * t.offset);
  }
  detail += ")";
  double lo = INFINITY, hi = -INFINITY;
  for (const StraightStretch& t : s.stretches) lo = std::min(lo, t.course), hi = std::max(hi, t.course);
  const double apart = (hi - lo) * kDegrees;
  detail += ": a steering sensor's zero, or a pull the single-track model lacks (tire conicity, an alignment's split), "
            "which the model reads alike as sensor_offset (steering_angle), or a steady side force";
  detail += printfString(apart > 90.0
                             ? " (a crosswind would change sign with the direction of travel: these straights run %.0f "
                               "deg apart and agree, so not a crosswind)"
                             : " such as a crosswind (these straights run within %.0f deg of each other: not told apart)",
                         apart);
  detail += "; reported, not corrected";
  return {inputCheck(log.source, "delta", "offset", detail)};
}

}  // namespace lane_keeping
