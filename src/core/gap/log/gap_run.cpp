#include "lane_keeping/gap/log/gap_run.h"

#include <array>
#include <utility>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

bool statesInitial(const FlatParams& params) {
  for (const auto& [key, entry] : params.entries()) {
    if (startsWith(key, "simulation.initial.")) return true;
  }
  return false;
}

}  // namespace

bool isScenarioKey(const std::string& key) {
  static const std::array<const char*, 3> prefixes{"path.", "simulation.initial.", "tracker.excitation_"};
  for (const char* p : prefixes) {
    if (startsWith(key, p)) return true;
  }
  static const std::array<const char*, 8> keys{"simulation.duration", "simulation.log_rate", "simulation.name",
                                               "simulation.description", "vehicle.speed", "vehicle.speed_variation",
                                               "vehicle.speed_wavelength", "vehicle.speed_profile"};
  for (const char* k : keys) {
    if (key == k) return true;
  }
  return false;
}

std::string scenarioKeysDescription() {
  return "path.*, simulation.initial.*, simulation.duration, simulation.log_rate, simulation.name, "
         "simulation.description, vehicle.speed, vehicle.speed_variation, vehicle.speed_wavelength, "
         "vehicle.speed_profile, "
         "tracker.excitation_*";
}

GapRun gapRun(GapLog log, const FlatParams& nominal, const FlatParams& scenario, const std::string& scenario_source) {
  std::vector<ConfigProblem> problems;
  FlatParams settings = scenario;
  settings.erasePrefix("log.");  // a log mapping (log_mapping.h) is read by whoever reads the log
  for (const auto& [key, entry] : settings.entries()) {
    if (!isScenarioKey(key)) {
      problems.push_back({key, entry.location,
                          "is not a per-run setting: a scenario may set " + scenarioKeysDescription() +
                              "; the car, its controllers and delays belong to the nominal configuration"});
    }
  }
  if (!problems.empty()) throw ConfigError(problems);
  FlatParams combined = nominal;
  combined.erasePrefix("log.");
  combined.overlayFlat(settings);
  GapRun run;
  run.config = simConfigFromFlat(combined);
  run.log = std::move(log);
  run.scenario = scenario_source;
  run.initial_from_log = !statesInitial(combined);
  return run;
}

GapRun gapRun(GapLog log, const FlatParams& nominal, const std::string& scenario_file) {
  FlatParams scenario;
  scenario.overlayFile(scenario_file);
  return gapRun(std::move(log), nominal, scenario, scenario_file);
}

GapRun gapRun(GapLog log, const SimConfig& shared) {
  GapRun run;
  run.log = std::move(log);
  run.config = shared;
  return run;
}

SimConfig withInitialStateFromLog(SimConfig config, const GapLog& log, double sigma1) {
  if (log.t.empty()) throw InputError(log.source + ": no samples to take an initial state from");
  InitialState& init = config.simulation.initial;
  // A partial log gives what it has; the rest stays as configured (a bus log has no pose: the replays
  // that need one are skipped, and the closed loop starts at the configured pose).
  auto first = [](const std::vector<double>& column, double otherwise) { return column.empty() ? otherwise : column.front(); };
  init.x = first(log.x, init.x);
  init.y = first(log.y, init.y);
  init.psi = first(log.psi, init.psi);
  init.delta = first(log.delta, init.delta);
  init.sigma2 = first(log.yaw_rate, init.sigma2);
  init.sigma3 = first(log.delta_rate, 0.0);
  init.sigma1 = sigma1;
  return config;
}

}  // namespace lane_keeping
