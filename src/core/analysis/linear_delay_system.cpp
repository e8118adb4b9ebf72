#include "lane_keeping/analysis/linear_delay_system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lane_keeping {

void LinearDelaySystem::add(double tau, const Eigen::MatrixXd& a) {
  if (!std::isfinite(tau) || tau < 0.0) {
    throw std::invalid_argument("LinearDelaySystem::add: delay " + std::to_string(tau) + " s must be finite and >= 0");
  }
  if (a.rows() != a0.rows() || a.cols() != a0.cols()) {
    throw std::invalid_argument("LinearDelaySystem::add: matrix is " + std::to_string(a.rows()) + "x" +
                                std::to_string(a.cols()) + ", the system has " + std::to_string(a0.rows()) + " states");
  }
  constexpr double kSameDelay = 1e-15;  // [s]: sums of the same hop delays in another order
  if (tau <= kSameDelay) {
    a0 += a;
    return;
  }
  for (auto& term : delayed) {
    if (std::fabs(term.delay - tau) <= kSameDelay) {
      term.matrix += a;
      return;
    }
  }
  delayed.push_back({tau, a});
  std::sort(delayed.begin(), delayed.end(), [](const DelayTerm& l, const DelayTerm& r) { return l.delay < r.delay; });
}

Eigen::MatrixXcd LinearDelaySystem::characteristicMatrix(Complex lambda) const {
  Eigen::MatrixXcd m = -a0.cast<Complex>();
  m.diagonal().array() += lambda;
  for (const auto& term : delayed) m -= std::exp(-lambda * term.delay) * term.matrix.cast<Complex>();
  return m;
}

Eigen::MatrixXcd LinearDelaySystem::characteristicMatrixDerivative(Complex lambda) const {
  Eigen::MatrixXcd m = Eigen::MatrixXcd::Identity(size(), size());
  for (const auto& term : delayed) m += (term.delay * std::exp(-lambda * term.delay)) * term.matrix.cast<Complex>();
  return m;
}

double LinearDelaySystem::coefficientNorm() const {
  double sum = a0.squaredNorm();
  for (const auto& term : delayed) sum += term.matrix.squaredNorm();
  return std::sqrt(sum);
}

}  // namespace lane_keeping
