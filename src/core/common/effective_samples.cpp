#include "lane_keeping/common/effective_samples.h"

#include <algorithm>

namespace lane_keeping {

double effectiveSampleCount(const std::vector<double>& deviations, const std::vector<std::size_t>& starts) {
  const double n = static_cast<double>(deviations.size());
  if (deviations.empty()) return 0.0;
  // `starts` in order: a cursor walks them once (a log with thousands of holes stays linear).
  std::vector<std::size_t> seams = starts;
  std::sort(seams.begin(), seams.end());
  auto seam = seams.begin();
  double squares = 0.0, lag = 0.0;
  for (std::size_t i = 0; i < deviations.size(); ++i) {
    squares += deviations[i] * deviations[i];
    while (seam != seams.end() && *seam < i) ++seam;
    if (i > 0 && (seam == seams.end() || *seam != i)) lag += deviations[i] * deviations[i - 1];
  }
  const double rho = squares > 0.0 ? std::clamp(lag / squares, 0.0, 0.999999) : 0.0;
  return std::clamp(n * (1.0 - rho) / (1.0 + rho), 1.0, n);
}

}  // namespace lane_keeping
