// The closed loop linearised about straight-line motion (analysis/closed_loop_linearization.h):
// structure of eq 20, entries against the printed equations worked by hand, autodiff against
// central differences, other tire models, per-hop delays, and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/analysis/plant_linearization.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/sim/model_factory.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

int indexOf(const LinearDelaySystem& s, const std::string& name) {
  const auto it = std::find(s.state_names.begin(), s.state_names.end(), name);
  return it == s.state_names.end() ? -1 : static_cast<int>(it - s.state_names.begin());
}

TEST(StabilityLinearization, PaperLoopHasTheStructureOfEq20) {
  const ClosedLoopLinearization lin = linearizeClosedLoop(loadSimConfig({scenario("fig9.yaml")}));
  EXPECT_EQ(lin.dde.state_names, (std::vector<std::string>{"y", "psi", "delta", "sigma1", "sigma2", "sigma3", "z"}));
  EXPECT_EQ(lin.dropped_states, (std::vector<std::string>{"x"}));
  ASSERT_EQ(lin.dde.delayed.size(), 2u);  // {tau2, tau1 + tau2}, nothing else
  EXPECT_DOUBLE_EQ(lin.dde.delayed[0].delay, 1.9019505e-3);
  EXPECT_DOUBLE_EQ(lin.dde.delayed[1].delay, 0.2 + 1.9019505e-3);
  EXPECT_DOUBLE_EQ(lin.k_p, 16000.0);  // p k_p0 = 2000 x 8
  EXPECT_DOUBLE_EQ(lin.k_d, 200.0);
  EXPECT_DOUBLE_EQ(lin.k_i, 1000.0);
}

TEST(StabilityLinearization, EntriesAgreeWithThePrintedEquationsWorkedByHand) {
  // Linear parts of eqs 2-13 at delta = 0 (F = 2a^2k tan(alpha), M = -(2/3) a^3 k tan(alpha)):
  //   Delta = (l-d)^2 m_F m + (m_F + m) J_G,   Theta = (J_F (m + m_F) + Delta) / (J_F Delta)
  // (Appendix B, eqs B.2 and B.15, the legible ones), Theta = d(sigma3')/d(M_S).
  const SimConfig c = loadSimConfig({scenario("fig9.yaml")});
  const ClosedLoopLinearization lin = linearizeClosedLoop(c);
  const LinearDelaySystem& s = lin.dde;
  const double l = 2.57, d = 1.54, b = l - d, m = 1100, mF = 10, JG = 1343, JF = 0.25, V = 15, a = 0.1, k = 2e6;
  const double Delta = b * b * mF * m + (mF + m) * JG;
  const double Theta = (JF * (m + mF) + Delta) / (JF * Delta);
  const double kp = 16000, kd = 200, ki = 1000, kpsi = 0.8, ky = 0.01;
  const int y = indexOf(s, "y"), psi = indexOf(s, "psi"), delta = indexOf(s, "delta"), s1 = indexOf(s, "sigma1"),
            s2 = indexOf(s, "sigma2"), s3 = indexOf(s, "sigma3"), z = indexOf(s, "z");
  const Eigen::MatrixXd& A0 = s.a0;
  const Eigen::MatrixXd& A2 = s.delayed[0].matrix;
  const Eigen::MatrixXd& A21 = s.delayed[1].matrix;
  // Kinematics (eq 2): y' = V psi + sigma1, psi' = sigma2, delta' = sigma3.
  EXPECT_NEAR(A0(y, psi), V, 1e-12);
  EXPECT_NEAR(A0(y, s1), 1.0, 1e-12);
  EXPECT_NEAR(A0(psi, s2), 1.0, 1e-12);
  EXPECT_NEAR(A0(delta, s3), 1.0, 1e-12);
  // Lateral force of the front tire on sigma1 (B.6 and B.5: the leading-point term a sigma3 of eq 8).
  EXPECT_NEAR(A0(s1, delta), 2 * a * a * k * JG / Delta, 1e-9);
  EXPECT_NEAR(A0(s1, s3), -2 * a * a * a * k * JG / (V * Delta), 1e-9);
  // Actuator (eq 12), delayed by tau2, through Theta.
  EXPECT_NEAR(A2(s3, delta), -kp * Theta, 1e-6);
  EXPECT_NEAR(A2(s3, s3), -kd * Theta, 1e-8);
  EXPECT_NEAR(A0(s3, z), ki * Theta, 1e-8);
  // Tracker (eq 11) through the actuator, delayed by tau1 + tau2: k_p delta_des + k_d delta_des' with
  // delta_des' = -k_psi sigma2 - k_y (V psi + sigma1).
  EXPECT_NEAR(A21(s3, psi), Theta * (-kp * kpsi - kd * ky * V), 1e-6);
  EXPECT_NEAR(A21(s3, y), Theta * (-kp * ky), 1e-8);
  EXPECT_NEAR(A21(s3, s2), Theta * (-kd * kpsi), 1e-8);
  // Integral of the delayed error (eq 13).
  EXPECT_NEAR(A21(z, y), -ky, 1e-12);
  EXPECT_NEAR(A21(z, psi), -kpsi, 1e-9);
  EXPECT_NEAR(A2(z, delta), -1.0, 1e-12);
  EXPECT_NEAR(A0(z, z), 0.0, 1e-12);
}

TEST(StabilityLinearization, AutodiffAgreesWithCentralDifferences) {
  for (const std::string tire : {"brush", "lugre_lumped"}) {
    const SimConfig c = loadSimConfig({scenario("fig9.yaml")}, {"tire.front.model=" + tire, "tire.rear.model=" + tire});
    const SingleTrackModel model = createVehicleModel(c);
    const PlantLinearization lin = linearizePlant(model);
    const int n = lin.size();
    for (int j = 0; j <= n; ++j) {
      // A relative step of 1e-6 along one state (or the torque): central difference of the double model.
      const double h = 1e-6;
      Eigen::VectorXd xp = lin.equilibrium, xm = lin.equilibrium, fp(n), fm(n);
      double up = 0.0, um = 0.0;
      if (j < n) {
        xp[j] += h;
        xm[j] -= h;
      } else {
        up = h;
        um = -h;
      }
      model.derivative(xp.data(), up, fp.data());
      model.derivative(xm.data(), um, fm.data());
      const Eigen::VectorXd fd = (fp - fm) / (2 * h);
      const Eigen::VectorXd ad = j < n ? Eigen::VectorXd(lin.a.col(j)) : lin.b;
      for (int i = 0; i < n; ++i) {
        // LuGre's |v_r| z terms are second order: differences see them only at O(h).
        EXPECT_NEAR(ad[i], fd[i], 1e-5 * (1.0 + std::fabs(fd[i]))) << tire << " d(" << lin.state_names[i] << ")/d("
                                                                    << (j < n ? lin.state_names[j] : "M_S") << ")";
      }
    }
  }
}

TEST(StabilityLinearization, LugreLongitudinalBristleStatesAreDecoupled) {
  const ClosedLoopLinearization lin =
      linearizeClosedLoop(loadSimConfig({scenario("fig9.yaml")}, {"tire.front.model=lugre_lumped", "tire.rear.model=lugre_lumped"}));
  ASSERT_FALSE(lin.dropped_states.empty());
  EXPECT_EQ(lin.dropped_states[0], "x");
  EXPECT_EQ(lin.dde.delayed.size(), 2u);
  // z~x (tire state 0) feeds nothing in free rolling (no longitudinal force acts on the single-track
  // model): if kept, its only entry is its own eq 38 rate -kappa r|w|/L = -(2/K_v) V/L = -150 1/s, a
  // decoupled stable root; if the model freezes it (row and column 0) it is dropped like x.
  for (const std::string name : {"front_tire[0]", "rear_tire[0]"}) {
    const int i = indexOf(lin.dde, name);
    if (i < 0) {
      EXPECT_NE(std::find(lin.dropped_states.begin(), lin.dropped_states.end(), name), lin.dropped_states.end());
      continue;
    }
    EXPECT_NEAR(lin.dde.a0(i, i), -150.0, 1e-9);
    EXPECT_NEAR(lin.dde.a0.col(i).norm(), 150.0, 1e-9);
    EXPECT_NEAR(lin.dde.a0.row(i).norm(), 150.0, 1e-9);
    for (const auto& t : lin.dde.delayed) EXPECT_EQ(t.matrix.col(i).norm() + t.matrix.row(i).norm(), 0.0);
  }
  EXPECT_EQ(lin.dde.size() + static_cast<int>(lin.dropped_states.size()), 7 + 3 + 3 + 1);
}

TEST(StabilityLinearization, PerHopDelaysGiveTheGeneralDelaySet) {
  SimConfig c = loadSimConfig({scenario("fig9.yaml")});
  c.delays.pose_to_tracker = 0.2;
  c.delays.desired_steering_to_actuator = 1e-3;
  c.delays.steering_angle_to_actuator = 2e-3;
  c.delays.torque_to_plant = 0.5e-3;
  const ClosedLoopLinearization lin = linearizeClosedLoop(c);
  std::vector<double> delays;
  for (const auto& t : lin.dde.delayed) delays.push_back(t.delay);
  // {tau_T, tau_meas, tau_T + tau_meas, tau_1 + tau_des, tau_T + tau_1 + tau_des}
  const std::vector<double> expected{0.5e-3, 2e-3, 2.5e-3, 0.201, 0.2015};
  ASSERT_EQ(delays.size(), expected.size());
  for (std::size_t i = 0; i < delays.size(); ++i) EXPECT_NEAR(delays[i], expected[i], 1e-15);
  // The integral term reaches the plant after tau_T only.
  EXPECT_NEAR(lin.dde.delayed[0].matrix(indexOf(lin.dde, "sigma3"), indexOf(lin.dde, "z")), 1000.0 * 4.0008, 1.0);
}

TEST(StabilityLinearization, NoStraightLineEquilibriumIsAClearError) {
  SimConfig bias = loadSimConfig({scenario("fig9.yaml")}, {"tracker.pose_bias_y=0.1"});
  try {
    linearizeClosedLoop(bias);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("pose_bias"), std::string::npos) << e.what();
  }
  SimConfig wind = loadSimConfig({scenario("fig9.yaml")}, {"disturbance.lateral_force=100"});
  try {
    linearizeClosedLoop(wind);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("not an equilibrium"), std::string::npos) << e.what();
  }
  SimConfig bad = loadSimConfig({scenario("fig9.yaml")});
  bad.vehicle.mass = -1.0;
  EXPECT_THROW(linearizeClosedLoop(bad), ConfigError);
}

TEST(StabilityLinearization, ConfigParametersByKey) {
  SimConfig c;
  setConfigNumber(c, "tracker.k_y", 0.15);
  EXPECT_EQ(c.tracker.k_y, 0.15);
  setConfigNumber(c, "tau2", 2e-3);
  EXPECT_EQ(c.delays.desired_steering_to_actuator, 2e-3);
  EXPECT_EQ(c.delays.steering_angle_to_actuator, 2e-3);
  EXPECT_EQ(configNumber(c, "tau2"), 2e-3);
  EXPECT_EQ(configParameterInfo("tracker.k_y").unit, "1/m");
  try {
    setConfigNumber(c, "tracker.k_yy", 1.0);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tracker.k_yy is not a numeric configuration key"), std::string::npos) << e.what();
  }
  EXPECT_THROW(setConfigNumber(c, "tire.front.model", 1.0), ConfigError);  // a choice, not a number
  EXPECT_THROW(setConfigNumber(c, "tracker.k_y", NAN), ConfigError);
  EXPECT_THROW(readingByName("no_such_reading"), ConfigError);
}

}  // namespace
}  // namespace lane_keeping
