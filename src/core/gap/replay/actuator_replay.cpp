#include "lane_keeping/gap/replay/actuator_replay.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lane_keeping/gap/replay/column_observer.h"
#include "lane_keeping/gap/replay/replay_shooting.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

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
