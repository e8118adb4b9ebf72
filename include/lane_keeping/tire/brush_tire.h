#pragma once
/// Beregi's brush tire: lateral force and aligning moment as static functions of the slip angle at
/// the leading point of the patch (eqs 6-7, coefficients Appendix A, slip angle eq 8).
/// It has no internal state. Small-slip slopes: dF/dtan(alpha) = 2 a^2 k (eq 9),
/// dM/dtan(alpha) = -(2/3) a^3 k (eq 10).
#include <cmath>

#include "lane_keeping/common/scalar.h"
#include "lane_keeping/tire/contact_kinematics.h"

namespace lane_keeping {

class BrushTire {
 public:
  /// @param normal_load F_z [N]; @param half_length a [m]; @param stiffness k [N/m^2];
  /// @param mu sliding and @param mu0 adhesion friction coefficients.
  BrushTire(double normal_load, double half_length, double stiffness, double mu, double mu0);

  static constexpr int kStateSize = 0;

  template <typename T>
  TireForces<T> evaluate(const ContactKinematics<T>& kinematics, const T* /*state*/, T* /*state_dot*/) const {
    TireForces<T> out;
    out.lateral_force = force(kinematics.tan_slip_angle);
    out.aligning_moment = moment(kinematics.tan_slip_angle);
    return out;
  }

  /// Eq 6 as a function of t = tan(alpha).
  template <typename T>
  T force(const T& t) const {
    using std::abs;
    const double s = sign(t);
    if (abs(toDouble(t)) >= tan_crit_) return T(mu_ * normal_load_ * s);
    const T t2 = t * t;
    return phi3_ * t2 * t + phi2_ * t2 * s + phi1_ * t;
  }

  /// Eq 7 as a function of t = tan(alpha).
  template <typename T>
  T moment(const T& t) const {
    const double s = sign(t);
    if (std::fabs(toDouble(t)) >= tan_crit_) return T(0.0);
    const T t2 = t * t;
    return mu4_ * t2 * t2 * s + mu3_ * t2 * t + mu2_ * t2 * s + mu1_ * t;
  }

  /// tan(alpha_crit) = 3 mu0 F_z / (2 a^2 k): the whole patch slides (F = mu F_z, M = 0 there).
  double tanCriticalSlip() const { return tan_crit_; }
  double halfLength() const { return a_; }
  double corneringStiffness() const { return phi1_; }
  double aligningStiffness() const { return -mu1_; }

 private:
  double normal_load_, a_, mu_;
  double phi1_, phi2_, phi3_;       // Beregi eqs A.1-A.3
  double mu1_, mu2_, mu3_, mu4_;    // Beregi eqs A.4-A.7
  double tan_crit_;
};

}  // namespace lane_keeping
