#pragma once
/// Exponential time differencing, fourth order: ETDRK4 of Cox & Matthews 2002 ("Exponential time
/// differencing for stiff systems", J. Comput. Phys. 176, 430-455), for x' = L x + N(t, x) with a
/// constant stiff linear part L and a non-stiff rest N:
///   a = e^{Lh/2} x + (h/2) phi1(Lh/2) N(t, x)
///   b = e^{Lh/2} x + (h/2) phi1(Lh/2) N(t + h/2, a)
///   c = e^{Lh/2} a + (h/2) phi1(Lh/2) (2 N(t + h/2, b) - N(t, x))
///   x(t + h) = e^{Lh} x + h [(phi1 - 3 phi2 + 4 phi3) N(t, x) + 2 (phi2 - 2 phi3) (N(t + h/2, a)
///              + N(t + h/2, b)) + (4 phi3 - phi2) N(t + h, c)],   phi_k at Lh,
/// phi1(z) = (e^z - 1) / z, phi2(z) = (e^z - 1 - z) / z^2, phi3(z) = (e^z - 1 - z - z^2 / 2) / z^3.
///
/// L enters only through matrix functions, so the step is bounded by N alone: a stiff linear mode is
/// stepped exactly, and the solution of x' = L x + const is exact at any step. Where L is zero the
/// scheme is classical RK4 (phi_k(0) = 1 / k!). The matrices come from one exponential of a block
/// matrix per step length (Van Loan 1978; Sidje's Expokit uses the same augmentation):
///   exp([[A, I, 0, 0], [0, 0, I, 0], [0, 0, 0, I], [0, 0, 0, 0]]) = [[e^A, phi1(A), phi2(A), phi3(A)], ...].
/// Only the states L couples enter the exponential (a 4-state column in a 9-state replay: 16 x 16
/// rather than 36 x 36). Cox & Matthews' scheme is fourth order when L commutes with N's Jacobian and at least second order
/// otherwise (Hochbruck & Ostermann 2005); the replays use it for a column's spring-damper, whose
/// coupling to the tire and friction terms is weak at the steps N allows.
#include <vector>

#include <Eigen/Core>

namespace lane_keeping {

class Etdrk4 {
 public:
  /// The linear part L (square, finite; std::invalid_argument otherwise).
  explicit Etdrk4(Eigen::MatrixXd linear);

  const Eigen::MatrixXd& linear() const { return l_; }

  /// Advances x by h. n(stage, const VectorXd& x, VectorXd& n_of_x) evaluates N (the derivative minus
  /// L x): stage 0 at t, stages 1 and 2 at t + h/2, stage 3 at t + h. The matrices are cached for the
  /// last two step lengths (a log's sample intervals repeat to rounding).
  template <class Nonlinear>
  void step(Nonlinear&& n, double h, Eigen::VectorXd& x) {
    const Matrices& m = matricesFor(h);
    n(0, x, nx_);
    a_.noalias() = m.e_half * x;
    a_.noalias() += m.p_half * nx_;
    n(1, a_, na_);
    b_.noalias() = m.e_half * x;
    b_.noalias() += m.p_half * na_;
    n(2, b_, nb_);
    c_.noalias() = m.e_half * a_;
    scratch_ = 2.0 * nb_ - nx_;
    c_.noalias() += m.p_half * scratch_;
    n(3, c_, nc_);
    scratch_ = na_ + nb_;
    a_.noalias() = m.e * x;  // (a is spent: it holds the result)
    a_.noalias() += m.f1 * nx_;
    a_.noalias() += m.f2 * scratch_;
    a_.noalias() += m.f3 * nc_;
    x = a_;
  }

  /// The matrix functions of L h (exposed for tests): e^{Lh}, phi1, phi2, phi3.
  struct Phi {
    Eigen::MatrixXd exp, phi1, phi2, phi3;
  };
  static Phi phiFunctions(const Eigen::MatrixXd& a);

 private:
  struct Matrices {
    double h = -1.0;
    Eigen::MatrixXd e, e_half, p_half, f1, f2, f3;
  };
  /// The step's matrices: from the cache when h equals a cached step to 1e-9 (relative), else
  /// computed into the older of the two entries. Two, because a shooting interval starting between
  /// samples alternates a first partial step with the log's regular one.
  const Matrices& matricesFor(double h);
  /// phi_k of L h on the states L couples (its nonzero rows and columns), 1 / k! on the others.
  Phi phiOfStep(double h) const;

  Eigen::MatrixXd l_;
  std::vector<Eigen::Index> coupled_;  ///< states with a nonzero row or column of L
  Matrices cache_[2];
  int older_ = 0;
  Eigen::VectorXd nx_, na_, nb_, nc_, a_, b_, c_, scratch_;
};

}  // namespace lane_keeping
