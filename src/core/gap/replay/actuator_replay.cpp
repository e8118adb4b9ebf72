#include "lane_keeping/gap/replay/actuator_replay.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "lane_keeping/gap/log/time_holes.h"
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
  // Across a hole in the log's time axis (time_holes.h) the integral ran on unlogged: after it, its value
  // is as unknown as at the start, so each stretch between holes has an offset of its own (one offset for
  // the whole log left a 5 s hole's jump of k_i z in the residual: an actuator "gap" of 0.22).
  const auto stretches = holeFreeStretches(times);
  std::vector<std::size_t> stretch_of;  // per trace sample
  std::size_t stretch = 0;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    while (stretch + 1 < stretches.size() && i >= stretches[stretch].second) ++stretch;
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
    stretch_of.push_back(stretch);
  }
  // The integral's value at the start of the log (and after each hole) is unknown: a constant torque
  // offset k_i z0 per stretch, fitted.
  std::vector<double> offset(stretches.size() + 1, 0.0), count(stretches.size() + 1, 0.0);
  for (std::size_t k = 0; k < base.size(); ++k) {
    offset[stretch_of[k]] += trace.measured[k] - base[k];
    count[stretch_of[k]] += 1.0;
  }
  for (std::size_t s = 0; s < offset.size(); ++s) offset[s] = count[s] > 0.0 && p.ki() != 0.0 ? offset[s] / count[s] : 0.0;
  for (std::size_t k = 0; k < base.size(); ++k) trace.predicted.push_back(base[k] + offset[stretch_of[k]]);
  out.traces.push_back(std::move(trace));
  return out;
}

}  // namespace lane_keeping
