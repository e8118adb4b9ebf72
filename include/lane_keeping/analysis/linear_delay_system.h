#pragma once
/// A linear retarded delay-differential system with discrete delays (Beregi eq 20, generalised):
///   x'(t) = A0 x(t) + sum_j A_j x(t - tau_j),      0 < tau_1 < tau_2 < ... (distinct)
/// and its characteristic matrix (Beregi eq 21, written as lambda I - ...):
///   Delta(lambda) = lambda I - A0 - sum_j A_j exp(-lambda tau_j),   D(lambda) = det Delta(lambda).
/// The characteristic roots are the lambda with D(lambda) = 0; the system is exponentially stable iff
/// every root has a negative real part.
#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace lane_keeping {

using Complex = std::complex<double>;

struct DelayTerm {
  double delay = 0.0;      ///< tau_j [s], > 0
  Eigen::MatrixXd matrix;  ///< A_j
};

struct LinearDelaySystem {
  Eigen::MatrixXd a0;                   ///< A0 (undelayed part)
  std::vector<DelayTerm> delayed;       ///< distinct positive delays, ascending
  std::vector<std::string> state_names; ///< one per state, e.g. "y", "delta", "front.z_y", "z"

  int size() const { return static_cast<int>(a0.rows()); }
  double maxDelay() const { return delayed.empty() ? 0.0 : delayed.back().delay; }

  /// Adds A to the term of delay tau (A0 when tau == 0), merging delays that agree to 1e-15 s.
  /// Throws std::invalid_argument for a negative or non-finite tau or a wrongly sized A.
  void add(double tau, const Eigen::MatrixXd& a);

  /// Delta(lambda) = lambda I - A0 - sum_j A_j exp(-lambda tau_j).
  Eigen::MatrixXcd characteristicMatrix(Complex lambda) const;
  /// d Delta / d lambda = I + sum_j tau_j A_j exp(-lambda tau_j).
  Eigen::MatrixXcd characteristicMatrixDerivative(Complex lambda) const;
  /// Frobenius norm of [A0, A_1, ...]: the scale for relative residuals.
  double coefficientNorm() const;
};

}  // namespace lane_keeping
