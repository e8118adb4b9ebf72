#pragma once
/// How a log's columns map to the diagnosis's schema (DESIGN §5): logs of real cars name their columns
/// differently, record the steering-wheel angle instead of the road-wheel angle, torques in the bus's
/// own units, time in ms. A `log:` section says so, in the nominal configuration (for every log), in a
/// scenario, or in a file of its own (lk_gap --log-map FILE after a --log):
///
///   log:
///     time: {column: timestamp_ms, unit: ms}           # s (default), ms, us or ns
///     columns:
///       delta:  {column: steering_wheel_angle, scale: 0.0667, offset: 0}   # value = scale * raw + offset
///       torque: {column: eps_torque, unscaled: true}   # units unknown: marked, not used where they matter
///       psi:    {column: gnss_course, course: true}    # the direction of travel, not the body's heading
///       x:      {column: east}
///       yaw_rate: {column: yaw, shift: 0.2}            # logged 0.2 s late (column_shift.h)
///       vy:     {column: lateral_velocity}             # optional: lateral velocity of G, body frame
///       v:      {column: speed, speed_of: cg}          # which speed: cg (default) or front_axle (V of eq 1)
///
/// A schema column not listed keeps its own name; a listed one is read only from its mapped column.
#include <map>
#include <string>

namespace YAML {
class Node;
}

namespace lane_keeping {

/// Which speed a log's `v` column holds (`v: {column: ..., speed_of: cg | front_axle}`). The diagnosis's
/// replays need V of Beregi eq 1 and convert a centre-of-gravity speed into it (gap/log/logged_speed.h).
enum class LoggedSpeed {
  kCentreOfGravity,  ///< `cg` (the default): |velocity of G|, what lk_simulate and the nodes log, a bus or GNSS gives
  kFrontAxle,        ///< `front_axle`: V of eq 1, the front axle's speed along its wheel
};

struct ColumnMapping {
  std::string column;      ///< the log's column name
  double scale = 1.0;      ///< schema value = scale * raw + offset
  double offset = 0.0;
  bool unscaled = false;   ///< the raw values are in unknown units (e.g. torque in bus counts)
  /// [s] the column was logged this late (negative: early): the schema value at t is the raw value at
  /// t + shift, interpolated linearly on the log's time base (column_shift.h). |shift| <= kMaxColumnShift.
  double shift = 0.0;
  /// psi only: the column is the course over ground (the direction the car moves, a GNSS receiver's
  /// heading), not where the body points: it differs by the body slip angle.
  bool course = false;
  /// v only: which speed the column holds (`speed_of: cg | front_axle`).
  LoggedSpeed speed_of = LoggedSpeed::kCentreOfGravity;
  std::string location;    ///< file:line of the entry, for messages
};

/// [s] the largest time shift a mapping may give a column: a sensor or bus latency is milliseconds to a
/// few tenths of a second; a shift of seconds is a clock error, to be fixed in the log itself.
constexpr double kMaxColumnShift = 10.0;

struct LogMapping {
  std::string source;                           ///< the file the mapping came from ("" = none)
  std::string time_column = "t";
  double time_scale = 1.0;                      ///< seconds per unit of the time column
  std::map<std::string, ColumnMapping> columns; ///< schema column -> mapping

  bool empty() const { return source.empty() && columns.empty() && time_column == "t" && time_scale == 1.0; }
  /// The log's column that holds schema column `schema` (itself when not mapped).
  std::string columnFor(const std::string& schema) const;
};

/// The schema's columns: t, x, y, psi, yaw_rate, v, vy, ay, delta, delta_rate, delta_des, torque.
bool isSchemaColumn(const std::string& name);

/// The mapping under `log_section` (the node of the `log:` key), read from `file`. Throws ConfigError
/// naming file:line and the key: an unknown schema column, an unknown time unit, a scale that is zero or
/// not finite, a shift that is not finite or beyond kMaxColumnShift, a column mapped twice, an entry
/// without `column`.
LogMapping logMappingFromYaml(const YAML::Node& log_section, const std::string& file);
/// The `log:` section of a YAML file, or an empty mapping if it has none. Throws ConfigError as above,
/// or if the file cannot be read.
LogMapping readLogMapping(const std::string& file);

}  // namespace lane_keeping
