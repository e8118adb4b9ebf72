#pragma once
/// The effective number of independent samples of a series of deviations (from a fit or a mean), n (1 - rho1) /
/// (1 + rho1) with rho1 its lag-1 autocorrelation (clamped to [0, 1)), at least 1 and at most n: 20 Hz samples of a
/// slow error (a body slip, an integrated sensor's noise, a driver's corrections) are not as many independent ones,
/// and a standard error counted with n would be too small by the square root of the ratio.
#include <cstddef>
#include <vector>

namespace lane_keeping {

/// `deviations` may hold several stretches one after the other: `starts` lists where each after the first
/// begins, and no lag is taken across them.
double effectiveSampleCount(const std::vector<double>& deviations, const std::vector<std::size_t>& starts = {});

}  // namespace lane_keeping
