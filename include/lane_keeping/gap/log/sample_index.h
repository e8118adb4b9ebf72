#pragma once
/// The sample of a log at or before a time, found in O(1) on a uniformly sampled log: the replays ask
/// it several times per integration step (12 % of a column fit's time went to std::upper_bound over
/// the log's stamps, lk_gap under perf). The guess is the sample a uniform rate puts there; a few steps
/// walk it over jitter and repeated stamps, and a binary search takes over where the guess is farther
/// off (a gap in the log), so the answer is upper_bound's on any non-decreasing stamps.
#include <cstddef>
#include <vector>

namespace lane_keeping {

class SampleIndex {
 public:
  SampleIndex() = default;
  /// For these stamps (non-decreasing, not empty); they are passed again to each query.
  explicit SampleIndex(const std::vector<double>& times);

  /// Index of the last stamp <= t; 0 if t is at or before the first; the last index if t is at or after
  /// the last (or NaN), as std::upper_bound(times, t) - 1 clamped to the stamps.
  std::size_t atOrBefore(const std::vector<double>& times, double t) const;

 private:
  double first_ = 0.0;
  double per_second_ = 0.0;  ///< samples per second over the log (0: a single stamp, or all equal)
};

}  // namespace lane_keeping
