#pragma once
/// Deur's distributed LuGre brush tire, discretised in space (eq 22): N bristles per direction at
/// zeta_i = (i-1) L/(N-1), the leading one undeflected (z_1 = 0), first-order upwind transport:
///   dz_i/dt = v_r,i - sigma0 |v_r,i| / g(v_r,i) z_i - r|w| (N-1)/L (z_i - z_(i-1)),  i = 2..N
/// Forces and moment are the trapezoidal-rule sums of eqs 18, 20 and 21:
///   F = (1/L) int p (sigma0 z + sigma1 dz/dt + sigma2 v_r) dzeta,
///   M = (1/L) int p (sigma0 z_y + sigma1 dz_y/dt + sigma2 v_ry) (L/2 - zeta) dzeta.
/// With turn_slip, the lateral slip speed varies along the patch with the wheel yaw rate r:
///   v_ry(zeta) = v_ry(centre) - (L/2 - zeta) r                      (Velenis eq 64b, our signs)
/// State layout: [z_x,2 .. z_x,N, z_y,2 .. z_y,N] (2 (N-1) states).
///
/// This is the high-fidelity reference of the lumped model. Its steady state converges to Deur's
/// closed forms (eqs 25, 30) at first order in 1/N (exactly at small slip, where z is linear in zeta).
#include <cmath>
#include <vector>

#include "lane_keeping/common/scalar.h"
#include "lane_keeping/tire/contact_kinematics.h"
#include "lane_keeping/tire/contact_pressure.h"
#include "lane_keeping/tire/lugre_lumped_tire.h"
#include "lane_keeping/tire/sliding_friction.h"

namespace lane_keeping {

class LugreDistributedTire {
 public:
  LugreDistributedTire(const LugreCoefficients& coefficients, const SlidingFriction& friction,
                       const ContactPressure& pressure, int bristles, bool turn_slip);

  int stateSize() const { return 2 * (n_ - 1); }
  int bristles() const { return n_; }

  template <typename T>
  TireForces<T> evaluate(const ContactKinematics<T>& k, const T* z, T* z_dot) const {
    const double L = c_.contact_length;
    const int m = n_ - 1;  // states per direction
    const T* zx = z;
    const T* zy = z + m;
    T* zx_dot = z_dot;
    T* zy_dot = z_dot + m;
    const T transport = k.wheel_speed * (static_cast<double>(m) / L);

    TireForces<T> out;
    const T v_r_uniform = slipSpeedNorm(k.longitudinal_slip_speed, k.lateral_slip_speed);
    const T g_uniform = g_(v_r_uniform);
    T prev_x(0.0), prev_y(0.0);  // z_1 = 0
    for (int j = 0; j < m; ++j) {
      const int i = j + 1;  // bristle index from 0 at the leading edge
      T v_ry = k.lateral_slip_speed;
      T v_r = v_r_uniform;
      T g = g_uniform;
      if (turn_slip_) {
        v_ry = k.lateral_slip_speed - (0.5 * L - zeta_[i]) * k.yaw_rate;
        v_r = slipSpeedNorm(k.longitudinal_slip_speed, v_ry);
        g = g_(v_r);
      }
      const T c0 = v_r / g;
      zx_dot[j] = k.longitudinal_slip_speed - c_.sigma0x * c0 * zx[j] - transport * (zx[j] - prev_x);
      zy_dot[j] = v_ry - c_.sigma0y * c0 * zy[j] - transport * (zy[j] - prev_y);
      prev_x = zx[j];
      prev_y = zy[j];
      const double w = weight_[i];  // trapezoid weight (h/L) times pressure
      const T fy = c_.sigma0y * zy[j] + c_.sigma1 * zy_dot[j] + c_.sigma2 * v_ry;
      out.longitudinal_force = out.longitudinal_force +
                               w * (c_.sigma0x * zx[j] + c_.sigma1 * zx_dot[j] + c_.sigma2 * k.longitudinal_slip_speed);
      out.lateral_force = out.lateral_force + w * fy;
      out.aligning_moment = out.aligning_moment + w * fy * (0.5 * L - zeta_[i]);
    }
    // The leading bristle carries no deflection but does carry the viscous term.
    if (c_.sigma2 != 0.0) {
      T v_ry0 = k.lateral_slip_speed;
      if (turn_slip_) v_ry0 = k.lateral_slip_speed - 0.5 * L * k.yaw_rate;
      out.longitudinal_force = out.longitudinal_force + weight_[0] * c_.sigma2 * k.longitudinal_slip_speed;
      out.lateral_force = out.lateral_force + weight_[0] * c_.sigma2 * v_ry0;
      out.aligning_moment = out.aligning_moment + weight_[0] * c_.sigma2 * v_ry0 * (0.5 * L);
    }
    return out;
  }

  /// Exact steady state of the discretised model (the upwind recurrence solved bristle by bristle).
  TireForces<double> steadyState(const ContactKinematics<double>& k, std::vector<double>* state = nullptr) const;

  const LugreCoefficients& coefficients() const { return c_; }
  const ContactPressure& pressure() const { return pressure_; }

 private:
  LugreCoefficients c_;
  SlidingFriction g_;
  ContactPressure pressure_;
  int n_;
  bool turn_slip_;
  std::vector<double> zeta_;    ///< bristle positions from the leading edge [m]
  std::vector<double> weight_;  ///< trapezoid weight (h/L, halved at the ends) times p(zeta)
};

}  // namespace lane_keeping
