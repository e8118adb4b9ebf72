#include "lane_keeping/analysis/stability_json.h"

#include <cmath>

#include "lane_keeping/analysis/config_parameter.h"

namespace lane_keeping {

using json = StabilityJson;

json rootJson(Complex r, bool refined) {
  return json{{"re", r.real()}, {"im", r.imag()}, {"frequency_hz", std::fabs(r.imag()) / (2 * M_PI)}, {"refined", refined}};
}

json spectrumJson(const Spectrum& s, int count) {
  json roots = json::array();
  for (std::size_t i = 0; i < s.roots.size() && static_cast<int>(i) < count; ++i) {
    roots.push_back(rootJson(s.roots[i].value, s.roots[i].refined));
  }
  return roots;
}

json ddeJson(const ClosedLoopLinearization& lin, const Spectrum* spectrum, int degree) {
  json delays = json::array();
  for (const auto& t : lin.dde.delayed) delays.push_back(t.delay);
  json d{{"states", lin.dde.state_names}, {"dropped_states", lin.dropped_states}, {"delays_s", delays},
         {"k_p", lin.k_p}, {"k_d", lin.k_d}, {"k_i", lin.k_i}};
  if (spectrum) {
    d["discretisation"] = {{"method", "Chebyshev collocation of each delay line (infinitesimal generator) + Newton on det Delta"},
                           {"degree_per_delay_line", degree},
                           {"delay_line_ranks", spectrum->ranks},
                           {"matrix_order", spectrum->dimension}};
  }
  return d;
}

json pointJson(const SimConfig& c) {
  return json{{"k_psi", c.tracker.k_psi},
              {"k_y", c.tracker.k_y},
              {"p", c.actuator.p},
              {"tau1_s", c.delays.pose_to_tracker},
              {"tau_desired_s", c.delays.desired_steering_to_actuator},
              {"tau_measured_s", c.delays.steering_angle_to_actuator},
              {"tau_torque_s", c.delays.torque_to_plant},
              {"tire_front", c.tire_front.model},
              {"tire_rear", c.tire_rear.model}};
}

std::string equationsName(const std::string& reading) { return reading.empty() ? "printed" : reading; }

json criticalDelayJson(const SimConfig& c, const CriticalDelay& critical, const CriticalDelayOptions& options, int count) {
  const Crossing& cross = critical.crossing;
  const Spectrum& here = critical.configured;
  json j;
  j["tau2_critical_s"] = cross.found ? json(cross.parameter) : json(nullptr);
  j["frequency_hz"] = cross.found ? json(cross.frequencyHz()) : json(nullptr);
  j["omega_rad_s"] = cross.found ? json(cross.angularFrequency()) : json(nullptr);
  j["found"] = cross.found;
  if (!cross.found) j["reason"] = "tau2 scan [s]: " + cross.reason;
  if (cross.found) j["crossing_root"] = rootJson(cross.root);
  const bool equal_tau2 = c.delays.desired_steering_to_actuator == c.delays.steering_angle_to_actuator;
  j["tau2_configured_s"] = equal_tau2 ? json(c.delays.steering_angle_to_actuator) : json(nullptr);
  if (!equal_tau2) j["note"] = "the configured actuator delays differ; tau2_critical_s sets both to one value";
  if (cross.found && equal_tau2) j["tau2_margin"] = cross.parameter / c.delays.steering_angle_to_actuator;
  j["stable_at_configured"] = here.abscissa() < 0.0;
  j["spectral_abscissa_at_configured"] = here.abscissa();
  j["rightmost_roots"] = spectrumJson(here, count);
  j["point"] = pointJson(c);
  j["equations"] = equationsName(options.reading);
  j["dde"] = ddeJson(critical.linearization, &here, options.spectrum.degree);
  j["scan"] = {{"tau2_from_s", critical.scan.start}, {"tau2_to_s", critical.scan.end}, {"steps", critical.scan.steps},
               {"spectra", cross.spectra}};
  return j;
}

json rootsJson(const SimConfig& c, const Spectrum& s, const std::string& reading, int count, int degree) {
  const ClosedLoopLinearization lin = linearizeClosedLoop(c);
  return json{{"equations", equationsName(reading)},
              {"stable", s.abscissa() < 0.0},
              {"spectral_abscissa", s.abscissa()},
              {"unstable_roots", s.unstableCount()},
              {"rightmost_roots", spectrumJson(s, count)},
              {"point", pointJson(c)},
              {"dde", ddeJson(lin, &s, degree)}};
}

json boundaryJson(const SimConfig& c, const std::string& param, const Crossing& cross, const std::string& reading) {
  const ConfigParameterInfo info = configParameterInfo(param);
  json j{{"param", param}, {"unit", info.unit}, {"equations", equationsName(reading)},
         {"found", cross.found},
         {"critical", cross.found ? json(cross.parameter) : json(nullptr)},
         {"frequency_hz", cross.found ? json(cross.frequencyHz()) : json(nullptr)},
         {"spectral_abscissa_at_from", cross.abscissa_start}, {"point", pointJson(c)}};
  if (cross.found) j["crossing_root"] = rootJson(cross.root);
  if (!cross.found) j["reason"] = cross.reason;
  return j;
}

}  // namespace lane_keeping
