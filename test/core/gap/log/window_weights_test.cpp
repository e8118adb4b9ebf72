// The smoothing filter's window weights, remembered per thread across calls on a uniform time base
// (window_weights.h): they must be the local quadratic fit's, must never serve one time base's or
// order's weights for another, and the memory they hold must stay bounded.
#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <utility>
#include <vector>

#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/log/window_weights.h"

namespace lane_keeping {
namespace {

TEST(WindowWeights, ReproduceAQuadraticAndItsFirstTwoDerivatives) {
  // p(t) = 2 - 3 t + 4 t^2 around t_i: a quadratic fit gives back p(0) = 2, p'(0) = -3, p''(0) = 8
  // from any window of at least three samples, centred or at an edge.
  UniformWindowWeights memo(std::size_t{1} << 20);
  for (const double h : {1e-3, 0.01, 1.0 / 1024.0}) {
    for (int order = 0; order <= 2; ++order) {
      memo.select(h, order);
      for (const auto& [before, after] : std::vector<std::pair<std::size_t, std::size_t>>{
               {2, 2}, {0, 4}, {4, 0}, {100, 101}, {0, 250}, {250, 3}}) {
        const std::vector<double>& w = memo.weights(before, after);
        ASSERT_EQ(w.size(), before + after + 1);
        double sum = 0.0;
        for (std::size_t k = 0; k < w.size(); ++k) {
          const double t = (static_cast<double>(k) - static_cast<double>(before)) * h;
          sum += w[k] * (2.0 - 3.0 * t + 4.0 * t * t);
        }
        const double exact = order == 0 ? 2.0 : (order == 1 ? -3.0 : 8.0);
        const double samples = static_cast<double>(before + after);
        // (An edge window's derivative weights grow as 1 / (samples h)^order.)
        EXPECT_NEAR(sum, exact, 1e-9 * std::pow(1.0 / h, order) * (1.0 + samples))
            << "h " << h << " order " << order << " window (" << before << ", " << after << ")";
      }
    }
  }
}

/// smoothedDerivative on a thread of its own: one whose memo has seen nothing else.
std::vector<double> smoothedOnAFreshThread(const std::vector<double>& t, const std::vector<double>& y,
                                           double half_width, int order) {
  std::vector<double> out;
  std::thread([&] { out = smoothedDerivative(t, y, half_width, order); }).join();
  return out;
}

TEST(WindowWeights, OneTimeBaseOrOrderNeverGetsAnothersWeights) {
  // Two uniform time bases whose steps differ by 2.4 % and one series on each, smoothed in turn on
  // one thread with both orders: each output must be the same to the last bit as on a thread that
  // smoothed nothing before. (Weights keyed without the step or the order would be the other's.)
  std::vector<double> t_a, t_b, y;
  for (int i = 0; i < 3000; ++i) {
    t_a.push_back(0.001 * i);
    t_b.push_back(i / 1024.0);
    y.push_back(std::sin(0.007 * i) + 0.01 * std::cos(911.0 * i));
  }
  const double half_width = 0.05;
  std::vector<std::vector<double>> expected;
  for (const auto* t : {&t_a, &t_b}) {
    for (int order = 0; order <= 1; ++order) expected.push_back(smoothedOnAFreshThread(*t, y, half_width, order));
  }
  std::thread([&] {
    for (int round = 0; round < 2; ++round) {
      std::size_t k = 0;
      for (const auto* t : {&t_a, &t_b}) {
        for (int order = 0; order <= 1; ++order, ++k) {
          EXPECT_EQ(smoothedDerivative(*t, y, half_width, order), expected[k]) << "round " << round << " case " << k;
          // And each (the same step and order) with another half-width: other windows, the same shapes.
          EXPECT_EQ(smoothedDerivative(*t, y, 2.0 * half_width, order),
                    smoothedOnAFreshThread(*t, y, 2.0 * half_width, order));
        }
      }
    }
  }).join();
  // The two steps' order-1 outputs differ (the keys above were tested on something that tells them apart).
  EXPECT_NE(expected[1], expected[3]);
}

TEST(WindowWeights, TheLeastRecentlyUsedTimeBasesGoBeyondTheCapacityButNeverTheSelectedOne) {
  UniformWindowWeights memo(1000);  // doubles
  memo.select(0.001, 0);
  const std::vector<double>* first = &memo.weights(200, 200);  // 401 doubles
  memo.select(0.002, 0);
  memo.weights(200, 200);
  memo.select(0.003, 0);
  memo.weights(200, 200);
  EXPECT_EQ(memo.timeBases(), 3u);
  EXPECT_EQ(memo.doublesHeld(), 1203u);
  // Selecting the first again makes 0.002 the least recently used: it goes, and the first's weights
  // are still the ones solved before (the same vector, not solved again).
  memo.select(0.001, 0);
  EXPECT_EQ(memo.timeBases(), 2u);
  EXPECT_EQ(memo.doublesHeld(), 802u);
  EXPECT_EQ(&memo.weights(200, 200), first);
  // A time base alone over the capacity stays while it is the one in use.
  UniformWindowWeights small(100);
  small.select(0.001, 1);
  small.weights(200, 200);
  small.select(0.001, 1);
  EXPECT_EQ(small.timeBases(), 1u);
  EXPECT_EQ(small.doublesHeld(), 401u);
  small.select(0.002, 1);  // now the old one is not in use
  EXPECT_EQ(small.timeBases(), 1u);
  EXPECT_EQ(small.doublesHeld(), 0u);
}

}  // namespace
}  // namespace lane_keeping
