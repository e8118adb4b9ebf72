#include "lane_keeping/gap/log/linear_resample.h"

#include <algorithm>

namespace lane_keeping {

std::vector<double> linearAt(const std::vector<double>& t, const std::vector<double>& values, const std::vector<double>& at) {
  if (values.empty() || values.size() != t.size()) return {};
  std::vector<double> out(at.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    while (j + 2 < t.size() && t[j + 1] <= at[i]) ++j;
    while (j > 0 && t[j] > at[i]) --j;
    const double w = t.size() > 1 ? (at[i] - t[j]) / (t[j + 1] - t[j]) : 0.0;
    out[i] = t.size() > 1 ? values[j] + std::clamp(w, 0.0, 1.0) * (values[j + 1] - values[j]) : values[j];
  }
  return out;
}

}  // namespace lane_keeping
