// gap_metrics: the white-noise floor and excess of a replay residual, and the combined gap with and
// without a noise-only reference.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "lane_keeping/gap/evaluation/gap_metrics.h"

namespace lane_keeping {
namespace {

/// A residual of white noise (std `noise`) plus a slow sine (amplitude `amplitude`), scale 1.
ReplayTrace trace(double noise, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  ReplayTrace t;
  t.name = "delta";
  for (int i = 0; i < 20000; ++i) {
    const double time = i * 2e-3;
    t.t.push_back(time);
    t.measured.push_back(amplitude * std::sin(2.0 * M_PI * 0.5 * time) + noise * unit(rng));
    t.predicted.push_back(0.0);
  }
  t.breaks = {0, 5000, 10000, 15000};
  return t;
}

SubsystemScore subsystem(double excess, double reference) {
  SubsystemScore s;
  s.excess = excess;
  s.reference = reference;
  return s;
}

TEST(GapMetrics, FloorIsTheWhiteNoiseAndExcessTheSmoothPart) {
  const TraceScore noise_only = scoreTrace(trace(0.01, 0.0, 1));
  EXPECT_NEAR(noise_only.floor, 0.01, 0.0005);
  EXPECT_NEAR(noise_only.nrmse, 0.01, 0.0005);
  EXPECT_EQ(noise_only.excess, 0.0);  // within the 10 % tolerance of the floor

  const TraceScore with_sine = scoreTrace(trace(0.01, 0.05, 2));
  EXPECT_NEAR(with_sine.floor, 0.01, 0.0005);  // second differences do not see the 0.5 Hz sine
  // excess^2 = nrmse^2 - 1.1 floor^2 = (0.05^2 / 2 + 0.01^2) - 1.1 0.01^2
  EXPECT_NEAR(with_sine.excess, std::sqrt(0.05 * 0.05 / 2 - 0.1 * 0.01 * 0.01), 0.001);

  SubsystemReplay replay;
  replay.traces = {trace(0.01, 0.0, 3), trace(0.01, 0.05, 4)};
  const SubsystemScore s = scoreReplay(replay);
  EXPECT_NEAR(s.excess, std::sqrt(0.5 * with_sine.excess * with_sine.excess), 0.001);  // RMS over outputs
}

TEST(GapMetrics, CombinedGapIsNetOfTheNoiseReference) {
  EXPECT_NEAR(combinedGap({subsystem(3e-3, 0.0), subsystem(4e-3, 0.0)}), 5e-3, 1e-15);
  // Each subsystem counts only what stands above its reference; one below it counts zero, not less.
  EXPECT_NEAR(combinedGap({subsystem(5e-3, 3e-3), subsystem(2e-3, 3e-3)}), 4e-3, 1e-15);
  EXPECT_EQ(combinedGap({subsystem(2e-3, 3e-3)}), 0.0);
  EXPECT_EQ(combinedGap({}), 0.0);
}

}  // namespace
}  // namespace lane_keeping
