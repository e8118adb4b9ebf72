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
/// Only the states L couples enter the exponential and the matrix products (a 4-state column in a
/// 9-state replay: a 16 x 16 exponential rather than 36 x 36); on the others the step is RK4's.
/// Cox & Matthews' scheme is fourth order when L commutes with N's Jacobian and at least second order
/// otherwise (Hochbruck & Ostermann 2005); the replays use it for a column's spring-damper, whose
/// coupling to the tire and friction terms is weak at the steps N allows.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace lane_keeping {

class Etdrk4 {
 public:
  /// The linear part L (square, finite; std::invalid_argument otherwise).
  explicit Etdrk4(Eigen::MatrixXd linear);

  /// Advances x by h. n(stage, const VectorXd& x, VectorXd& n_of_x) evaluates N (the derivative minus
  /// L x): stage 0 at t, stages 1 and 2 at t + h/2, stage 3 at t + h. The matrices are cached for the
  /// last four step lengths (a log's sample intervals repeat to rounding).
  template <class Nonlinear>
  void step(Nonlinear&& n, double h, Eigen::VectorXd& x) {
    advance(n, h, x, nullptr);
  }

  /// As step, and the state at t + h/2 into `mid` from the step's own stages, no further evaluation
  /// of N: the exact solution of x' = L x + p(t) for the quadratic p through N(t, x), the two
  /// midpoint stages' mean and N(t + h, c), which the scheme's last line integrates over the whole step
  /// (Cox & Matthews' last line is that integral over h), integrated over half of it:
  ///   x(t + h/2) = e^{Lh/2} x + [h/2 phi1 - 3h/4 phi2 + h/2 phi3] N_x + [h/2 phi2 - h/2 phi3] (N_a + N_b)
  ///                + [h/2 phi3 - h/4 phi2] N_c,   phi_k at L h/2
  /// (the integral of tau^k e^{(tau - s)L} is k! tau^{k+1} phi_{k+1}(tau L)). Where L is zero it is
  /// RK4's third-order continuous extension at theta = 1/2 (weights 5/24, 1/6, 1/6, -1/24).
  template <class Nonlinear>
  void stepWithMidpoint(Nonlinear&& n, double h, Eigen::VectorXd& x, Eigen::VectorXd& mid) {
    mid.resize(x.size());
    advance(n, h, x, &mid);
  }

  /// The matrix functions of L h (exposed for tests): e^{Lh}, phi1, phi2, phi3.
  struct Phi {
    Eigen::MatrixXd exp, phi1, phi2, phi3;
  };
  static Phi phiFunctions(const Eigen::MatrixXd& a);

 private:
  /// On the coupled states only (k x k); g1..g3 weigh the stages in the midpoint's dense output.
  struct Matrices {
    double h = -1.0;
    Eigen::MatrixXd e, e_half, p_half, f1, f2, f3, g1, g2, g3;
  };
  template <class Nonlinear>
  void advance(Nonlinear& n, double h, Eigen::VectorXd& x, Eigen::VectorXd* mid) {
    const Matrices& m = matricesFor(h);
    const double half = 0.5 * h;
    n(0, x, nx_);
    // On the states L does not couple the scheme is RK4's, in RK4's own order of operations.
    combine(m.e_half, x, m.p_half, nx_, a_);
    for (Eigen::Index i : plain_) a_[i] = x[i] + half * nx_[i];
    n(1, a_, na_);
    combine(m.e_half, x, m.p_half, na_, b_);
    for (Eigen::Index i : plain_) b_[i] = x[i] + half * na_[i];
    n(2, b_, nb_);
    for (Eigen::Index i : coupled_) scratch_[i] = 2.0 * nb_[i] - nx_[i];
    combine(m.e_half, a_, m.p_half, scratch_, c_);
    for (Eigen::Index i : plain_) c_[i] = x[i] + h * nb_[i];
    n(3, c_, nc_);
    if (mid != nullptr) {  // from the old x, before it changes
      weighStages(m.e_half, m.g1, m.g2, m.g3, x, *mid);
      for (Eigen::Index i : plain_) {
        (*mid)[i] = x[i] + h * ((5.0 / 24.0) * nx_[i] + (1.0 / 6.0) * (na_[i] + nb_[i]) - (1.0 / 24.0) * nc_[i]);
      }
    }
    // The coupled states from the old x, into scratch, before x changes.
    weighStages(m.e, m.f1, m.f2, m.f3, x, scratch_);
    for (Eigen::Index i : coupled_) x[i] = scratch_[i];
    const double sixth = h / 6.0;
    for (Eigen::Index i : plain_) x[i] += sixth * (((nx_[i] + 2.0 * na_[i]) + 2.0 * nb_[i]) + nc_[i]);
  }
  /// out = e x + w1 N_x + w2 (N_a + N_b) + w3 N_c on the coupled states: the step's end (e^{Lh}, f1..f3)
  /// or its midpoint (e^{Lh/2}, g1..g3) from the four stages.
  void weighStages(const Eigen::MatrixXd& e, const Eigen::MatrixXd& w1, const Eigen::MatrixXd& w2,
                   const Eigen::MatrixXd& w3, const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
    if (coupled_.size() == kColumnStates) return weighStages<kColumnStates>(e, w1, w2, w3, x, out);
    return weighStages<0>(e, w1, w2, w3, x, out);
  }
  /// out = e x + p v on the coupled states (plain loops: Eigen's dynamic-size product cost more in
  /// dispatch than a 4 x 4 block's arithmetic, 8 % of a diagnosis).
  void combine(const Eigen::MatrixXd& e, const Eigen::VectorXd& x, const Eigen::MatrixXd& p, const Eigen::VectorXd& v,
               Eigen::VectorXd& out) const {
    if (coupled_.size() == kColumnStates) return combine<kColumnStates>(e, x, p, v, out);
    return combine<0>(e, x, p, v, out);
  }
  /// A compliant column's spring-damper couples 4 states (the wheel's angle and rate, the column's):
  /// with the count known at compile time the loops unroll (the steering replay's ETDRK4 products were
  /// 29 % of a motor-side column fit's instructions). The same operations in the same order, so the same
  /// bits; K = 0 takes the count from coupled_.
  static constexpr std::size_t kColumnStates = 4;
  template <std::size_t K>
  void weighStages(const Eigen::MatrixXd& e, const Eigen::MatrixXd& w1, const Eigen::MatrixXd& w2,
                   const Eigen::MatrixXd& w3, const Eigen::VectorXd& x, Eigen::VectorXd& out) const {
    const Eigen::Index k = K > 0 ? static_cast<Eigen::Index>(K) : static_cast<Eigen::Index>(coupled_.size());
    for (Eigen::Index r = 0; r < k; ++r) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < k; ++j) {
        const Eigen::Index cj = coupled_[j];
        sum += e(r, j) * x[cj] + w1(r, j) * nx_[cj] + w2(r, j) * (na_[cj] + nb_[cj]) + w3(r, j) * nc_[cj];
      }
      out[coupled_[r]] = sum;
    }
  }
  template <std::size_t K>
  void combine(const Eigen::MatrixXd& e, const Eigen::VectorXd& x, const Eigen::MatrixXd& p, const Eigen::VectorXd& v,
               Eigen::VectorXd& out) const {
    const Eigen::Index k = K > 0 ? static_cast<Eigen::Index>(K) : static_cast<Eigen::Index>(coupled_.size());
    for (Eigen::Index r = 0; r < k; ++r) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < k; ++j) sum += e(r, j) * x[coupled_[j]] + p(r, j) * v[coupled_[j]];
      out[coupled_[r]] = sum;
    }
  }
  /// The step's matrices: from the cache when h equals a cached step to 1e-9 (relative), else
  /// computed into the least recently used entry. Four, because a shooting interval starting between
  /// samples has a first partial step, then the log's regular one, and a replay stepping over two
  /// samples at a time a single one where an odd count remains.
  const Matrices& matricesFor(double h);
  /// phi_k of L h on the states L couples (its nonzero rows and columns; on the others phi_k = 1 / k!).
  Phi phiOfStep(double h) const;

  Eigen::MatrixXd l_;
  std::vector<Eigen::Index> coupled_;  ///< states with a nonzero row or column of L
  std::vector<Eigen::Index> plain_;    ///< the others
  static constexpr int kCached = 4;
  Matrices cache_[kCached];
  long uses_[kCached] = {};  ///< the clock of each entry's last use (least recently used is replaced)
  long clock_ = 0;
  Eigen::VectorXd nx_, na_, nb_, nc_, a_, b_, c_, scratch_;
};

}  // namespace lane_keeping
