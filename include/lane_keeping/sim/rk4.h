#pragma once
/// Classical fixed-step Runge-Kutta (4th order), with a workspace so a step allocates nothing.
/// The derivative callable receives the stage index so the caller can supply the input at the
/// stage's time: stage 0 at t, stages 1 and 2 at t + h/2, stage 3 at t + h.
///
/// The stage combinations are plain loops over the state (13 values for the LuGre-lumped car):
/// Eigen's expression templates for a dynamic size spent more on set-up than on the arithmetic
/// (RK4 vector work 6 % of a closed-loop step, issue #2 profile). The sums keep Eigen's order,
/// ((k1 + 2 k2) + 2 k3) + k4, so the trajectory is unchanged bit for bit.
#include <Eigen/Core>

namespace lane_keeping {

class Rk4 {
 public:
  explicit Rk4(int size) : k1_(size), k2_(size), k3_(size), k4_(size), probe_(size) {}

  /// Advances x by h. f(stage, const VectorXd& x, VectorXd& x_dot). If `k1` is given it is used as
  /// f(0, x) (the caller evaluated it already, e.g. for outputs); it must not be x.
  template <class Derivative>
  void step(Derivative&& f, double h, Eigen::VectorXd& x, const Eigen::VectorXd* k1 = nullptr) {
    if (k1_.size() != x.size()) resize(static_cast<int>(x.size()));
    const Eigen::Index n = x.size();
    const double* __restrict a = k1_.data();
    if (k1 != nullptr) {
      a = k1->data();  // read where it is (a copy cost a pass over the state per step)
    } else {
      f(0, x, k1_);
    }
    const double half = 0.5 * h;
    axpy(n, x.data(), half, a, probe_.data());
    f(1, probe_, k2_);
    axpy(n, x.data(), half, k2_.data(), probe_.data());
    f(2, probe_, k3_);
    axpy(n, x.data(), h, k3_.data(), probe_.data());
    f(3, probe_, k4_);
    const double sixth = h / 6.0;
    const double* __restrict b = k2_.data();
    const double* __restrict c = k3_.data();
    const double* __restrict d = k4_.data();
    double* __restrict xs = x.data();
    for (Eigen::Index i = 0; i < n; ++i) xs[i] += sixth * (((a[i] + 2.0 * b[i]) + 2.0 * c[i]) + d[i]);
  }

 private:
  /// out = x + w k. Restrict: the arrays are distinct, so the loop vectorises without alias checks.
  static void axpy(Eigen::Index n, const double* __restrict x, double w, const double* __restrict k,
                   double* __restrict out) {
    for (Eigen::Index i = 0; i < n; ++i) out[i] = x[i] + w * k[i];
  }
  void resize(int size) {
    k1_.resize(size);
    k2_.resize(size);
    k3_.resize(size);
    k4_.resize(size);
    probe_.resize(size);
  }

  Eigen::VectorXd k1_, k2_, k3_, k4_, probe_;
};

}  // namespace lane_keeping
