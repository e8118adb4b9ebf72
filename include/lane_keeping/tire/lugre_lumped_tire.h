#pragma once
/// Deur's lumped LuGre tire (eqs 33-57): three states, the pressure-weighted mean deflections
/// z~x, z~y (eq 33) and the torque state psi (eq 44).
///
///   dz~/dt  = v_r - [sigma0 |v_r| / g + kappa r|w| / L] z~                              (eq 38)
///   F       = sigma0 z~ + sigma1 dz~/dt + sigma2 v_r                                     (eq 34b)
///   dpsi/dt = K_v v_ry - [sigma0y |v_r| / g + 2 lambda1 r|w| / L] psi
///             + (2/L)(1 - lambda2) r|w| z~y                                              (eq 51)
///   M_z     = L/2 [sigma0y (z~y - psi) + sigma1 (dz~y/dt - dpsi/dt) + (1 - K_v) sigma2 v_ry]   (eq 45)
///
/// kappa: variable (eq 39, = eq 40 / 43) so that the steady state equals the distributed model, or
/// constant (Deur §5.1, 1.2). lambda: eq 53 (= eq 54 / 57); lambda2 fixed, lambda1 from eq 56.
///
/// Departure from eq 56 as printed (documented in docs/findings.md): eq 56 evaluates the ratio
/// ((2/L)(1-lambda2) r|w| z~y + K_v v_ry) / ((2/L) r|w| z~y + K_v v_ry) at the *instantaneous* z~y,
/// which is 0/0 at straight running and changes sign in transients (lambda1 -> +-inf). We evaluate
/// it at the steady-state z~y = v_ry / (sigma0y |v_r| / g + kappa r|w| / L) of the current slip,
/// where v_ry cancels. In steady state this is eq 56 exactly; for lambda2 = 0 (the default, Deur's
/// basic model) it is lambda1 = lambda either way.
#include <cmath>
#include <type_traits>

#include "lane_keeping/common/scalar.h"
#include "lane_keeping/tire/contact_kinematics.h"
#include "lane_keeping/tire/contact_pressure.h"
#include "lane_keeping/tire/sliding_friction.h"

namespace lane_keeping {

struct LugreCoefficients {
  double contact_length;  ///< L [m]
  double sigma0x;         ///< [N/m]
  double sigma0y;         ///< [N/m]
  double sigma1;          ///< [N s/m]
  double sigma2;          ///< [N s/m]
};

class LugreLumpedTire {
 public:
  enum StateIndex { kZx = 0, kZy = 1, kPsi = 2 };
  static constexpr int kStateSize = 3;

  /// @param kappa_constant <= 0 selects the variable kappa of eq 39.
  LugreLumpedTire(const LugreCoefficients& coefficients, const SlidingFriction& friction,
                  const ContactPressure& pressure, double kappa_constant, double lambda2)
      : c_(coefficients), g_(friction), pressure_(pressure), kappa_constant_(kappa_constant), lambda2_(lambda2),
        kv_(pressure.kv()), inv_L_(1.0 / coefficients.contact_length),
        sigma0y_over_g_(friction.isConstant() ? coefficients.sigma0y / friction.constantValue() : 0.0) {}

  template <typename T>
  [[gnu::always_inline]] TireForces<T> evaluate(const ContactKinematics<T>& k, const T* z, T* z_dot) const {
    using std::abs;
    const double L = c_.contact_length;
    const T& w = k.wheel_speed;
    const T v_r = toDouble(k.longitudinal_slip_speed) == 0.0 ? T(abs(k.lateral_slip_speed))
                                                              : slipSpeedNorm(k.longitudinal_slip_speed, k.lateral_slip_speed);
    // sigma0 |v_r| / g, the LuGre bristle-tip term (g constant when mu = mu0: no division)
    const T c0y = sigma0y_over_g_ > 0.0 ? T(sigma0y_over_g_ * v_r) : T(c_.sigma0y * v_r / g_(v_r));

    // kappa (eq 39) and lambda (eq 53) at y = L / Z = L c0 / w.
    T kappa_y, lambda;
    if (toDouble(w) > 0.0) {
      const auto f = pressure_.factors(
          T(toDouble(k.inv_wheel_speed) != 0.0 ? L * c0y * k.inv_wheel_speed : L * c0y / w));
      kappa_y = kappa_constant_ > 0.0 ? T(kappa_constant_) : f.kappa;
      lambda = f.lambda;
    } else {  // standstill: no transport; the factors multiply w = 0
      kappa_y = T(0.0);
      lambda = T(1.0 / kv_);
    }
    const T conv_y = kappa_y * w * inv_L_;  // convective (transport) term of eq 38
    z_dot[kZy] = k.lateral_slip_speed - (c0y + conv_y) * z[kZy];  // eq 38

    TireForces<T> out;
    if (std::is_same_v<T, double> && toDouble(k.longitudinal_slip_speed) == 0.0 && toDouble(z[kZx]) == 0.0) {
      // Free rolling with a relaxed longitudinal bristle: eq 38 keeps z~x = 0 exactly; skip it. (Not for
      // autodiff scalars: d(dz~x/dt)/dz~x = -(sigma0x |v_r| / g + kappa r|w| / L) is not zero.)
      z_dot[kZx] = T(0.0);
      out.longitudinal_force = T(0.0);
    } else {
      const T c0x = c_.sigma0x * v_r / g_(v_r);
      const T conv_x = kappa(c0x, w) * w * inv_L_;
      z_dot[kZx] = k.longitudinal_slip_speed - (c0x + conv_x) * z[kZx];  // eq 38
      out.longitudinal_force = c_.sigma0x * z[kZx] + c_.sigma1 * z_dot[kZx] + c_.sigma2 * k.longitudinal_slip_speed;
    }

    // lambda1 r|w| from eq 56 (steady-state ratio, see header).
    T lambda1_w = lambda * w;
    if (lambda2_ != 0.0) {
      const T d = c0y + conv_y;  // > 0 whenever w > 0
      const T ratio = toDouble(d) > 0.0 ? (2.0 * inv_L_ * (1.0 - lambda2_) * w / d + kv_) / (2.0 * inv_L_ * w / d + kv_)
                                         : T(1.0);
      lambda1_w = (0.5 * L) * (ratio * (c0y + 2.0 * lambda * w * inv_L_) - c0y);
    }
    z_dot[kPsi] = kv_ * k.lateral_slip_speed - (c0y + 2.0 * inv_L_ * lambda1_w) * z[kPsi] +
                  2.0 * inv_L_ * (1.0 - lambda2_) * w * z[kZy];  // eq 51

    out.lateral_force = c_.sigma0y * z[kZy] + c_.sigma1 * z_dot[kZy] + c_.sigma2 * k.lateral_slip_speed;  // eq 34b
    out.aligning_moment = (L / 2.0) * (c_.sigma0y * (z[kZy] - z[kPsi]) + c_.sigma1 * (z_dot[kZy] - z_dot[kPsi]) +
                                       (1.0 - kv_) * c_.sigma2 * k.lateral_slip_speed);  // eq 45
    return out;
  }

  /// Steady state for constant slip (dz/dt = 0): closed form of eqs 38 and 51.
  TireForces<double> steadyState(const ContactKinematics<double>& k, double* state = nullptr) const;

  const LugreCoefficients& coefficients() const { return c_; }
  const ContactPressure& pressure() const { return pressure_; }
  const SlidingFriction& friction() const { return g_; }
  bool variableKappa() const { return kappa_constant_ <= 0.0; }

  /// kappa for the bristle-tip term c0 = sigma0 |v_r| / g at wheel speed w: y = L / Z = L c0 / w.
  template <typename T>
  T kappa(const T& c0, const T& w) const {
    if (kappa_constant_ > 0.0) return T(kappa_constant_);
    if (toDouble(w) <= 0.0) return T(0.0);  // standstill: no transport, the factor is irrelevant
    return pressure_.kappa(T(c_.contact_length * c0 / w));
  }

 private:
  LugreCoefficients c_;
  SlidingFriction g_;
  ContactPressure pressure_;
  double kappa_constant_;
  double lambda2_;
  double kv_;
  double inv_L_;
  double sigma0y_over_g_;  ///< sigma0y / g when g is constant (mu_s = mu_k), else 0
};

}  // namespace lane_keeping
