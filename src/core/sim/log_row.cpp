#include "lane_keeping/sim/log_row.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <ostream>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

const std::vector<std::string>& logColumns() {
  static const char* const names[] = {
      "t",        "x",        "y",        "psi",       "yaw_rate",  "v",           "ay",
      "delta",    "delta_rate", "delta_des", "torque",  "sigma1",    "delta_des_rate", "e_y",
      "e_psi",    "alpha_f",  "alpha_r",  "force_f",   "force_r",   "moment_f",    "moment_r",
      "integral", "torque_applied", "x_true", "y_true", "psi_true"};
  static_assert(sizeof(names) / sizeof(names[0]) == kLogColumnCount, "a name for every column of logValues()");
  static const std::vector<std::string> columns(std::begin(names), std::end(names));
  return columns;
}

void logValues(const LogRow& r, double* values) {
  const VehicleStateSample& s = r.state;
  const double row[] = {
      r.t,       s.x,        s.y,        s.psi,       s.sigma2,          s.speed,
      s.lateral_acceleration, s.delta, s.sigma3, r.delta_des, r.torque_command, s.sigma1,
      r.delta_des_rate, r.e_y, r.e_psi, s.slip_angle_front, s.slip_angle_rear, s.force_front,
      s.force_rear, s.moment_front, s.moment_rear, r.integral, s.torque, r.x_true, r.y_true, r.psi_true};
  static_assert(sizeof(row) / sizeof(row[0]) == kLogColumnCount, "a value for every column of logColumns()");
  for (std::size_t i = 0; i < kLogColumnCount; ++i) values[i] = row[i];
}

std::vector<double> logValues(const LogRow& r) {
  std::vector<double> values(kLogColumnCount);
  logValues(r, values.data());
  return values;
}

void writeLogCsv(std::ostream& out, const std::vector<LogRow>& rows) {
  const auto& columns = logColumns();
  for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
  out << "\n";
  char buffer[32];
  for (const auto& row : rows) {
    const std::vector<double> values = logValues(row);
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::snprintf(buffer, sizeof(buffer), "%.17g", values[i]);
      if (i) out << ',';
      out << buffer;
    }
    out << "\n";
  }
}

void writeLogCsv(const std::string& path, const std::vector<LogRow>& rows) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open for writing");
  writeLogCsv(out, rows);
  // The stream buffers: a full disk may show only when the last block goes out, at close.
  out.close();
  if (out.fail()) {
    throw InputError(path + ": writing " + std::to_string(rows.size()) + " log rows failed (disk full?): " +
                     std::strerror(errno));
  }
}

}  // namespace lane_keeping
