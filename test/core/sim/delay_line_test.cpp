// Delay lines keyed by nanosecond stamps: policy, coverage, pruning, bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/sim/delay_line.h"

namespace lane_keeping {
namespace {

TEST(DelayLine, LinearInterpolationBetweenStampsInSeconds) {
  DelayLine<TorqueCommand> line("torque", 1'901'950, Hold::kLinear, 100'000);  // tau2 = 1.90195 ms
  for (int k = 0; k <= 100; ++k) line.push(k * 100'000, TorqueCommand{static_cast<double>(k)});  // value = t / 0.1 ms
  // Read at t = 5 ms: query 5 ms - 1.90195 ms = 3.09805 ms -> 30.9805 (not a multiple of the step).
  ASSERT_TRUE(line.covers(5'000'000));
  EXPECT_NEAR(line.at(5'000'000).torque, 30.9805, 1e-12);
  // Before the first sample: the initial history is the first value.
  EXPECT_DOUBLE_EQ(line.at(1'000'000).torque, 0.0);
  // Beyond the latest sample + delay: not covered, and reading throws instead of extrapolating.
  EXPECT_FALSE(line.covers(10'000'000 + 1'901'951));
  EXPECT_THROW(line.at(10'000'000 + 1'901'951), ScheduleError);
}

TEST(DelayLine, ZeroOrderHoldUsesTheProducerPeriodForCoverage) {
  DelayLine<TorqueCommand> line("torque", 0, Hold::kZeroOrder, 1'000'000);  // 1 kHz producer
  line.push(0, TorqueCommand{1.0});
  line.push(1'000'000, TorqueCommand{2.0});
  EXPECT_TRUE(line.covers(1'999'999));   // next sample is due at 2 ms
  EXPECT_FALSE(line.covers(2'000'000));
  EXPECT_DOUBLE_EQ(line.at(1'999'999).torque, 2.0);
  EXPECT_DOUBLE_EQ(line.at(999'999).torque, 1.0);
}

TEST(DelayLine, DiscardKeepsWhatLaterReadsNeed) {
  DelayLine<SteeringMeasurement> line("delta", 200'000, Hold::kLinear, 100'000);
  for (int k = 0; k < 50; ++k) line.push(k * 100'000, SteeringMeasurement{k * 0.1, 0.0});
  line.discardBefore(2'250'000);  // query 2.05 ms: keeps the sample at 2.0 ms and later
  EXPECT_EQ(line.size(), 30u);
  EXPECT_NEAR(line.at(2'250'000).delta, 2.05, 1e-12);
  EXPECT_NEAR(line.at(4'000'000).delta, 3.8, 1e-12);
  // Ring buffer keeps working after wrap-around and growth.
  for (int k = 50; k < 500; ++k) {
    line.push(k * 100'000, SteeringMeasurement{k * 0.1, 0.0});
    line.discardBefore(k * 100'000);
  }
  EXPECT_NEAR(line.at(49'950'000).delta, 49.75, 1e-9);
}

TEST(DelayLine, RejectsStampsThatDoNotIncrease) {
  DelayLine<TorqueCommand> line("torque", 0, Hold::kLinear, 100'000);
  line.push(100, TorqueCommand{1.0});
  EXPECT_THROW(line.push(100, TorqueCommand{2.0}), InputError);
  EXPECT_THROW(line.push(50, TorqueCommand{2.0}), InputError);
}

TEST(Time, NanosecondRoundingAndConversion) {
  EXPECT_EQ(secondsToNanoseconds(1.9019505e-3), 1'901'951);  // 1901950.5 ns rounds away from zero
  EXPECT_EQ(secondsToNanoseconds(1e-4), 100'000);
  EXPECT_EQ(periodFromRate(10000.0), 100'000);
  EXPECT_DOUBLE_EQ(nanosecondsToSeconds(100'000), 1e-4);
  EXPECT_THROW(secondsToNanoseconds(std::nan("")), std::invalid_argument);
  EXPECT_THROW(periodFromRate(0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lane_keeping
