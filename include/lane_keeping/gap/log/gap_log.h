#pragma once
/// A log of a real (or generated) run, as the gap diagnosis reads it (DESIGN §5).
///
/// Only t is required; every other column may be absent (an empty vector): a log of a real car often
/// lacks the desired steering angle or the torque command, and the diagnosis replays the subsystems
/// whose inputs and outputs are present (subsystem_replay.h). t is strictly increasing (any, not
/// necessarily uniform, sampling). Rows holding NaN/Inf in a column the diagnosis uses are skipped and
/// counted, never silently used.
#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/gap/log/log_mapping.h"

namespace lane_keeping {

struct GapLog {
  std::string source;  ///< file (and topic set) it came from, for messages and the report

  std::vector<double> t;          ///< [s], strictly increasing
  std::vector<double> x, y, psi;  ///< measured pose of G in map [m, m, rad]
  std::vector<double> yaw_rate;   ///< [rad/s]
  std::vector<double> delta;      ///< measured front-wheel steering angle [rad]
  std::vector<double> delta_des;  ///< desired steering angle as the tracker produced it [rad]
  std::vector<double> torque;     ///< steering torque command M_S [N m]
  std::vector<double> v;          ///< optional: speed [m/s] (empty if absent), of the point speed_of says
  /// which speed v holds: the centre of gravity's (lk_simulate's, the nodes', a bus's) unless the log
  /// mapping says `v: {column: ..., speed_of: front_axle}` (V of Beregi eq 1); logged_speed.h converts
  LoggedSpeed speed_of = LoggedSpeed::kCentreOfGravity;
  /// optional: lateral velocity of G in the body frame [m/s] (sigma1 of Beregi eq 1, left positive), as an
  /// INS or an optical sensor measures it; without it the replays differentiate the pose (log_signals.h)
  std::vector<double> vy;
  std::vector<double> ay;         ///< optional: lateral acceleration at G [m/s^2] (empty if absent)
  std::vector<double> delta_rate; ///< optional: steering rate [rad/s] (empty if absent)

  /// Schema columns whose units are unknown (a log mapping's `unscaled`, e.g. torque in bus counts):
  /// present, but not used where their scale matters.
  std::set<std::string> unscaled;
  std::string mapping;            ///< the log mapping applied ("" = none)
  /// psi is the course over ground, not the body's heading (log mapping `course: true`): the replays
  /// compare it with the model's heading plus body slip, and the lateral velocity is not derived from it.
  bool psi_is_course = false;

  std::size_t rows_read = 0;      ///< data rows in the file
  std::size_t rows_skipped = 0;   ///< rows dropped for NaN/Inf (counted in the report)
  std::vector<std::string> notes; ///< human-readable remarks (which rows were skipped, and why)

  std::size_t size() const { return t.size(); }
  /// Whether schema column `name` is present (and, with `scaled`, in known units).
  bool has(const std::string& name, bool scaled = false) const;
  bool hasSpeed() const { return !v.empty(); }
  bool hasLateralAcceleration() const { return !ay.empty(); }
  bool hasSteeringRate() const { return !delta_rate.empty(); }
  bool hasLateralVelocity() const { return !vy.empty(); }
  /// The values of schema column `name` (log_mapping.h), or nullptr for a name outside the schema.
  const std::vector<double>* column(const std::string& name) const;
  std::vector<double>* column(const std::string& name);
  double duration() const { return t.empty() ? 0.0 : t.back() - t.front(); }
  /// Median sample spacing [s].
  double medianStep() const;
  /// Rows [begin, end) as a new log (for held-out segments).
  GapLog slice(std::size_t begin, std::size_t end) const;
};

/// Reads a CSV log with a header row. Column order is free; extra columns are ignored; columns are found
/// by their schema names or through `mapping` (log_mapping.h), which also scales them.
/// Throws InputError naming the file and, where it applies, the line and column: missing file,
/// empty file, no time column, unparsable cell, non-increasing t, fewer than 10 valid rows; and if a
/// column the mapping names is not in the file.
/// Rows with NaN/Inf (or empty cells) in a used column are skipped and counted. A heading that wraps at
/// +-pi is unwrapped (angle_unwrap.h) and columns the mapping shifts in time are moved onto the time
/// base (column_shift.h); the notes say so.
GapLog readCsvLog(const std::string& path, const LogMapping& mapping = {});

/// A log's columns in memory (a pandas DataFrame handed over by the Python module): names as a CSV
/// header would give them, and each column's values (NaN for a missing value).
struct LogTable {
  std::string source;                       ///< names the table in messages, e.g. "DataFrame logs[0]"
  std::vector<std::string> columns;         ///< column names
  std::vector<std::vector<double>> values;  ///< values[c][row], one vector per column, equal lengths
};

/// The log of a table, by readCsvLog's rules after parsing (the mapping, the required t, NaN/Inf rows
/// skipped and counted, strictly increasing time, values no car produces refused): a table holding a
/// CSV file's numbers gives the log that file gives. Errors name the table and the row (from 0).
GapLog gapLogFromTable(const LogTable& table, const LogMapping& mapping = {});

/// Writes a GapLog as CSV (the same columns), full precision.
void writeCsvLog(const std::string& path, const GapLog& log);

/// Converts the rows of a simulation run (sim/log_row.h) into a GapLog (all optional columns set).
struct LogRow;
GapLog gapLogFromRows(const std::vector<LogRow>& rows, const std::string& source);

}  // namespace lane_keeping
