#pragma once
/// The contract of a log the readers return (gap/log/gap_log.h), checked by the csv and log-mapping
/// harnesses alike: at least 10 rows, t finite and strictly increasing, every present column as long as
/// t and finite within 1e9 (the readers refuse what a car cannot produce).
#include <cmath>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {
namespace fuzz {

inline void checkLogContract(const GapLog& log) {
  if (log.size() < 10) finding("a log with " + std::to_string(log.size()) + " rows was accepted");
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (!std::isfinite(log.t[i])) finding("non-finite t accepted");
    if (i > 0 && !(log.t[i] > log.t[i - 1])) finding("t not strictly increasing at row " + std::to_string(i));
  }
  const std::vector<double>* columns[] = {&log.x,      &log.y,      &log.psi, &log.yaw_rate, &log.delta, &log.delta_des,
                                          &log.torque, &log.v,      &log.vy,  &log.ay,       &log.delta_rate};
  for (const std::vector<double>* column : columns) {
    if (column->empty()) continue;
    if (column->size() != log.size()) finding("a column's length differs from t's");
    for (double v : *column) {
      if (!std::isfinite(v) || std::fabs(v) > 1e9) finding("value " + std::to_string(v) + " accepted");
    }
  }
}

}  // namespace fuzz
}  // namespace lane_keeping
