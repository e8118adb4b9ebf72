#pragma once
/// Numeric configuration parameters addressed by their dotted key ("tracker.k_psi"), for the
/// parameter axes of stability charts and critical-value searches. One alias: `tau2` is Beregi's
/// lower-level delay, i.e. delays.desired_steering_to_actuator and delays.steering_angle_to_actuator
/// moved together (eq 12).
#include <string>

#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

struct ConfigParameterInfo {
  std::string key;   ///< as given (alias included)
  std::string unit;  ///< "" for dimensionless
  std::string doc;   ///< the schema's one-line meaning
};

/// Sets the number at `key`. Throws ConfigError if `key` is not a numeric key of the schema (the
/// message lists a few valid ones) or `value` is not finite. Ranges are checked by validate().
void setConfigNumber(SimConfig& config, const std::string& key, double value);
/// The number at `key` (for an unset optional number: NaN). Throws ConfigError like setConfigNumber.
double configNumber(const SimConfig& config, const std::string& key);
/// Unit and meaning of `key`. Throws ConfigError for an unknown key.
ConfigParameterInfo configParameterInfo(const std::string& key);

}  // namespace lane_keeping
