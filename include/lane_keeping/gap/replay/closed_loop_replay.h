#pragma once
/// The full closed loop simulated from a log's first sample — "how far" as a user sees it when they
/// add an effect to their simulation — and the check that a configuration keeps that loop bounded
/// over the log's span (the logged car did: a fitted effect under which the loop diverges
/// contradicts the log, see diagnosis.cpp).
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

/// `config` started at the log's first sample: pose, yaw rate, steering angle and rate from the log,
/// sigma1 = `sigma1_0`; run for `duration` seconds (clamped to the log's span), logged at `log_rate`; a
/// logged speed that varies followed in time (withLoggedSpeed: the closed-loop replay, the bounded-loop
/// checks and how far drive as the car drove).
SimConfig closedLoopConfigOnLog(SimConfig config, const LogSignals& log, double sigma1_0, double duration,
                                double log_rate);

struct ClosedLoopReplay {
  double gap = std::numeric_limits<double>::quiet_NaN();  ///< RMS over y, yaw rate, delta of RMS(residual)/RMS(measured)
  /// Each channel's RMS(residual)/RMS(measured), y, yaw rate, delta: `gap` is their RMS.
  std::array<double, 3> channel_gaps{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::quiet_NaN()};
  std::vector<double> t, y, yaw_rate, delta;             ///< simulated, at the log's sample times
  std::string note;                                      ///< why the replay failed or diverged ("" if it did not)
};

/// Simulates the closed loop of `config` over the whole log and compares y, yaw rate and delta. `changes`
/// (times from the log's start) take effect mid-run, as lk_simulate --change makes them (change_schedule.h).
ClosedLoopReplay closedLoopReplay(const SimConfig& config, const LogSignals& log, double sigma1_0,
                                  const std::vector<TimedChange>& changes = {});

/// What a perfect model's closed-loop replay would leave of each channel's gap (y, yaw rate, delta): the log's
/// white noise at `sigma` (m, rad/s, rad; estimatedNoise) over the channel's RMS(measured), as `gap` divides.
/// A residual is the model's miss plus that noise, uncorrelated: E[RMS^2] = miss^2 + sigma^2.
std::array<double, 3> closedLoopNoiseFloor(const LogSignals& log, const std::array<double, 3>& sigma);

/// The replay's gap net of `floor` (closedLoopNoiseFloor), channel by channel in quadrature:
/// sqrt(mean over channels of max(0, gap_c^2 - floor_c^2)); NaN where the replay gave no gap.
double netClosedLoopGap(const ClosedLoopReplay& replay, const std::array<double, 3>& floor);

struct LoopDivergence {
  bool diverged = false;
  double time = std::numeric_limits<double>::quiet_NaN();  ///< [s] after the log's start
  std::string message;
};

/// Runs the closed loop of `config` on the log for `horizon` seconds (at most the log's span) and
/// reports whether it diverged (DivergenceMonitor's limits; an invalid or unschedulable configuration
/// counts as diverged at t = 0) or its steering-torque command left +-`max_torque` (checked at 200 Hz).
LoopDivergence closedLoopDivergence(const SimConfig& config, const LogSignals& log, double sigma1_0, double horizon,
                                    double max_torque = std::numeric_limits<double>::infinity());

}  // namespace lane_keeping
