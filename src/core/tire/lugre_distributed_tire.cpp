#include "lane_keeping/tire/lugre_distributed_tire.h"

namespace lane_keeping {

LugreDistributedTire::LugreDistributedTire(const LugreCoefficients& coefficients, const SlidingFriction& friction,
                                           const ContactPressure& pressure, int bristles, bool turn_slip)
    : c_(coefficients), g_(friction), pressure_(pressure), n_(bristles), turn_slip_(turn_slip) {
  const double h = 1.0 / (n_ - 1);  // spacing in s = zeta / L
  zeta_.resize(n_);
  weight_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    const double s = i * h;
    zeta_[i] = s * c_.contact_length;
    const double end_factor = (i == 0 || i == n_ - 1) ? 0.5 : 1.0;
    weight_[i] = h * end_factor * pressure_.at(s);
  }
}

TireForces<double> LugreDistributedTire::steadyState(const ContactKinematics<double>& k,
                                                     std::vector<double>* state) const {
  const int m = n_ - 1;
  std::vector<double> z(2 * m, 0.0);
  const double L = c_.contact_length;
  const double transport = k.wheel_speed * m / L;
  double prev_x = 0.0, prev_y = 0.0;
  for (int j = 0; j < m; ++j) {
    const int i = j + 1;
    double v_ry = k.lateral_slip_speed;
    if (turn_slip_) v_ry = k.lateral_slip_speed - (0.5 * L - zeta_[i]) * k.yaw_rate;
    const double v_r = slipSpeedNorm(k.longitudinal_slip_speed, v_ry);
    const double c0 = v_r / g_(v_r);
    // 0 = v - sigma0 c0 z_i - transport (z_i - z_(i-1))  =>  z_i = (v + transport z_(i-1)) / (sigma0 c0 + transport)
    const double dx = c_.sigma0x * c0 + transport;
    const double dy = c_.sigma0y * c0 + transport;
    z[j] = dx > 0.0 ? (k.longitudinal_slip_speed + transport * prev_x) / dx : 0.0;
    z[m + j] = dy > 0.0 ? (v_ry + transport * prev_y) / dy : 0.0;
    prev_x = z[j];
    prev_y = z[m + j];
  }
  std::vector<double> z_dot(2 * m);
  const TireForces<double> forces = evaluate(k, z.data(), z_dot.data());
  if (state != nullptr) *state = z;
  return forces;
}

}  // namespace lane_keeping
