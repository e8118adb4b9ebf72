// Training and held-out data: every kind of excitation on both sides of a single log, whole runs held
// out when there are several.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/gap/diagnosis_data.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// 30 s at 100 Hz: a strong steering transient in the first 4 s (the initial correction of an offset),
/// then a weak steady excitation.
GapLog transientLog(const std::string& name, double duration = 30.0) {
  GapLog log;
  log.source = name;
  for (int i = 0; i <= static_cast<int>(duration * 100.0); ++i) {
    const double t = 0.01 * i;
    const double transient = t < 4.0 ? std::exp(-0.5 * t) : 0.0;
    log.t.push_back(t);
    log.x.push_back(15.0 * t);
    log.y.push_back(0.0);
    log.psi.push_back(0.0);
    log.yaw_rate.push_back(0.02 * transient * std::sin(2.0 * M_PI * t) + 1e-3 * std::sin(0.7 * t));
    log.delta.push_back(0.05 * transient * std::sin(2.0 * M_PI * t) + 1e-3 * std::sin(0.7 * t));
    log.delta_des.push_back(log.delta.back() * 1.1);
    log.torque.push_back(80.0 * transient * std::cos(2.0 * M_PI * t) + 0.5 * std::sin(0.7 * t));
  }
  return log;
}

RunData run(const GapLog& log) {
  return {std::make_shared<const LogSignals>(log), std::make_shared<const SimConfig>()};
}

double heldTimeBefore(const DataSplit& split, double t_end) {
  double held = 0.0;
  for (const auto& set : split.held) {
    for (const auto& s : set.segments) held += std::max(0.0, std::min(s.t1, t_end) - s.t0);
  }
  return held;
}

TEST(DataSplit, AStartingTransientLiesOnBothSides) {
  const DiagnosisOptions options;
  const DataSplit split = splitData({run(transientLog("one.csv"))}, {}, options);
  EXPECT_EQ(split.method, "excitation-balanced blocks");
  ASSERT_EQ(split.held.size(), 1u);
  // Equal 3 s blocks from 0.6 s put 0.6-3.6 s in training and only 0.4 s of the transient in held-out
  // data; balanced blocks cut it into short blocks on both sides.
  const double held_in_transient = heldTimeBefore(split, 4.0);
  EXPECT_GT(held_in_transient, 1.0) << "held-out time within the transient";
  EXPECT_LT(held_in_transient, 2.4);
  for (const auto& [kind, share] : split.coverage) {
    EXPECT_GT(share, 0.3) << kind;
    EXPECT_LT(share, 0.7) << kind;
  }
  for (const auto& set : {split.train[0], split.held[0]}) {
    for (const auto& s : set.segments) EXPECT_GE(s.t1 - s.t0, options.min_block_length - 1e-9);
  }
}

TEST(DataSplit, SeveralRunsHoldOutWholeRuns) {
  const DataSplit split =
      splitData({run(transientLog("a.csv", 20.0)), run(transientLog("b.csv", 30.0)), run(transientLog("c.csv", 25.0))},
                {}, DiagnosisOptions{});
  EXPECT_EQ(split.method, "whole runs");
  ASSERT_EQ(split.train.size(), 2u);
  ASSERT_EQ(split.held.size(), 1u);
  // By duration: b (30 s) trains, c (25 s) is held out, a (20 s) trains.
  EXPECT_EQ(split.held[0].log->log().source, "c.csv");
  EXPECT_EQ(split.held_blocks, std::vector<std::string>{"c.csv (whole run)"});
}

TEST(DataSplit, GivenHeldOutRunsScoreAndTheRestTrains) {
  const DataSplit split = splitData({run(transientLog("a.csv"))}, {run(transientLog("b.csv"))}, DiagnosisOptions{});
  EXPECT_EQ(split.method, "held-out runs");
  EXPECT_EQ(split.train[0].log->log().source, "a.csv");
  EXPECT_EQ(split.held[0].log->log().source, "b.csv");
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
