#include "lane_keeping/gap/evaluation/residual_structure.h"

#include <cmath>

namespace lane_keeping {
namespace {

/// Interval index of each sample of a trace (a break at b starts a new interval at sample b).
std::vector<int> intervalOf(const ReplayTrace& trace) {
  std::vector<int> interval(trace.t.size(), 0);
  std::size_t next = 0;
  int current = 0;
  std::vector<std::size_t> breaks = trace.breaks;
  for (std::size_t i = 0; i < interval.size(); ++i) {
    while (next < breaks.size() && breaks[next] <= i) {
      if (breaks[next] == i && i > 0) ++current;
      ++next;
    }
    interval[i] = current;
  }
  return interval;
}

}  // namespace

ResidualStructure residualStructure(const SubsystemReplay& replay, const std::vector<double>& input) {
  ResidualStructure out;
  for (const ReplayTrace& trace : replay.traces) {
    const std::vector<double> r = trace.residual();
    const std::size_t n = r.size();
    if (n < 2 * kResidualLags) continue;
    const std::vector<int> interval = intervalOf(trace);
    double r2 = 0.0;
    for (double v : r) r2 += v * v;
    if (!(r2 > 0.0)) continue;
    for (int k = 1; k <= kResidualLags; ++k) {
      double sum = 0.0;
      for (std::size_t i = 0; i + k < n; ++i) {
        if (interval[i] == interval[i + k]) sum += r[i] * r[i + k];
      }
      const double rho = sum / r2;
      out.whiteness += static_cast<double>(n) * rho * rho;
    }
    if (input.size() != n) continue;
    double mean = 0.0;
    for (double u : input) mean += u;
    mean /= static_cast<double>(n);
    double u2 = 0.0;
    for (double u : input) u2 += (u - mean) * (u - mean);
    if (!(u2 > 0.0)) continue;
    const double norm = std::sqrt(r2 * u2);
    for (int k = 0; k <= kResidualLags; ++k) {
      double sum = 0.0;
      for (std::size_t i = k; i < n; ++i) {
        if (interval[i] == interval[i - k]) sum += r[i] * (input[i - k] - mean);
      }
      const double rho = sum / norm;
      out.input_correlation += static_cast<double>(n) * rho * rho;
    }
  }
  return out;
}

}  // namespace lane_keeping
