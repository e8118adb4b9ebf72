// Deur's distributed LuGre tire (eq 22): steady state vs the closed forms 25a/25b (uniform pressure)
// and 30a/30b (trapezoid), first-order convergence of the upwind discretisation, and steadyState()
// vs the time integration of evaluate().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "lane_keeping/tire/lugre_distributed_tire.h"
#include "lugre_test_support.h"

namespace lane_keeping {
namespace {

using deur::kDeg;
using deur::Case;
using deur::cases;
using deur::kSpeed;
using deur::LugreSetup;
using deur::relErr;

LugreDistributedTire distributed(const LugreSetup& s, int n) {
  return LugreDistributedTire(s.coefficients, s.friction, s.pressure, n, false);
}

// Slips where M is well away from its sign change (Deur A.2 changes sign near 12 deg) and y = L/Z
// is 0.2..5, so that the closed forms are well conditioned.
const double kSlipsDeg[] = {1.0, 2.0, 4.0, 8.0};

TEST(LugreDistributedTire, SteadyStateConvergesToEqs25And30) {
  // Measured (N = 4000): |dF|/F <= 1.7e-4, |dM|/|M| <= 1.7e-3 (largest: Deur A.2 at 8 deg, where M is
  // small, -15 N m); at N = 100 up to 6.8e-3 and 6.6e-2.
  for (const Case& c : cases()) {
    const LugreDistributedTire tire = distributed(c.setup, 4000);
    for (double a : kSlipsDeg) {
      SCOPED_TRACE(std::string(c.name) + " alpha = " + std::to_string(a));
      const ContactKinematics<double> k = deur::pureLateral(a * kDeg, kSpeed);
      const TireForces<double> exact = deur::steadyState(c.setup, k);
      const TireForces<double> f = tire.steadyState(k);
      EXPECT_LT(relErr(f.lateral_force, exact.lateral_force), 2e-4);
      EXPECT_LT(relErr(f.aligning_moment, exact.aligning_moment), 2e-3);
      EXPECT_NEAR(f.longitudinal_force, 0.0, 1e-12);
      // Sign convention: F left-positive with v_ry, M counter-clockwise positive, negative here.
      EXPECT_GT(f.lateral_force, 0.0);
      EXPECT_LT(f.aligning_moment, 0.0);
    }
  }
}

TEST(LugreDistributedTire, CombinedSlipEqualsEq25a) {
  // v_rx != 0: the two directions are coupled only through g(|v_r|) (eq 17). sigma0x = 2 sigma0y and
  // Stribeck friction make the two Z_{x,y} (eq 24) differ.
  LugreSetup s = deur::deurUniformSetup();
  for (double vrx : {0.5, -0.8, 3.0}) {
    ContactKinematics<double> k;
    k.wheel_speed = 15.0;
    k.longitudinal_slip_speed = vrx;
    k.lateral_slip_speed = 1.0;
    const TireForces<double> exact = deur::steadyState(s, k);
    SCOPED_TRACE(vrx);
    EXPECT_GT(std::fabs(exact.longitudinal_force), 100.0);
    const TireForces<double> f = distributed(s, 4000).steadyState(k);
    EXPECT_LT(relErr(f.longitudinal_force, exact.longitudinal_force), 3e-4);
    EXPECT_LT(relErr(f.lateral_force, exact.lateral_force), 3e-4);
    EXPECT_LT(relErr(f.aligning_moment, exact.aligning_moment), 3e-3);
    EXPECT_EQ(f.longitudinal_force > 0, vrx > 0);
    // Friction circle: |F| < g(|v_r|).
    EXPECT_LT(std::hypot(f.longitudinal_force, f.lateral_force), s.friction(std::hypot(vrx, 1.0)));
  }
}

TEST(LugreDistributedTire, UpwindDiscretisationIsFirstOrder) {
  // Error vs eqs 25/30 at N = 100, 200, 400, 800: each doubling of N halves it.
  // Measured orders log2(e_N / e_2N): F 0.98-1.03 everywhere; M 0.89-1.0 (uniform) and 0.8-1.45
  // (trapezoid: its kinks, not on the grid, add an irregular O(1/N^2) part).
  for (const Case& c : cases()) {
    for (double a : {2.0, 4.0, 8.0}) {
      SCOPED_TRACE(std::string(c.name) + " alpha = " + std::to_string(a));
      const ContactKinematics<double> k = deur::pureLateral(a * kDeg, kSpeed);
      const TireForces<double> exact = deur::steadyState(c.setup, k);
      double prev_f = 0.0, prev_m = 0.0;
      for (int n : {100, 200, 400, 800}) {
        const TireForces<double> f = distributed(c.setup, n).steadyState(k);
        const double ef = relErr(f.lateral_force, exact.lateral_force);
        const double em = relErr(f.aligning_moment, exact.aligning_moment);
        EXPECT_LT(f.lateral_force, exact.lateral_force);  // upwind diffusion: F from below
        if (n > 100) {
          EXPECT_NEAR(std::log2(prev_f / ef), 1.0, 0.07) << "N = " << n;
          // Uniform: 0.89-1.0. Trapezoid: 0.8-1.45 (default trapezoid at 8 deg: the O(1/N) and O(1/N^2)
          // parts of the M error nearly cancel at N = 400, giving 1.41 there).
          if (c.setup.pressure.isUniform()) {
            EXPECT_NEAR(std::log2(prev_m / em), 1.0, 0.15) << "N = " << n;
          } else {
            EXPECT_NEAR(std::log2(prev_m / em), 1.1, 0.4) << "N = " << n;
          }
        }
        prev_f = ef;
        prev_m = em;
      }
    }
  }
}

TEST(LugreDistributedTire, SteadyStateEqualsTimeIntegrationOfEvaluate) {
  // RK4 of the 2 (N-1) ODEs at constant combined slip from z = 0 for 0.2 s (the slowest decay rate
  // is sigma0 |v_r|/g + r|w|(N-1)/L, >> 1/0.2 s); transport CFL r|w|(N-1)/L dt = 0.03.
  const LugreSetup s = deur::deurTrapezoidSetup();
  const LugreDistributedTire tire = distributed(s, 60);
  ContactKinematics<double> k = deur::pureLateral(3.0 * kDeg, kSpeed);
  k.longitudinal_slip_speed = -0.4;  // braking as well
  std::vector<double> z(tire.stateSize(), 0.0);
  const double dt = 1e-5;
  for (int i = 0; i < 20000; ++i) {
    deur::rk4Step([&](const std::vector<double>& x, std::vector<double>& xd) { tire.evaluate(k, x.data(), xd.data()); },
                  z, dt);
  }
  std::vector<double> z_ss;
  const TireForces<double> ss = tire.steadyState(k, &z_ss);
  std::vector<double> z_dot(tire.stateSize());
  const TireForces<double> f = tire.evaluate(k, z.data(), z_dot.data());
  ASSERT_EQ(z_ss.size(), z.size());
  for (size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(z[i], z_ss[i], 1e-12) << i;
  EXPECT_NEAR(f.lateral_force, ss.lateral_force, 1e-9 * std::fabs(ss.lateral_force));
  EXPECT_NEAR(f.longitudinal_force, ss.longitudinal_force, 1e-9 * std::fabs(ss.longitudinal_force));
  EXPECT_NEAR(f.aligning_moment, ss.aligning_moment, 1e-9 * std::fabs(ss.aligning_moment));
  // And the steady state is a fixed point of evaluate().
  std::vector<double> zd_ss(tire.stateSize());
  tire.evaluate(k, z_ss.data(), zd_ss.data());
  for (double v : zd_ss) EXPECT_NEAR(v, 0.0, 1e-12);
}

TEST(LugreDistributedTire, SmallSlipStiffnessIsEqs27And32) {
  // At small slip z is linear in zeta, which the upwind scheme reproduces exactly; what is left is
  // the trapezoidal-rule sum of a quadratic (M) or, for the trapezoid, of kinks off the grid: O(1/N^2).
  // Measured at N = 400: F 4e-7 (uniform), 4.6e-6 (trapezoid); M 1.2e-5, 2.3e-5.
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const double L = c.setup.coefficients.contact_length, s0 = c.setup.coefficients.sigma0y;
    const double rl = c.setup.pressure.leftMargin(), rr = c.setup.pressure.rightMargin();
    const double alpha = 1e-7;
    const TireForces<double> f = distributed(c.setup, 400).steadyState(deur::pureLateral(alpha, kSpeed));
    EXPECT_NEAR(f.lateral_force / std::tan(alpha) / deur::corneringStiffness(L, s0, rl, rr), 1.0, 2e-5);
    EXPECT_NEAR(-f.aligning_moment / std::tan(alpha) / deur::aligningStiffness(L, s0, rl, rr), 1.0, 5e-5);
  }
}

TEST(LugreDistributedTire, OddInSlipAndZeroAtZeroSlip) {
  const LugreSetup s = deur::deurTrapezoidSetup();
  const LugreDistributedTire tire = distributed(s, 200);
  for (double a : {0.3, 2.0, 10.0}) {
    const TireForces<double> p = tire.steadyState(deur::pureLateral(a * kDeg, kSpeed));
    const TireForces<double> m = tire.steadyState(deur::pureLateral(-a * kDeg, kSpeed));
    EXPECT_GT(p.lateral_force, 0.0);
    EXPECT_DOUBLE_EQ(m.lateral_force, -p.lateral_force);
    EXPECT_DOUBLE_EQ(m.aligning_moment, -p.aligning_moment);
  }
  const TireForces<double> zero = tire.steadyState(deur::pureLateral(0.0, kSpeed));
  EXPECT_EQ(zero.lateral_force, 0.0);
  EXPECT_EQ(zero.aligning_moment, 0.0);
}

TEST(LugreDistributedTire, TurnSlipForceFromYawRate) {
  // Turn slip (Velenis eq 64b in our signs): the base point at x = L/2 - zeta ahead of the centre
  // moves laterally at v_y + r x, so v_ry(zeta) = v_ry - (L/2 - zeta) r. For pure yaw at small r the
  // steady deflection is z(zeta) = int_0^zeta v_ry / (r|w|) = -(r / r|w|) zeta (L - zeta) / 2 (a
  // parabola, symmetric about the centre), so with uniform pressure
  //   F_y = sigma0 (1/L) int z dzeta = -sigma0 r L^2 / (12 r|w|),   M_z = 0 (to first order in r).
  // A CCW yaw rate pushes the tire to the right (F < 0). Without turn slip the yaw rate is ignored.
  const LugreSetup s = deur::defaultSetup(ContactPressure::uniform());
  const LugreDistributedTire on(s.coefficients, s.friction, s.pressure, 2000, true);
  const LugreDistributedTire off(s.coefficients, s.friction, s.pressure, 2000, false);
  ContactKinematics<double> k = deur::pureLateral(0.0, kSpeed);
  k.yaw_rate = 1e-4;  // rad/s
  const double L = s.coefficients.contact_length;
  const double expected = -s.coefficients.sigma0y * k.yaw_rate * L * L / (12.0 * k.wheel_speed);
  const TireForces<double> f = on.steadyState(k);
  EXPECT_NEAR(f.lateral_force / expected, 1.0, 2e-3);  // first-order quadrature of v_ry: O(1/N)
  EXPECT_LT(std::fabs(f.aligning_moment), 2e-3 * std::fabs(expected) * L);
  const TireForces<double> g = off.steadyState(k);
  EXPECT_EQ(g.lateral_force, 0.0);
  EXPECT_EQ(g.aligning_moment, 0.0);
  // Turn slip on, yaw rate zero: identical to the plain model.
  const ContactKinematics<double> k2 = deur::pureLateral(2.0 * kDeg, kSpeed);
  EXPECT_DOUBLE_EQ(on.steadyState(k2).lateral_force, off.steadyState(k2).lateral_force);
  // steadyState and evaluate agree with turn slip too (fixed point).
  ContactKinematics<double> k3 = k2;
  k3.yaw_rate = 0.5;
  std::vector<double> z;
  on.steadyState(k3, &z);
  std::vector<double> zd(on.stateSize());
  on.evaluate(k3, z.data(), zd.data());
  for (double v : zd) EXPECT_NEAR(v, 0.0, 1e-12);
}

}  // namespace
}  // namespace lane_keeping
