#include "lane_keeping/gap/log/logged_speed.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

double frontAxleSpeed(double cg_speed, double sigma1, double yaw_rate, double delta, double cg_to_front_axle) {
  const double u = std::sqrt(std::max(0.0, cg_speed * cg_speed - sigma1 * sigma1));
  return u * std::cos(delta) + (sigma1 + cg_to_front_axle * yaw_rate) * std::sin(delta);
}

bool holdsCentreOfGravitySpeed(const GapLog& log) {
  return log.hasSpeed() && log.speed_of == LoggedSpeed::kCentreOfGravity;
}

GapLog withFrontAxleSpeed(const LogSignals& signals, const VehicleParams& vehicle) {
  GapLog out = signals.log();
  if (!holdsCentreOfGravitySpeed(out)) return out;
  using C = LogSignals;
  const double b = vehicle.cgToFrontAxle();
  auto channel = [&](C::Channel c) { return signals.has(c) ? &signals.samples(c) : nullptr; };
  const std::vector<double>* sigma1 = channel(C::kSigma1);
  const std::vector<double>* yaw_rate = channel(C::kYawRate);
  const std::vector<double>* delta = channel(C::kDelta);
  for (std::size_t i = 0; i < out.v.size(); ++i) {
    out.v[i] = frontAxleSpeed(out.v[i], sigma1 ? (*sigma1)[i] : 0.0, yaw_rate ? (*yaw_rate)[i] : 0.0,
                              delta ? (*delta)[i] : 0.0, b);
  }
  out.speed_of = LoggedSpeed::kFrontAxle;
  return out;
}

PointList speedProfileFromLog(const LogSignals& log, double rate, double half_width) {
  if (!log.has(LogSignals::kSpeed)) throw InputError(log.log().source + ": the log has no speed (v) to follow");
  const std::vector<double>& t = log.times();
  const std::vector<double> smooth = smoothedDerivative(t, log.samples(LogSignals::kSpeed), half_width, 0);
  const double t0 = log.start(), span = log.end() - t0;
  std::vector<Point2> points;
  std::size_t i = 0;
  auto at = [&](double time) {  // linear between the smoothed samples
    while (i + 2 < t.size() && t[i + 1] <= time) ++i;
    if (t.size() < 2) return smooth.front();
    const double w = std::min(1.0, std::max(0.0, (time - t[i]) / (t[i + 1] - t[i])));
    return smooth[i] + w * (smooth[i + 1] - smooth[i]);
  };
  const auto steps = static_cast<long>(std::floor(span * rate + 1e-9));
  for (long k = 0; k <= steps; ++k) {
    const double s = static_cast<double>(k) / rate;
    points.push_back({s, at(t0 + s)});
  }
  // The end, unless a point lies within the profile's minimum spacing of it.
  if (span - points.back()[0] >= VehicleParams::kMinProfileSpacing) points.push_back({span, at(t0 + span)});
  return PointList(std::move(points));
}

SimConfig withLoggedSpeed(SimConfig config, const LogSignals& log) {
  if (!log.speedVaries()) return config;
  config.vehicle.speed_variation = 0.0;
  config.vehicle.speed_profile = speedProfileFromLog(log);
  return config;
}

}  // namespace lane_keeping
