#include "lane_keeping/gap/log/log_signals.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/time_holes.h"
#include "lane_keeping/gap/log/window_weights.h"

namespace lane_keeping {

std::vector<double> smoothedDerivative(const std::vector<double>& t, const std::vector<double>& values,
                                       double half_width, int order) {
  const std::size_t n = t.size();
  std::vector<double> out(n, 0.0);
  if (n == 0) return out;
  // A log sampled uniformly (to rounding) has windows of a few shapes only (samples before and after
  // t_i: the interior one, the edges, and +-1 where rounding moves a sample across the half-width):
  // their weights are solved once per shape, and each output is one dot product (a Savitzky-Golay
  // filter as a convolution). Solving the 3x3 least squares at every sample was a quarter of a 1 kHz
  // diagnosis (60,000 samples x 200-sample windows x 19 noise-only logs).
  const double h = n > 1 ? (t[n - 1] - t[0]) / static_cast<double>(n - 1) : 0.0;
  bool uniform = n > 1 && h > 0.0;
  for (std::size_t j = 0; uniform && j < n; ++j) uniform = std::fabs(t[j] - t[0] - j * h) <= 1e-6 * h;
  // Each sample's window [a_i, b_i]: at least two samples each side where the log allows, so the
  // quadratic is determined.
  std::vector<std::size_t> first(n), last(n);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (lo < i && t[i] - t[lo] > half_width) ++lo;
    while (hi + 1 < n && t[hi + 1] - t[i] <= half_width) ++hi;
    std::size_t a = std::min(lo, i >= 2 ? i - 2 : 0);
    std::size_t b = std::max(hi, std::min(n - 1, i + 2));
    if (b - a < 2) {
      a = a > 0 ? a - 1 : a;
      b = std::min(n - 1, b + 1);
    }
    first[i] = a;
    last[i] = b;
  }
  // A window's shape: the samples before and after t_i, (i - a_i, b_i - i). Its weights are found
  // from the samples before, then among the few shapes with that many (a map's search per sample was
  // a fifth of the filter); a shape first met in this call comes from this thread's weights of earlier
  // calls on the same step (window_weights.h), solved there if none has met it.
  std::size_t widest = 0;
  for (std::size_t i = 0; i < n; ++i) widest = std::max(widest, last[i] - first[i]);
  std::vector<std::vector<std::pair<std::size_t, const std::vector<double>*>>> shapes_before(uniform ? widest + 1 : 0);
  UniformWindowWeights* remembered = nullptr;
  if (uniform) {
    remembered = &windowWeightsOfThisThread();
    remembered->select(h, order);
  }
  std::vector<double> s;
  // Fit v = c0 + c1 (t - t_i) + c2 (t - t_i)^2 by least squares (scaled time): the weights of i's window.
  auto weightsAt = [&](std::size_t i, std::vector<double>* local) -> const std::vector<double>& {
    const std::size_t a = first[i], b = last[i];
    if (uniform) {
      auto& candidates = shapes_before[i - a];  // (after, its weights)
      for (const auto& [after, weights] : candidates) {
        if (after == b - i) return *weights;
      }
      const std::vector<double>& weights = remembered->weights(i - a, b - i);
      candidates.emplace_back(b - i, &weights);
      return weights;
    }
    const double scale = std::max(t[b] - t[a], 1e-12);
    s.clear();
    for (std::size_t j = a; j <= b; ++j) s.push_back((t[j] - t[i]) / scale);
    *local = quadraticWeights(s, scale, order);
    return *local;
  };
  std::vector<double> local;
  constexpr std::size_t kLanes = 4;
  for (std::size_t i = 0; i < n;) {
    if (uniform && i + kLanes <= n) {
      // Four neighbours' sums side by side, each over its own window and weights in the same order as
      // alone, so each is the same to the last bit; independent, they do not wait on one another's
      // additions. (Rounding moves a sample across the half-width here and there, so neighbours' windows
      // differ by a sample at an end: the common length first, then each one's rest.)
      const std::vector<double>* w[kLanes];
      const double* v[kLanes];
      std::size_t len[kLanes];
      for (std::size_t k = 0; k < kLanes; ++k) {
        w[k] = &weightsAt(i + k, &local);  // (uniform: the shape's weights, which stay in place)
        v[k] = values.data() + first[i + k];
        len[k] = last[i + k] - first[i + k] + 1;
      }
      const std::size_t common = *std::min_element(len, len + kLanes);
      const double *w0 = w[0]->data(), *w1 = w[1]->data(), *w2 = w[2]->data(), *w3 = w[3]->data();
      double sum[kLanes] = {0.0, 0.0, 0.0, 0.0};
      for (std::size_t j = 0; j < common; ++j) {
        sum[0] += w0[j] * v[0][j];
        sum[1] += w1[j] * v[1][j];
        sum[2] += w2[j] * v[2][j];
        sum[3] += w3[j] * v[3][j];
      }
      for (std::size_t k = 0; k < kLanes; ++k) {
        for (std::size_t j = common; j < len[k]; ++j) sum[k] += (*w[k])[j] * v[k][j];
        out[i + k] = sum[k];
      }
      i += kLanes;
      continue;
    }
    const std::vector<double>& w = weightsAt(i, &local);
    const double* v = values.data() + first[i];
    const std::size_t len = last[i] - first[i] + 1;
    double sum = 0.0;
    for (std::size_t j = 0; j < len; ++j) sum += w[j] * v[j];
    out[i] = sum;
    ++i;
  }
  return out;
}

std::vector<double> splineDerivative(const std::vector<double>& t, const std::vector<double>& y) {
  const std::size_t n = t.size();
  std::vector<double> out(n, 0.0);
  if (n < 2) return out;
  if (n == 2) {
    out[0] = out[1] = (y[1] - y[0]) / (t[1] - t[0]);
    return out;
  }
  // Second derivatives M_i of the natural spline (M_0 = M_{n-1} = 0): for i = 1 .. n-2,
  // h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (slope_i - slope_{i-1}); Thomas algorithm.
  std::vector<double> h(n - 1), slope(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = t[i + 1] - t[i];
    slope[i] = (y[i + 1] - y[i]) / h[i];
  }
  std::vector<double> diag(n, 1.0), upper(n, 0.0), rhs(n, 0.0), m(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double lower = h[i - 1];
    diag[i] = 2.0 * (h[i - 1] + h[i]);
    upper[i] = h[i];
    rhs[i] = 6.0 * (slope[i] - slope[i - 1]);
    if (i > 1) {  // eliminate the sub-diagonal with the previous (already reduced) row
      const double w = lower / diag[i - 1];
      diag[i] -= w * upper[i - 1];
      rhs[i] -= w * rhs[i - 1];
    }
  }
  for (std::size_t i = n - 2; i >= 1; --i) {
    m[i] = (rhs[i] - upper[i] * m[i + 1]) / diag[i];
    if (i == 1) break;
  }
  for (std::size_t i = 0; i + 1 < n; ++i) out[i] = slope[i] - h[i] * (2.0 * m[i] + m[i + 1]) / 6.0;
  out[n - 1] = slope[n - 2] + h[n - 2] * (m[n - 2] + 2.0 * m[n - 1]) / 6.0;
  return out;
}

double fourthDifferenceNoise(const std::vector<double>& v) {
  if (v.size() < 8) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 2; i + 2 < v.size(); ++i) {
    const double d = v[i - 2] - 4.0 * v[i - 1] + 6.0 * v[i] - 4.0 * v[i + 1] + v[i + 2];
    sum += d * d;
  }
  return std::sqrt(sum / (v.size() - 4) / 70.0);
}

namespace {

using Stretches = std::vector<std::pair<std::size_t, std::size_t>>;

/// f(t, v) on each stretch of samples, concatenated; f itself where there is one stretch.
template <typename F>
std::vector<double> perStretch(const Stretches& stretches, const std::vector<double>& t, const std::vector<double>& v,
                               F f) {
  if (stretches.size() <= 1 || v.size() != t.size()) return f(t, v);
  std::vector<double> out;
  out.reserve(t.size());
  for (const auto& [begin, end] : stretches) {
    const std::vector<double> ts(t.begin() + begin, t.begin() + end), vs(v.begin() + begin, v.begin() + end);
    const std::vector<double> part = f(ts, vs);
    out.insert(out.end(), part.begin(), part.end());
  }
  return out;
}

/// fourthDifferenceNoise over the fourth differences within each stretch.
double noiseOver(const Stretches& stretches, const std::vector<double>& v) {
  if (stretches.size() <= 1 || v.empty()) return fourthDifferenceNoise(v);  // (an absent channel: 0)
  double sum = 0.0, terms = 0.0;
  for (const auto& [begin, end] : stretches) {
    if (end - begin < 8) continue;
    for (std::size_t i = begin + 2; i + 2 < end; ++i) {
      const double d = v[i - 2] - 4.0 * v[i - 1] + 6.0 * v[i] - 4.0 * v[i + 1] + v[i + 2];
      sum += d * d;
    }
    terms += static_cast<double>(end - begin - 4);
  }
  return terms > 0.0 ? std::sqrt(sum / terms / 70.0) : 0.0;
}

}  // namespace

LogSignals::LogSignals(GapLog log, const SmoothingWindows& windows)
    : log_(std::move(log)), index_(log_.t), values_(kChannels), smoothed_(kChannels), noise_(kChannels, 0.0) {
  const auto& t = log_.t;
  // Derivatives, smoothing and noise estimates stay within each stretch between holes of the time axis
  // (time_holes.h): across a 5 s hole a derivative's window, a spline or a fourth difference invents what
  // the car did, and the noise estimated across it was several times too high (the noise-only reference
  // of a holed log then swallowed a steering friction's gap). A log without holes is one stretch.
  const Stretches stretches = holeFreeStretches(t);
  auto smoothed = [&](const std::vector<double>& v, double half_width, int order) {
    return perStretch(stretches, t, v, [&](const std::vector<double>& ts, const std::vector<double>& vs) {
      return smoothedDerivative(ts, vs, half_width, order);
    });
  };
  auto splineRate = [&](const std::vector<double>& v) {
    return perStretch(stretches, t, v, [](const std::vector<double>& ts, const std::vector<double>& vs) {
      return splineDerivative(ts, vs);
    });
  };
  auto noiseOf = [&](const std::vector<double>& v) { return noiseOver(stretches, v); };
  values_[kX] = log_.x;
  values_[kY] = log_.y;
  values_[kPsi] = log_.psi;
  values_[kYawRate] = log_.yaw_rate;
  values_[kDelta] = log_.delta;
  values_[kDeltaDes] = log_.delta_des;
  values_[kTorque] = log_.torque;
  values_[kSpeed] = log_.v;
  values_[kLateralAcceleration] = log_.ay;
  // Derived channels exist where their sources do (a partial log lacks some; has() says which).
  const bool pose = !log_.x.empty() && !log_.y.empty() && !log_.psi.empty();
  if (log_.hasSteeringRate()) values_[kDeltaRate] = log_.delta_rate;
  else if (!log_.delta.empty()) values_[kDeltaRate] = smoothed(log_.delta, windows.steering, 1);
  if (!values_[kDeltaRate].empty()) {
    values_[kDeltaAcceleration] = smoothed(values_[kDeltaRate], windows.steering, 1);
  }
  // delta_des is computed by the tracker, not measured: differentiated through a spline, not smoothed,
  // so that the identification excitation's top frequencies keep their rate (splineDerivative).
  if (!log_.delta_des.empty()) values_[kDeltaDesRate] = splineRate(log_.delta_des);
  if (!log_.yaw_rate.empty()) values_[kYawAcceleration] = smoothed(log_.yaw_rate, windows.steering, 1);
  if (!log_.x.empty()) values_[kXDot] = smoothed(log_.x, windows.position, 1);
  if (!log_.y.empty()) values_[kYDot] = smoothed(log_.y, windows.position, 1);
  if (log_.hasLateralVelocity()) {
    values_[kSigma1] = log_.vy;  // measured (an INS, an optical sensor): not differentiated from the pose
  } else if (pose && !log_.psi_is_course) {
    // (A course over ground is the velocity's own direction: the lateral velocity across it is 0 by
    // definition and says nothing of the body's; it is left to the replays to estimate.)
    values_[kSigma1].resize(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
      values_[kSigma1][i] = -values_[kXDot][i] * std::sin(log_.psi[i]) + values_[kYDot][i] * std::cos(log_.psi[i]);
    }
  }
  if (!log_.v.empty()) values_[kSpeedRate] = smoothed(log_.v, windows.position, 1);
  if (!log_.x.empty()) smoothed_[kX] = smoothed(log_.x, windows.pose, 0);
  if (!log_.y.empty()) smoothed_[kY] = smoothed(log_.y, windows.pose, 0);
  if (!log_.psi.empty()) smoothed_[kPsi] = smoothed(log_.psi, windows.pose, 0);
  if (!log_.delta.empty()) smoothed_[kDelta] = smoothed(log_.delta, windows.steering, 0);
  if (log_.hasSteeringRate()) smoothed_[kDeltaRate] = smoothed(log_.delta_rate, windows.steering, 0);
  else smoothed_[kDeltaRate] = values_[kDeltaRate];
  // The gyro's and the accelerometer's, for a latency undone along them (sensor_correction.h): over the
  // pose's window, so that the carry between samples adds little noise of its own.
  if (!log_.yaw_rate.empty()) smoothed_[kYawRate] = smoothed(log_.yaw_rate, windows.pose, 0);
  if (!log_.ay.empty()) smoothed_[kLateralAcceleration] = smoothed(log_.ay, windows.pose, 0);
  for (Channel c : {kX, kY, kPsi, kYawRate, kDelta, kDeltaDes, kTorque, kSpeed, kLateralAcceleration}) {
    noise_[c] = noiseOf(values_[c]);
  }
  double step = log_.medianStep();
  if (!(step > 0.0)) step = 0.01;
  auto derivativeNoise = [&](double sigma, double half_width) {
    const double n = std::max(5.0, 2.0 * half_width / step + 1.0);
    return sigma * std::sqrt(3.0 / (n * half_width * half_width));
  };
  noise_[kDeltaRate] = log_.hasSteeringRate() ? noiseOf(values_[kDeltaRate])
                                              : derivativeNoise(noise_[kDelta], windows.steering);
  noise_[kSigma1] = log_.hasLateralVelocity() ? noiseOf(log_.vy)
                                              : derivativeNoise(std::max(noise_[kX], noise_[kY]), windows.position);
  if (!log_.v.empty()) {
    const std::vector<double> v = smoothed(log_.v, windows.position, 0);
    double mean = 0.0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    const double spread = std::sqrt(ss / static_cast<double>(v.size()));
    speed_varies_ = spread > 0.01 * std::fabs(mean) && spread > 3.0 * noise_[kSpeed];
  }
}

double LogSignals::fastestSpeed(double configured) const {
  if (!speed_varies_) return configured;
  double fastest = 0.0;
  for (double v : values_[kSpeed]) fastest = std::max(fastest, std::fabs(v));
  return fastest;
}

void LogSignals::throwMissing(Channel c) const {
  throw LaneKeepingError(log_.source + ": the log has no " + name(c) + " (a partial log)");
}

double LogSignals::nearestAlongSmoothed(Channel c, double t) const {
  const auto& smoothed = smoothed_[c];
  if (smoothed.empty()) return at(c, t);
  const Position p = positionAt(t);
  if (p.edge != 0) return p.edge < 0 ? values_[c].front() : values_[c].back();
  const std::size_t i = p.i;
  const double w = p.w;
  const std::size_t j = w > 0.5 ? i + 1 : i;  // the nearest sample
  const double along = smoothed[i] + w * (smoothed[i + 1] - smoothed[i]);
  return values_[c][j] + (along - smoothed[j]);
}

const char* LogSignals::name(Channel c) {
  static const char* names[] = {"x",         "y",          "psi",        "yaw_rate",     "delta",  "delta_des",
                                "torque",    "v",          "ay",         "delta_rate",   "delta_acceleration",
                                "delta_des_rate", "yaw_acceleration", "x_dot", "y_dot", "sigma1", "speed_rate"};
  return names[c];
}

}  // namespace lane_keeping
