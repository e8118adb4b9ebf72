// Pacejka's Magic Formula with Velenis Table 1 coefficients (F_y: B 0.244, C 1.5, D 1936, E -0.132;
// M_z: B 0.247, C 2.56, D -15.53, E -3.92; slip angle in degrees).
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/tire/magic_formula_tire.h"
#include "lane_keeping/tire/tire.h"

namespace lane_keeping {
namespace {

constexpr double kDeg = M_PI / 180.0;

ContactKinematics<double> slip(double alpha_deg, double speed = 15.0) {
  ContactKinematics<double> k;
  k.tan_slip_angle = std::tan(alpha_deg * kDeg);
  k.wheel_speed = speed * std::cos(alpha_deg * kDeg);
  k.lateral_slip_speed = speed * std::sin(alpha_deg * kDeg);
  return k;
}

TireForces<double> at(const MagicFormulaTire& t, double alpha_deg) {
  return t.evaluate(slip(alpha_deg), static_cast<const double*>(nullptr), static_cast<double*>(nullptr));
}

TEST(MagicFormulaTire, CorneringStiffnessAtReferenceLoad) {
  const MagicFormulaParams p;
  const MagicFormulaTire tire(p, p.reference_load, 1.0);
  // B C D = 0.244 * 1.5 * 1936 = 708.576 N/deg = 40598.4 N/rad (the "40599", rounded).
  EXPECT_NEAR(tire.corneringStiffness(), 40598.41, 0.01);
  EXPECT_NEAR(tire.corneringStiffness(), 708.576 * 180.0 / M_PI, 1e-9);
  // Numerical slope at 1e-6 deg (curve is odd, so the error is O(alpha^2)).
  EXPECT_NEAR(at(tire, 1e-6).lateral_force / (1e-6 * kDeg), 40598.41, 0.01);
  // M_z: -B C D = 0.247 * 2.56 * 15.53 = 9.8198 N m/deg = 562.64 N m/rad; dM/dalpha < 0.
  EXPECT_NEAR(tire.aligningStiffness(), 0.247 * 2.56 * 15.53 * 180.0 / M_PI, 1e-9);
  EXPECT_NEAR(-at(tire, 1e-6).aligning_moment / (1e-6 * kDeg), tire.aligningStiffness(), 1e-4);
  // The Tire wrapper.
  TireParams tp;
  tp.model = "magic_formula";
  const Tire wrapped = createTire(tp, tp.magic_formula.reference_load);
  EXPECT_DOUBLE_EQ(wrapped.corneringStiffness(), tire.corneringStiffness());
  EXPECT_DOUBLE_EQ(wrapped.aligningStiffness(), tire.aligningStiffness());
  EXPECT_EQ(wrapped.stateSize(), 0);
}

TEST(MagicFormulaTire, CurveEqualsFormulaAtHandValues) {
  // Y = D sin(C atan(B a - E (B a - atan(B a)))), a in degrees. Hand check at 5 deg:
  // B a = 1.22, atan = 0.883886, 1.22 + 0.132 (1.22 - 0.883886) = 1.264367, atan = 0.901774,
  // 1.5 * that = 1.352661, sin = 0.976249, F = 1936 * 0.976249 = 1890.02 N.
  const MagicFormulaParams p;
  const MagicFormulaTire tire(p, p.reference_load, 1.0);
  struct Row {
    double alpha_deg, fy, mz;
  };
  const Row rows[] = {{1.0, 681.7479403038401, -9.589620187312155},
                      {2.0, 1226.997210089851, -15.402506486421927},
                      {5.0, 1890.0177894156182, -1.004095377732236},
                      {10.0, 1882.4221295205596, 7.99041300926201},
                      {20.0, 1691.6210179399377, 10.523627221889512}};
  for (const Row& r : rows) {
    SCOPED_TRACE(r.alpha_deg);
    const TireForces<double> f = at(tire, r.alpha_deg);
    EXPECT_NEAR(f.lateral_force, r.fy, 1e-9);
    EXPECT_NEAR(f.aligning_moment, r.mz, 1e-11);
    EXPECT_EQ(f.longitudinal_force, 0.0);
  }
  EXPECT_NEAR(at(tire, 5.0).lateral_force, 1890.02, 0.01);
  // D scales with mu F_z / F_z0.
  const MagicFormulaTire heavy(p, 4000.0, 0.8);
  EXPECT_NEAR(at(heavy, 2.0).lateral_force, 1.6 * 1226.997210089851, 1e-9);
  EXPECT_NEAR(heavy.corneringStiffness(), 1.6 * tire.corneringStiffness(), 1e-9);
}

TEST(MagicFormulaTire, SaturatesAtDAndIsOdd) {
  const MagicFormulaParams p;
  const MagicFormulaTire tire(p, p.reference_load, 1.0);
  double peak = 0.0, peak_alpha = 0.0;
  for (double a = 0.0; a <= 40.0; a += 0.001) {
    const double f = at(tire, a).lateral_force;
    if (f > peak) {
      peak = f;
      peak_alpha = a;
    }
  }
  // sin(C atan(.)) reaches 1 (C = 1.5 > 1): the peak is exactly D, near 6.9 deg.
  EXPECT_NEAR(peak, p.fy_d, 1e-4);
  EXPECT_GT(peak_alpha, 5.0);
  EXPECT_LT(peak_alpha, 9.0);
  // Beyond the peak it falls monotonically towards D sin(C pi/2) = 0.707 D (reached only as
  // alpha -> inf; 1450 N = 0.75 D at 89 deg).
  double prev = peak;
  for (double a = std::ceil(peak_alpha); a <= 89.0; a += 1.0) {
    const double f = at(tire, a).lateral_force;
    EXPECT_LT(f, prev) << a;
    EXPECT_GT(f, p.fy_d * std::sin(1.5 * M_PI / 2)) << a;
    prev = f;
  }
  EXPECT_NEAR(at(tire, 89.0).lateral_force, 1450.49, 0.01);
  for (double a : {0.1, 1.0, 3.0, 7.0, 15.0, 45.0}) {
    const TireForces<double> fp = at(tire, a), fm = at(tire, -a);
    EXPECT_GT(fp.lateral_force, 0.0);  // opposes the slip: sign(F) = sign(v_ry)
    EXPECT_LE(fp.lateral_force, p.fy_d);
    EXPECT_DOUBLE_EQ(fm.lateral_force, -fp.lateral_force);
    EXPECT_DOUBLE_EQ(fm.aligning_moment, -fp.aligning_moment);
  }
  EXPECT_EQ(at(tire, 0.0).lateral_force, 0.0);
}

}  // namespace
}  // namespace lane_keeping
