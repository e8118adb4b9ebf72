// Spectral collocation of the DDE (analysis/dde_spectrum.h): the Chebyshev matrix, a DDE with
// known roots, convergence with the degree, and why one grid over the whole delay range is not used.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Eigenvalues>

#include "lane_keeping/analysis/chebyshev.h"
#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

LinearDelaySystem paperLoop(double tau2) {
  SimConfig c = loadSimConfig({scenario("fig9.yaml")});
  c.delays.desired_steering_to_actuator = tau2;
  c.delays.steering_angle_to_actuator = tau2;
  return linearizeClosedLoop(c).dde;
}

/// The discretised eigenvalue nearest `target`.
Complex nearestEigenvalue(const Eigen::MatrixXd& g, Complex target) {
  const Eigen::EigenSolver<Eigen::MatrixXd> es(g, false);
  Complex best = es.eigenvalues()[0];
  for (int i = 0; i < es.eigenvalues().size(); ++i) {
    if (std::abs(es.eigenvalues()[i] - target) < std::abs(best - target)) best = es.eigenvalues()[i];
  }
  return best;
}

TEST(StabilitySpectrum, ChebyshevMatrixDifferentiatesPolynomialsExactly) {
  const ChebyshevGrid g = chebyshevGrid(8);
  EXPECT_DOUBLE_EQ(g.nodes[0], 1.0);
  EXPECT_DOUBLE_EQ(g.nodes[8], -1.0);
  const Eigen::VectorXd u = g.nodes.array().pow(5) - 2.0 * g.nodes.array().square();  // x^5 - 2x^2
  const Eigen::VectorXd du = g.differentiation * u;
  for (int i = 0; i <= 8; ++i) EXPECT_NEAR(du[i], 5 * std::pow(g.nodes[i], 4) - 4 * g.nodes[i], 1e-12);
  // Trefethen's corner entry D_00 = (2N^2 + 1)/6.
  EXPECT_NEAR(g.differentiation(0, 0), (2 * 64 + 1) / 6.0, 1e-12);
  EXPECT_THROW(chebyshevGrid(0), std::invalid_argument);
}

TEST(StabilitySpectrum, ScalarDelayEquationHasLambertWRoots) {
  // x' = -x(t - 1): lambda = W_k(-1); the rightmost pair is W_0(-1) = -0.318131505204764 +- 1.337235701430689 i.
  LinearDelaySystem s;
  s.a0 = Eigen::MatrixXd::Zero(1, 1);
  s.add(1.0, -Eigen::MatrixXd::Ones(1, 1));
  const Spectrum spectrum = computeSpectrum(s);
  ASSERT_FALSE(spectrum.roots.empty());
  EXPECT_NEAR(spectrum.roots[0].value.real(), -0.318131505204764, 1e-12);
  EXPECT_NEAR(spectrum.roots[0].value.imag(), 1.337235701430689, 1e-12);
  EXPECT_TRUE(spectrum.roots[0].refined);
  // The next branch, W_1(-1) = -2.062277729598284 + 7.588631178472513 i (scipy.special.lambertw).
  EXPECT_NEAR(spectrum.roots[1].value.real(), -2.062277729598284, 1e-10);
  EXPECT_NEAR(spectrum.roots[1].value.imag(), 7.588631178472513, 1e-10);
  EXPECT_EQ(spectrum.unstableCount(), 0);
  // x' = +0.5 x(t - 1) has one real root in the right half plane (0.5 e^{-lambda} = lambda: 0.3517).
  LinearDelaySystem u;
  u.a0 = Eigen::MatrixXd::Zero(1, 1);
  u.add(1.0, 0.5 * Eigen::MatrixXd::Ones(1, 1));
  const Spectrum su = computeSpectrum(u);
  EXPECT_NEAR(su.roots[0].value.real(), 0.351733711249196, 1e-12);
  EXPECT_EQ(su.unstableCount(), 1);
}

TEST(StabilitySpectrum, CollocationConvergesWithTheDegree) {
  // Paper loop at tau2 = 1.9019505 ms. Error of the discretised (unrefined) eigenvalues against the
  // Newton-refined roots, for the 122 Hz lower-level mode and the 0.67 Hz lateral mode.
  const LinearDelaySystem s = paperLoop(1.9019505e-3);
  Complex steering(31.0, 768.7), lateral(-1.24, 4.19);
  ASSERT_TRUE(refineRoot(s, &steering));
  ASSERT_TRUE(refineRoot(s, &lateral));
  EXPECT_NEAR(steering.real(), 31.00997965, 1e-6);
  EXPECT_NEAR(steering.imag(), 768.68110252, 1e-6);
  EXPECT_LT(relativeResidual(s, steering), 1e-14);
  std::vector<double> steering_error, lateral_error;
  const std::vector<int> degrees{4, 8, 16, 32, 64, 96, 128};
  for (int m : degrees) {
    const Eigen::MatrixXd g = collocationMatrix(s, m);
    EXPECT_EQ(g.rows(), 7 + 4 * m);  // two delay lines of rank 2
    steering_error.push_back(std::abs(nearestEigenvalue(g, steering) - steering) / std::abs(steering));
    lateral_error.push_back(std::abs(nearestEigenvalue(g, lateral) - lateral) / std::abs(lateral));
  }
  std::printf("  degree M | order | rel. error 122 Hz mode | rel. error 0.67 Hz mode\n");
  for (std::size_t i = 0; i < degrees.size(); ++i) {
    std::printf("  %8d | %5d | %22.2e | %22.2e\n", degrees[i], 7 + 4 * degrees[i], steering_error[i], lateral_error[i]);
  }
  // Lateral mode: |lambda| (tau1 + tau2) / 2 ~ 0.45, resolved at once; spectral (faster than any
  // power) convergence down to round-off by M = 16.
  EXPECT_LT(lateral_error[0], 1e-3);
  EXPECT_LT(lateral_error[1], 1e-7);
  EXPECT_LT(lateral_error[2], 1e-11);
  // Lower-level mode: already within 1e-3 relative at M = 4 (its tracker component is small), and
  // exact to round-off once M exceeds |lambda| (tau1 + tau2) / 2 ~ 78, the Chebyshev resolution
  // limit of e^{lambda theta} on the long line.
  EXPECT_LT(steering_error[0], 1e-3);
  EXPECT_LT(steering_error[5], 1e-9);   // M = 96
  EXPECT_LT(steering_error[6], 1e-10);  // M = 128
  EXPECT_LT(steering_error[6], steering_error[3]);
  // The refined roots do not depend on M: every degree gives the same rightmost root.
  for (int m : {8, 16, 24, 48}) {
    SpectrumOptions o;
    o.degree = m;
    const Spectrum sp = computeSpectrum(s, o);
    EXPECT_NEAR(sp.roots[0].value.real(), steering.real(), 1e-9) << m;
    EXPECT_NEAR(sp.roots[0].value.imag(), steering.imag(), 1e-9) << m;
    EXPECT_TRUE(sp.roots[0].refined);
  }
}

TEST(StabilitySpectrum, OneGridOverTheWholeDelayRangeGivesSpuriousRoots) {
  // The textbook discretisation (one Chebyshev grid on [-(tau1 + tau2), 0] for the whole state,
  // x(-tau2) interpolated) at tau2 = 1.7 ms, where the loop is stable (rightmost root -0.0625):
  // with N = 60 its rightmost eigenvalue is a spurious unstable ~130 Hz one; it needs N ~ 120.
  // The per-delay-line collocation used here is right at M = 8.
  const LinearDelaySystem s = paperLoop(1.7e-3);
  const int n = s.size();
  const double T = s.maxDelay(), tau2 = s.delayed[0].delay;
  auto oneGridAbscissa = [&](int N) {
    const ChebyshevGrid grid = chebyshevGrid(N);
    auto lagrange = [&](double x) {  // barycentric weights (Trefethen, Berrut): row of interpolation at x
      Eigen::RowVectorXd w(N + 1);
      for (int j = 0; j <= N; ++j) w[j] = ((j == 0 || j == N) ? 0.5 : 1.0) * (j % 2 ? -1.0 : 1.0) / (x - grid.nodes[j]);
      return Eigen::RowVectorXd(w / w.sum());
    };
    Eigen::MatrixXd g = Eigen::MatrixXd::Zero((N + 1) * n, (N + 1) * n);
    for (int i = 1; i <= N; ++i) {
      for (int j = 0; j <= N; ++j) {
        g.block(i * n, j * n, n, n) = (2.0 / T) * grid.differentiation(i, j) * Eigen::MatrixXd::Identity(n, n);
      }
    }
    const Eigen::RowVectorXd l2 = lagrange(1.0 - 2.0 * tau2 / T);
    g.block(0, 0, n, n) += s.a0;
    for (int j = 0; j <= N; ++j) {
      g.block(0, j * n, n, n) += l2[j] * s.delayed[0].matrix;
      if (j == N) g.block(0, j * n, n, n) += s.delayed[1].matrix;  // x(-T) is the last node
    }
    const Eigen::EigenSolver<Eigen::MatrixXd> es(g, false);
    double a = -1e300;
    for (int i = 0; i < es.eigenvalues().size(); ++i) a = std::max(a, es.eigenvalues()[i].real());
    return a;
  };
  EXPECT_GT(oneGridAbscissa(60), 1.0);                  // spurious instability
  EXPECT_NEAR(oneGridAbscissa(120), -0.0625, 1e-4);     // right once resolved (order 847)
  SpectrumOptions o;
  o.degree = 8;
  EXPECT_NEAR(computeSpectrum(s, o).abscissa(), -0.0624981, 1e-6);  // order 39
}

TEST(StabilitySpectrum, BadInputIsRejected) {
  LinearDelaySystem s;
  EXPECT_THROW(computeSpectrum(s), std::invalid_argument);  // empty
  s.a0 = Eigen::MatrixXd::Zero(2, 2);
  EXPECT_THROW(s.add(-1.0, Eigen::MatrixXd::Zero(2, 2)), std::invalid_argument);
  EXPECT_THROW(s.add(NAN, Eigen::MatrixXd::Zero(2, 2)), std::invalid_argument);
  EXPECT_THROW(s.add(1.0, Eigen::MatrixXd::Zero(3, 3)), std::invalid_argument);
  SpectrumOptions o;
  o.degree = 1;
  EXPECT_THROW(computeSpectrum(paperLoop(1e-4), o), std::invalid_argument);
}

}  // namespace
}  // namespace lane_keeping
