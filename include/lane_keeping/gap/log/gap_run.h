#pragma once
/// A logged run and the configuration it ran under (DESIGN §5): the shared nominal configuration
/// (vehicle, tires, steering, controllers, delays: what the diagnosis tests) with the run's own
/// scenario overlaid — what differs from run to run: the road, the initial state, the duration, the
/// speed, the identification test signal. Logs from different roads, initial offsets and durations
/// are diagnosed together this way; every stage (replays, noise reference, fits, closed-loop replays)
/// uses each run's own configuration.
#include <string>
#include <vector>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

struct GapRun {
  GapLog log;
  SimConfig config;           ///< the nominal with this run's scenario
  std::string scenario;       ///< the scenario's source ("" = the shared configuration)
  /// The configuration does not state the initial state (no simulation.initial key in the nominal or
  /// the scenario): the diagnosis estimates it from the log's first samples.
  bool initial_from_log = false;
};

/// Whether `key` may appear in a scenario: path.*, simulation.initial.*, simulation.{duration,
/// log_rate, name, description}, vehicle.{speed, speed_variation, speed_wavelength, speed_profile},
/// tracker.excitation_*. Everything else describes the car or its controllers and belongs to the
/// nominal configuration, which the diagnosis tests.
bool isScenarioKey(const std::string& key);
/// The allowed keys as text, for error messages.
std::string scenarioKeysDescription();

/// The nominal (`nominal`, as read from its files and --set) with `scenario` overlaid: a YAML file, or
/// a FlatParams already read (e.g. from a bag). Throws ConfigError naming file:line and key for a key
/// that is not a per-run setting, and for every problem of the combined configuration. A `log:` section
/// (a log mapping, log_mapping.h) in either is left to the log reader.
GapRun gapRun(GapLog log, const FlatParams& nominal, const std::string& scenario_file);
GapRun gapRun(GapLog log, const FlatParams& nominal, const FlatParams& scenario, const std::string& scenario_source);
/// A run under the shared configuration (no scenario): initial state as configured.
GapRun gapRun(GapLog log, const SimConfig& shared);

/// `config` with its initial state taken from the first samples of `log` (pose, yaw rate, steering
/// angle and rate; lateral velocity `sigma1`).
SimConfig withInitialStateFromLog(SimConfig config, const GapLog& log, double sigma1);

}  // namespace lane_keeping
