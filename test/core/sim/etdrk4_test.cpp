// The exponential integrator (sim/etdrk4.h): its matrix functions against their closed forms, exact
// steps of a forced stiff oscillator at a step 20 times its period's radian, classical RK4 where the
// linear part is zero, fourth-order convergence on a stiff scalar problem, and bad input refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lane_keeping/sim/etdrk4.h"
#include "lane_keeping/sim/rk4.h"

namespace lane_keeping {
namespace {

TEST(Etdrk4, PhiFunctionsOfADiagonalMatrixAreTheScalarClosedForms) {
  // phi1(z) = (e^z - 1) / z, phi2 = (e^z - 1 - z) / z^2, phi3 = (e^z - 1 - z - z^2 / 2) / z^3; for a
  // tiny z the closed forms cancel, and the series 1 / k! + z / (k + 1)! is exact to rounding.
  const Eigen::Vector4d z(-30.0, -1.5, 0.7, 1e-7);
  const Etdrk4::Phi phi = Etdrk4::phiFunctions(z.asDiagonal().toDenseMatrix());
  for (int i = 0; i < 4; ++i) {
    const double x = z[i], e = std::exp(x);
    const bool tiny = std::fabs(x) < 1e-3;
    const double p1 = tiny ? 1.0 + x / 2.0 : (e - 1.0) / x;
    const double p2 = tiny ? 0.5 + x / 6.0 : (e - 1.0 - x) / (x * x);
    const double p3 = tiny ? 1.0 / 6.0 + x / 24.0 : (e - 1.0 - x - 0.5 * x * x) / (x * x * x);
    EXPECT_NEAR(phi.exp(i, i), e, 1e-13 * e) << "z = " << x;
    EXPECT_NEAR(phi.phi1(i, i), p1, 1e-12 * std::fabs(p1)) << "z = " << x;
    EXPECT_NEAR(phi.phi2(i, i), p2, 1e-11 * std::fabs(p2)) << "z = " << x;
    EXPECT_NEAR(phi.phi3(i, i), p3, 1e-10 * std::fabs(p3)) << "z = " << x;
    for (int j = 0; j < 4; ++j) {
      if (j != i) EXPECT_EQ(phi.phi3(i, j), 0.0);
    }
  }
}

TEST(Etdrk4, AForcedStiffOscillatorIsSteppedExactlyFarBeyondRk4sLimit) {
  // x'' = -w^2 x - 2 zeta w x' + F, w = 1e4 rad/s, zeta = 0.02, from rest: the closed form is
  // x = F / w^2 (1 - e^{-zeta w t} (cos(wd t) + zeta w / wd sin(wd t))). The step 2 ms is w h = 20
  // (RK4 diverges beyond 2.8); the constant force is N, and ETD is exact for a constant N.
  const double w = 1e4, zeta = 0.02, force = 3.0, wd = w * std::sqrt(1.0 - zeta * zeta);
  Eigen::Matrix2d l;
  l << 0.0, 1.0, -w * w, -2.0 * zeta * w;
  Etdrk4 etd(l);
  Eigen::VectorXd x = Eigen::Vector2d::Zero();
  const double h = 2e-3;
  for (int k = 1; k <= 25; ++k) {
    etd.step([&](int, const Eigen::VectorXd&, Eigen::VectorXd& n) { n << 0.0, force; }, h, x);
    const double t = k * h;
    const double exact =
        force / (w * w) * (1.0 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)));
    ASSERT_NEAR(x[0], exact, 1e-12 * force / (w * w)) << "t = " << t;
  }
}

TEST(Etdrk4, AColumnsFourCoupledStatesAreSteppedExactly) {
  // The steering replay's linear part: the road wheel (J_F) and the column (J_c) on a spring-damper,
  // states (delta, delta', column, column'), stiff at the replay's 2 ms step (sqrt(k (1/J_c + 1/J_F)) h
  // = 4.6, past RK4's 2.8). Four coupled states take the unrolled products (Etdrk4::kColumnStates).
  // A constant N (a torque on each inertia) is integrated exactly: every step and its midpoint must
  // equal e^{Lh} x + h phi1(Lh) N (at h/2 for the midpoint), to the rounding of entries up to
  // k / J_c = 5e6 1/s^2 (1.7e-9 of the column rate after 4 steps). Then an N that depends on the state
  // (a soft spring to ground on each inertia, so that the stages the products form enter the result):
  // x' = (L + M) x, whose exact step is e^{(L + M) h} x. M does not commute with L, so the scheme is
  // of second order here (Hochbruck & Ostermann 2005): within 1e-4 of the largest state (1.9e-5
  // measured; a stage product with its phi matrix transposed misses by 3.7e-3).
  const double k = 1e5, c = 5.0, jf = 0.25, jc = 0.02, h = 2e-3;
  Eigen::Matrix4d l;
  l << 0.0, 1.0, 0.0, 0.0,  //
      -k / jf, -c / jf, k / jf, c / jf,  //
      0.0, 0.0, 0.0, 1.0,  //
      k / jc, c / jc, -k / jc, -c / jc;
  const Eigen::Vector4d force(0.0, 2.0 / jf, 0.0, -3.0 / jc);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(1, 0) = -1.0 / jf, m(3, 2) = -1.0 / jc;
  Eigen::VectorXd start(4);
  start << 0.01, -0.2, 0.012, 0.1;
  for (const bool constant : {true, false}) {
    Etdrk4 etd(l);
    const Eigen::Matrix4d a = constant ? l : Eigen::Matrix4d(l + m);
    const Etdrk4::Phi whole = Etdrk4::phiFunctions(a * h), half = Etdrk4::phiFunctions(a * (0.5 * h));
    const Eigen::Vector4d drive = constant ? force : Eigen::Vector4d::Zero();
    const double tolerance = constant ? 1e-7 : 1e-4;
    Eigen::VectorXd x = start, mid(4);
    Eigen::Vector4d exact = start;
    for (int step = 1; step <= 40; ++step) {
      const Eigen::Vector4d exact_mid = half.exp * exact + 0.5 * h * half.phi1 * drive;
      exact = whole.exp * exact + h * whole.phi1 * drive;
      etd.stepWithMidpoint(
          [&](int, const Eigen::VectorXd& s, Eigen::VectorXd& n) {
            if (constant) {
              n = force;
            } else {
              n = m * s;
            }
          },
          h, x, mid);
      for (int i = 0; i < 4; ++i) {
        const double scale = exact.cwiseAbs().maxCoeff();
        ASSERT_NEAR(x[i], exact[i], tolerance * scale) << "state " << i << ", step " << step << ", constant " << constant;
        if (constant) ASSERT_NEAR(mid[i], exact_mid[i], tolerance * scale) << "state " << i << ", step " << step;
      }
    }
    EXPECT_GT(std::fabs(x[0] - 0.01), 1e-4) << "the wheel did not move: nothing compared";
  }
}

/// A non-stiff nonlinear test problem: a pendulum with a time-varying torque.
void pendulum(double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
  q_dot[0] = q[1];
  q_dot[1] = -9.81 * std::sin(q[0]) - 0.3 * q[1] + std::cos(2.0 * t);
}

TEST(Etdrk4, WithAZeroLinearPartItIsClassicalRk4) {
  Etdrk4 etd(Eigen::MatrixXd::Zero(2, 2));
  Rk4 rk4(2);
  Eigen::VectorXd a(2), b(2);
  a << 0.4, -1.0;
  b = a;
  const double h = 0.05;
  for (int k = 0; k < 200; ++k) {
    const double t = k * h;
    auto at = [&](int stage, const Eigen::VectorXd& q, Eigen::VectorXd& d) {
      pendulum(t + (stage == 0 ? 0.0 : stage == 3 ? h : 0.5 * h), q, d);
    };
    etd.step(at, h, a);
    rk4.step(at, h, b);
  }
  // Bit for bit: on states L does not couple the step is RK4's, in its order of operations.
  EXPECT_EQ(a[0], b[0]);
  EXPECT_EQ(a[1], b[1]);
  EXPECT_GT(std::fabs(a[0] - 0.4), 0.01);  // it moved
}

/// u' = lambda u + sin(t) u^2 - cos(3 t), lambda = -200, from u = 1 to t = 1 in steps of h.
double stiffScalar(double h) {
  Etdrk4 etd(Eigen::MatrixXd::Constant(1, 1, -200.0));
  Eigen::VectorXd u = Eigen::VectorXd::Ones(1);
  const int steps = static_cast<int>(std::lround(1.0 / h));
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    etd.step([&](int stage, const Eigen::VectorXd& x, Eigen::VectorXd& n) {
      const double s = t + (stage == 0 ? 0.0 : stage == 3 ? h : 0.5 * h);
      n[0] = std::sin(s) * x[0] * x[0] - std::cos(3.0 * s);
    }, h, u);
  }
  return u[0];
}

TEST(Etdrk4, ConvergesAtFourthOrderOnAStiffScalarProblemAndStaysAccurateWhereRk4Diverges) {
  // Halving h divides the error by 2^4 = 16 once lambda h is within a few units (Cox & Matthews'
  // scheme is fourth order when L commutes with N's Jacobian, as a scalar does; measured 13.5, 16.0,
  // 16.5 at lambda h = -2.5, -1.25, -0.6). At lambda h = -20, far past RK4's real-axis limit of -2.8,
  // the error is still ~1e-7.
  const double reference = stiffScalar(1.0 / 8000.0);
  double previous = std::fabs(stiffScalar(0.025) - reference);
  for (double h : {0.0125, 0.00625, 0.003125}) {
    const double error = std::fabs(stiffScalar(h) - reference);
    EXPECT_GT(previous / error, 12.0) << "h = " << h << ": " << previous << " -> " << error;
    EXPECT_LT(previous / error, 20.0) << "h = " << h << ": " << previous << " -> " << error;
    previous = error;
  }
  EXPECT_LT(std::fabs(stiffScalar(0.1) - reference), 1e-6);
}

TEST(Etdrk4, TheMidpointOfAForcedStiffOscillatorsStepIsItsClosedForm) {
  // The dense output at h/2 (stepWithMidpoint) integrates the step's quadratic in N exactly over half of
  // it: exact for a constant force at w h = 20, as the step's end is; the end unchanged bit for bit.
  const double w = 1e4, zeta = 0.02, force = 3.0, wd = w * std::sqrt(1.0 - zeta * zeta);
  Eigen::Matrix2d l;
  l << 0.0, 1.0, -w * w, -2.0 * zeta * w;
  Etdrk4 with_mid(l), plain(l);
  Eigen::VectorXd x = Eigen::Vector2d::Zero(), y = x, mid;
  auto exact = [&](double t) {
    return force / (w * w) * (1.0 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)));
  };
  const double h = 2e-3;
  auto constant = [&](int, const Eigen::VectorXd&, Eigen::VectorXd& n) { n << 0.0, force; };
  double swing = 0.0;
  for (int k = 0; k < 25; ++k) {
    with_mid.stepWithMidpoint(constant, h, x, mid);
    plain.step(constant, h, y);
    ASSERT_NEAR(mid[0], exact((k + 0.5) * h), 1e-12 * force / (w * w)) << "t = " << (k + 0.5) * h;
    ASSERT_EQ(x[0], y[0]);
    ASSERT_EQ(x[1], y[1]);
    swing = std::max(swing, std::fabs(mid[0] - x[0]));
  }
  EXPECT_GT(swing, 1e-3 * force / (w * w));  // the midpoints are not the ends
}

/// The largest error of the midpoints' dense output on stiffScalar's problem with steps of h, at the
/// midpoints from t = `from` on, against the same problem stepped at h / 64.
double stiffScalarMidpointError(double h, double from) {
  auto nonlinear = [](double s, const Eigen::VectorXd& x, Eigen::VectorXd& n) {
    n[0] = std::sin(s) * x[0] * x[0] - std::cos(3.0 * s);
  };
  Etdrk4 coarse(Eigen::MatrixXd::Constant(1, 1, -200.0)), fine(Eigen::MatrixXd::Constant(1, 1, -200.0));
  Eigen::VectorXd u = Eigen::VectorXd::Ones(1), v = u, mid;
  const int steps = static_cast<int>(std::lround(0.5 / h)), sub = 64;
  const double hf = h / sub;
  double worst = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    coarse.stepWithMidpoint(
        [&](int stage, const Eigen::VectorXd& x, Eigen::VectorXd& n) {
          nonlinear(t + (stage == 0 ? 0.0 : stage == 3 ? h : 0.5 * h), x, n);
        },
        h, u, mid);
    for (int j = 0; j < sub; ++j) {
      const double tf = t + j * hf;
      fine.step([&](int stage, const Eigen::VectorXd& x, Eigen::VectorXd& n) {
        nonlinear(tf + (stage == 0 ? 0.0 : stage == 3 ? hf : 0.5 * hf), x, n);
      }, hf, v);
      if (j + 1 == sub / 2 && t >= from) worst = std::max(worst, std::fabs(mid[0] - v[0]));
    }
  }
  return worst;
}

TEST(Etdrk4, TheMidpointsDenseOutputConvergesAtThirdOrderOrBetter) {
  // A quadratic in N integrated exactly: past the initial layer (u = 1 relaxes onto the slow solution at
  // lambda = -200, 5 ms; from t = 0.1 s on) the midpoints' error falls at least 2^3 = 8-fold per halving
  // of h (measured 11, 14, 15: the steps' own fourth order showing through). Inside the layer, where
  // lambda h = -5 ... -1.25, the stages are order-reduced (Hochbruck & Ostermann 2005) and the error
  // does not fall before lambda h is small; it stays ~1e-6 of the solution's unit scale.
  double previous = stiffScalarMidpointError(0.0125, 0.1);
  for (double h : {0.00625, 0.003125, 0.0015625}) {
    const double error = stiffScalarMidpointError(h, 0.1);
    EXPECT_GT(previous / error, 8.0) << "h = " << h << ": " << previous << " -> " << error;
    previous = error;
  }
  EXPECT_LT(previous, 1e-11);
  for (double h : {0.025, 0.0125, 0.00625}) EXPECT_LT(stiffScalarMidpointError(h, 0.0), 2e-6) << "h = " << h;
}

TEST(Etdrk4, RefusesANonSquareOrNonFiniteLinearPartAndABadStep) {
  EXPECT_THROW(Etdrk4(Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
  EXPECT_THROW(Etdrk4(Eigen::MatrixXd::Constant(2, 2, std::nan(""))), std::invalid_argument);
  Etdrk4 etd(Eigen::MatrixXd::Identity(1, 1));
  Eigen::VectorXd x = Eigen::VectorXd::Ones(1);
  auto zero = [](int, const Eigen::VectorXd&, Eigen::VectorXd& n) { n.setZero(); };
  EXPECT_THROW(etd.step(zero, 0.0, x), std::invalid_argument);
  EXPECT_THROW(etd.step(zero, std::nan(""), x), std::invalid_argument);
  etd.step(zero, 0.5, x);
  EXPECT_NEAR(x[0], std::exp(0.5), 1e-14);
}

}  // namespace
}  // namespace lane_keeping
