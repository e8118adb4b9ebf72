// The median the diagnosis and the benchmark share (median.h): of an even count the mean of the middle two,
// whatever the order of the values.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "lane_keeping/common/median.h"

namespace lane_keeping {
namespace {

TEST(Median, OddCountsTakeTheMiddleEvenCountsTheMeanOfTheMiddleTwo) {
  EXPECT_DOUBLE_EQ(median({}), 0.0);
  EXPECT_DOUBLE_EQ(median({4.0}), 4.0);
  EXPECT_DOUBLE_EQ(median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);  // not the upper middle value, 3
  EXPECT_DOUBLE_EQ(median({5.0, 5.0, 1.0, 9.0, 9.0, 1.0}), 5.0);
  // Every order of the same values gives the same median.
  std::vector<double> v{0.7, 0.1, 0.9, 0.3, 0.5, 0.2, 0.8, 0.4};
  for (int k = 0; k < 8; ++k) {
    EXPECT_DOUBLE_EQ(median(v), 0.45);
    std::rotate(v.begin(), v.begin() + 3, v.end());
  }
}

}  // namespace
}  // namespace lane_keeping
