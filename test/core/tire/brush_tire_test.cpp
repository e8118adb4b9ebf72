// Beregi's brush tire: eqs 6-7 with the Appendix A coefficients.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/tire/brush_tire.h"
#include "lane_keeping/vehicle/vehicle_params.h"

namespace lane_keeping {
namespace {

constexpr double kA = 0.1;    // Beregi Table 1
constexpr double kK = 2.0e6;  // Beregi Table 1

double frontLoad() { return VehicleParams{}.frontAxleLoad(); }

// Fiala/Pacejka closed form of the brush model with mu = mu0 (what App. A expands):
// theta = C |t| / (3 mu Fz), F = mu Fz (3 theta - 3 theta^2 + theta^3) sgn t,
// M = -mu Fz a theta (1 - theta)^3 sgn t, with C = 2 a^2 k.
double fialaForce(double t, double fz, double mu) {
  const double theta = 2 * kA * kA * kK * std::fabs(t) / (3 * mu * fz);
  if (theta >= 1) return mu * fz * (t > 0 ? 1 : -1);
  return mu * fz * (3 * theta - 3 * theta * theta + theta * theta * theta) * (t > 0 ? 1 : -1);
}
double fialaMoment(double t, double fz, double mu) {
  const double theta = 2 * kA * kA * kK * std::fabs(t) / (3 * mu * fz);
  if (theta >= 1) return 0.0;
  return -mu * fz * kA * theta * std::pow(1 - theta, 3) * (t > 0 ? 1 : -1);
}

TEST(BrushTire, ForceAndMomentEqualEqs6And7) {
  const double fz = frontLoad();
  const BrushTire tire(fz, kA, kK, 1.0, 1.0);
  for (double alpha_deg : {-12.0, -5.0, -1.0, -0.1, 0.05, 0.5, 2.0, 4.0, 8.0, 11.0, 20.0}) {
    const double t = std::tan(alpha_deg * M_PI / 180.0);
    SCOPED_TRACE(alpha_deg);
    EXPECT_NEAR(tire.force(t), fialaForce(t, fz, 1.0), 1e-9 * fz);
    EXPECT_NEAR(tire.moment(t), fialaMoment(t, fz, 1.0), 1e-9 * fz * kA);
  }
}

TEST(BrushTire, CoefficientsOfAppendixA) {
  // Hand-computed values of A.1-A.7 at Fz = 4000 N, mu = 0.8, mu0 = 1 (mu != mu0 exercises both terms).
  const double fz = 4000, mu = 0.8, mu0 = 1.0, a = kA, k = kK;
  const BrushTire tire(fz, a, k, mu, mu0);
  const double t = 0.02;
  const double phi1 = 2 * a * a * k;
  const double phi2 = -8 * std::pow(a, 4) * k * k / (3 * fz * mu0) + 4 * std::pow(a, 4) * k * k * mu / (3 * fz * mu0 * mu0);
  const double phi3 = 8 * std::pow(a, 6) * std::pow(k, 3) / (9 * fz * fz * mu0 * mu0) -
                      16 * std::pow(a, 6) * std::pow(k, 3) * mu / (27 * fz * fz * std::pow(mu0, 3));
  EXPECT_DOUBLE_EQ(phi1, 40000.0);
  EXPECT_NEAR(tire.force(t), phi3 * t * t * t + phi2 * t * t + phi1 * t, 1e-9);
  EXPECT_NEAR(tire.force(-t), -(phi3 * t * t * t + phi2 * t * t + phi1 * t), 1e-9);
}

TEST(BrushTire, SmallSlipSlopesAreEqs9And10) {
  const BrushTire tire(frontLoad(), kA, kK, 1.0, 1.0);
  // F(t)/t = phi1 + phi2 |t| + ...: at t = 1e-9 the quadratic term contributes ~1e-4 N/rad.
  const double h = 1e-9;
  EXPECT_NEAR(tire.force(h) / h, 2 * kA * kA * kK, 1e-3);                 // 40000 N/rad
  EXPECT_NEAR(tire.moment(h) / h, -2.0 / 3.0 * std::pow(kA, 3) * kK, 1e-4);  // -1333.3 N m/rad
}

TEST(BrushTire, ContinuousAtFullSlidingForUnequalFriction) {
  // App. A with mu != mu0: at tan(alpha_crit) = 3 mu0 Fz / (2 a^2 k) the cubic meets mu Fz and M meets 0.
  const double fz = frontLoad();
  for (double mu : {0.5, 0.8, 1.0}) {
    const BrushTire tire(fz, kA, kK, mu, 1.0);
    const double tc = tire.tanCriticalSlip();
    SCOPED_TRACE(mu);
    EXPECT_NEAR(tire.force(tc * (1 - 1e-12)), mu * fz, 1e-6 * fz);
    EXPECT_NEAR(tire.moment(tc * (1 - 1e-12)), 0.0, 1e-6 * fz * kA);
    EXPECT_DOUBLE_EQ(tire.force(tc * 1.5), mu * fz);
    EXPECT_DOUBLE_EQ(tire.moment(tc * 1.5), 0.0);
  }
}

TEST(BrushTire, ForceOpposesSlipAndIsOdd) {
  const BrushTire tire(frontLoad(), kA, kK, 1.0, 1.0);
  for (double t : {1e-4, 0.01, 0.1, 0.3, 1.0}) {
    EXPECT_GT(tire.force(t), 0.0);
    EXPECT_LT(tire.moment(t) , 0.0 + (t > tire.tanCriticalSlip() ? 1e-12 : 0.0));
    EXPECT_DOUBLE_EQ(tire.force(-t), -tire.force(t));
    EXPECT_DOUBLE_EQ(tire.moment(-t), -tire.moment(t));
  }
}

}  // namespace
}  // namespace lane_keeping
