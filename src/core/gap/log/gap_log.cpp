// CSV logs for the gap diagnosis (DESIGN §5): reading with errors that name file, line and column,
// writing at full precision, conversion from simulator rows.
#include "lane_keeping/gap/log/gap_log.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/angle_unwrap.h"
#include "lane_keeping/gap/log/column_shift.h"
#include "lane_keeping/gap/log/time_holes.h"
#include "lane_keeping/sim/log_row.h"

namespace lane_keeping {
namespace {

constexpr std::size_t kMinValidRows = 10;
constexpr std::size_t kListedLines = 5;  // skipped-row line numbers quoted in the note

/// The columns the diagnosis uses, in DESIGN §5 order, with the member each fills.
struct ColumnSpec {
  const char* name;
  bool required;
  std::vector<double> GapLog::*member;
  /// The largest magnitude a car produces, with its unit: a value beyond it is a units or mapping error
  /// (or a corrupt file), which the fits would otherwise "explain" with a confident verdict.
  double limit;
  const char* unit;
};

/// A column in units nobody stated (log mapping `unscaled`, e.g. torque in bus counts) is only held to
/// what any bus encodes.
constexpr double kUnscaledLimit = 1e9;

const std::vector<ColumnSpec>& columnSpecs() {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  static const std::vector<ColumnSpec> specs{
      {"t", true, &GapLog::t, kNone, "s"},
      {"x", false, &GapLog::x, 1e8, "m"},            // a map frame spanning a continent
      {"y", false, &GapLog::y, 1e8, "m"},
      {"psi", false, &GapLog::psi, 1e5, "rad"},      // unwrapped over a day of driving
      {"yaw_rate", false, &GapLog::yaw_rate, 10.0, "rad/s"},  // a spin is 2-3 rad/s
      {"v", false, &GapLog::v, 150.0, "m/s"},
      {"vy", false, &GapLog::vy, 50.0, "m/s"},       // a car sliding sideways at 180 km/h
      {"ay", false, &GapLog::ay, 100.0, "m/s^2"},   // 10 g: a crash, not driving
      {"delta", false, &GapLog::delta, 1.6, "rad"},  // the road-wheel angle; pi/2 is the model's singularity
      {"delta_rate", false, &GapLog::delta_rate, 50.0, "rad/s"},
      {"delta_des", false, &GapLog::delta_des, 1.6, "rad"},
      {"torque", false, &GapLog::torque, 1e5, "N m"},  // steering torques are tens to thousands of N m
  };
  return specs;
}

std::string trim(const std::string& s) {
  const char* ws = " \t\r\n\v\f";
  const std::size_t b = s.find_first_not_of(ws);
  if (b == std::string::npos) return "";
  const std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

/// Splits on commas; each cell is trimmed and loses one pair of surrounding double quotes.
std::vector<std::string> splitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string cell = trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (cell.size() >= 2 && cell.front() == '"' && cell.back() == '"') cell = trim(cell.substr(1, cell.size() - 2));
    cells.push_back(cell);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return cells;
}

/// Parses a whole cell as a double. Empty -> NaN (a missing value, skipped like NaN).
/// "nan", "inf", "-inf", "infinity" (any case) parse to the non-finite values.
bool parseCell(const std::string& cell, double* value) {
  if (cell.empty()) {
    *value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const char* begin = cell.c_str();
  char* end = nullptr;
  errno = 0;
  const double parsed = std::strtod(begin, &end);
  if (end == begin || *end != '\0') return false;
  // Overflow (ERANGE with +-HUGE_VAL) is kept as +-inf: non-finite, so the row is skipped.
  *value = parsed;
  return true;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

std::string formatDouble(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof(buffer), "%.17g", v);
  return buffer;
}

std::string lineList(const std::vector<std::size_t>& lines, const char* word) {
  std::string out = word;
  for (std::size_t i = 0; i < lines.size() && i < kListedLines; ++i) out += (i ? ", " : " ") + std::to_string(lines[i]);
  if (lines.size() > kListedLines) out += ", ... (" + std::to_string(lines.size()) + " in all)";
  return out;
}

/// One data row as read: its file line and the value of each present used column (NaN if missing).
struct RawRow {
  std::size_t line;
  std::vector<double> values;  // indexed like `present`
};

/// How messages name a row: "file.csv:12" (a CSV file's line) or "DataFrame 'run' row 10" (a table's
/// row position, from 0).
struct RowNaming {
  std::string source;
  bool csv = true;
  std::string word() const { return csv ? "line" : "row"; }
  std::string at(std::size_t line) const { return csv ? source + ":" + std::to_string(line) : source + " row " + std::to_string(line); }
};

/// The log from its parsed rows (values of the `present` specs, in their order; t first): units
/// (the mapping's scale and offset), optional columns without a finite value dropped, time strictly
/// increasing, values no car produces refused, rows with a non-finite used value skipped and counted.
/// readCsvLog and gapLogFromTable share it, so a file and the same table in memory give the same log.
GapLog finishLog(const RowNaming& naming, const std::vector<ColumnSpec>& specs, const std::vector<std::size_t>& present,
                 std::vector<RawRow> rows, const LogMapping& mapping) {
  GapLog log;
  log.source = naming.source;
  log.rows_read = rows.size();
  log.mapping = mapping.source;
  // Units: value = scale * raw + offset for mapped columns, seconds for the time column.
  for (std::size_t p = 0; p < present.size(); ++p) {
    const std::string& name = specs[present[p]].name;
    double scale = 1.0, offset = 0.0;
    if (name == std::string("t")) {
      scale = mapping.time_scale;
    } else if (const auto it = mapping.columns.find(name); it != mapping.columns.end()) {
      scale = it->second.scale;
      offset = it->second.offset;
      if (it->second.unscaled) log.unscaled.insert(name);
      if (it->second.course) log.psi_is_course = true;
      if (name == std::string("v")) log.speed_of = it->second.speed_of;
    }
    if (scale == 1.0 && offset == 0.0) continue;
    for (RawRow& r : rows) r.values[p] = scale * r.values[p] + offset;
  }

  // An optional column that holds no finite value at all is treated as absent (with a note);
  // otherwise it is used, and a row with a non-finite cell in it is skipped.
  std::vector<bool> use(present.size(), true);
  for (std::size_t p = 0; p < present.size(); ++p) {
    if (specs[present[p]].required || rows.empty()) continue;
    const bool any_finite = std::any_of(rows.begin(), rows.end(), [&](const RawRow& r) { return std::isfinite(r.values[p]); });
    if (!any_finite) {
      use[p] = false;
      log.notes.push_back(naming.source + ": optional column '" + specs[present[p]].name +
                          "' has no finite value; treated as absent");
    }
  }

  // Time must increase strictly over the rows that carry a finite t (t is column 0 of `present`).
  const std::size_t t_index = 0;
  double last_t = std::numeric_limits<double>::quiet_NaN();
  std::size_t last_line = 0;
  bool have_last = false;  // a table's rows count from 0
  for (const RawRow& r : rows) {
    const double t = r.values[t_index];
    if (!std::isfinite(t)) continue;
    if (have_last && !(t > last_t)) {
      throw InputError(naming.at(r.line) + ": column 't': time not strictly increasing: t = " + formatDouble(t) +
                       " follows t = " + formatDouble(last_t) + " (" + naming.word() + " " + std::to_string(last_line) +
                       ")");
    }
    last_t = t;
    last_line = r.line;
    have_last = true;
  }

  // Values no car produces: a wrong unit or scale (a steering-wheel angle in degrees, torque in counts
  // read as N m) or a corrupt file. Fatal, naming the line: the diagnosis would fit them.
  for (std::size_t p = 0; p < present.size(); ++p) {
    if (!use[p]) continue;
    const ColumnSpec& spec = specs[present[p]];
    const bool unscaled = log.unscaled.count(spec.name) > 0;
    const double limit = unscaled ? kUnscaledLimit : spec.limit;
    for (const RawRow& r : rows) {
      const double v = r.values[p];
      if (std::isfinite(v) && std::fabs(v) > limit) {
        throw InputError(naming.at(r.line) + ": column '" + spec.name + "' holds " + formatDouble(v) +
                         ", beyond what a car produces (|" + spec.name + "| <= " + formatDouble(limit) + " " +
                         (unscaled ? "in any unit" : spec.unit) +
                         "); check the column's unit, or its scale in the log mapping");
      }
    }
  }

  // Keep the rows whose used cells are all finite.
  std::vector<std::size_t> skipped_lines;
  std::vector<std::size_t> bad_per_column(present.size(), 0);
  for (std::size_t p = 0; p < present.size(); ++p)
    if (use[p]) (log.*specs[present[p]].member).reserve(rows.size());
  for (const RawRow& r : rows) {
    bool ok = true;
    for (std::size_t p = 0; p < present.size(); ++p) {
      if (use[p] && !std::isfinite(r.values[p])) {
        ok = false;
        ++bad_per_column[p];
      }
    }
    if (!ok) {
      skipped_lines.push_back(r.line);
      continue;
    }
    for (std::size_t p = 0; p < present.size(); ++p)
      if (use[p]) (log.*specs[present[p]].member).push_back(r.values[p]);
  }
  log.rows_skipped = skipped_lines.size();
  if (!skipped_lines.empty()) {
    std::string by_column;
    for (std::size_t p = 0; p < present.size(); ++p) {
      if (bad_per_column[p] == 0) continue;
      by_column += std::string(by_column.empty() ? "" : ", ") + specs[present[p]].name + " " +
                   std::to_string(bad_per_column[p]);
    }
    log.notes.push_back(naming.source + ": skipped " + std::to_string(skipped_lines.size()) + " of " +
                        std::to_string(rows.size()) + " rows with NaN/Inf/empty cells (" +
                        lineList(skipped_lines, naming.csv ? "lines" : "rows") + "; cells by column: " + by_column +
                        ")");
  }
  // A heading that wraps at +-pi, unwrapped (before any shift interpolates across a wrap); columns logged
  // late, moved back onto the time base (the mapping's `shift:`).
  unwrapHeading(&log);
  applyColumnShifts(&log, mapping);
  if (log.size() < kMinValidRows) {
    throw InputError(naming.source + ": only " + std::to_string(log.size()) + " valid data rows (" +
                     std::to_string(rows.size()) + " read, " + std::to_string(log.rows_skipped) +
                     " skipped for NaN/Inf/empty cells); at least " + std::to_string(kMinValidRows) + " are needed");
  }
  return log;
}

/// The header position of each spec (through the log mapping, if any), -1 if absent. Throws InputError
/// at `where` (the header's place) for a column found twice, a mapped column missing from the
/// `container` ("file", "table") or a required column missing.
std::vector<int> columnPositions(const std::vector<std::string>& header, const LogMapping& mapping, const std::string& where,
                                 const std::string& container) {
  const std::vector<ColumnSpec>& specs = columnSpecs();
  std::vector<int> position(specs.size(), -1);  // header index of each spec, -1 if absent
  std::vector<std::string> missing;
  for (std::size_t s = 0; s < specs.size(); ++s) {
    const std::string column = mapping.columnFor(specs[s].name);
    const bool mapped = column != specs[s].name;
    for (std::size_t h = 0; h < header.size(); ++h) {
      if (header[h] != column) continue;
      if (position[s] >= 0) {
        throw InputError(where + ": column '" + column +
                         "' appears twice (columns " + std::to_string(position[s] + 1) + " and " +
                         std::to_string(h + 1) + ")");
      }
      position[s] = static_cast<int>(h);
    }
    if (position[s] < 0 && mapped) {
      const auto it = mapping.columns.find(specs[s].name);
      throw InputError(where + ": column '" + column + "' (mapped to " +
                       specs[s].name + " by " + (it == mapping.columns.end() ? mapping.source : it->second.location) +
                       ") is not in the " + container + "; columns found: " + joinNames(header));
    }
    if (position[s] < 0 && specs[s].required) missing.push_back(specs[s].name);
  }
  if (!missing.empty()) {
    throw InputError(where + ": missing required column" +
                     (missing.size() > 1 ? "s " : " ") + joinNames(missing) + "; columns found: " + joinNames(header));
  }
  return position;
}

}  // namespace

bool GapLog::has(const std::string& name, bool scaled) const {
  for (const ColumnSpec& spec : columnSpecs()) {
    if (name == spec.name) return !(this->*spec.member).empty() && !(scaled && unscaled.count(name));
  }
  return false;
}

const std::vector<double>* GapLog::column(const std::string& name) const {
  for (const ColumnSpec& spec : columnSpecs()) {
    if (name == spec.name) return &(this->*spec.member);
  }
  return nullptr;
}

std::vector<double>* GapLog::column(const std::string& name) {
  return const_cast<std::vector<double>*>(static_cast<const GapLog*>(this)->column(name));
}

double GapLog::medianStep() const { return medianTimeStep(t); }

GapLog GapLog::slice(std::size_t begin, std::size_t end) const {
  if (begin > end || end > t.size()) {
    throw std::out_of_range("GapLog::slice(" + std::to_string(begin) + ", " + std::to_string(end) + ") of " + source +
                            " with " + std::to_string(t.size()) + " rows");
  }
  GapLog out;
  out.source = source + "[" + std::to_string(begin) + ":" + std::to_string(end) + "]";
  out.unscaled = unscaled;
  out.mapping = mapping;
  out.psi_is_course = psi_is_course;
  out.speed_of = speed_of;
  for (const ColumnSpec& spec : columnSpecs()) {
    const std::vector<double>& from = this->*spec.member;
    if (from.empty()) continue;  // absent optional column stays absent
    (out.*spec.member).assign(from.begin() + static_cast<std::ptrdiff_t>(begin),
                              from.begin() + static_cast<std::ptrdiff_t>(end));
  }
  // The parent keeps the skip counts and notes; a slice reports only its own rows, so that
  // training and held-out slices of one file do not count the same skipped rows twice.
  out.rows_read = end - begin;
  out.rows_skipped = 0;
  return out;
}

GapLog readCsvLog(const std::string& path, const LogMapping& mapping) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int err = errno;
    throw InputError(path + ": cannot open log file" + (err ? std::string(" (") + std::strerror(err) + ")" : ""));
  }
  const std::vector<ColumnSpec>& specs = columnSpecs();

  // Header: the first non-blank line.
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::string> header;
  std::size_t header_line = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line_number == 1 && line.size() >= 3 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);  // UTF-8 BOM
    if (trim(line).empty()) continue;
    header = splitCells(line);
    header_line = line_number;
    break;
  }
  if (in.bad()) throw InputError(path + ": read error");
  if (header.empty()) {
    std::vector<std::string> names;
    for (const ColumnSpec& spec : specs) names.push_back(std::string(spec.name) + (spec.required ? "" : " (optional)"));
    throw InputError(path + ": empty file (no header row; expected columns " + joinNames(names) + ")");
  }

  const std::vector<int> position = columnPositions(header, mapping, path + ":" + std::to_string(header_line), "file");
  std::vector<std::size_t> present;  // spec indices present in the file
  for (std::size_t s = 0; s < specs.size(); ++s)
    if (position[s] >= 0) present.push_back(s);

  // Data rows: parse every used cell (errors are fatal), keep non-finite values for now.
  std::vector<RawRow> rows;
  while (std::getline(in, line)) {
    ++line_number;
    if (trim(line).empty()) continue;
    const std::vector<std::string> cells = splitCells(line);
    if (cells.size() != header.size()) {
      throw InputError(path + ":" + std::to_string(line_number) + ": row has " + std::to_string(cells.size()) +
                       " cells, the header (line " + std::to_string(header_line) + ") has " +
                       std::to_string(header.size()));
    }
    RawRow row{line_number, std::vector<double>(present.size())};
    for (std::size_t p = 0; p < present.size(); ++p) {
      const std::size_t col = static_cast<std::size_t>(position[present[p]]);
      if (!parseCell(cells[col], &row.values[p])) {
        throw InputError(path + ":" + std::to_string(line_number) + ": column '" + specs[present[p]].name +
                         "' (column " + std::to_string(col + 1) + "): cannot parse '" + cells[col] +
                         "' as a number");
      }
    }
    rows.push_back(std::move(row));
  }
  if (in.bad()) throw InputError(path + ": read error after line " + std::to_string(line_number));

  return finishLog(RowNaming{path, true}, specs, present, std::move(rows), mapping);
}

GapLog gapLogFromTable(const LogTable& table, const LogMapping& mapping) {
  if (table.values.size() != table.columns.size()) {
    throw InputError(table.source + ": " + std::to_string(table.columns.size()) + " column names but " +
                     std::to_string(table.values.size()) + " columns of values");
  }
  const std::size_t rows_in_table = table.columns.empty() ? 0 : table.values.front().size();
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    if (table.values[c].size() != rows_in_table) {
      throw InputError(table.source + ": column '" + table.columns[c] + "' has " + std::to_string(table.values[c].size()) +
                       " values, column '" + table.columns.front() + "' has " + std::to_string(rows_in_table));
    }
  }
  const std::vector<ColumnSpec>& specs = columnSpecs();
  const std::vector<int> position = columnPositions(table.columns, mapping, table.source, "table");
  std::vector<std::size_t> present;  // spec indices present in the table
  for (std::size_t s = 0; s < specs.size(); ++s)
    if (position[s] >= 0) present.push_back(s);
  std::vector<RawRow> rows;
  rows.reserve(rows_in_table);
  for (std::size_t i = 0; i < rows_in_table; ++i) {
    RawRow row{i, std::vector<double>(present.size())};
    for (std::size_t p = 0; p < present.size(); ++p) row.values[p] = table.values[static_cast<std::size_t>(position[present[p]])][i];
    rows.push_back(std::move(row));
  }
  return finishLog(RowNaming{table.source, false}, specs, present, std::move(rows), mapping);
}

void writeCsvLog(const std::string& path, const GapLog& log) {
  const std::vector<ColumnSpec>& specs = columnSpecs();
  std::vector<const ColumnSpec*> columns;
  for (const ColumnSpec& spec : specs) {
    const std::vector<double>& values = log.*spec.member;
    if (!spec.required && values.empty()) continue;
    if (values.size() != log.t.size()) {
      throw InputError(path + ": cannot write log '" + log.source + "': column '" + spec.name + "' has " +
                       std::to_string(values.size()) + " values, t has " + std::to_string(log.t.size()));
    }
    columns.push_back(&spec);
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path + ": cannot open for writing");
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c]->name;
  out << '\n';
  char buffer[40];
  for (std::size_t i = 0; i < log.t.size(); ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      std::snprintf(buffer, sizeof(buffer), "%.17g", (log.*columns[c]->member)[i]);
      if (c) out << ',';
      out << buffer;
    }
    out << '\n';
  }
  out.flush();
  if (!out) throw InputError(path + ": write failed");
}

GapLog gapLogFromRows(const std::vector<LogRow>& rows, const std::string& source) {
  GapLog log;
  log.source = source;
  log.rows_read = rows.size();
  std::vector<std::size_t> skipped;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const LogRow& r = rows[i];
    const VehicleStateSample& s = r.state;
    const double values[] = {r.t,     s.x,     s.y,           s.psi,       s.sigma2, s.speed,
                             s.lateral_acceleration, s.delta, s.sigma3, r.delta_des, r.torque_command};
    if (!std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); })) {
      skipped.push_back(i);
      continue;
    }
    if (!log.t.empty() && !(r.t > log.t.back())) {
      throw InputError(source + ": row " + std::to_string(i) + ": time not strictly increasing: t = " +
                       formatDouble(r.t) + " follows t = " + formatDouble(log.t.back()));
    }
    log.t.push_back(r.t);
    log.x.push_back(s.x);
    log.y.push_back(s.y);
    log.psi.push_back(s.psi);
    log.yaw_rate.push_back(s.sigma2);
    log.v.push_back(s.speed);
    log.ay.push_back(s.lateral_acceleration);
    log.delta.push_back(s.delta);
    log.delta_rate.push_back(s.sigma3);
    log.delta_des.push_back(r.delta_des);
    log.torque.push_back(r.torque_command);
  }
  log.rows_skipped = skipped.size();
  if (!skipped.empty()) {
    log.notes.push_back(source + ": skipped " + std::to_string(skipped.size()) + " of " + std::to_string(rows.size()) +
                        " rows with NaN/Inf values (" + lineList(skipped, "rows") + ")");
  }
  return log;
}

}  // namespace lane_keeping
