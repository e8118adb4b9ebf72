#include "lane_keeping/gap/log/time_holes.h"

#include <algorithm>

namespace lane_keeping {

double medianTimeStep(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> steps(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) steps[i - 1] = t[i] - t[i - 1];
  const std::size_t mid = steps.size() / 2;
  std::nth_element(steps.begin(), steps.begin() + mid, steps.end());
  if (steps.size() % 2 == 1) return steps[mid];
  return 0.5 * (steps[mid] + *std::max_element(steps.begin(), steps.begin() + mid));
}

std::vector<TimeHole> timeHoles(const std::vector<double>& t) {
  std::vector<TimeHole> out;
  const double step = medianTimeStep(t);
  if (!(step > 0.0)) return out;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i] - t[i - 1] > kHoleSteps * step) out.push_back({t[i - 1], t[i]});
  }
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> holeFreeStretches(const std::vector<double>& t) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  if (t.empty()) return out;
  const double step = medianTimeStep(t);
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= t.size(); ++i) {
    if (i < t.size() && !(step > 0.0 && t[i] - t[i - 1] > kHoleSteps * step)) continue;
    if (!out.empty() && i - begin < kMinStretch) {
      out.back().second = i;  // too short on its own: joined to the one before
    } else {
      out.emplace_back(begin, i);
    }
    begin = i;
  }
  if (out.size() > 1 && out.front().second - out.front().first < kMinStretch) {  // the first: to the one after
    out[1].first = 0;
    out.erase(out.begin());
  }
  return out;
}

}  // namespace lane_keeping
