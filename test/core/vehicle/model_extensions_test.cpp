// Optional model extensions (off by default): tire relaxation, steering system (limit, dead band,
// friction, compliance), body disturbance, localisation bias. Off, they change nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/model_factory.h"
#include "lane_keeping/sim/rk4.h"

#include <Eigen/LU>

namespace lane_keeping {
namespace {

SimConfig brushConfig() {
  SimConfig c;
  c.tire_front.model = c.tire_rear.model = "brush";
  return c;
}

Eigen::VectorXd genericState(const SingleTrackModel& m) {
  InitialState s;
  s.delta = 0.02;
  s.sigma1 = 0.1;
  s.sigma2 = 0.05;
  s.sigma3 = 0.3;
  return m.initialState(s);
}

TEST(ModelExtensions, EachPartsStatesFollowTheLastPartsWhateverTheModels) {
  // The gap replays copy the steering system's and the front tire's states, and the two tires', as one
  // block each (replay::copyStates): the layout of single_track_model.h must hold for every tire model,
  // with and without relaxation, and every steering system.
  for (const char* tire : {"brush", "lugre_lumped", "lugre_distributed", "magic_formula"}) {
    for (double relaxation : {0.0, 0.4}) {
      for (int steering = 0; steering < 4; ++steering) {
        SimConfig c;
        c.tire_front.model = c.tire_rear.model = tire;
        c.tire_front.relaxation_length = relaxation;
        if (steering & 1) c.steering.column_stiffness = 4000.0;
        if (steering & 2) {
          c.steering.friction_model = "lugre";  // a state only with friction to carry
          c.steering.coulomb_friction = 2.0;
        }
        const SingleTrackModel m = createVehicleModel(c);
        const std::string what = std::string(tire) + ", relaxation " + std::to_string(relaxation) + ", steering " +
                                 std::to_string(steering);
        EXPECT_EQ(m.steeringStateOffset(), kRigidStateSize) << what;
        EXPECT_EQ(m.steering().stateSize(), (steering & 1 ? 2 : 0) + (steering & 2 ? 1 : 0)) << what;
        EXPECT_EQ(m.frontTireOffset(), m.steeringStateOffset() + m.steering().stateSize()) << what;
        EXPECT_EQ(m.rearTireOffset(), m.frontTireOffset() + m.frontTire().stateSize()) << what;
        EXPECT_EQ(m.stateSize(), m.rearTireOffset() + m.rearTire().stateSize()) << what;
        EXPECT_EQ(m.frontTire().stateSize() - m.rearTire().stateSize(), relaxation > 0.0 ? 2 : 0) << what;
      }
    }
  }
}

TEST(ModelExtensions, DefaultsAreBeregisModel) {
  const SimConfig c = brushConfig();
  const SingleTrackModel plain = createVehicleModel(c.vehicle, c.tire_front, c.tire_rear);
  const SingleTrackModel full = createVehicleModel(c);
  ASSERT_EQ(plain.stateSize(), full.stateSize());
  const Eigen::VectorXd x = genericState(plain);
  Eigen::VectorXd a(plain.stateSize()), b(full.stateSize());
  plain.derivative(x.data(), 7.0, a.data());
  full.derivative(x.data(), 7.0, b.data());
  EXPECT_EQ(a, b);
}

TEST(ModelExtensions, TorqueLimitAndDeadBand) {
  SimConfig c = brushConfig();
  c.steering.torque_limit = 50.0;
  const SingleTrackModel limited = createVehicleModel(c);
  const SingleTrackModel plain = createVehicleModel(brushConfig());
  const Eigen::VectorXd x = genericState(plain);
  Eigen::VectorXd a(7), b(7);
  limited.derivative(x.data(), 400.0, a.data());
  plain.derivative(x.data(), 50.0, b.data());
  EXPECT_EQ(a, b);  // 400 N m saturates to 50
  c.steering.torque_limit = 0.0;
  c.steering.dead_band = 2.0;
  const SingleTrackModel banded = createVehicleModel(c);
  banded.derivative(x.data(), 1.5, a.data());
  plain.derivative(x.data(), 0.0, b.data());
  EXPECT_EQ(a, b);  // inside the band: nothing
  banded.derivative(x.data(), 5.0, a.data());
  plain.derivative(x.data(), 3.0, b.data());
  EXPECT_EQ(a, b);  // outside: shifted by the band
}

TEST(ModelExtensions, TanhFrictionOpposesTheSteeringRate) {
  SimConfig c = brushConfig();
  c.steering.coulomb_friction = 3.0;
  c.steering.viscous_friction = 0.5;
  const SingleTrackModel friction = createVehicleModel(c);
  const SingleTrackModel plain = createVehicleModel(brushConfig());
  const Eigen::VectorXd x = genericState(plain);  // sigma3 = 0.3 rad/s >> friction_velocity
  Eigen::VectorXd a(7), b(7);
  friction.derivative(x.data(), 0.0, a.data());
  const double expected = 3.0 * std::tanh(0.3 / 0.01) + 0.5 * 0.3;
  plain.derivative(x.data(), -expected, b.data());
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * (1 + std::fabs(b[i])));
}

TEST(ModelExtensions, LugreFrictionSticksThenSlides) {
  // Rotate the wheel at constant rate: the LuGre state settles so that the friction torque is
  // g(w) + b w (Deur eq 9 steady state), i.e. the tanh model's Coulomb level at rates >> w_s.
  SimConfig c = brushConfig();
  c.steering.friction_model = "lugre";
  c.steering.coulomb_friction = 2.0;
  c.steering.breakaway_friction = 3.0;
  const SingleTrackModel m = createVehicleModel(c);
  ASSERT_EQ(m.stateSize(), 8);
  Eigen::VectorXd x = genericState(m), x_dot(8);
  const int z = m.steeringStateOffset();
  for (int i = 0; i < 20000; ++i) {  // integrate only the friction state (explicit Euler, tiny step)
    m.derivative(x.data(), 0.0, x_dot.data());
    x[z] += 1e-5 * x_dot[z];  // 0.2 s: ~30 time constants g / (sigma0 w)
  }
  m.derivative(x.data(), 0.0, x_dot.data());
  const double w = 0.3, g = 2.0 + 1.0 * std::exp(-(w / 0.01) * (w / 0.01));
  EXPECT_NEAR(x[z] * c.steering.friction_stiffness, g, 1e-6);
}

TEST(ModelExtensions, StiffColumnBehavesLikeARigidOneWithTheColumnInertiaAdded) {
  // Constant torque on a very stiff, damped column: the wheel moves like a rigid steering whose
  // inertia is J_F + J_c (0.25 + 0.02 kg m^2); against J_F alone it lags by ~7 %.
  SimConfig c = brushConfig();
  c.steering.column_stiffness = 1e5;
  c.steering.column_damping = 60.0;
  const SingleTrackModel compliant = createVehicleModel(c);
  ASSERT_EQ(compliant.stateSize(), 9);
  Eigen::VectorXd x = compliant.initialState(InitialState{});
  Rk4 rk4(9);
  for (int i = 0; i < 2000; ++i) {
    rk4.step([&](int, const Eigen::VectorXd& s, Eigen::VectorXd& d) { compliant.derivative(s.data(), 20.0, d.data()); },
             1e-5, x);
  }
  SimConfig rigid_config = brushConfig();
  rigid_config.vehicle.steering_inertia += c.steering.column_inertia;
  const SingleTrackModel rigid = createVehicleModel(rigid_config);
  Eigen::VectorXd r = rigid.initialState(InitialState{});
  for (int i = 0; i < 2000; ++i) {
    rk4.step([&](int, const Eigen::VectorXd& s, Eigen::VectorXd& d) { rigid.derivative(s.data(), 20.0, d.data()); },
             1e-5, r);  // (a workspace of another size is fine: Rk4 resizes it)
  }
  EXPECT_NEAR(x[kDelta], r[kDelta], 0.01 * std::fabs(r[kDelta]));
  EXPECT_GT(std::fabs(r[kDelta]), 1e-4);
}

TEST(ModelExtensions, ProgressiveColumnTransmitsTheCubicSpringTorque) {
  // Column at rest, twisted against the wheel, no command: J_c theta_c'' = -k t (1 + (t / a)^2).
  SimConfig c = brushConfig();
  c.steering.column_stiffness = 1500.0;
  c.steering.column_damping = 15.0;
  c.steering.column_inertia = 0.05;
  const int column = createVehicleModel(c).steeringStateOffset();
  for (const double twist : {0.01, 0.03, -0.06}) {
    c.steering.column_stiffening_angle = 0.0;
    const SingleTrackModel linear = createVehicleModel(c);
    c.steering.column_stiffening_angle = 0.03;
    const SingleTrackModel progressive = createVehicleModel(c);
    Eigen::VectorXd x = progressive.initialState(InitialState{});
    x[column] = x[kDelta] + twist;
    Eigen::VectorXd d_lin(x.size()), d_prog(x.size());
    linear.derivative(x.data(), 0.0, d_lin.data());
    progressive.derivative(x.data(), 0.0, d_prog.data());
    const double r = twist / 0.03;
    EXPECT_NEAR(d_lin[column + 1], -1500.0 * twist / 0.05, 1e-9 * 1500.0 / 0.05);
    // At the stiffening angle the secant stiffness is twice the linear one.
    EXPECT_NEAR(d_prog[column + 1], -1500.0 * twist * (1.0 + r * r) / 0.05, 1e-9 * 1500.0 / 0.05);
  }
}

TEST(ModelExtensions, TireRelaxationLagsTheForce) {
  // Relaxation length 0.5 m at V = 15 m/s: time constant 33.3 ms; the steady state is unchanged.
  TireParams p;
  p.model = "brush";
  p.relaxation_length = 0.5;
  const Tire tire = createTire(p, 6000.0);
  ASSERT_EQ(tire.stateSize(), 2);
  ContactKinematics<double> k;
  k.tan_slip_angle = 0.01;
  k.wheel_speed = 15.0;
  // Room for the largest tire state (the lumped LuGre's 3): Tire::evaluate dispatches over every model, and
  // GCC's -Warray-bounds saw the LuGre branch (unreachable for a brush tire) index a 2-element array.
  double state[3] = {0.0, 0.0, 0.0}, dot[3];
  const double target = tire.steadyState(k).lateral_force;
  for (int i = 0; i < 3333; ++i) {  // 33.33 ms with explicit Euler at 10 us
    tire.evaluate(k, state, dot);
    state[0] += 1e-5 * dot[0];
    state[1] += 1e-5 * dot[1];
  }
  EXPECT_NEAR(state[0] / target, 1.0 - std::exp(-1.0), 2e-3);
}

TEST(ModelExtensions, DisturbanceMakesStraightLineNoLongerAnEquilibrium) {
  SimConfig c = brushConfig();
  c.disturbance.lateral_force = 300.0;
  const SingleTrackModel m = createVehicleModel(c);
  const Eigen::VectorXd x = m.initialState(InitialState{});
  Eigen::VectorXd d(7);
  m.derivative(x.data(), 0.0, d.data());
  // M sigma_dot = (300, 0, 0): sigma1_dot = 300 (M^-1)_11.
  const Eigen::Vector3d expected = m.massMatrix(0.0).inverse() * Eigen::Vector3d(300.0, 0.0, 0.0);
  EXPECT_NEAR(d[kSigma1], expected[0], 1e-12);
  EXPECT_NEAR(d[kSigma2], expected[1], 1e-12);
  EXPECT_GT(d[kSigma1], 0.0);
}

TEST(ModelExtensions, PoseBiasShiftsTheTrackerCommand) {
  TrackerParams p;
  p.pose_bias_y = 0.2;
  const PathTracker biased(p, createPath(PathParams{}));
  const PathTracker plain(TrackerParams{}, createPath(PathParams{}));
  const PoseSample pose{0.0, 0.5, 0.0, 15.0, 0.0, 0.0};
  EXPECT_NEAR(biased.command(pose).delta_des - plain.command(pose).delta_des, -0.01 * 0.2, 1e-15);
}

TEST(ModelExtensions, ClosedLoopWithEveryExtensionRuns) {
  SimConfig c;  // lumped LuGre
  c.simulation.duration = 3.0;
  c.tire_front.relaxation_length = c.tire_rear.relaxation_length = 0.3;
  c.steering.friction_model = "lugre";
  c.steering.coulomb_friction = 1.0;
  c.steering.breakaway_friction = 1.5;
  c.steering.torque_limit = 200.0;
  c.steering.column_stiffness = 2e4;
  c.steering.column_damping = 20.0;
  c.disturbance.lateral_force = 200.0;
  c.tracker.pose_bias_y = 0.05;
  const RunResult r = ClosedLoop(c).run();
  EXPECT_FALSE(r.diverged()) << r.message;
  EXPECT_LT(std::fabs(r.rows.back().e_y), 1.0);
}

}  // namespace
}  // namespace lane_keeping
