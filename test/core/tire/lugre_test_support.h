#pragma once
// Support for the LuGre tests: Deur's steady-state closed forms (written out independently of the tire
// code), the parameter sets used, and a plain RK4 integrator.
//
// Sign convention check (eqs 25b, 30b): our M is counter-clockwise positive and negative for a small
// positive lateral slip v_ry (pneumatic trail behind the centre, contact_kinematics.h). Deur's eqs
// 25b and 30b as printed give the same sign: for rho = Z/L -> inf the bracket of 25b tends to
// 1/(12 rho^2) > 0, so M = -(v_ry/|v_r|) g Z /(12 rho^2) < 0 for v_ry > 0. They are used as printed.
//
// Eq 30b was re-derived from eqs 21, 23 and the trapezoid (Fig 7) with sympy:
//   M = (v_ry/|v_r|) g L [ (1-K_v)/2 - int_0^1 p(s) e^{-s/rho} (1/2 - s) ds ],
// whose closed form is identical to the printed 30b (symbolic difference 0; e.g. at r_l = 0.134,
// r_r = 0.707, rho = 0.2 both give -2 int(...) = -0.0931535447436829). The OCR text is not garbled.
// Likewise eqs 30a, 31a and 32b equal the defining integrals symbolically, and eqs 40-41 and 54 equal
// eqs 39 and 53 (evaluated with sympy at 15 digits for rho = 0.02..20).
#include <cmath>
#include <functional>
#include <vector>

#include "lane_keeping/tire/contact_kinematics.h"
#include "lane_keeping/tire/contact_pressure.h"
#include "lane_keeping/tire/lugre_lumped_tire.h"
#include "lane_keeping/tire/sliding_friction.h"

namespace lane_keeping {
namespace deur {

constexpr double kDeg = M_PI / 180.0;

/// Pure lateral slip at wheel-centre speed V: v_rx = 0, v_ry = V sin(alpha), r|w| = V cos(alpha).
inline ContactKinematics<double> pureLateral(double alpha_rad, double speed) {
  ContactKinematics<double> k;
  k.tan_slip_angle = std::tan(alpha_rad);
  k.wheel_speed = speed * std::cos(alpha_rad);
  k.longitudinal_slip_speed = 0.0;
  k.lateral_slip_speed = speed * std::sin(alpha_rad);
  return k;
}

/// Eq 25a / 30a bracket terms and 25b / 30b; uniform if p.isUniform().
inline TireForces<double> steadyState(const LugreCoefficients& c, const SlidingFriction& friction,
                                      const ContactPressure& p, const ContactKinematics<double>& k) {
  const double L = c.contact_length;
  const double vx = k.longitudinal_slip_speed, vy = k.lateral_slip_speed, w = k.wheel_speed;
  const double vr = std::hypot(vx, vy);
  TireForces<double> out;
  if (vr == 0.0) return out;
  const double g = friction(vr);
  const double rl = p.leftMargin(), rr = p.rightMargin();
  const double pm = 2.0 / (1.0 + rr - rl);                                // eq 28
  const double kv = 2.0 / 3.0 * (1.0 + rr + rr * rr - rl * rl) / (1.0 + rr - rl);  // eq 31a
  auto force = [&](double v, double sigma0) {
    const double Z = std::fabs(w / vr) * g / sigma0;  // eq 24
    if (p.isUniform()) {
      return v / vr * g * (1.0 - Z / L * (1.0 - std::exp(-L / Z))) + c.sigma2 * v;  // eq 25a
    }
    const double rho = Z / L;  // eq 31b
    const double bracket = rho / rl * (1.0 - std::exp(-rl / rho)) -
                           rho / (1.0 - rr) * (std::exp(-rr / rho) - std::exp(-1.0 / rho));
    return v / vr * g * (1.0 - pm * rho * bracket) + c.sigma2 * v;  // eq 30a
  };
  out.longitudinal_force = force(vx, c.sigma0x);
  out.lateral_force = force(vy, c.sigma0y);
  const double Zy = std::fabs(w / vr) * g / c.sigma0y;
  const double rho = Zy / L;
  if (p.isUniform()) {
    out.aligning_moment = -vy / vr * g * Zy * (0.5 - rho + (0.5 + rho) * std::exp(-1.0 / rho));  // eq 25b
  } else {
    const double bracket = (4.0 * rho - 1.0) / rl - (4.0 * rho + 2.0 * rl - 1.0) / rl * std::exp(-rl / rho) -
                           (4.0 * rho + 2.0 * rr - 1.0) / (1.0 - rr) * std::exp(-rr / rho) +
                           (4.0 * rho + 1.0) / (1.0 - rr) * std::exp(-1.0 / rho);
    out.aligning_moment = vy / vr * g * L / 2.0 * (1.0 - kv + pm * rho * rho * bracket) +
                          L / 2.0 * (1.0 - kv) * c.sigma2 * vy;  // eq 30b
  }
  return out;
}

/// Classic RK4 step for x' = f(x); f(x, xdot) writes xdot.
inline void rk4Step(const std::function<void(const std::vector<double>&, std::vector<double>&)>& f,
                    std::vector<double>& x, double h) {
  const size_t n = x.size();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), tmp(n);
  f(x, k1);
  for (size_t i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k1[i];
  f(tmp, k2);
  for (size_t i = 0; i < n; ++i) tmp[i] = x[i] + 0.5 * h * k2[i];
  f(tmp, k3);
  for (size_t i = 0; i < n; ++i) tmp[i] = x[i] + h * k3[i];
  f(tmp, k4);
  for (size_t i = 0; i < n; ++i) x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
}

/// A LuGre parameter set: coefficients, friction and pressure.
struct LugreSetup {
  LugreCoefficients coefficients;
  SlidingFriction friction;
  ContactPressure pressure;
};

/// Project defaults (TireParams): a = 0.1 m, k = 2e6 N/m^2 => L = 0.2 m, sigma0 = k L = 4e5 N/m,
/// mu = mu0 = 1 (g constant), at the front axle load m g d / l (Beregi Table 1).
inline double frontAxleLoad() { return 1100.0 * 9.81 * 1.54 / 2.57; }
inline LugreSetup defaultSetup(const ContactPressure& pressure) {
  return {{0.2, 4.0e5, 4.0e5, 0.0, 0.0}, SlidingFriction(frontAxleLoad(), 1.0, 1.0, 3.5, 0.6), pressure};
}
/// Deur App. A: F_z = 4 kN, L sigma0x = 314e3 N, L sigma0y = 159.2e3 N, Stribeck friction.
/// A.2 (trapezoid r_l = 0.134, r_r = 0.707): L = 0.303 m, F_C/F_z = 0.648, F_S/F_z = 1.671, v_s = 3.49.
/// A.1 (uniform) gives no L; we take 0.25 m (Deur §8: L = 0.25 m at 4 kN), F_C/F_z = 0.64, F_S/F_z = 1.76.
inline LugreSetup deurTrapezoidSetup() {
  const double L = 0.303;
  return {{L, 314e3 / L, 159.2e3 / L, 0.0, 0.0}, SlidingFriction(4000.0, 0.648, 1.671, 3.49, 0.6),
          ContactPressure::trapezoidal(0.134, 0.707)};
}
inline LugreSetup deurUniformSetup() {
  const double L = 0.25;
  return {{L, 314e3 / L, 159.2e3 / L, 0.0, 0.0}, SlidingFriction(4000.0, 0.64, 1.76, 3.48, 0.6),
          ContactPressure::uniform()};
}

inline TireForces<double> steadyState(const LugreSetup& s, const ContactKinematics<double>& k) {
  return steadyState(s.coefficients, s.friction, s.pressure, k);
}

/// Eq 27a/32a: K_y = L sigma0y K_v / 2.  Eq 27b/32b: K_z.
inline double corneringStiffness(double L, double sigma0y, double rl, double rr) {
  return 0.5 * L * sigma0y * (2.0 / 3.0) * (1.0 + rr + rr * rr - rl * rl) / (1.0 + rr - rl);
}
inline double aligningStiffness(double L, double sigma0y, double rl, double rr) {
  return L * L * sigma0y / 6.0 * (rr * rr * rr + rl * rl - rl * rl * rl) / (1.0 + rr - rl);
}

/// Wheel-centre speed of the steady-state checks [m/s].
constexpr double kSpeed = 15.0;

inline double relErr(double value, double reference) { return std::fabs(value - reference) / std::fabs(reference); }

/// The parameter sets every LuGre steady-state test runs over.
struct Case {
  const char* name;
  LugreSetup setup;
};

inline std::vector<Case> cases() {
  return {{"default uniform", defaultSetup(ContactPressure::uniform())},
          {"default trapezoid", defaultSetup(ContactPressure::trapezoidal(0.134, 0.707))},
          {"Deur A.1 uniform", deurUniformSetup()},
          {"Deur A.2 trapezoid", deurTrapezoidSetup()}};
}

}  // namespace deur
}  // namespace lane_keeping
