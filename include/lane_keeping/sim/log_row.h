#pragma once
/// One row of the run log (DESIGN §5 columns first, then extras), and the CSV writer/reader.
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

struct LogRow {
  double t = 0.0;                 ///< [s]
  VehicleStateSample state;       ///< plant state and outputs at t (state.torque: the torque acting on the
                                  ///< wheel at t, i.e. the command delayed by delays.torque_to_plant)
  double torque_command = 0.0;    ///< M_S as the actuator commands it at t [N m] (the `torque` column)
  double delta_des = 0.0;         ///< tracker output at t [rad]
  double delta_des_rate = 0.0;    ///< [rad/s]
  double e_y = 0.0, e_psi = 0.0;  ///< errors of the actual (undelayed) state from the path [m, rad]
  double integral = 0.0;          ///< actuator integral z at the latest actuator sample <= t [rad s]
  /// The true pose of G (`state` holds what the sensors report: sensors.*, sensor_model.h) [m, m, rad].
  double x_true = 0.0, y_true = 0.0, psi_true = 0.0;
};

/// Column names in file order. The first eleven are DESIGN §5's (`torque` is the command M_S);
/// `torque_applied` is the torque acting on the wheel; x_true, y_true, psi_true the true pose (the x, y,
/// psi columns are the localisation's report).
const std::vector<std::string>& logColumns();
/// The number of columns of logColumns().
constexpr std::size_t kLogColumnCount = 26;
/// Values of a row in logColumns() order.
std::vector<double> logValues(const LogRow& row);
/// The same into `values` (kLogColumnCount doubles): what the CSV writer prints and the Python module's
/// log arrays hold (src/python), so the two cannot differ.
void logValues(const LogRow& row, double* values);

/// Writes the header and rows (full double precision, so a log can be replayed exactly).
void writeLogCsv(std::ostream& out, const std::vector<LogRow>& rows);
void writeLogCsv(const std::string& path, const std::vector<LogRow>& rows);

}  // namespace lane_keeping
