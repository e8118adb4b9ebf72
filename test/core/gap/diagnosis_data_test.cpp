// Training and held-out data: every kind of excitation on both sides of a single log, whole runs held
// out when there are several.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

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
  RunData out;
  out.log = std::make_shared<const LogSignals>(log);
  out.config = std::make_shared<const SimConfig>();
  return out;
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
  // The first 2 s, a start transient (startsWithTransient), alternate in slivers; every block after them
  // is at least min_block_length long.
  for (const auto& set : {split.train[0], split.held[0]}) {
    for (const auto& s : set.segments) {
      if (s.t1 <= kStartTransientWindow + 1e-9) {
        EXPECT_NEAR(s.t1 - s.t0, s.t0 < kStartSliver ? kStartSliver - kStartTransientLead : kStartSliver, 1e-9);
      } else {
        EXPECT_GE(s.t1 - s.t0, options.min_block_length - 1e-9);
      }
    }
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

/// `log` without the rows in [from, to).
GapLog withHole(GapLog log, double from, double to) {
  GapLog out = log;
  for (auto* column : {&out.t, &out.x, &out.y, &out.psi, &out.yaw_rate, &out.delta, &out.delta_des, &out.torque}) {
    column->clear();
  }
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (log.t[i] >= from && log.t[i] < to) continue;
    out.t.push_back(log.t[i]);
    out.x.push_back(log.x[i]);
    out.y.push_back(log.y[i]);
    out.psi.push_back(log.psi[i]);
    out.yaw_rate.push_back(log.yaw_rate[i]);
    out.delta.push_back(log.delta[i]);
    out.delta_des.push_back(log.delta_des[i]);
    out.torque.push_back(log.torque[i]);
  }
  return out;
}

// Issue 48: the replays integrated across a 5 s hole with the inputs interpolated over it.
TEST(DataSplit, NoSegmentSpansAHoleAndEachStartsAMarginAfterIt) {
  const DiagnosisOptions options;
  const RunData holed = run(withHole(transientLog("holed.csv"), 12.0, 17.0));  // samples 11.99 and 17.0 around it
  for (const DataSplit& split : {splitData({holed}, {}, options), splitData({holed}, {holed}, options),
                                 splitData({holed, run(transientLog("b.csv"))}, {}, options)}) {
    for (const auto* sets : {&split.train, &split.held}) {
      for (const Dataset& set : *sets) {
        if (set.log->log().source != "holed.csv") continue;
        for (const TimeSegment& s : set.segments) {
          EXPECT_TRUE(s.t1 <= 11.99 + 1e-9 || s.t0 >= 17.0 + options.start_margin - 1e-9)
              << split.method << ": segment " << s.t0 << "-" << s.t1;
          if (s.t1 > kStartTransientWindow + 1e-9) {  // not a sliver
            EXPECT_GE(s.t1 - s.t0, kMinPieceBetweenHoles - 1e-9);
          }
        }
      }
    }
  }
  // What is left is used: the data before and after the hole.
  const std::vector<Dataset> whole = wholeLogs({holed}, options.start_margin);
  ASSERT_EQ(whole.size(), 1u);
  ASSERT_EQ(whole[0].segments.size(), 2u);
  EXPECT_NEAR(whole[0].segments[0].t0, kStartTransientLead, 1e-9);  // the run starts with a transient
  EXPECT_NEAR(whole[0].segments[0].t1, 11.99, 1e-9);
  EXPECT_NEAR(whole[0].segments[1].t0, 17.6, 1e-9);
}

TEST(UnavailableSubsystems, AStuckChannelRulesOutTheReplaysThatReadIt) {
  GapLog log = transientLog("stuck.csv");
  for (double& d : log.delta) d = 0.0;
  const std::vector<RunData> runs = prepareRuns({gapRun(log, SimConfig{})});
  const InputCheck* stuck = nullptr;
  for (const InputCheck& c : runs[0].input_checks) {
    if (c.kind == "stuck") stuck = &c;
  }
  ASSERT_NE(stuck, nullptr);
  EXPECT_EQ(stuck->channel, "delta");
  const auto unavailable = unavailableSubsystems(runs);
  EXPECT_EQ(unavailable.size(), 3u);  // the tracker reads no steering angle
  for (const char* name : {"steering", "chassis", "actuator"}) {
    ASSERT_TRUE(unavailable.count(name)) << name;
    EXPECT_EQ(unavailable.at(name), "stuck.csv: " + stuck->detail);
  }
  EXPECT_TRUE(availableSubsystems(runs).count("tracker"));
  EXPECT_TRUE(unavailableSubsystems(prepareRuns({gapRun(transientLog("fine.csv"), SimConfig{})})).empty());
}

// A fit's coarse data (candidate_fit.h): every k-th chassis-horizon piece of each set, spread over the
// whole of it, each set keeping at least its first piece.
TEST(DecimatedData, KeepsEveryKthPieceOfEachSetSpreadOverTheSegments) {
  const DataSplit split = splitData({run(transientLog("a.csv"))}, {}, DiagnosisOptions{});
  ASSERT_EQ(split.train.size(), 1u);
  const std::vector<TimeSegment>& segments = split.train[0].segments;
  ASSERT_GE(segments.size(), 4u);
  auto length = [](const std::vector<TimeSegment>& v) {
    double sum = 0.0;
    for (const auto& s : v) sum += s.t1 - s.t0;
    return sum;
  };
  auto inside = [&](const TimeSegment& piece) {
    for (const auto& s : segments) {
      if (piece.t0 >= s.t0 - 1e-12 && piece.t1 <= s.t1 + 1e-12) return true;
    }
    return false;
  };
  // Stride 1: the same time, cut into pieces no longer than the chassis horizon.
  const std::vector<Dataset> all = decimatedData(split.train, 2.0, 1);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_NEAR(length(all[0].segments), length(segments), 1e-9);
  std::size_t pieces = 0;
  for (const auto& s : segments) pieces += static_cast<std::size_t>(std::ceil((s.t1 - s.t0) / 2.0 - 1e-9));
  EXPECT_EQ(all[0].segments.size(), pieces);
  for (const auto& piece : all[0].segments) {
    EXPECT_LE(piece.t1 - piece.t0, 2.0 + 1e-12);
    EXPECT_TRUE(inside(piece));
  }
  // Stride 3: pieces 0, 3, 6, ... of those, in order, the first one the set's start.
  const std::vector<Dataset> coarse = decimatedData(split.train, 2.0, 3);
  ASSERT_EQ(coarse[0].segments.size(), (pieces + 2) / 3);
  for (std::size_t k = 0; k < coarse[0].segments.size(); ++k) {
    EXPECT_EQ(coarse[0].segments[k].t0, all[0].segments[3 * k].t0);
    EXPECT_EQ(coarse[0].segments[k].t1, all[0].segments[3 * k].t1);
  }
  EXPECT_EQ(coarse[0].segments.front().t0, segments.front().t0);
  // Spread over the set: the last kept piece lies in its last three pieces.
  EXPECT_GE(coarse[0].segments.back().t0, all[0].segments[pieces - 3].t0);
  // Several sets: counted per set, so a short set keeps its first piece and the order is kept.
  const std::vector<Dataset> two = decimatedData({split.train[0], {split.train[0].log, split.train[0].config, {{1.0, 1.5}}}}, 2.0, 3);
  ASSERT_EQ(two.size(), 2u);
  ASSERT_EQ(two[1].segments.size(), 1u);
  EXPECT_EQ(two[1].segments[0].t0, 1.0);
  EXPECT_EQ(two[1].segments[0].t1, 1.5);
  EXPECT_THROW(decimatedData(split.train, 0.0, 3), std::invalid_argument);
  EXPECT_THROW(decimatedData(split.train, 2.0, 0), std::invalid_argument);
}

// The coarse data of a fit: every third piece of a set up to 12 pieces (every log of the benchmark
// families, so their fits are unchanged), the square root of a longer set's pieces otherwise, so the
// coarse search grows as sqrt(n) (issue 18), each set decimated on its own.
TEST(CoarseFitData, StrideThreeOnShortSetsSquareRootOfTheirPiecesOnLongOnes) {
  const DataSplit split = splitData({run(transientLog("a.csv"))}, {}, DiagnosisOptions{});
  const Dataset& base = split.train[0];
  auto set = [&](double seconds) { return Dataset{base.log, base.config, {{0.0, seconds}}}; };
  const double piece = 2.0;
  EXPECT_EQ(pieceCount({set(14.0)}, piece), 7u);
  EXPECT_EQ(pieceCount({set(13.0)}, piece), 7u);  // a shorter last piece counts
  EXPECT_EQ(pieceCount({set(14.0), set(42.0)}, piece), 28u);
  // (pieces, expected stride): 7 and 12 pieces keep 3 (sqrt 2.6, 3.5); 21 take 5 (4.6); 600 take 24.
  for (const auto& [seconds, stride] : std::vector<std::pair<double, std::size_t>>{{14.0, 3}, {24.0, 3}, {42.0, 5}, {1200.0, 24}}) {
    const std::vector<Dataset> coarse = coarseFitData({set(seconds)}, piece, 3);
    const std::vector<Dataset> expected = decimatedData({set(seconds)}, piece, stride);
    ASSERT_EQ(coarse.size(), 1u);
    ASSERT_EQ(coarse[0].segments.size(), expected[0].segments.size()) << seconds << " s";
    for (std::size_t k = 0; k < coarse[0].segments.size(); ++k) EXPECT_EQ(coarse[0].segments[k].t0, expected[0].segments[k].t0);
  }
  // 20 minutes: 600 pieces, 25 of them in the coarse data (within one of sqrt(600) = 24.5).
  EXPECT_EQ(pieceCount(coarseFitData({set(1200.0)}, piece, 3), piece), 25u);
  // The minimum stride wins where it is larger than the root.
  EXPECT_EQ(pieceCount(coarseFitData({set(42.0)}, piece, 7), piece), 3u);
  // Each set on its own: a short set beside a long one keeps its own stride 3.
  const std::vector<Dataset> both = coarseFitData({set(14.0), set(1200.0)}, piece, 3);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].segments.size(), 3u);
  EXPECT_EQ(both[1].segments.size(), 25u);
  EXPECT_THROW(coarseFitData({set(14.0)}, 0.0, 3), std::invalid_argument);
  EXPECT_THROW(coarseFitData({set(14.0)}, piece, 0), std::invalid_argument);
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
