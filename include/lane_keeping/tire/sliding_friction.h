#pragma once
/// Sliding friction function of the LuGre bristle, scaled by the normal load:
///   g(v_r) = F_z (mu_k + (mu_s - mu_k) exp(-|v_r / v_s|^delta))      (Deur eqs 6 and 61)
#include <cmath>

#include "lane_keeping/common/scalar.h"

namespace lane_keeping {

class SlidingFriction {
 public:
  SlidingFriction(double normal_load, double mu_kinetic, double mu_static, double stribeck_velocity,
                  double stribeck_exponent)
      : normal_load_(normal_load),
        mu_k_(mu_kinetic),
        mu_s_(mu_static),
        v_s_(stribeck_velocity),
        exponent_(stribeck_exponent) {}

  /// g(v_r) [N] for a slip speed v_r >= 0.
  template <typename T>
  T operator()(const T& slip_speed) const {
    using std::exp;
    using std::pow;
    if (mu_s_ == mu_k_ || toDouble(slip_speed) == 0.0) {
      // No Stribeck drop (the default mu = mu0), or at zero slip where g = F_z mu_s. Skipping pow()
      // keeps the Jet derivative finite at v_r = 0 (|v_r|^0.6 has an infinite slope there).
      return T(normal_load_ * (toDouble(slip_speed) == 0.0 ? mu_s_ : mu_k_));
    }
    return normal_load_ * (mu_k_ + (mu_s_ - mu_k_) * exp(-pow(slip_speed / v_s_, exponent_)));
  }

  /// True when g does not depend on the slip speed (mu_s = mu_k).
  bool isConstant() const { return mu_s_ == mu_k_; }
  double constantValue() const { return normal_load_ * mu_k_; }
  double normalLoad() const { return normal_load_; }
  double staticCoefficient() const { return mu_s_; }
  double kineticCoefficient() const { return mu_k_; }

 private:
  double normal_load_;
  double mu_k_;
  double mu_s_;
  double v_s_;
  double exponent_;
};

}  // namespace lane_keeping
