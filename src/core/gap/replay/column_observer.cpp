#include "lane_keeping/gap/replay/column_observer.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "lane_keeping/gap/replay/replay_shooting.h"
#include "lane_keeping/sim/rk4.h"

namespace lane_keeping {

using C = LogSignals::Channel;

namespace {

/// The torque the column receives for a commanded m: the dead band, then the limit (as the plant).
double appliedTorque(const SteeringParams& p, double m) {
  if (p.dead_band > 0.0) m = std::fabs(m) <= p.dead_band ? 0.0 : m - std::copysign(p.dead_band, m);
  if (p.torque_limit > 0.0) m = std::clamp(m, -p.torque_limit, p.torque_limit);
  return m;
}

/// One sample interval of x' = A x + B u with u linear over it (first-order hold):
///   x(h) = Phi x(0) + Gamma u(0) + Lambda (u(h) - u(0)) / h,
/// read off exp(S h) for S = [[A, B, 0], [0, 0, I], [0, 0, 0]] (the input and its constant slope as
/// states; Van Loan's block form).
struct HoldStep {
  double h = -1.0;  // none computed yet
  Eigen::Matrix2d phi = Eigen::Matrix2d::Zero();
  Eigen::Matrix<double, 2, 3> gamma = Eigen::Matrix<double, 2, 3>::Zero(), lambda = Eigen::Matrix<double, 2, 3>::Zero();

  void compute(const Eigen::Matrix2d& a, const Eigen::Matrix<double, 2, 3>& b, double step) {
    Eigen::Matrix<double, 8, 8> s = Eigen::Matrix<double, 8, 8>::Zero();
    s.block<2, 2>(0, 0) = a;
    s.block<2, 3>(0, 2) = b;
    s.block<3, 3>(2, 5).setIdentity();
    const Eigen::Matrix<double, 8, 8> m = (s * step).exp();
    h = step;
    phi = m.block<2, 2>(0, 0);
    gamma = m.block<2, 3>(0, 2);
    lambda = m.block<2, 3>(0, 5);
  }
};

}  // namespace

ColumnObserver::ColumnObserver(const SimConfig& config, const LogSignals& log) : log_(log) {
  const SteeringParams& p = config.steering;
  const double tau = config.delays.torque_to_plant;
  const auto& times = log.times();
  std::vector<double> applied(times.size());
  std::size_t hint = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    applied[i] = appliedTorque(p, log.at(C::kTorque, std::max(log.start(), times[i] - tau), &hint));
  }
  angle_.reserve(times.size());
  rate_.reserve(times.size());
  // Started twisted by the first torque, at the wheel's rate.
  angle_.push_back(log.samples(C::kDelta).front() + applied.front() / p.column_stiffness);
  rate_.push_back(log.samples(C::kDeltaRate).front());
  if (p.column_stiffening_angle > 0.0) {
    rk4(p, tau);
  } else {
    exact(p, applied);
  }
}

void ColumnObserver::exact(const SteeringParams& p, const std::vector<double>& applied) {
  const auto& times = log_.times();
  const auto& delta = log_.samples(C::kDelta);
  const auto& delta_rate = log_.samples(C::kDeltaRate);
  const double inv_j = 1.0 / p.column_inertia;
  Eigen::Matrix2d a;
  a << 0.0, 1.0, -p.column_stiffness * inv_j, -p.column_damping * inv_j;
  Eigen::Matrix<double, 2, 3> b;
  b << 0.0, 0.0, 0.0, inv_j, p.column_stiffness * inv_j, p.column_damping * inv_j;
  HoldStep step;
  Eigen::Vector2d x(angle_.front(), rate_.front());
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double h = times[i] - times[i - 1];
    if (h <= 0.0) {  // a repeated stamp: no time passes
      angle_.push_back(x[0]);
      rate_.push_back(x[1]);
      continue;
    }
    // A log's intervals repeat (to rounding): one matrix exponential per distinct interval.
    if (std::fabs(h - step.h) > 1e-9 * h) step.compute(a, b, h);
    const Eigen::Vector3d u0(applied[i - 1], delta[i - 1], delta_rate[i - 1]);
    const Eigen::Vector3d u1(applied[i], delta[i], delta_rate[i]);
    x = step.phi * x + step.gamma * u0 + step.lambda * ((u1 - u0) / h);
    if (!x.allFinite()) x.setZero();  // never feed NaN on (bad parameters reach here only through a fit)
    angle_.push_back(x[0]);
    rate_.push_back(x[1]);
  }
}

void ColumnObserver::rk4(const SteeringParams& p, double tau) {
  const LogSignals& log = log_;
  const auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    const double twist = q[0] - log.at(C::kDelta, t);
    double spring = p.column_stiffness * twist;
    spring *= 1.0 + std::pow(twist / p.column_stiffening_angle, 2);
    const double transmitted = spring + p.column_damping * (q[1] - log.at(C::kDeltaRate, t));
    q_dot[0] = q[1];
    q_dot[1] = (appliedTorque(p, log.at(C::kTorque, std::max(log.start(), t - tau))) - transmitted) / p.column_inertia;
  };
  // RK4 stays stable and accurate well inside h (sqrt(k / J) + c / J) < 1; the progressive column
  // stiffens with twist, three times the base rate covers it.
  const double fastest =
      3.0 * std::sqrt(p.column_stiffness / p.column_inertia) + p.column_damping / p.column_inertia;
  const double step = std::min(2e-4, 0.5 / fastest);
  const auto& times = log.times();
  Eigen::VectorXd q(2);
  q << angle_.front(), rate_.front();
  Rk4 rk4(2);
  for (std::size_t i = 1; i < times.size(); ++i) {
    replay::integrate(f, times[i - 1], times[i], step, q, rk4);
    if (!q.allFinite()) q.setZero();
    angle_.push_back(q[0]);
    rate_.push_back(q[1]);
  }
}

SteeringMeasurement ColumnObserver::at(double t) const {
  const auto& times = log_.times();
  const std::size_t i = log_.indexAtOrBefore(t);
  if (i + 1 >= times.size() || t <= times[i]) return {angle_[i], rate_[i]};
  const double w = (t - times[i]) / (times[i + 1] - times[i]);
  return {angle_[i] + w * (angle_[i + 1] - angle_[i]), rate_[i] + w * (rate_[i + 1] - rate_[i])};
}

}  // namespace lane_keeping
