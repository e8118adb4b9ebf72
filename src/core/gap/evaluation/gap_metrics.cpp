#include "lane_keeping/gap/evaluation/gap_metrics.h"

#include <algorithm>
#include <cmath>

namespace lane_keeping {

namespace {
constexpr double kNoiseTolerance = 1.1;
}  // namespace

TraceScore scoreTrace(const ReplayTrace& trace) {
  TraceScore score;
  score.name = trace.name;
  const std::vector<double> r = trace.residual();
  score.samples = r.size();
  if (r.empty()) return score;
  double sum = 0.0;
  for (double v : r) sum += v * v;
  score.nrmse = std::sqrt(sum / r.size());
  // Second differences within intervals (a break at index b means b starts a new interval).
  std::vector<bool> starts(r.size() + 1, false);
  starts[0] = true;
  for (std::size_t b : trace.breaks) {
    if (b < starts.size()) starts[b] = true;
  }
  double d2 = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 1; i + 1 < r.size(); ++i) {
    if (starts[i] || starts[i + 1]) continue;  // the three samples must share an interval
    const double q = r[i - 1] - 2.0 * r[i] + r[i + 1];
    d2 += q * q;
    ++count;
  }
  score.floor = count > 0 ? std::sqrt(d2 / count / 6.0) : 0.0;
  // Residual variance within 10 % of the white-noise variance counts as noise: the floor estimate has
  // its own scatter, and noise that is not quite white (filtered derivatives) sits a little above it.
  score.excess = std::sqrt(std::max(0.0, score.nrmse * score.nrmse - kNoiseTolerance * score.floor * score.floor));
  return score;
}

SubsystemScore scoreReplay(const SubsystemReplay& replay) {
  SubsystemScore score;
  score.name = replay.name;
  score.diverged_intervals = replay.diverged_intervals;
  double n2 = 0.0, f2 = 0.0, e2 = 0.0;
  for (const auto& trace : replay.traces) {
    score.traces.push_back(scoreTrace(trace));
    n2 += score.traces.back().nrmse * score.traces.back().nrmse;
    f2 += score.traces.back().floor * score.traces.back().floor;
    e2 += score.traces.back().excess * score.traces.back().excess;
  }
  const double k = std::max<std::size_t>(1, replay.traces.size());
  score.nrmse = std::sqrt(n2 / k);
  score.floor = std::sqrt(f2 / k);
  score.excess = std::sqrt(e2 / k);
  return score;
}

double netExcess(const SubsystemScore& score) {
  return std::sqrt(std::max(0.0, score.excess * score.excess - score.reference * score.reference));
}

double combinedGap(const std::vector<SubsystemScore>& scores) {
  double sum = 0.0;
  for (const auto& s : scores) sum += netExcess(s) * netExcess(s);
  return std::sqrt(sum);
}

}  // namespace lane_keeping
