#include "lane_keeping/gap/log/sensor_correction.h"

#include <algorithm>
#include <cmath>

namespace lane_keeping {

bool sensorsChangeTheLog(const SensorParams& sensors) { return !sensors.exact(); }

std::shared_ptr<const LogSignals> correctedForSensors(const std::shared_ptr<const LogSignals>& log,
                                                     const SensorParams& sensors) {
  if (!sensorsChangeTheLog(sensors)) return log;
  return std::make_shared<const LogSignals>(log->withSensorsUndone(sensors));
}

LogSignals LogSignals::withSensorsUndone(const SensorParams& s) const {
  LogSignals out(*this);
  const std::vector<double>& t = log_.t;
  const double steering_latency = s.steering_angle_latency, yaw_latency = s.yaw_rate_latency,
               ay_latency = s.lateral_acceleration_latency, pose_latency = s.pose_latency;
  const double latest = std::max({steering_latency, yaw_latency, ay_latency, pose_latency});
  // The samples whose every channel can be read L later: a latency cuts the log's end.
  std::size_t n = t.size();
  if (latest > 0.0) {
    while (n > 2 && t[n - 1] + latest > t.back()) --n;
  }

  // Channel c (and its smoothed curve) read `latency` later at the first n samples: raw channels along
  // their smoothed curve (one white sample's noise), smooth ones by interpolation.
  auto shifted = [&](Channel c, double latency) {
    std::vector<double>& v = out.values_[c];
    std::vector<double>& smooth = out.smoothed_[c];
    if (v.empty()) return;
    if (latency > 0.0) {
      for (std::size_t i = 0; i < n; ++i) {
        const double at_time = t[i] + latency;
        v[i] = smoothed_[c].empty() ? at(c, at_time) : nearestAlongSmoothed(c, at_time);
        if (!smooth.empty()) {
          const Position p = positionAt(at_time);
          const std::vector<double>& from = smoothed_[c];
          smooth[i] = p.edge != 0 ? (p.edge < 0 ? from.front() : from.back()) : from[p.i] + p.w * (from[p.i + 1] - from[p.i]);
        }
      }
    }
    v.resize(n);
    if (!smooth.empty()) smooth.resize(n);
  };
  auto affine = [&](Channel c, double bias, double scale) {
    if (bias == 0.0 && scale == 1.0) return;
    for (double& x : out.values_[c]) x = (x - bias) / scale;
    for (double& x : out.smoothed_[c]) x = (x - bias) / scale;
    out.noise_[c] /= std::fabs(scale);
  };

  for (Channel c : {kDelta, kDeltaRate, kDeltaAcceleration}) shifted(c, steering_latency);
  for (Channel c : {kYawRate, kYawAcceleration}) shifted(c, yaw_latency);
  shifted(kLateralAcceleration, ay_latency);
  for (Channel c : {kX, kY, kPsi, kXDot, kYDot, kSigma1}) shifted(c, pose_latency);
  for (Channel c : {kDeltaDes, kTorque, kSpeed, kDeltaDesRate, kSpeedRate}) shifted(c, 0.0);

  // Offsets and gains (the angle sensor's gain is a steering ratio: its rate and acceleration scale too).
  affine(kDelta, s.steering_angle_bias, s.steering_angle_scale);
  affine(kDeltaRate, 0.0, s.steering_angle_scale);
  affine(kDeltaAcceleration, 0.0, s.steering_angle_scale);
  affine(kYawRate, s.yaw_rate_bias, s.yaw_rate_scale);
  affine(kYawAcceleration, 0.0, s.yaw_rate_scale);
  affine(kLateralAcceleration, s.lateral_acceleration_bias, 1.0);
  // The localisation's bias at the reported x (varying along the road when configured so); the lateral
  // velocity of G turns with the heading (row 2 of Beregi eq 1 with the true psi).
  if (s.poseBiased() && !out.values_[kY].empty() && !out.values_[kX].empty()) {
    const bool turn = s.pose_bias_psi != 0.0 && !out.values_[kSigma1].empty();
    for (std::size_t i = 0; i < n; ++i) {
      const double scale = s.poseBiasScale(out.values_[kX][i]);
      out.values_[kY][i] -= scale * s.pose_bias_y;
      if (!out.smoothed_[kY].empty()) out.smoothed_[kY][i] -= scale * s.pose_bias_y;
      if (!out.values_[kPsi].empty()) {
        out.values_[kPsi][i] -= scale * s.pose_bias_psi;
        if (!out.smoothed_[kPsi].empty()) out.smoothed_[kPsi][i] -= scale * s.pose_bias_psi;
      }
      if (turn) {
        const double psi = out.values_[kPsi][i];
        out.values_[kSigma1][i] = -out.values_[kXDot][i] * std::sin(psi) + out.values_[kYDot][i] * std::cos(psi);
      }
    }
  }

  // The log itself: its first n rows, its sensor columns as the channels now hold them.
  GapLog& g = out.log_;
  for (std::vector<double>* column : {&g.t, &g.x, &g.y, &g.psi, &g.yaw_rate, &g.delta, &g.delta_des, &g.torque, &g.v,
                                      &g.ay, &g.delta_rate}) {
    if (column->size() > n) column->resize(n);
  }
  if (!g.x.empty()) g.x = out.values_[kX];
  if (!g.y.empty()) g.y = out.values_[kY];
  if (!g.psi.empty()) g.psi = out.values_[kPsi];
  if (!g.yaw_rate.empty()) g.yaw_rate = out.values_[kYawRate];
  if (!g.delta.empty()) g.delta = out.values_[kDelta];
  if (!g.delta_rate.empty()) g.delta_rate = out.values_[kDeltaRate];
  if (!g.ay.empty()) g.ay = out.values_[kLateralAcceleration];
  if (n < t.size()) out.index_ = SampleIndex(g.t);
  return out;
}

}  // namespace lane_keeping
