#include "lane_keeping/sim/run_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace lane_keeping {

std::vector<std::string> describeChanges(std::vector<ScheduledChange> changes) {
  sortForSummary(changes);
  std::vector<std::string> lines;
  for (const ScheduledChange& change : changes) lines.push_back(change.describe());
  return lines;
}

RunSummary summarizeRun(const SimConfig& config, const RunResult& result) {
  RunSummary s;
  s.scenario = config.simulation.name;
  s.changes = describeChanges(result.changes);
  s.diverged = result.diverged();
  s.stop_message = result.message;
  s.duration = result.end_time;
  const auto& rows = result.rows;
  if (rows.empty()) return s;

  std::vector<double> lateral, steering;
  lateral.reserve(rows.size());
  steering.reserve(rows.size());
  for (const auto& r : rows) {
    const double ey = r.e_y;
    if (std::fabs(ey) > s.peak_lateral_offset) {
      s.peak_lateral_offset = std::fabs(ey);
      s.peak_lateral_offset_time = r.t;
    }
    s.peak_steering_angle = std::max(s.peak_steering_angle, std::fabs(r.state.delta));
    s.peak_torque = std::max(s.peak_torque, std::fabs(r.torque_command));
    s.peak_lateral_acceleration = std::max(s.peak_lateral_acceleration, std::fabs(r.state.lateral_acceleration));
    s.peak_slip_angle =
        std::max({s.peak_slip_angle, std::fabs(r.state.slip_angle_front), std::fabs(r.state.slip_angle_rear)});
    if (std::fabs(ey) > 0.5 * config.path.lane_width) s.left_lane = true;
    lateral.push_back(ey);
    steering.push_back(r.state.delta - r.delta_des);
  }
  s.final_lateral_offset = rows.back().e_y;
  s.settling_band = config.simulation.settling_fraction * s.peak_lateral_offset;
  // Settled from the first time after which |e_y| never leaves the band again.
  s.settling_time = -1.0;
  if (!s.diverged) {
    std::size_t last_outside = rows.size();
    for (std::size_t i = rows.size(); i-- > 0;) {
      if (std::fabs(rows[i].e_y) > s.settling_band) {
        last_outside = i;
        break;
      }
    }
    if (last_outside == rows.size()) {
      s.settling_time = rows.front().t;
    } else if (last_outside + 1 < rows.size()) {
      s.settling_time = rows[last_outside + 1].t;
    }
  }
  const double dt = rows.size() > 1 ? (rows.back().t - rows.front().t) / (rows.size() - 1) : 0.0;
  s.lateral = analyzeOscillation(lateral, dt);
  s.steering = analyzeOscillation(steering, dt);
  return s;
}

namespace {

std::string describeOscillation(const OscillationEstimate& o, const char* unit, double scale) {
  char buffer[256];
  if (!o.valid) return "no signal";
  if (!o.regular) {
    std::snprintf(buffer, sizeof(buffer),
                  "no regular oscillation (spectral peak %.3g Hz); %s, rate %+.3g 1/s, RMS %.3g -> %.3g %s",
                  o.frequency_hz, o.trend().c_str(), o.growth_rate, o.rms_first * scale, o.rms_last * scale, unit);
    return buffer;
  }
  std::snprintf(buffer, sizeof(buffer), "%.4g Hz over %d cycles, %s (growth rate %+.3g 1/s, amplitude %.3g -> %.3g %s)",
                o.frequency_hz, o.cycles, o.trend().c_str(), o.growth_rate, o.rms_first * std::sqrt(2.0) * scale,
                o.rms_last * std::sqrt(2.0) * scale, unit);
  return buffer;
}

}  // namespace

std::string formatSummary(const RunSummary& s) {
  std::ostringstream out;
  char line[256];
  out << "== lane_keeping run summary: " << s.scenario << " ==\n";
  if (s.diverged) {
    out << "result:                 DIVERGED — " << s.stop_message << "\n";
  } else {
    out << "result:                 completed " << s.duration << " s\n";
  }
  for (std::size_t i = 0; i < s.changes.size(); ++i) {
    out << (i == 0 ? "changes:                " : "                        ") << s.changes[i] << "\n";
  }
  std::snprintf(line, sizeof(line), "final lateral offset:   %+.4g m\n", s.final_lateral_offset);
  out << line;
  std::snprintf(line, sizeof(line), "peak lateral offset:    %.4g m at t = %.3f s%s\n", s.peak_lateral_offset,
                s.peak_lateral_offset_time, s.left_lane ? "  (left the lane)" : "");
  out << line;
  if (s.settling_time >= 0.0) {
    std::snprintf(line, sizeof(line), "settling time:          %.3f s (|e_y| stays within %.3g m)\n", s.settling_time,
                  s.settling_band);
  } else {
    std::snprintf(line, sizeof(line), "settling time:          not settled (band %.3g m)\n", s.settling_band);
  }
  out << line;
  std::snprintf(line, sizeof(line), "peak steering angle:    %.4g rad (%.3g deg)\n", s.peak_steering_angle,
                s.peak_steering_angle * 180.0 / M_PI);
  out << line;
  std::snprintf(line, sizeof(line), "peak steering torque:   %.4g N m\n", s.peak_torque);
  out << line;
  std::snprintf(line, sizeof(line), "peak lateral accel.:    %.4g m/s^2, peak slip angle %.3g deg\n",
                s.peak_lateral_acceleration, s.peak_slip_angle * 180.0 / M_PI);
  out << line;
  out << "lateral mode (e_y):     " << describeOscillation(s.lateral, "m", 1.0) << "\n";
  out << "steering mode (d-d_des): " << describeOscillation(s.steering, "mrad", 1e3) << "\n";
  return out.str();
}

}  // namespace lane_keeping
