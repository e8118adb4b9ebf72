#pragma once
/// Rightmost characteristic roots of a LinearDelaySystem (roots of Beregi eq 21) by spectral
/// collocation of the infinitesimal generator (Breda, Maset & Vermiglio, SIAM J Sci Comput 27(2),
/// 2005; Chebyshev matrix of Trefethen 2000, see chebyshev.h), each root then refined by Newton on
/// det Delta(lambda) = 0.
///
/// Resolution. The delays differ by three orders of magnitude (tau_2 ~ 0.1-2 ms, tau_1 + tau_2 ~
/// 0.2 s) and the lower-level mode oscillates at 100-150 Hz, i.e. ~25 periods over the long delay:
/// one Chebyshev grid on [-(tau_1 + tau_2), 0] needs degree ~120 before its rightmost eigenvalue
/// stops being spurious (measured: test/core/dde_spectrum_test.cpp). We therefore collocate each
/// delay line on its own interval. Every A_j has low rank r_j (the tracker output, the measured
/// steering angle and rate, the torque): A_j = B_j C_j (SVD). With w_j(t, theta) = C_j x(t + theta)
/// on [-tau_j, 0] the DDE is the transport system
///   x' = A0 x + sum_j B_j w_j(-tau_j),   d w_j/dt = d w_j/d theta,   w_j(t, 0) = C_j x(t),
/// whose characteristic equation is exactly eq 21. Each w_j is a polynomial of degree M in theta
/// collocated at the Chebyshev points of [-tau_j, 0]: the delayed value is the end node (no
/// interpolation), the short delay gets as fine a grid as the long one, and the matrix has order
/// n + M sum_j r_j (7 + 4M for the paper's loop) instead of n (M + 1).
///
/// The discretised eigenvalues are the seeds; Newton (d log det Delta / d lambda = tr(Delta^-1
/// Delta'), Jacobi's formula) makes each one a root of the exact characteristic equation to
/// ~1e-12 relative, so the reported roots do not depend on M once the seeds lie in their basins.
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "lane_keeping/analysis/linear_delay_system.h"

namespace lane_keeping {

struct SpectrumOptions {
  int degree = 24;                  ///< Chebyshev degree M per delay line
  int seeds = 10;                   ///< rightmost discretised eigenvalues (Im >= 0) refined by Newton
  int newton_iterations = 40;
  double newton_tolerance = 1e-12;  ///< Newton stops when |step| <= tol max(1, |lambda|)
  double rank_tolerance = 1e-12;    ///< singular values below tol * largest are dropped from A_j
};

struct CharacteristicRoot {
  Complex value;            ///< the root, Im >= 0 (its conjugate is a root too)
  Complex discretised;      ///< the collocation eigenvalue it was refined from
  bool refined = false;     ///< Newton converged (else `value` is the unrefined eigenvalue)
  int newton_iterations = 0;
  double frequencyHz() const;
};

struct Spectrum {
  std::vector<CharacteristicRoot> roots;  ///< distinct, rightmost first, one per conjugate pair
  int dimension = 0;                      ///< order of the collocation matrix
  std::vector<int> ranks;                 ///< r_j of each delay term
  /// Largest real part among `roots` (-inf if there are none).
  double abscissa() const;
  /// Roots with Re > tolerance, conjugates counted (so a complex pair counts 2).
  int unstableCount(double tolerance = 1e-9) const;
};

/// The collocation matrix (order n + M sum_j r_j). `ranks` receives r_j.
Eigen::MatrixXd collocationMatrix(const LinearDelaySystem& system, int degree, double rank_tolerance = 1e-12,
                                  std::vector<int>* ranks = nullptr);

/// Rightmost roots: eigenvalues of the collocation matrix, the `seeds` rightmost refined by Newton.
/// Throws std::invalid_argument for degree < 2, seeds < 1 or an empty system.
Spectrum computeSpectrum(const LinearDelaySystem& system, const SpectrumOptions& options = {});

/// Newton on det Delta(lambda) = 0 from *lambda; true if it converged (then *lambda is the root).
bool refineRoot(const LinearDelaySystem& system, Complex* lambda, int max_iterations = 40,
                double tolerance = 1e-12, int* iterations = nullptr);

/// Smallest singular value of Delta(lambda) divided by (|lambda| + coefficientNorm()): ~1e-16 at a
/// root. For checks (SVD: use on small systems).
double relativeResidual(const LinearDelaySystem& system, Complex lambda);

}  // namespace lane_keeping
