#pragma once
/// What a stability computation will cost, known before it starts: `lk_stability fig3 --n 1000000`,
/// `roots --degree 100000` and a 100000 x 100000 chart ended in std::bad_alloc naming no option, and
/// `--degree 1500` ran for hours. A spectrum (dde_spectrum.h) solves a dense eigenvalue problem whose
/// order is the state count plus the Chebyshev degree times the delay terms' ranks, so its memory grows
/// with the order squared and its time with the order cubed; a chart computes one spectrum per point.
#include <cstddef>
#include <string>

#include "lane_keeping/analysis/linear_delay_system.h"
#include "lane_keeping/common/resources.h"

namespace lane_keeping {

struct SpectrumCost {
  int order = 0;         ///< of the collocation matrix (dde_spectrum.h)
  double bytes = 0.0;    ///< peak memory of one spectrum [bytes]
  double seconds = 0.0;  ///< time of one spectrum on one core [s]
};

/// Measured on this project's 2-core VM (docs/reliability.md): the paper's loop has order 13 + 4 x degree
/// (four delay terms of rank 1); one spectrum at degree 150 (order 613) took 2.1 s and at degree 250
/// (order 1013) 11.3 s beside builds (load 11), about 9-11e-9 s x order^3, and a third of that on a quiet
/// machine: the estimate takes 5e-9. Memory: about kCopies dense real matrices of the order (38 MB peak at
/// order 1013).
constexpr double kSecondsPerOrderCubed = 5e-9;
constexpr double kCopies = 4.0;

/// The cost of one spectrum of `system` at `degree` per delay line (the ranks as computeSpectrum finds
/// them with `rank_tolerance`). The time is an estimate within a factor of a few; the order is exact.
SpectrumCost spectrumCost(const LinearDelaySystem& system, int degree, double rank_tolerance = 1e-12);

}  // namespace lane_keeping
