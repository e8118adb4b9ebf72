#include "lane_keeping/analysis/closed_loop_linearization.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/control/path.h"
#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/control/steering_actuator.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {
namespace {

/// K = d(delta_des, delta_des_dot)/d(pose) of PathTracker::command (Beregi eq 11 and its exact
/// time derivative) on a straight lane, by central differences about `pose0` (step 1e-6 relative:
/// truncation error ~1e-12 relative, the command is smooth there).
Eigen::MatrixXd trackerJacobian(const PathTracker& tracker, const PoseSample& pose0) {
  auto asArray = [](const PoseSample& p) { return std::array<double, 6>{p.x, p.y, p.psi, p.x_dot, p.y_dot, p.yaw_rate}; };
  auto fromArray = [](const std::array<double, 6>& v) { return PoseSample{v[0], v[1], v[2], v[3], v[4], v[5]}; };
  const std::array<double, 6> base = asArray(pose0);
  Eigen::MatrixXd k(2, 6);
  for (int j = 0; j < 6; ++j) {
    const double h = 1e-6 * std::max(1.0, std::fabs(base[j]));
    std::array<double, 6> plus = base, minus = base;
    plus[j] += h;
    minus[j] -= h;
    const SteeringCommand up = tracker.command(fromArray(plus));
    const SteeringCommand down = tracker.command(fromArray(minus));
    k(0, j) = (up.delta_des - down.delta_des) / (2.0 * h);
    k(1, j) = (up.delta_des_rate - down.delta_des_rate) / (2.0 * h);
  }
  return k;
}

bool zeroRowAndColumn(const LinearDelaySystem& s, int i) {
  auto clean = [i](const Eigen::MatrixXd& m) { return m.row(i).isZero(0.0) && m.col(i).isZero(0.0); };
  if (!clean(s.a0)) return false;
  for (const auto& term : s.delayed) {
    if (!clean(term.matrix)) return false;
  }
  return true;
}

bool zeroColumn(const LinearDelaySystem& s, int i) {
  if (!s.a0.col(i).isZero(0.0)) return false;
  for (const auto& term : s.delayed) {
    if (!term.matrix.col(i).isZero(0.0)) return false;
  }
  return true;
}

LinearDelaySystem keepStates(const LinearDelaySystem& s, const std::vector<int>& keep) {
  const int m = static_cast<int>(keep.size());
  auto pick = [&](const Eigen::MatrixXd& full) {
    Eigen::MatrixXd out(m, m);
    for (int r = 0; r < m; ++r) {
      for (int c = 0; c < m; ++c) out(r, c) = full(keep[r], keep[c]);
    }
    return out;
  };
  LinearDelaySystem out;
  out.a0 = pick(s.a0);
  for (const auto& term : s.delayed) out.delayed.push_back({term.delay, pick(term.matrix)});
  for (int i : keep) out.state_names.push_back(s.state_names[i]);
  return out;
}

}  // namespace

ClosedLoopLinearization linearizeClosedLoop(const SimConfig& config, const LinearizationOptions& options) {
  config.validate();
  return assembleClosedLoop(config, linearizePlant(createVehicleModel(config)), options);
}

ClosedLoopLinearization assembleClosedLoop(const SimConfig& config, const PlantLinearization& plant,
                                           const LinearizationOptions& options) {
  ClosedLoopLinearization out;
  out.tau_tracker = config.delays.pose_to_tracker;
  out.tau_desired = config.delays.desired_steering_to_actuator;
  out.tau_measured = config.delays.steering_angle_to_actuator;
  out.tau_torque = config.delays.torque_to_plant;

  // Tracker on a straight lane (the equilibrium of eq 19 exists only there).
  PathParams straight;
  straight.type = "straight";
  const PathTracker tracker(config.tracker, createPath(straight));
  const PoseSample pose0{0.0, 0.0, 0.0, plant.drift[kX], plant.drift[kY], 0.0};
  const SteeringCommand at_rest = tracker.command(pose0);
  if (std::fabs(at_rest.delta_des) > 1e-12 || std::fabs(at_rest.delta_des_rate) > 1e-12) {
    std::ostringstream message;
    message << "stability analysis: the tracker commands delta_des = " << at_rest.delta_des
            << " rad at straight-line motion on the lane centre, so it is not an equilibrium; set "
               "tracker.pose_bias_y and tracker.pose_bias_psi to 0";
    throw ConfigError(message.str());
  }
  out.tracker_jacobian = trackerJacobian(tracker, pose0);

  // Eq 12 coefficients as the actuator applies them (the law is linear: unit responses).
  const ActuatorParams& ap = config.actuator;
  const double m0 = SteeringActuator::torque(ap, 0.0, 0.0, 0.0);
  out.k_p = SteeringActuator::torque(ap, 1.0, 0.0, 0.0) - m0;
  out.k_d = SteeringActuator::torque(ap, 0.0, 1.0, 0.0) - m0;
  out.k_i = SteeringActuator::torque(ap, 0.0, 0.0, 1.0) - m0;
  const double kd_desired = options.derivative_on_desired_rate ? out.k_d : 0.0;

  // Full state: plant states, then z.
  const int np = plant.size();
  const int n = np + 1;
  const int iz = np;
  const Eigen::MatrixXd c = out.tracker_jacobian * plant.poseJacobian();  // rows: delta_des, delta_des_dot
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  b.head(np) = plant.b;
  auto row = [n](int i) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
    r[i] = 1.0;
    return r;
  };
  Eigen::RowVectorXd c_des = Eigen::RowVectorXd::Zero(n), c_des_rate = Eigen::RowVectorXd::Zero(n);
  c_des.head(np) = c.row(0);
  c_des_rate.head(np) = c.row(1);

  LinearDelaySystem full;
  full.a0 = Eigen::MatrixXd::Zero(n, n);
  full.a0.topLeftCorner(np, np) = plant.a;
  full.state_names = plant.state_names;
  full.state_names.push_back("z");
  const double t1 = out.tau_tracker, td = out.tau_desired, tm = out.tau_measured, tt = out.tau_torque;
  // Plant input M_S(t - tau_T) = k_p e + k_d e' + k_i z, all at t - tau_T.
  full.add(tt + t1 + td, b * (out.k_p * c_des + kd_desired * c_des_rate));
  full.add(tt + tm, -b * (out.k_p * row(kDelta) + out.k_d * row(kSigma3)));
  full.add(tt, b * (out.k_i * row(iz)));
  // Integral: z'(t) = e(t) (the actuator integrates the error it receives, eq 13 delayed by tau_2).
  full.add(t1 + td, row(iz).transpose() * c_des);
  full.add(tm, -row(iz).transpose() * row(kDelta));

  // Drop the neutral direction x (checked: nothing depends on it) and frozen states.
  if (!zeroColumn(full, kX)) {
    throw ModelError("linearisation: the closed loop depends on x at straight-line motion; the neutral direction "
                     "of Beregi §3 is missing (is the tracker's lane straight?)");
  }
  std::vector<int> keep;
  for (int i = 0; i < n; ++i) {
    if (i == kX || (i != iz && zeroRowAndColumn(full, i))) {
      out.dropped_states.push_back(full.state_names[i]);
    } else {
      keep.push_back(i);
    }
  }
  out.dde = keepStates(full, keep);
  return out;
}

}  // namespace lane_keeping
