#include "lane_keeping/tire/lugre_lumped_tire.h"

namespace lane_keeping {

TireForces<double> LugreLumpedTire::steadyState(const ContactKinematics<double>& k, double* state) const {
  // Solve eqs 38 and 51 with zero derivatives; the lambda1 product follows evaluate().
  double z[kStateSize] = {0.0, 0.0, 0.0};
  const double L = c_.contact_length;
  const double w = k.wheel_speed;
  const double v_r = slipSpeedNorm(k.longitudinal_slip_speed, k.lateral_slip_speed);
  const double g = g_(v_r);
  const double c0x = c_.sigma0x * v_r / g;
  const double c0y = c_.sigma0y * v_r / g;
  const double dx = c0x + kappa(c0x, w) * w / L;
  const double dy = c0y + kappa(c0y, w) * w / L;
  z[kZx] = dx > 0.0 ? k.longitudinal_slip_speed / dx : 0.0;
  z[kZy] = dy > 0.0 ? k.lateral_slip_speed / dy : 0.0;
  // One evaluation with psi = 0 gives dpsi/dt = b - a psi with a = decay rate; solve psi = b / a.
  double z_dot[kStateSize];
  evaluate(k, z, z_dot);
  const double b = z_dot[kPsi];
  z[kPsi] = 1.0;
  evaluate(k, z, z_dot);
  const double a = b - z_dot[kPsi];
  z[kPsi] = a > 0.0 ? b / a : 0.0;
  if (state != nullptr) {
    for (int i = 0; i < kStateSize; ++i) state[i] = z[i];
  }
  return evaluate(k, z, z_dot);
}

}  // namespace lane_keeping
