#include "lane_keeping/analysis/critical_delay.h"

#include <sstream>

#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/common/errors.h"

namespace lane_keeping {

LinearDelaySystem loopDelaySystem(const SimConfig& config, const std::string& reading) {
  if (reading.empty()) return linearizeClosedLoop(config).dde;
  return linearizeUnderReading(config, readingByName(reading));
}

SystemFamily loopFamily(const SimConfig& config, const std::string& key, const std::string& reading) {
  if (reading.empty()) return configFamily(config, key);
  configParameterInfo(key);  // an unknown key fails here, before any linearisation
  const EquationReading equations = readingByName(reading);
  if (key == "tau2") return readingFamily(config, equations);
  return [config, key, equations](double v) {
    SimConfig at = config;
    setConfigNumber(at, key, v);
    return linearizeUnderReading(at, equations);
  };
}

CriticalDelay criticalDelay(const SimConfig& config, const CriticalDelayOptions& options) {
  if (!(options.tau2_to > options.tau2_from) || !(options.tau2_from > 0.0) || options.steps < 1) {
    std::ostringstream why;
    why << "critical delay scan: need 0 < tau2_from < tau2_to and steps >= 1, got tau2_from = " << options.tau2_from
        << " s, tau2_to = " << options.tau2_to << " s, steps = " << options.steps;
    throw ConfigError(why.str());
  }
  CriticalDelay out;
  out.linearization = linearizeClosedLoop(config);
  out.configured = computeSpectrum(loopDelaySystem(config, options.reading), options.spectrum);
  out.scan.start = options.tau2_from;
  out.scan.end = options.tau2_to;
  out.scan.steps = options.steps;
  out.scan.spectrum = options.spectrum;
  out.crossing = findFirstCrossing(loopFamily(config, "tau2", options.reading), out.scan);
  return out;
}

}  // namespace lane_keeping
