#pragma once
/// Classical fixed-step Runge-Kutta (4th order), with a workspace so a step allocates nothing.
/// The derivative callable receives the stage index so the caller can supply the input at the
/// stage's time: stage 0 at t, stages 1 and 2 at t + h/2, stage 3 at t + h.
#include <Eigen/Core>

namespace lane_keeping {

class Rk4 {
 public:
  explicit Rk4(int size) : k1_(size), k2_(size), k3_(size), k4_(size), probe_(size) {}

  /// Advances x by h. f(stage, const VectorXd& x, VectorXd& x_dot). If `k1` is given it is used as
  /// f(0, x) (the caller evaluated it already, e.g. for outputs).
  template <class Derivative>
  void step(Derivative&& f, double h, Eigen::VectorXd& x, const Eigen::VectorXd* k1 = nullptr) {
    if (k1 != nullptr) {
      k1_ = *k1;
    } else {
      f(0, x, k1_);
    }
    probe_ = x + (0.5 * h) * k1_;
    f(1, probe_, k2_);
    probe_ = x + (0.5 * h) * k2_;
    f(2, probe_, k3_);
    probe_ = x + h * k3_;
    f(3, probe_, k4_);
    x += (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  }

 private:
  Eigen::VectorXd k1_, k2_, k3_, k4_, probe_;
};

}  // namespace lane_keeping
