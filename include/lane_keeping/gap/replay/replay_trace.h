#pragma once
/// What a subsystem replay produces and how it is run (subsystem_replay.h): the compared outputs
/// (measured and predicted, with their shooting-interval breaks), the time segments replayed, and the
/// shooting horizons and steps of the integrated replays.
#include <string>
#include <utility>
#include <vector>

namespace lane_keeping {

struct TimeSegment {
  double t0 = 0.0, t1 = 0.0;  ///< [s], half-open [t0, t1)
};

/// One compared output of a replay.
struct ReplayTrace {
  std::string name;                     ///< e.g. "delta", "yaw_rate"
  std::vector<double> t, measured, predicted;
  double scale = 1.0;                   ///< normalisation: RMS of the measured output over the whole log
  std::vector<std::size_t> breaks;      ///< indices where a new shooting interval (or log) starts
  std::vector<double> residual() const;  ///< (measured - predicted) / scale
  /// Appends another trace of the same output (another log or segment set); keeps the breaks.
  void append(const ReplayTrace& other);
};

struct SubsystemReplay {
  std::string name;                  ///< tracker | actuator | steering | chassis
  std::vector<ReplayTrace> traces;
  int diverged_intervals = 0;        ///< shooting intervals that left the model's domain
  /// chassis only: the model's estimate of sigma1 (lateral velocity of G) at the compared times,
  /// fitted through the interval's initial conditions — the steering replay's best sigma1 input.
  std::vector<std::pair<double, double>> sigma1_estimate;
};

struct ReplayOptions {
  double steering_horizon = 0.15;    ///< [s]
  double steering_step = 2e-3;       ///< longest integration step [s] (shorter for fast tires and friction,
                                     ///< and for a progressive column; a linear column is stepped exactly)
  /// A linear column's replay steps over two samples at a time where both fit in the step, the first
  /// from the step's dense output (steering_replay.cpp); false: every sample ends a step.
  bool steering_midpoint_output = true;
  double chassis_horizon = 2.0;      ///< [s]
  double chassis_step = 4e-3;        ///< RK4 step [s] (reduced automatically for fast tire dynamics)
  double chassis_compare_period = 0.01;  ///< compare the chassis outputs at most at 100 Hz [s]
  bool estimate_initial_conditions = true;  ///< project out the nuisance initial conditions
};

}  // namespace lane_keeping
