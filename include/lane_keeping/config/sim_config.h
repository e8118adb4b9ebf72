#pragma once
/// The one configuration schema shared by nodes, tools and tests (DESIGN §2).
/// Compiled-in defaults are the paper's values; config/default.yaml lists them all; scenario
/// files overlay only what differs; `--set key=value` overrides last.
#include <ostream>
#include <string>
#include <vector>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/control/actuator_params.h"
#include "lane_keeping/control/path_params.h"
#include "lane_keeping/control/tracker_params.h"
#include "lane_keeping/sim/delay_params.h"
#include "lane_keeping/sim/sensor_params.h"
#include "lane_keeping/sim/simulation_params.h"
#include "lane_keeping/tire/tire_params.h"
#include "lane_keeping/vehicle/steering_params.h"
#include "lane_keeping/vehicle/vehicle_params.h"

namespace lane_keeping {

struct SimConfig {
  VehicleParams vehicle;
  SteeringParams steering;
  DisturbanceParams disturbance;
  TireParams tire_front;
  TireParams tire_rear;
  PathParams path;
  TrackerParams tracker;
  ActuatorParams actuator;
  DelayParams delays;
  SensorParams sensors;
  SimulationParams simulation;

  void visit(ParamVisitor& v);
  /// All problems: ranges (RangeChecker), cross-field rules, and integration stability limits.
  std::vector<ConfigProblem> problems() const;
  /// Throws ConfigError listing every problem; `source` adds file:line locations.
  void validate(const FlatParams* source = nullptr) const;
  void print(std::ostream& out, bool with_docs = false) const;
};

/// Paper defaults, then each file in order, then each "key=value". Unknown keys, type errors and
/// invalid values all fail with a ConfigError that names the key and the file:line.
SimConfig loadSimConfig(const std::vector<std::string>& files, const std::vector<std::string>& assignments = {});
/// The same from overlays already gathered (files, YAML texts, a Python dict: src/python): a `log:`
/// section is left to the log reader, then simConfigFromFlat.
SimConfig loadSimConfig(FlatParams source);
/// Whether a key the source lacks keeps its compiled-in default (files: an overlay names only what it
/// changes) or is an error (a ROS parameter tree, which the launch files load complete from
/// config/default.yaml: a key missing there means the server does not hold what the user thinks).
enum class MissingKeys { kDefault, kRefuse };
/// Same from an already assembled FlatParams (ROS parameter trees arrive this way). With
/// MissingKeys::kRefuse every required key must be present; the error names each one missing.
SimConfig simConfigFromFlat(const FlatParams& source, MissingKeys missing = MissingKeys::kDefault);

}  // namespace lane_keeping
