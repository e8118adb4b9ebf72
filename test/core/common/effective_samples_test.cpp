// The effective sample count of a series (common/effective_samples.h) and a printf into a string of any length
// (common/printf_string.h): the two helpers the input checks' findings share.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "lane_keeping/common/effective_samples.h"
#include "lane_keeping/common/printf_string.h"

namespace lane_keeping {
namespace {

TEST(EffectiveSamples, WhiteNoiseCountsAllAnAr1SeriesItsClosedForm) {
  std::mt19937 rng(11u);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<double> white(20000), slow(20000);
  double x = 0.0;
  for (std::size_t i = 0; i < white.size(); ++i) {
    white[i] = unit(rng);
    x = 0.9 * x + unit(rng);  // AR(1), rho = 0.9: n (1 - 0.9) / (1 + 0.9) = 0.0526 n
    slow[i] = x;
  }
  EXPECT_NEAR(effectiveSampleCount(white) / 20000.0, 1.0, 0.03);
  EXPECT_NEAR(effectiveSampleCount(slow) / 20000.0, 0.1 / 1.9, 0.006);
  // A constant deviation (rho -> 1) counts as one sample; nothing as none.
  EXPECT_DOUBLE_EQ(effectiveSampleCount(std::vector<double>(50, 0.3)), 1.0);
  EXPECT_DOUBLE_EQ(effectiveSampleCount({}), 0.0);
}

TEST(EffectiveSamples, NoLagIsTakenAcrossTheStretchesStarts) {
  // Two stretches, each a constant of its own sign: across the seam the lag would be negative.
  std::vector<double> two(20, 1.0);
  for (std::size_t i = 10; i < 20; ++i) two[i] = -1.0;
  EXPECT_NEAR(effectiveSampleCount(two, {10}), 20.0 * 0.1 / 1.9, 1e-12);  // rho = 18 / 20 within the two
  EXPECT_NEAR(effectiveSampleCount(two), 20.0 * 0.15 / 1.85, 1e-12);      // the seam's -1 taken: rho = 17 / 20
}

TEST(PrintfString, AnyLengthAndTheFormatsNumbers) {
  EXPECT_EQ(printfString("%.3f and %zu %s", 0.84126, std::size_t{3}, "laps"), "0.841 and 3 laps");
  const std::string longer = printfString("%s", std::string(2000, 'x').c_str());  // a fixed buffer cut such at 512
  EXPECT_EQ(longer.size(), 2000u);
  EXPECT_EQ(printfString("%s", ""), "");
}

}  // namespace
}  // namespace lane_keeping
