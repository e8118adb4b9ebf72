// The O(1) sample lookup of the replays (gap/log/sample_index.h) must be std::upper_bound's answer on any
// non-decreasing stamps: uniform, jittered, with repeated stamps and with a gap where its guess is far
// off, at random times and at the stamps themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "lane_keeping/gap/log/sample_index.h"

namespace lane_keeping {
namespace {

std::size_t reference(const std::vector<double>& times, double t) {
  if (t <= times.front()) return 0;
  return static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
}

void expectUpperBoundsAnswer(const std::vector<double>& times, const std::string& what) {
  const SampleIndex index(times);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> within(times.front() - 0.5, times.back() + 0.5);
  int mismatches = 0;
  for (int k = 0; k < 20000; ++k) {
    const double t = within(rng);
    mismatches += index.atOrBefore(times, t) != reference(times, t);
  }
  for (double t : times) {
    mismatches += index.atOrBefore(times, t) != reference(times, t);
    mismatches += index.atOrBefore(times, std::nextafter(t, -1e9)) != reference(times, std::nextafter(t, -1e9));
  }
  EXPECT_EQ(mismatches, 0) << what;
  EXPECT_EQ(index.atOrBefore(times, std::numeric_limits<double>::quiet_NaN()), times.size() - 1) << what;
}

TEST(SampleIndex, IsUpperBoundsAnswerOnAnyNonDecreasingStamps) {
  std::vector<double> uniform, jittered, repeated, gap;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.2e-2, 0.2e-2);
  for (int i = 0; i < 3000; ++i) {
    uniform.push_back(12.5 + 0.01 * i);
    jittered.push_back(12.5 + 0.01 * i + jitter(rng));  // +-20 % of the step: still increasing
    repeated.push_back(12.5 + 0.01 * (i - i / 7));      // every seventh stamp repeats the one before
    gap.push_back(12.5 + 0.01 * i + (i >= 1000 ? 1.0 : 0.0));  // 100 samples lost at 22.5 s
  }
  expectUpperBoundsAnswer(uniform, "uniform");
  expectUpperBoundsAnswer(jittered, "jittered");
  expectUpperBoundsAnswer(repeated, "repeated stamps");
  expectUpperBoundsAnswer(gap, "a gap");
  expectUpperBoundsAnswer({4.0}, "one stamp");
  expectUpperBoundsAnswer({4.0, 4.0, 4.0}, "one stamp three times");
  expectUpperBoundsAnswer({0.0, 1.0}, "two stamps");
}

}  // namespace
}  // namespace lane_keeping
