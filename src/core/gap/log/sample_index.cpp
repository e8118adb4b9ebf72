#include "lane_keeping/gap/log/sample_index.h"

#include <algorithm>
#include <cmath>

namespace lane_keeping {

namespace {
/// Steps the guess may walk before the binary search takes over: jitter and a repeated stamp move it
/// by one or two; a gap in the log by as many samples as it lost.
constexpr int kWalk = 4;
}  // namespace

SampleIndex::SampleIndex(const std::vector<double>& times) {
  if (times.size() < 2 || !(times.back() > times.front())) return;
  first_ = times.front();
  per_second_ = static_cast<double>(times.size() - 1) / (times.back() - times.front());
}

std::size_t SampleIndex::atOrBefore(const std::vector<double>& times, double t) const {
  if (times.empty() || t <= times.front()) return 0;
  const std::size_t last = times.size() - 1;
  if (!(t < times.back())) return last;  // (also NaN, as upper_bound gives)
  // Here times.front() < t < times.back(): the answer i has times[i] <= t < times[i + 1], i < last.
  if (per_second_ > 0.0) {
    std::size_t i = std::min(last, static_cast<std::size_t>((t - first_) * per_second_));
    for (int step = 0; step < kWalk; ++step) {
      if (times[i] > t) {
        --i;  // i > 0: times[0] < t
      } else if (times[i + 1] <= t) {
        ++i;  // i + 1 < last: times[last] > t
      } else {
        return i;
      }
    }
  }
  return static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
}

}  // namespace lane_keeping
