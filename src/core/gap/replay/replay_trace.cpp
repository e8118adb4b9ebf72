#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

std::vector<double> ReplayTrace::residual() const {
  std::vector<double> r(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) r[i] = (measured[i] - predicted[i]) / scale;
  return r;
}

void ReplayTrace::append(const ReplayTrace& other) {
  const std::size_t offset = t.size();
  breaks.push_back(offset);
  for (std::size_t b : other.breaks) breaks.push_back(offset + b);
  t.insert(t.end(), other.t.begin(), other.t.end());
  // Keep residuals comparable: re-express the other's values in this trace's scale is unnecessary,
  // both store raw values; the normalisation of the first trace is kept.
  measured.insert(measured.end(), other.measured.begin(), other.measured.end());
  predicted.insert(predicted.end(), other.predicted.begin(), other.predicted.end());
}

}  // namespace lane_keeping
