#pragma once
/// What a replay's residual still holds, as system identification tests a model (Ljung, System
/// Identification, §16.6): whether the residual is white, and whether it is independent of the input
/// that drives the subsystem. Both statistics are computed within shooting intervals only (a residual
/// restarts at each interval) and are compared, never with a chi-square table, but with the same
/// statistics of the noise-only null draws (noise_null.h): noise propagated through a replay's inputs
/// is not white either, and only the draws know by how much.
///
///  * whiteness  Q = sum over lags k = 1..m of N rho(k)^2 (Ljung-Box without the small-sample factor),
///               rho(k) the residual's autocorrelation at lag k over pairs inside one interval;
///  * input      Q_u = sum over lags k = 0..m of N rho_ru(k)^2, rho_ru(k) the correlation of the residual
///               at t with the input at t - k (the past input: a model that misses a dynamic effect
///               leaves a residual that follows the input's history).
/// N is the number of residual samples. m = kResidualLags.
#include <string>
#include <vector>

#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

constexpr int kResidualLags = 20;

struct ResidualStructure {
  double whiteness = 0.0;          ///< Q of the residual (summed over the subsystem's traces)
  double input_correlation = 0.0;  ///< Q_u against the subsystem's input (summed over its traces)
};

/// The statistics of `replay`'s residual; `input` holds the subsystem's input at every sample of its
/// (concatenated) traces — the same length as each trace — or is empty (then input_correlation = 0).
ResidualStructure residualStructure(const SubsystemReplay& replay, const std::vector<double>& input);

}  // namespace lane_keeping
