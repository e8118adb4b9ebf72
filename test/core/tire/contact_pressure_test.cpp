// Normal pressure along the patch and the lumped factors kappa(y), lambda(y), y = L / Z (Deur eqs 24,
// 31b), against Deur's closed forms: eqs 40-41 and 54 (trapezoid), 43 and 57 (uniform), limits 42, 55.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "lane_keeping/tire/contact_pressure.h"

namespace lane_keeping {
namespace {

constexpr double kRl = 0.134;  // Deur App. A.2
constexpr double kRr = 0.707;

// ---- Deur's closed forms, written out as printed (rho = Z / L = 1 / y) ----
double pm(double rl, double rr) { return 2.0 / (1.0 + rr - rl); }                              // eq 28
double kv(double rl, double rr) { return 2.0 / 3.0 * (1.0 + rr + rr * rr - rl * rl) / (1.0 + rr - rl); }  // eq 31a

double kappaEq40(double y, double rl, double rr) {
  const double rho = 1.0 / y;
  const double E = rho / rl * (1.0 - std::exp(-rl / rho)) -
                   rho / (1.0 - rr) * (std::exp(-rr / rho) - std::exp(-1.0 / rho));  // eq 41
  return 1.0 / (1.0 / (pm(rl, rr) * E) - rho);                                       // eq 40
}

double lambdaEq54(double y, double rl, double rr) {
  const double rho = 1.0 / y, p = pm(rl, rr);
  const double num = 1.0 + p * rho *
                               (rho / rl - (rho + rl) / rl * std::exp(-rl / rho) -
                                (rho + rr) / (1.0 - rr) * std::exp(-rr / rho) + (rho + 1.0) / (1.0 - rr) * std::exp(-1.0 / rho));
  const double den = kv(rl, rr) - 2.0 * p * rho * rho *
                                       (2.0 * rho / rl - (2.0 * rho + rl) / rl * std::exp(-rl / rho) -
                                        (2.0 * rho + rr) / (1.0 - rr) * std::exp(-rr / rho) +
                                        (2.0 * rho + 1.0) / (1.0 - rr) * std::exp(-1.0 / rho));
  return num / den;
}

double kappaEq43(double y) {
  const double Z_L = 1.0 / y;
  return (1.0 - std::exp(-y)) / (1.0 - Z_L * (1.0 - std::exp(-y)));
}

double lambdaEq57(double y) {
  const double Z_L = 1.0 / y;
  return (1.0 - std::exp(-y)) / (1.0 + 2.0 * Z_L * std::exp(-y) - 2.0 * Z_L * Z_L * (1.0 - std::exp(-y)));
}

// y where the closed forms are well conditioned (they subtract O(1/y^k) terms). Checked against
// 50-digit mpmath: eqs 40, 43, 57 are good to < 5e-13 on all of these; eq 54 loses digits fastest
// (7e-11 at y = 0.1, 1.7e-10 at y = 0.05), hence its looser bound below y = 0.2.
const std::vector<double> kWellConditionedY{0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 15.0, 20.0, 50.0};

TEST(ContactPressure, PeakAndKvAreEqs28And31a) {
  const ContactPressure trap = ContactPressure::trapezoidal(kRl, kRr);
  EXPECT_NEAR(trap.peak(), 2.0 / 1.573, 1e-15);                                       // eq 28
  EXPECT_NEAR(trap.kv(), 2.0 / 3.0 * (1.0 + kRr + kRr * kRr - kRl * kRl) / 1.573, 1e-15);  // eq 31a
  EXPECT_NEAR(trap.kv(), 0.927693579148, 1e-12);
  const ContactPressure uni = ContactPressure::uniform();
  EXPECT_TRUE(uni.isUniform());
  EXPECT_FALSE(trap.isUniform());
  EXPECT_DOUBLE_EQ(uni.peak(), 1.0);
  EXPECT_DOUBLE_EQ(uni.kv(), 1.0);

  // The shape p(s) (Fig 7): integrates to 1 (eq 19) and K_v = 2 int s p ds (eq 31a), by a fine
  // midpoint rule that is independent of the closed forms above.
  const int n = 200000;
  double area = 0.0, moment = 0.0;
  for (int i = 0; i < n; ++i) {
    const double s = (i + 0.5) / n;
    area += trap.at(s) / n;
    moment += 2.0 * s * trap.at(s) / n;
  }
  EXPECT_NEAR(area, 1.0, 1e-9);
  EXPECT_NEAR(moment, trap.kv(), 1e-9);
  EXPECT_NEAR(trap.at(kRl / 2), trap.peak() / 2, 1e-15);
  EXPECT_NEAR(trap.at(0.5), trap.peak(), 1e-15);
  EXPECT_NEAR(trap.at(1.0), 0.0, 1e-15);
  EXPECT_NEAR(trap.at(0.0), 0.0, 1e-15);
}

TEST(ContactPressure, UniformKappaLambdaEqualEqs43And57) {
  const ContactPressure p = ContactPressure::uniform();
  for (double y : kWellConditionedY) {
    SCOPED_TRACE(y);
    EXPECT_NEAR(p.kappa(y) / kappaEq43(y), 1.0, 1e-10);
    EXPECT_NEAR(p.lambda(y) / lambdaEq57(y), 1.0, 1e-10);
  }
}

TEST(ContactPressure, TrapezoidalKappaLambdaEqualEqs40And54) {
  const ContactPressure p = ContactPressure::trapezoidal(kRl, kRr);
  for (double y : kWellConditionedY) {
    SCOPED_TRACE(y);
    EXPECT_NEAR(p.kappa(y) / kappaEq40(y, kRl, kRr), 1.0, 1e-10);
    EXPECT_NEAR(p.lambda(y) / lambdaEq54(y, kRl, kRr), 1.0, y < 0.2 ? 1e-9 : 1e-10);
  }
  // A second trapezoid (margins near the ends) exercises the other pieces.
  const ContactPressure q = ContactPressure::trapezoidal(0.02, 0.77);  // Velenis Table 2 margins
  for (double y : kWellConditionedY) {
    if (y < 0.2) continue;  // 1/r_l = 50 makes the closed forms worse conditioned
    SCOPED_TRACE(y);
    EXPECT_NEAR(q.kappa(y) / kappaEq40(y, 0.02, 0.77), 1.0, 1e-9);
    EXPECT_NEAR(q.lambda(y) / lambdaEq54(y, 0.02, 0.77), 1.0, 1e-9);
  }
}

TEST(ContactPressure, AccurateWhereClosedFormsCancel) {
  // 50-digit mpmath values of eqs 40/43/54/57 at small y, where the double closed forms lose up to
  // 1e-9 (eq 54 at y = 0.02) and everything at y = 1e-6. The exact integrals keep full precision.
  struct Ref {
    double y, kappa_u, lambda_u, kappa_t, lambda_t;
  };
  const Ref refs[] = {
      {1e-6, 1.9999996666667222, 1.4999998125000297, 2.1558839055663195, 1.7115191460335648},
      {1e-3, 1.9996667222185182, 1.4998125296861326, 2.1555141373000033, 1.7113333855397041},
      {0.02, 1.9933555258767783, 1.4962618640234251, 2.1484988229983178, 1.707809962502407},
  };
  const ContactPressure u = ContactPressure::uniform();
  const ContactPressure t = ContactPressure::trapezoidal(kRl, kRr);
  for (const Ref& r : refs) {
    SCOPED_TRACE(r.y);
    EXPECT_NEAR(u.kappa(r.y), r.kappa_u, 2e-15);
    EXPECT_NEAR(u.lambda(r.y), r.lambda_u, 2e-15);
    EXPECT_NEAR(t.kappa(r.y), r.kappa_t, 4e-15);
    EXPECT_NEAR(t.lambda(r.y), r.lambda_t, 4e-15);
  }
}

TEST(ContactPressure, LimitsAreEqs42And55) {
  const ContactPressure t = ContactPressure::trapezoidal(kRl, kRr);
  const ContactPressure u = ContactPressure::uniform();
  const double kv_t = kv(kRl, kRr);
  const double lambda_max_t =
      1.5 * ((kRr * kRr + kRr + 1 - kRl * kRl) / 3) / ((kRr * kRr * kRr + kRr * kRr + kRr + 1 - kRl * kRl * kRl) / 4);  // eq 55b
  EXPECT_NEAR(lambda_max_t, 1.7115193320051808, 1e-14);
  EXPECT_NEAR(t.lambdaMax(), lambda_max_t, 1e-15);
  for (double y : {0.0, 1e-300, 1e-12}) {
    SCOPED_TRACE(y);
    EXPECT_NEAR(t.kappa(y), 2.0 / kv_t, 1e-11);       // eq 42b: kappa_max = 2 / K_v = 2.1559
    EXPECT_NEAR(t.lambda(y), lambda_max_t, 1e-11);    // eq 55b: 1.7115
    EXPECT_NEAR(u.kappa(y), 2.0, 1e-11);              // uniform kappa_max = 2
    EXPECT_NEAR(u.lambda(y), 1.5, 1e-11);             // uniform lambda_max = 1.5
  }
  // y -> inf: kappa -> 0 (eq 42a), lambda -> 1/K_v (eq 55a); uniform kappa, lambda -> 1.
  // The approach is O(1/y): kappa_t ~ p_m / (r_l y), kappa_u ~ 1 + 1/y, lambda_u ~ 1 + 2/y^2.
  for (double y : {1e4, 1e6, 1e8}) {
    SCOPED_TRACE(y);
    EXPECT_GT(t.kappa(y), 0.0);
    EXPECT_NEAR(t.kappa(y), 0.0, 1.1 * pm(kRl, kRr) / (kRl * y));
    EXPECT_NEAR(t.lambda(y), 1.0 / kv_t, 10.0 / y);
    EXPECT_NEAR(u.kappa(y), 1.0, 1.1 / y);
    EXPECT_NEAR(u.lambda(y), 1.0, 1.1 / y);
  }
  // Finite (no 0 * inf from exp(-y) times powers of y) up to the largest y a double holds.
  for (double y : {1e17, 1e160, 1e300}) {
    SCOPED_TRACE(y);
    EXPECT_NEAR(t.kappa(y), 0.0, 1e-15);
    EXPECT_NEAR(t.lambda(y), 1.0 / kv_t, 1e-15);
    EXPECT_NEAR(u.kappa(y), 1.0, 1e-15);
    EXPECT_NEAR(u.lambda(y), 1.0, 1e-15);
  }
}

TEST(ContactPressure, MonotonicallyDecreasing) {
  for (const ContactPressure& p : {ContactPressure::uniform(), ContactPressure::trapezoidal(kRl, kRr)}) {
    double prev_k = p.kappa(0.0), prev_l = p.lambda(0.0);
    int checked = 0;
    for (double y = 1e-8; y < 1e5; y *= 1.05) {
      const double k = p.kappa(y), l = p.lambda(y);
      ASSERT_TRUE(std::isfinite(k) && std::isfinite(l)) << y;
      // Allow rounding ties where the change per step is below machine precision (tiny y).
      ASSERT_LE(k, prev_k + 1e-15) << "kappa at y = " << y;
      ASSERT_LE(l, prev_l + 1e-15) << "lambda at y = " << y;
      prev_k = k;
      prev_l = l;
      ++checked;
    }
    EXPECT_GT(checked, 500);
    // Over that range kappa falls from kappa_max to (nearly) kappa_min: 2 -> 1 (uniform),
    // 2.156 -> 0 (trapezoid); lambda from lambda_max to lambda_min.
    if (p.isUniform()) {
      EXPECT_NEAR(p.kappa(1e5), 1.0, 2e-5);
      EXPECT_NEAR(p.lambda(1e5), 1.0, 2e-5);
    } else {
      EXPECT_LT(p.kappa(1e5), 2e-4);
      EXPECT_NEAR(p.lambda(1e5), 1.0 / p.kv(), 1e-3);
    }
  }
}

TEST(ContactPressure, SmoothAtTinyYAndAcrossSeriesSwitches) {
  const ContactPressure t = ContactPressure::trapezoidal(kRl, kRr);
  const ContactPressure u = ContactPressure::uniform();
  for (const ContactPressure* p : {&t, &u}) {
    for (double y : {0.0, 1e-300, 1e-200, 1e-12}) {
      EXPECT_TRUE(std::isfinite(p->kappa(y)));
      EXPECT_TRUE(std::isfinite(p->lambda(y)));
    }
    // Linear near 0: the difference quotient has a limit (uniform: d kappa/dy = -1/3 from eq 43's
    // series 2 - y/3 + ..., d lambda/dy = -3/16 from eq 57's).
    const double dk1 = (p->kappa(1e-4) - p->kappa(0.0)) / 1e-4;
    const double dk2 = (p->kappa(1e-6) - p->kappa(0.0)) / 1e-6;
    const double dl1 = (p->lambda(1e-4) - p->lambda(0.0)) / 1e-4;
    const double dl2 = (p->lambda(1e-6) - p->lambda(0.0)) / 1e-6;
    EXPECT_NEAR(dk1, dk2, 1e-4 * std::fabs(dk2) + 1e-8);
    EXPECT_NEAR(dl1, dl2, 1e-4 * std::fabs(dl2) + 1e-8);
    EXPECT_LT(dk2, 0.0);
    EXPECT_LT(dl2, 0.0);
    if (p == &u) {
      EXPECT_NEAR(dk2, -1.0 / 3.0, 1e-5);
      EXPECT_NEAR(dl2, -3.0 / 16.0, 1e-5);
    }
    // Continuous where e(.) and A_n(.) switch from series to closed form (y c = 0.5 or 2 for
    // c = r_l, r_r, 1).
    for (double y : {0.5, 2.0, 2.0 / kRr, 2.0 / kRl, 0.5 / kRl, 0.5 / kRr}) {
      SCOPED_TRACE(y);
      const double lo = y * (1 - 1e-13), hi = y * (1 + 1e-13);
      EXPECT_NEAR(p->kappa(lo), p->kappa(hi), 3e-13);
      EXPECT_NEAR(p->lambda(lo), p->lambda(hi), 3e-13);
    }
  }
}

TEST(ContactPressure, FactorsEqualKappaAndLambda) {
  // factors() (used by the lumped model) evaluates uniform kappa, lambda by degree-8 polynomials below
  // y = 0.4 and through phi-functions above (series below y = 1, recurrence beyond): it must agree
  // with kappa(), lambda() everywhere, across both switches, and as y -> inf (y = L c0 / r|w|: a wheel
  // speed near zero), where lambda -> 1.
  for (const ContactPressure& p : {ContactPressure::uniform(), ContactPressure::trapezoidal(kRl, kRr)}) {
    for (double y : {0.0, 1e-300, 1e-12, 1e-3, 0.1, 0.2, 0.3, 0.399999999999, 0.4, 0.400000000001, 0.999999999999, 1.0, 1.000000000001, 2.0, 10.0, 1e3, 1e6,
                     1e12, 1e17, 1e300}) {
      SCOPED_TRACE(y);
      const auto f = p.factors(y);
      EXPECT_NEAR(f.kappa, p.kappa(y), 2e-14);  // kappa, lambda are O(1) or (trapezoid kappa) -> 0
      EXPECT_NEAR(f.lambda, p.lambda(y), 2e-14);
    }
  }
}

}  // namespace
}  // namespace lane_keeping
