#pragma once
/// A column resampled at other times: linear interpolation between samples, held at the first and last
/// value outside them. Used where a column moves onto another time base (column_shift.h) and where a
/// simulated column is compared with a log's rows (noise_reference.h).
#include <vector>

namespace lane_keeping {

/// `values` (sampled at increasing times `t`, the same length) at the times `at`; empty if `values` is empty
/// or of another length than `t`. Fastest for increasing `at`.
std::vector<double> linearAt(const std::vector<double>& t, const std::vector<double>& values, const std::vector<double>& at);

}  // namespace lane_keeping
