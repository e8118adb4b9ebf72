#pragma once
/// Pacejka's Magic Formula with Velenis Table 1 coefficients (from Bakker, Nyborg & Pacejka 1987),
/// a steady-state (stateless) reference for comparing the brush and LuGre static curves:
///   Y(alpha) = D sin(C atan(B a - E (B a - atan(B a)))),  a = alpha in degrees,
/// for F_y and M_z with their own B, C, D, E. D is scaled by mu F_z / F_z0 (Table 1 holds at
/// F_z0 = 2000 N, Velenis §5.3). The slip angle is taken at the contact centre, tan(alpha) =
/// v_ry / r|w|. With Table 1 the cornering stiffness is B C D = 708.6 N/deg = 40.6 kN/rad at F_z0,
/// close to the brush's 2 a^2 k = 40 kN/rad, but it grows with the load.
#include <cmath>

#include "lane_keeping/tire/contact_kinematics.h"
#include "lane_keeping/tire/tire_params.h"

namespace lane_keeping {

class MagicFormulaTire {
 public:
  MagicFormulaTire(const MagicFormulaParams& params, double normal_load, double mu)
      : p_(params), scale_(mu * normal_load / params.reference_load) {}

  static constexpr int kStateSize = 0;

  template <typename T>
  TireForces<T> evaluate(const ContactKinematics<T>& k, const T* /*state*/, T* /*state_dot*/) const {
    using std::atan;
    using std::atan2;
    using std::sin;
    const T alpha_deg = atan2(k.lateral_slip_speed, k.wheel_speed) * (180.0 / M_PI);
    TireForces<T> out;
    out.lateral_force = scale_ * curve(alpha_deg, p_.fy_b, p_.fy_c, p_.fy_d, p_.fy_e);
    out.aligning_moment = scale_ * curve(alpha_deg, p_.mz_b, p_.mz_c, p_.mz_d, p_.mz_e);
    return out;
  }

  /// dF/dalpha at 0 [N/rad]: B C D * 180/pi * scale.
  double corneringStiffness() const { return scale_ * p_.fy_b * p_.fy_c * p_.fy_d * 180.0 / M_PI; }
  /// -dM/dalpha at 0 [N m/rad].
  double aligningStiffness() const { return -scale_ * p_.mz_b * p_.mz_c * p_.mz_d * 180.0 / M_PI; }

 private:
  template <typename T>
  static T curve(const T& x, double b, double c, double d, double e) {
    using std::atan;
    using std::sin;
    const T bx = b * x;
    return d * sin(c * atan(bx - e * (bx - atan(bx))));
  }

  MagicFormulaParams p_;
  double scale_;
};

}  // namespace lane_keeping
