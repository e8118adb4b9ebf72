#include "lane_keeping/gap/actuator_replay.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lane_keeping/gap/replay_shooting.h"
#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

namespace {

/// The motor side of a compliant column (steering.angle_sensor = column), which the log does not hold:
/// the column driven by the applied torque (the logged command, delayed by delays.torque_to_plant and
/// clamped by the torque limit) and by the logged road wheel through the torsion bar and its damper
/// (the equations of SingleTrackModel::steeringSystem), started twisted by the first torque.
class ColumnObserver {
 public:
  ColumnObserver(const SimConfig& config, const LogSignals& log) : log_(log) {
    const SteeringParams& p = config.steering;
    const double tau = config.delays.torque_to_plant;
    const auto applied = [&](double t) {
      double m = log.at(C::kTorque, std::max(log.start(), t - tau));
      if (p.dead_band > 0.0) m = std::fabs(m) <= p.dead_band ? 0.0 : m - std::copysign(p.dead_band, m);
      if (p.torque_limit > 0.0) m = std::clamp(m, -p.torque_limit, p.torque_limit);
      return m;
    };
    const auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
      const double twist = q[0] - log.at(C::kDelta, t);
      double spring = p.column_stiffness * twist;
      if (p.column_stiffening_angle > 0.0) spring *= 1.0 + std::pow(twist / p.column_stiffening_angle, 2);
      const double transmitted = spring + p.column_damping * (q[1] - log.at(C::kDeltaRate, t));
      q_dot[0] = q[1];
      q_dot[1] = (applied(t) - transmitted) / p.column_inertia;
    };
    // RK4 stays stable and accurate well inside h (sqrt(k / J) + c / J) < 1.
    const double fastest = std::sqrt(p.column_stiffness / p.column_inertia) + p.column_damping / p.column_inertia;
    const double step = std::min(2e-4, 0.5 / fastest);
    const auto& times = log.times();
    Eigen::VectorXd q(2);
    q[0] = log.at(C::kDelta, times.front()) + applied(times.front()) / p.column_stiffness;
    q[1] = log.at(C::kDeltaRate, times.front());
    Rk4 rk4(2);
    angle_.reserve(times.size());
    rate_.reserve(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
      if (i > 0) integrate(f, times[i - 1], times[i], step, q, rk4);
      if (!q.allFinite()) q.setZero();  // cannot happen within the step bound; never feed NaN on
      angle_.push_back(q[0]);
      rate_.push_back(q[1]);
    }
  }

  /// The column's angle and rate at t (linear between log samples).
  SteeringMeasurement at(double t) const {
    const auto& times = log_.times();
    const std::size_t i = log_.indexAtOrBefore(t);
    if (i + 1 >= times.size() || t <= times[i]) return {angle_[i], rate_[i]};
    const double w = (t - times[i]) / (times[i + 1] - times[i]);
    return {angle_[i] + w * (angle_[i + 1] - angle_[i]), rate_[i] + w * (rate_[i + 1] - rate_[i])};
  }

 private:
  const LogSignals& log_;
  std::vector<double> angle_, rate_;
};

}  // namespace

SubsystemReplay replayActuator(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments) {
  SubsystemReplay out;
  out.name = "actuator";
  const ActuatorParams& p = config.actuator;
  const double tau_des = config.delays.desired_steering_to_actuator;
  const double tau_meas = config.delays.steering_angle_to_actuator;
  const double lag = std::max(tau_des, tau_meas);
  // The actuator's angle sensor: the logged road wheel, or the motor side of a compliant column.
  std::optional<ColumnObserver> column;
  if (config.steering.columnSensor() && config.steering.compliant()) column.emplace(config, log);
  ReplayTrace trace = makeTrace("torque", log.samples(C::kTorque));
  const auto& times = log.times();
  // z(t - tau2): trapezoid over the logged error from the first usable sample (eq 13).
  double z = 0.0, previous_t = 0.0, previous_e = 0.0;
  bool started = false;
  std::vector<double> base;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    if (t - lag < log.start()) continue;
    // The measured angle and rate: nearest samples carried along their smoothed curves (interpolated
    // 0.1 ms back, their noise was coloured and read as excess; LogSignals::nearestAlongSmoothed).
    double measured = 0.0, measured_rate = 0.0;
    if (column) {
      const SteeringMeasurement m = column->at(t - tau_meas);
      measured = m.delta;
      measured_rate = m.delta_rate;
    } else {
      measured = log.nearestAlongSmoothed(C::kDelta, t - tau_meas);
      measured_rate = log.nearestAlongSmoothed(C::kDeltaRate, t - tau_meas);
    }
    const double e = log.at(C::kDeltaDes, t - tau_des) - measured;
    const double e_rate = log.at(C::kDeltaDesRate, t - tau_des) - measured_rate;
    if (started) z += 0.5 * (t - previous_t) * (previous_e + e);
    started = true;
    previous_t = t;
    previous_e = e;
    if (!inSegments(t, segments)) continue;
    trace.t.push_back(t);
    trace.measured.push_back(log.samples(C::kTorque)[i]);
    base.push_back(p.kp() * e + p.kd() * e_rate + p.ki() * z);  // eq 12 with z(start) = 0
  }
  // The integral's value at the start of the log is unknown: a constant torque offset k_i z0, fitted.
  double offset = 0.0;
  for (std::size_t k = 0; k < base.size(); ++k) offset += trace.measured[k] - base[k];
  if (!base.empty() && p.ki() != 0.0) offset /= base.size();
  else offset = 0.0;
  for (double b : base) trace.predicted.push_back(b + offset);
  out.traces.push_back(std::move(trace));
  return out;
}

}  // namespace lane_keeping
