#include "lane_keeping/gap/log/column_shift.h"
#include "lane_keeping/gap/log/linear_resample.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

std::string seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g s", s);
  return text;
}

/// `values` (on `t`) at times t + shift, linear interpolation; t + shift must lie within [t.front(), t.back()].
std::vector<double> shifted(const std::vector<double>& t, const std::vector<double>& values, double shift) {
  std::vector<double> at(t);
  for (double& x : at) x += shift;
  return linearAt(t, values, at);
}

}  // namespace

void applyColumnShifts(GapLog* log, const LogMapping& mapping) {
  std::vector<std::pair<std::string, const ColumnMapping*>> moves;
  for (const auto& [schema, column] : mapping.columns) {
    if (column.shift == 0.0) continue;
    const std::vector<double>* values = log->column(schema);
    if (values == nullptr || values->empty()) {
      log->notes.push_back("log mapping " + column.location + ": shift of " + schema + " by " + seconds(column.shift) +
                           " ignored: the log has no " + schema);
      continue;
    }
    moves.emplace_back(schema, &column);
  }
  if (moves.empty()) return;
  const std::vector<double>& t = log->t;
  // The rows every shifted column has a value for: t + s within the log.
  double latest_early = 0.0, largest_late = 0.0;  // the most negative and the most positive shift
  for (const auto& [schema, column] : moves) {
    latest_early = std::min(latest_early, column->shift);
    largest_late = std::max(largest_late, column->shift);
  }
  const double keep_from = t.front() - latest_early, keep_to = t.back() - largest_late;
  const std::size_t begin = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), keep_from - 1e-12) - t.begin());
  const std::size_t end = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), keep_to + 1e-12) - t.begin());
  if (end < begin + 2) {
    const ColumnMapping* widest = moves.front().second;
    for (const auto& [schema, column] : moves) {
      if (std::abs(column->shift) > std::abs(widest->shift)) widest = column;
    }
    throw InputError(log->source + ": the log mapping's time shifts (the largest " + seconds(widest->shift) + " at " +
                     widest->location + ") leave fewer than two rows of a log of " + seconds(log->duration()));
  }
  for (const auto& [schema, column] : moves) {
    std::vector<double>& values = *log->column(schema);
    values = shifted(t, values, column->shift);
    log->notes.push_back(schema + " shifted by " + seconds(column->shift) + " (log mapping " + column->location +
                         "): its value at t is the logged one at t + " + seconds(column->shift) +
                         ", interpolated linearly");
  }
  const std::size_t dropped = begin + (t.size() - end);
  if (dropped > 0) {
    const std::size_t rows_read = log->rows_read, rows_skipped = log->rows_skipped;
    std::vector<std::string> notes = log->notes;
    GapLog kept = log->slice(begin, end);
    kept.source = log->source;
    kept.rows_read = rows_read;
    kept.rows_skipped = rows_skipped;
    notes.push_back(std::to_string(dropped) + " rows dropped where a shifted column would read beyond the log (" +
                    std::to_string(begin) + " at the start, " + std::to_string(t.size() - end) + " at the end)");
    kept.notes = std::move(notes);
    *log = std::move(kept);
  }
}

}  // namespace lane_keeping
