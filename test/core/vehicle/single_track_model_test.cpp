// Beregi's single-track model: the constraint of eq 1, the mass matrix of eq 4, straight-line motion.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {
namespace {

SingleTrackModel model(const std::string& tire) {
  TireParams t;
  t.model = tire;
  return createVehicleModel(VehicleParams{}, t, t);
}

// Row 1 of eq 1: the front axle's wheel-direction speed equals V. Relative to the size of its terms
// (x_dot and y_dot carry 1/cos(delta), which rounding amplifies when the wheel passes 90 degrees).
double constraintResidual(const SingleTrackModel& m, const Eigen::VectorXd& x) {
  Eigen::VectorXd x_dot(m.stateSize());
  m.derivative(x.data(), 0.0, x_dot.data());
  const double psi = x[kPsi], delta = x[kDelta], b = m.params().cgToFrontAxle();
  const double size = std::fabs(x_dot[kX]) + std::fabs(x_dot[kY]) + b * std::fabs(x_dot[kPsi]) + m.params().speed;
  return (std::cos(psi + delta) * x_dot[kX] + std::sin(psi + delta) * x_dot[kY] + b * std::sin(delta) * x_dot[kPsi] -
          m.params().speed) / size;
}

TEST(SingleTrackModel, KinematicsSatisfyEq1AlongATrajectory) {
  for (const std::string tire : {"brush", "lugre_lumped"}) {
    SCOPED_TRACE(tire);
    const SingleTrackModel m = model(tire);
    InitialState initial;
    initial.psi = 0.3;
    initial.delta = 0.05;
    initial.sigma1 = 0.4;
    initial.sigma2 = -0.2;
    initial.sigma3 = 0.5;
    Eigen::VectorXd x = m.initialState(initial);
    Rk4 rk4(m.stateSize());
    double worst = 0.0, worst_sigma1 = 0.0;
    for (int i = 0; i < 20000; ++i) {  // 2 s with a sinusoidal steering torque
      const double torque = 40.0 * std::sin(2.0 * M_PI * 1.5 * i * 1e-4);
      rk4.step([&](int, const Eigen::VectorXd& s, Eigen::VectorXd& d) { m.derivative(s.data(), torque, d.data()); },
               1e-4, x);
      worst = std::max(worst, std::fabs(constraintResidual(m, x)));
      // Row 2 of eq 1: sigma1 is the lateral velocity of G in the body frame.
      Eigen::VectorXd x_dot(m.stateSize());
      m.derivative(x.data(), torque, x_dot.data());
      const double size = std::fabs(x_dot[kX]) + std::fabs(x_dot[kY]) + std::fabs(x[kSigma1]);
      worst_sigma1 = std::max(worst_sigma1, std::fabs(-std::sin(x[kPsi]) * x_dot[kX] + std::cos(x[kPsi]) * x_dot[kY] -
                                                      x[kSigma1]) / size);
    }
    // Eq 2 satisfies eq 1 identically; what remains is rounding, relative to the terms' size (the
    // open-loop torque spins the wheel through 90 degrees, where x_dot and y_dot grow like 1/cos(delta)
    // out of terms that cancel). Measured: at most 1.3e-12; a kinematic error would be O(1).
    EXPECT_LT(worst, 1e-11);
    EXPECT_LT(worst_sigma1, 1e-11);
    EXPECT_GT(std::fabs(x[kDelta] - 0.05), 1e-3);  // the trajectory went somewhere
  }
}

TEST(SingleTrackModel, MassMatrixIsSymmetricPositiveDefinite) {
  const SingleTrackModel m = model("brush");
  for (double delta : {-1.2, -0.5, 0.0, 0.1, 0.7, 1.4}) {
    const Eigen::Matrix3d M = m.massMatrix(delta);
    EXPECT_DOUBLE_EQ(M(0, 1), M(1, 0));
    EXPECT_DOUBLE_EQ(M(1, 2), M(2, 1));
    EXPECT_DOUBLE_EQ(M(0, 2), 0.0);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "delta = " << delta;
  }
  // At delta = 0: m11 = m + m_F, m12 = m_F (l - d), m22 = J_F + J_G + m_F (l - d)^2 (eq 4).
  const Eigen::Matrix3d M0 = m.massMatrix(0.0);
  EXPECT_DOUBLE_EQ(M0(0, 0), 1110.0);
  EXPECT_NEAR(M0(0, 1), 10.0 * 1.03, 1e-12);
  EXPECT_NEAR(M0(1, 1), 0.25 + 1343.0 + 10.0 * 1.03 * 1.03, 1e-9);
  EXPECT_DOUBLE_EQ(M0(2, 2), 0.25);
}

TEST(SingleTrackModel, DerivativeSolvesTheMassMatrixSystem) {
  // sigma_dot from derivative() satisfies M sigma_dot = f for a generic state (eq 3).
  const SingleTrackModel m = model("brush");
  InitialState initial;
  initial.delta = 0.2;
  initial.sigma1 = 0.3;
  initial.sigma2 = 0.1;
  initial.sigma3 = -0.4;
  const Eigen::VectorXd x = m.initialState(initial);
  Eigen::VectorXd d1(m.stateSize()), d2(m.stateSize());
  m.derivative(x.data(), 0.0, d1.data());
  m.derivative(x.data(), 10.0, d2.data());
  // Only f3 changes with M_S, by 10 N m: M (d2 - d1) = (0, 0, 10).
  const Eigen::Vector3d dsigma(d2[kSigma1] - d1[kSigma1], d2[kSigma2] - d1[kSigma2], d2[kSigma3] - d1[kSigma3]);
  const Eigen::Vector3d f = m.massMatrix(0.2) * dsigma;
  EXPECT_NEAR(f[0], 0.0, 1e-9);
  EXPECT_NEAR(f[1], 0.0, 1e-9);
  EXPECT_NEAR(f[2], 10.0, 1e-9);
}

TEST(SingleTrackModel, StraightLineMotionIsAnEquilibrium) {
  for (const std::string tire : {"brush", "lugre_lumped", "lugre_distributed", "magic_formula"}) {
    SCOPED_TRACE(tire);
    const SingleTrackModel m = model(tire);
    InitialState initial;
    initial.y = 1.7;  // any lateral position: the plant alone has no preferred line
    const Eigen::VectorXd x = m.initialState(initial);
    Eigen::VectorXd x_dot(m.stateSize());
    m.derivative(x.data(), 0.0, x_dot.data());
    EXPECT_DOUBLE_EQ(x_dot[kX], 15.0);
    for (int i = 1; i < m.stateSize(); ++i) EXPECT_EQ(x_dot[i], 0.0) << "state " << i;
  }
}

TEST(SingleTrackModel, MirrorSymmetry) {
  // Reflecting y, psi, delta, sigma1..3 and the torque reflects the derivative (left/right symmetry).
  const SingleTrackModel m = model("lugre_lumped");
  InitialState a;
  a.y = 0.4;
  a.psi = 0.1;
  a.delta = 0.03;
  a.sigma1 = 0.2;
  a.sigma2 = 0.05;
  a.sigma3 = 0.3;
  InitialState b = a;
  b.y = -a.y;
  b.psi = -a.psi;
  b.delta = -a.delta;
  b.sigma1 = -a.sigma1;
  b.sigma2 = -a.sigma2;
  b.sigma3 = -a.sigma3;
  Eigen::VectorXd xa = m.initialState(a), xb = m.initialState(b);
  xa.tail(6) << 1e-4, 2e-4, -3e-5, 0.0, 1e-4, 5e-5;  // lumped tire states (x, y, psi per tire)
  xb.tail(6) = -xa.tail(6);
  Eigen::VectorXd da(m.stateSize()), db(m.stateSize());
  m.derivative(xa.data(), 12.0, da.data());
  m.derivative(xb.data(), -12.0, db.data());
  EXPECT_NEAR(da[kX], db[kX], 1e-12);
  for (int i = 1; i < m.stateSize(); ++i) EXPECT_NEAR(da[i], -db[i], 1e-9 * (1 + std::fabs(da[i]))) << i;
}

TEST(SingleTrackModel, SlipAnglesFollowEq8) {
  const SingleTrackModel m = model("brush");
  InitialState s;
  s.delta = 0.02;
  s.sigma1 = 0.1;
  s.sigma2 = 0.05;
  s.sigma3 = 0.2;
  const Eigen::VectorXd x = m.initialState(s);
  Eigen::VectorXd x_dot(m.stateSize());
  VehicleOutputs<double> out;
  m.derivative(x.data(), 0.0, x_dot.data(), &out);
  const double a = 0.1, l = 2.57, d = 1.54, V = 15.0, c = std::cos(0.02), sn = std::sin(0.02);
  const double tan_front = -(0.1 + (l - d) * 0.05 + a * (0.05 + 0.2)) / (V * c) + std::tan(0.02);
  const double tan_rear = -(0.1 - (d - a) * 0.05) * c / (V - (0.1 + (l - d) * 0.05) * sn);
  EXPECT_NEAR(out.tan_slip_front, tan_front, 1e-15);
  EXPECT_NEAR(out.tan_slip_rear, tan_rear, 1e-15);
}

}  // namespace
}  // namespace lane_keeping
