// Critical delays and gains of the linearised loop (analysis/stability_boundary.h): the paper's
// Fig 9 point, the higher-level boundary, the readings of the equations that move the lower-level
// boundary to the paper's 1.9019505 ms, and what LuGre tires change.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

constexpr double kPaperFig9Tau2 = 1.9019505e-3;

SimConfig fig9(const std::vector<std::string>& sets = {}) { return loadSimConfig({scenario("fig9.yaml")}, sets); }

Crossing criticalTau2(const SystemFamily& family) {
  ScanOptions scan;  // tau2 from 0.5 ms (stable in every case here) to 50 ms, 5 % apart
  scan.start = 0.5e-3;
  scan.steps = 95;
  scan.spectrum.degree = 16;
  return findFirstCrossing(family, scan);
}

TEST(StabilityCritical, LowerLevelDelayOfThePaperLoop) {
  // k_psi = 0.8, k_y = 0.01 1/m, tau1 = 0.2 s, p = 2000, brush tires, equations as printed.
  const Crossing c = criticalTau2(configFamily(fig9(), "tau2"));
  ASSERT_TRUE(c.found) << c.reason;
  EXPECT_GT(c.parameter, 1.5e-3);
  EXPECT_LT(c.parameter, kPaperFig9Tau2);
  EXPECT_NEAR(c.parameter, 1.763006093e-3, 1e-11);
  EXPECT_GT(c.frequencyHz(), 100.0);
  EXPECT_LT(c.frequencyHz(), 150.0);
  EXPECT_NEAR(c.frequencyHz(), 128.8976, 1e-3);
  EXPECT_NEAR(c.root.real(), 0.0, 1e-9);
  EXPECT_LT(c.abscissa_start, 0.0);  // stable for small tau2
  // Either side: 1.5 ms stable (rightmost: the integral mode -k_i/k_p = -0.0625), the paper's
  // 1.9019505 ms unstable at +31.0 1/s, 122.3 Hz.
  const Spectrum below = computeSpectrum(configFamily(fig9(), "tau2")(1.5e-3));
  EXPECT_NEAR(below.abscissa(), -0.0625, 1e-4);
  const Spectrum above = computeSpectrum(configFamily(fig9(), "tau2")(kPaperFig9Tau2));
  EXPECT_NEAR(above.abscissa(), 31.010, 1e-3);
  EXPECT_NEAR(above.roots[0].frequencyHz(), 122.339, 1e-3);
  EXPECT_EQ(above.unstableCount(), 2);
}

TEST(StabilityCritical, HigherLevelBoundaryOfThePaperLoop) {
  // tau2 = 0.1 ms: k_y from 0.01 up loses stability at 0.1405 1/m through a 0.52 Hz pair (so the
  // paper's Figs 7-8 gains, k_y = 0.15, are just unstable); k_psi from 0.8 up at 1.4355 (0.81 Hz).
  const SimConfig c = loadSimConfig({scenario("fig6.yaml")});
  ScanOptions scan;
  scan.start = 0.01;
  scan.end = 0.5;
  scan.steps = 100;
  const Crossing ky = findFirstCrossing(configFamily(c, "tracker.k_y"), scan);
  ASSERT_TRUE(ky.found);
  EXPECT_NEAR(ky.parameter, 0.140500, 1e-5);
  EXPECT_NEAR(ky.frequencyHz(), 0.5166, 1e-3);
  scan.start = 0.8;
  scan.end = 3.0;
  scan.geometric = false;
  const Crossing kpsi = findFirstCrossing(configFamily(c, "tracker.k_psi"), scan);
  ASSERT_TRUE(kpsi.found);
  EXPECT_NEAR(kpsi.parameter, 1.43551, 1e-4);
  EXPECT_NEAR(kpsi.frequencyHz(), 0.8120, 1e-3);
  // Unstable from the start: no crossing, and the reason says so.
  scan.start = 2.0;
  const Crossing none = findFirstCrossing(configFamily(c, "tracker.k_psi"), scan);
  EXPECT_FALSE(none.found);
  EXPECT_NE(none.reason.find("unstable already"), std::string::npos) << none.reason;
}

TEST(StabilityCritical, ReadingsOfTheEquationsAndThePaperValue) {
  // Which terms move tau2c, and which reading puts the paper's 1.9019505 ms just above it.
  const SimConfig c = fig9();
  std::map<std::string, Crossing> r;
  for (const auto& reading : candidateReadings()) r[reading.name] = criticalTau2(readingFamily(c, reading));
  EXPECT_NEAR(r["printed"].parameter, 1.763006e-3, 1e-9);  // = configFamily's: same linearisation
  EXPECT_NEAR(r["no_front_leading_point"].parameter, 1.816409e-3, 1e-9);       // +3.0 %
  EXPECT_NEAR(r["no_aligning_moment_in_f3"].parameter, 1.829401e-3, 1e-9);     // +3.8 %
  EXPECT_NEAR(r["aligning_moment_sign_in_f3"].parameter, 1.900948e-3, 1e-9);   // +7.8 %
  EXPECT_NEAR(r["decoupled_steering_inertia"].parameter, 1.763680e-3, 1e-9);   // +0.04 %
  EXPECT_NEAR(r["kd_on_measured_rate_only"].parameter, 1.762890e-3, 1e-9);     // -0.007 %
  EXPECT_NEAR(r["no_steering_mass"].parameter, 1.762998e-3, 1e-9);             // -0.0005 %
  EXPECT_NEAR(r["sign_in_f3_and_decoupled_inertia"].parameter, 1.901840e-3, 1e-9);
  // The sign reading is the only single change that lands within 0.1 % below the paper's value.
  for (const auto& [name, crossing] : r) {
    const double gap = kPaperFig9Tau2 / crossing.parameter - 1.0;
    if (name == "aligning_moment_sign_in_f3" || name == "sign_in_f3_and_decoupled_inertia") {
      EXPECT_GT(gap, 0.0) << name;
      EXPECT_LT(gap, 6e-4) << name;
    } else {
      EXPECT_GT(gap, 0.035) << name;
    }
    EXPECT_GT(crossing.frequencyHz(), 126.0) << name;
    EXPECT_LT(crossing.frequencyHz(), 130.0) << name;
  }
}

TEST(StabilityCritical, PaperTrendWithControlStrengthNeedsTheSignReading) {
  // Beregi §3: "larger values of p result in larger stable domains", bounded by p -> infinity. With
  // f3 = M_F + M_S as printed, the restoring aligning stiffness (a/3) 2a^2k = 1333 N m/rad lowers the
  // static steering gain k_p / (k_p + 1333), so the k_y boundary *shrinks* with p; with the sign
  // reading the gain is k_p / (k_p - 1333) and the boundary grows with p, as the paper says.
  ScanOptions scan;
  scan.start = 0.01;
  scan.end = 0.5;
  scan.steps = 60;
  auto kyCritical = [&](double p, const EquationReading& reading) {
    SimConfig c = loadSimConfig({scenario("fig6.yaml")});
    c.actuator.p = p;
    const SystemFamily family = [c, reading](double ky) {
      SimConfig at = c;
      at.tracker.k_y = ky;
      return linearizeUnderReading(at, reading);
    };
    return findFirstCrossing(family, scan).parameter;
  };
  const EquationReading printed = readingByName("printed"), sign = readingByName("aligning_moment_sign_in_f3");
  const double printed500 = kyCritical(500, printed), printed8000 = kyCritical(8000, printed);
  const double sign500 = kyCritical(500, sign), sign8000 = kyCritical(8000, sign);
  std::printf("  k_y boundary at k_psi = 0.8: printed p=500 %.5f p=8000 %.5f; sign reading p=500 %.5f p=8000 %.5f\n",
              printed500, printed8000, sign500, sign8000);
  EXPECT_NEAR(printed500, 0.15695, 1e-4);
  EXPECT_NEAR(printed8000, 0.13487, 1e-4);
  EXPECT_NEAR(sign500, 0.07814, 1e-4);
  EXPECT_NEAR(sign8000, 0.13063, 1e-4);
  EXPECT_GT(printed500, printed8000);
  EXPECT_LT(sign500, sign8000);
}

TEST(StabilityCritical, LugreTiresMoveTheBoundaries) {
  // Same loop with lumped LuGre tires (Deur eqs 38, 45, 51; same small-slip stiffnesses as the brush):
  // the tire lag (relaxation length L/kappa) filters the aligning moment at 128 Hz, which moves the
  // lower-level boundary up by 3.8 %, close to dropping M_F from f3 (1.8294 ms); the 0.5 Hz
  // higher-level boundary moves by 0.9 %.
  const SimConfig brush = fig9();
  const SimConfig lugre = fig9({"tire.front.model=lugre_lumped", "tire.rear.model=lugre_lumped"});
  const Crossing b = criticalTau2(configFamily(brush, "tau2"));
  const Crossing l = criticalTau2(configFamily(lugre, "tau2"));
  EXPECT_NEAR(b.parameter, 1.763006e-3, 1e-9);
  EXPECT_NEAR(l.parameter, 1.830238e-3, 1e-9);
  EXPECT_NEAR(l.frequencyHz(), 127.945, 1e-3);
  EXPECT_NEAR(l.parameter / b.parameter - 1.0, 0.0381, 5e-4);
  ScanOptions scan;
  scan.start = 0.01;
  scan.end = 0.5;
  scan.steps = 100;
  SimConfig lugre_fig6 = loadSimConfig({scenario("fig6.yaml")}, {"tire.front.model=lugre_lumped", "tire.rear.model=lugre_lumped"});
  const Crossing ky = findFirstCrossing(configFamily(lugre_fig6, "tracker.k_y"), scan);
  EXPECT_NEAR(ky.parameter, 0.141810, 1e-5);
  EXPECT_NEAR(ky.parameter / 0.140500 - 1.0, 0.0093, 2e-4);
}

}  // namespace
}  // namespace lane_keeping
