#include "lane_keeping/sim/etdrk4.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include <unsupported/Eigen/MatrixFunctions>

namespace lane_keeping {

Etdrk4::Etdrk4(Eigen::MatrixXd linear) : l_(std::move(linear)) {
  if (l_.rows() != l_.cols()) throw std::invalid_argument("Etdrk4: the linear part must be square");
  if (!l_.allFinite()) throw std::invalid_argument("Etdrk4: the linear part is not finite");
  const Eigen::Index n = l_.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const bool coupled = (l_.row(i).array() != 0.0).any() || (l_.col(i).array() != 0.0).any();
    (coupled ? coupled_ : plain_).push_back(i);
  }
  for (Eigen::VectorXd* v : {&nx_, &na_, &nb_, &nc_, &a_, &b_, &c_, &scratch_}) v->resize(n);
}

Etdrk4::Phi Etdrk4::phiFunctions(const Eigen::MatrixXd& a) {
  // Van Loan's augmentation: the exponential of [[A, I, 0, 0], [0, 0, I, 0], [0, 0, 0, I], [0, 0, 0, 0]]
  // holds e^A, phi1(A), phi2(A), phi3(A) along its first block row (each phi_k is the integral of
  // the one before, which the chain of identities performs).
  const Eigen::Index n = a.rows();
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(4 * n, 4 * n);
  s.topLeftCorner(n, n) = a;
  for (int k = 0; k < 3; ++k) s.block(k * n, (k + 1) * n, n, n).setIdentity();
  const Eigen::MatrixXd m = s.exp();
  return {m.block(0, 0, n, n), m.block(0, n, n, n), m.block(0, 2 * n, n, n), m.block(0, 3 * n, n, n)};
}

namespace {

/// Balances `a` in place by a diagonal similarity D^-1 A D with powers of two (exact in floating
/// point; Parlett & Reinsch 1969, as LAPACK's gebal), returning D. A column's L h mixes 1e-3 (h) with
/// 1e5 (k h / J_c): unbalanced, the scaling and squaring of its exponential lost eight digits (a
/// forced oscillator at w = 1e4 rad/s stepped at 2 ms was 2e-8 off its closed form, 3e-15 balanced).
Eigen::VectorXd balance(Eigen::MatrixXd& a) {
  const Eigen::Index n = a.rows();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  for (bool changed = true, first = true; changed || first; first = false) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double c = 0.0, r = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (j == i) continue;
        c += std::fabs(a(j, i));
        r += std::fabs(a(i, j));
      }
      if (c == 0.0 || r == 0.0) continue;
      const double total = c + r;
      double f = 1.0;
      while (c < r / 2.0) c *= 2.0, r /= 2.0, f *= 2.0;
      while (c >= 2.0 * r) c /= 2.0, r *= 2.0, f /= 2.0;
      if (c + r < 0.95 * total) {
        changed = true;
        d[i] *= f;
        a.col(i) *= f;
        a.row(i) /= f;
      }
    }
  }
  return d;
}

}  // namespace

Etdrk4::Phi Etdrk4::phiOfStep(double h) const {
  const Eigen::Index k = static_cast<Eigen::Index>(coupled_.size());
  if (k == 0) return {};
  Eigen::MatrixXd block(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    for (Eigen::Index j = 0; j < k; ++j) block(i, j) = h * l_(coupled_[i], coupled_[j]);
  }
  const Eigen::VectorXd d = balance(block);
  Phi phi = phiFunctions(block);
  // phi(A) = D phi(D^-1 A D) D^-1.
  for (Eigen::MatrixXd* f : {&phi.exp, &phi.phi1, &phi.phi2, &phi.phi3}) {
    for (Eigen::Index i = 0; i < k; ++i) {
      for (Eigen::Index j = 0; j < k; ++j) (*f)(i, j) *= d[i] / d[j];
    }
  }
  return phi;
}

const Etdrk4::Matrices& Etdrk4::matricesFor(double h) {
  ++clock_;
  int oldest = 0;
  for (int k = 0; k < kCached; ++k) {
    if (std::fabs(h - cache_[k].h) <= 1e-9 * std::fabs(h)) {
      uses_[k] = clock_;
      return cache_[k];
    }
    if (uses_[k] < uses_[oldest]) oldest = k;
  }
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("Etdrk4: the step must be positive and finite");
  Matrices& m = cache_[oldest];
  const Phi half = phiOfStep(0.5 * h);
  const Phi full = phiOfStep(h);
  m.e_half = half.exp;
  m.p_half = (0.5 * h) * half.phi1;
  m.e = full.exp;
  m.f1 = h * (full.phi1 - 3.0 * full.phi2 + 4.0 * full.phi3);
  m.f2 = (2.0 * h) * (full.phi2 - 2.0 * full.phi3);
  m.f3 = h * (4.0 * full.phi3 - full.phi2);
  // The midpoint's dense output (stepWithMidpoint): the same quadratic in N integrated over h/2.
  m.g1 = (0.5 * h) * half.phi1 - (0.75 * h) * half.phi2 + (0.5 * h) * half.phi3;
  m.g2 = (0.5 * h) * (half.phi2 - half.phi3);
  m.g3 = (0.5 * h) * half.phi3 - (0.25 * h) * half.phi2;
  m.h = h;
  uses_[oldest] = clock_;
  return m;
}

}  // namespace lane_keeping
