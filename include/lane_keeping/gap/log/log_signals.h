#pragma once
/// Continuous-time view of a log for the replays: linear interpolation of every column, and the
/// derivatives the replays need, estimated by local quadratic least squares (a Savitzky-Golay filter
/// for any sampling) so that measurement noise is not differentiated raw:
///   steering rate  delta_dot  (the delta_rate column if present, else d/dt delta), delta_ddot,
///   desired rate   delta_des_dot (the derivative of a cubic spline through delta_des: computed by the
///                  tracker, not measured, so it is not smoothed), yaw acceleration d/dt yaw_rate,
///   velocity of G  x_dot, y_dot,  and sigma1 = -x_dot sin(psi) + y_dot cos(psi) (row 2 of Beregi eq 1),
///                  or the logged lateral velocity vy where the log has one (gap_log.h),
///   the rate of the speed dV/dt (when the log has v), and, kept for nearestAlongSmoothed only, the pose
///   x, y, psi and the steering angle and rate smoothed by the same filter (value, zero lag).
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/sample_index.h"
#include "lane_keeping/sim/sensor_params.h"

namespace lane_keeping {

struct SmoothingWindows {
  double steering = 0.015;  ///< half-width [s] for delta, delta_des and yaw-rate derivatives
  double position = 0.10;   ///< half-width [s] for the velocity of G from x, y
  double pose = 0.05;       ///< half-width [s] for the smoothed pose x, y, psi (tracker replay)
};

class LogSignals {
 public:
  enum Channel {
    kX, kY, kPsi, kYawRate, kDelta, kDeltaDes, kTorque, kSpeed, kLateralAcceleration,
    kDeltaRate, kDeltaAcceleration, kDeltaDesRate, kYawAcceleration, kXDot, kYDot, kSigma1, kSpeedRate, kChannels
  };

  explicit LogSignals(GapLog log, const SmoothingWindows& windows = {});

  const GapLog& log() const { return log_; }
  double start() const { return log_.t.front(); }
  double end() const { return log_.t.back(); }
  bool has(Channel c) const { return !values_[c].empty(); }
  /// The log records a speed that varies beyond its noise: the RMS deviation of the smoothed speed from
  /// its mean exceeds 1 % of the mean and three times the speed's noise. The replays then take V and
  /// dV/dt (kSpeedRate) from the log instead of the configured constant speed.
  bool speedVaries() const { return speed_varies_; }
  /// The fastest logged speed (the configured one when the speed does not vary), for step bounds.
  double fastestSpeed(double configured) const;
  /// Where a time falls among the samples: between samples i and i + 1 at weight w of the second, or
  /// before the first (edge -1) or after the last (edge +1), where at() clamps. Found once, it serves
  /// every channel read at that time: a replay's derivative reads three to five, and finding the
  /// interval again for each was 9-11 % of lk_bench_gap's CPU (perf, 2026-11-27).
  struct Position {
    std::size_t i = 0;
    double w = 0.0;
    int edge = 0;
  };
  /// The position of t, found by indexAtOrBefore.
  Position positionAt(double t) const {
    if (const int edge = edgeOf(t)) return Position{0, 0.0, edge};
    // (indexAtOrBefore gives the last sample for a NaN time, which has no interval after it.)
    return between(std::min(indexAtOrBefore(t), log_.t.size() - 2), t);
  }
  /// The same position, found from the sample `*hint` (updated): a few steps for the near-monotone
  /// queries of a replay, indexAtOrBefore beyond them (a replay that starts its next interval, or its
  /// lead-in, seconds back).
  Position positionAt(double t, std::size_t* hint) const {
    if (const int edge = edgeOf(t)) return Position{0, 0.0, edge};
    const std::vector<double>& times = log_.t;
    std::size_t i = std::min(*hint, times.size() - 2);
    for (int step = 0;; ++step) {
      if (i > 0 && times[i] > t) {
        --i;
      } else if (i + 2 < times.size() && times[i + 1] <= t) {
        ++i;
      } else {
        break;  // times[i] <= t < times[i + 1]: the sample indexAtOrBefore finds (or t is NaN)
      }
      if (step == kHintWalk) {
        i = indexAtOrBefore(t);
        break;
      }
    }
    *hint = i;
    return between(i, t);
  }
  /// Linear interpolation at a position (the same value as at(c, t) at the position of t).
  double at(Channel c, const Position& p) const {
    const std::vector<double>& v = values_[c];
    if (v.empty()) throwMissing(c);
    if (p.edge != 0) return p.edge < 0 ? v.front() : v.back();
    return v[p.i] + p.w * (v[p.i + 1] - v[p.i]);
  }
  /// Linear interpolation; clamps to the first/last sample outside the log.
  double at(Channel c, double t) const { return at(c, positionAt(t)); }
  /// Same, starting the search from `*hint` (updated): O(1) for the near-monotone queries of a replay.
  double at(Channel c, double t, std::size_t* hint) const { return at(c, positionAt(t, hint)); }
  /// The sample nearest to t, carried to t along the channel's smoothed curve (x, y, psi, delta,
  /// delta_rate, yaw_rate, ay; other channels: plain interpolation): the noise of one sample wherever t
  /// falls.
  /// Linear interpolation between white-noisy samples averages two of them, so its noise midway is
  /// 1 / sqrt(2) of a sample's, and a delay fitted through it drifts to half-sample offsets (the
  /// tracker replay fitted 18.9 ms of extra sensing delay on noise-only 500 Hz logs: its residual was
  /// 0.039 at the true delay and 0.028 2.5 samples away). Smoothing alone would fix that but colour
  /// the residual, whose noise floor the scores estimate as white. (Interpolation colours it too: the
  /// actuator replay's delta at t - 0.1 ms on a 1 kHz log is 0.9 / 0.1 of two samples, whose second
  /// differences put the floor at 0.70 of the variance and left a noise "excess" of ~0.02.)
  double nearestAlongSmoothed(Channel c, double t) const;
  /// Values at the sample times.
  const std::vector<double>& samples(Channel c) const { return values_[c]; }
  const std::vector<double>& times() const { return log_.t; }
  /// Index of the last sample at or before t (0 if before the start): O(1) on a uniform log.
  std::size_t indexAtOrBefore(double t) const { return index_.atOrBefore(log_.t, t); }

  static const char* name(Channel c);

  /// The log with `sensors` undone: the true motion the physics replays compare with
  /// (sensor_correction.h, where it is defined and explained).
  LogSignals withSensorsUndone(const SensorParams& sensors) const;

  /// White-noise standard deviation of a channel, estimated from fourth differences of the samples
  /// (var(d4 x) = 70 sigma^2 for white noise; a smooth signal contributes ~h^4 x'''' ).
  /// For derived channels (delta_rate without a column, sigma1 without vy) it is propagated through the
  /// least-squares derivative: sigma' ~ sigma sqrt(3 / (n w^2)) for n samples in a half-width w.
  double noise(Channel c) const { return noise_[c]; }

 private:
  /// Steps from a hint before positionAt(t, hint) asks indexAtOrBefore.
  static constexpr int kHintWalk = 4;
  [[noreturn]] void throwMissing(Channel c) const;
  /// -1 at or before the first sample (and anywhere in a log of one sample), +1 at or after the last, 0
  /// between (and for NaN, whose position gives NaN).
  int edgeOf(double t) const {
    return log_.t.size() < 2 || t <= log_.t.front() ? -1 : (t >= log_.t.back() ? 1 : 0);
  }
  /// The position of t between samples i and i + 1.
  Position between(std::size_t i, double t) const {
    return Position{i, (t - log_.t[i]) / (log_.t[i + 1] - log_.t[i]), 0};
  }

  GapLog log_;
  SampleIndex index_;
  std::vector<std::vector<double>> values_;
  std::vector<std::vector<double>> smoothed_;  ///< per channel; empty where nearestAlongSmoothed interpolates
  std::vector<double> noise_;
  bool speed_varies_ = false;
};

/// sigma of white noise in a series by fourth differences.
double fourthDifferenceNoise(const std::vector<double>& values);

/// First derivative at every sample of the natural cubic spline through (t, values): for smooth,
/// noise-free series (delta_des). On a 100 Hz log the 0.5-12 Hz identification excitation in delta_des
/// is 8 samples per period at its top; the 5-point quadratic fit used before lost 29 % of the rate
/// there, and the actuator replay of a noise-free log missed the torque by 0.07-0.13 (normalised).
std::vector<double> splineDerivative(const std::vector<double>& t, const std::vector<double>& values);

/// Local quadratic least-squares fit of values over [t_i - half_width, t_i + half_width] (at least
/// two neighbours each side): its value (order 0), first (order 1) or second (order 2) derivative at
/// every sample.
std::vector<double> smoothedDerivative(const std::vector<double>& t, const std::vector<double>& values,
                                       double half_width, int order);

}  // namespace lane_keeping
