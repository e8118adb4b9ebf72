// The start of a log (issue 47, kind 2; diagnosis_data.h, startsWithTransient): a run that starts with a
// large correction keeps its first seconds (from 0.1 s), in slivers on both sides of a single log's split, so that an
// effect acting only there is seen on held-out data — and the same correction with nothing wrong raises
// no alarm.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/diagnosis_data.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

RunData runOf(const BenchmarkCase& c) {
  const GapLog log = generateBenchmarkLog(c);  // at the case's own rate, else 500 Hz
  RunData run;
  run.log = std::make_shared<const LogSignals>(log);
  run.config = std::make_shared<const SimConfig>(benchmarkCaseNominal(c));
  return run;
}

double timeWithin(const std::vector<Dataset>& sets, double t0, double t1) {
  double total = 0.0;
  for (const Dataset& set : sets) {
    for (const TimeSegment& s : set.segments) total += std::max(0.0, std::min(s.t1, t1) - std::max(s.t0, t0));
  }
  return total;
}

TEST(StartOfALog, ATransientIsFoundWhereTheStartHoldsTheExcitationOnly) {
  // A 2 m offset corrected on a straight road: the first 2 s hold about half the run's excitation.
  const RunData offset = runOf(independentCase("none-start-2m-straight-500Hz"));
  EXPECT_TRUE(startsWithTransient(*offset.log, *offset.config));
  // A sinusoidal road from the lane's centre (the pair's training run): its excitation is spread out.
  const RunData sinusoid = runOf(independentCase("none-start-pair-sinusoid-straight"));
  EXPECT_FALSE(startsWithTransient(*sinusoid.log, *sinusoid.config));
  // A log no longer than the window has no "start" apart from its whole.
  GapLog short_log = offset.log->log();
  const std::size_t rows = static_cast<std::size_t>(std::count_if(short_log.t.begin(), short_log.t.end(),
                                                                   [](double t) { return t <= 1.9; }));
  for (auto* column : {&short_log.t, &short_log.x, &short_log.y, &short_log.psi, &short_log.yaw_rate, &short_log.v,
                       &short_log.vy, &short_log.ay, &short_log.delta, &short_log.delta_rate, &short_log.delta_des,
                       &short_log.torque}) {
    if (column->size() > rows) column->resize(rows);
  }
  EXPECT_FALSE(startsWithTransient(LogSignals(short_log), *offset.config));
}

TEST(StartOfALog, ItsSliversLieOnBothSidesFromTheLead) {
  const DiagnosisOptions options;
  const RunData offset = runOf(independentCase("none-start-2m-straight-500Hz"));
  const RunData sinusoid = runOf(independentCase("none-start-pair-sinusoid-straight"));
  const double t0 = offset.log->start();
  // One run: the first 2 s alternate in 0.25 s slivers from the lead (0.1 s), training first; then the
  // balanced blocks.
  const DataSplit one = splitData({offset}, {}, options);
  ASSERT_EQ(one.train.size(), 1u);
  ASSERT_EQ(one.held.size(), 1u);
  EXPECT_NEAR(one.train[0].segments.front().t0, t0 + kStartTransientLead, 1e-12);
  EXPECT_NEAR(one.train[0].segments.front().t1, t0 + kStartSliver, 1e-12);
  EXPECT_NEAR(timeWithin(one.held, t0, t0 + 0.5), 0.25, 1e-9);  // the margin of 0.6 s left none of it
  EXPECT_NEAR(timeWithin(one.held, t0, t0 + kStartTransientWindow), 0.5 * kStartTransientWindow, 1e-9);
  EXPECT_NE(one.held_blocks.front().find("a start transient, in slivers of 0.25 s"), std::string::npos)
      << one.held_blocks.front();
  // Runs: the one that starts with a transient from the lead, the other after the margin.
  const DataSplit pair = splitData({sinusoid}, {offset}, options);
  EXPECT_NEAR(pair.held[0].segments.front().t0, t0 + kStartTransientLead, 1e-12);
  // "How far" asks for the whole run (margin 0): it gets it from the first sample, transient or not.
  EXPECT_NEAR(wholeLogs({offset}, 0.0)[0].segments.front().t0, t0, 1e-12);
  EXPECT_NEAR(pair.train[0].segments.front().t0, sinusoid.log->start() + options.start_margin, 1e-12);
  // A run without a transient is split as before: blocks from the margin, none shorter than the minimum.
  const DataSplit quiet = splitData({sinusoid}, {}, options);
  EXPECT_NEAR(quiet.train[0].segments.front().t0, sinusoid.log->start() + options.start_margin, 1e-12);
  for (const auto* sets : {&quiet.train, &quiet.held}) {
    for (const TimeSegment& s : sets->front().segments) EXPECT_GE(s.t1 - s.t0, options.min_block_length - 1e-9);
  }
}

TEST(StartOfALog, ATorqueLimitHitOnlyByTheInitialCorrectionIsNamedAndTheCorrectionAloneIsNot) {
  // The independent family's 100 Hz case: a 60 N m soft limit that only the correction of a 2.5 m offset
  // reaches (the nominal's torque is above it for half a second). Before the start was kept, the margin
  // and the first training block held all of it: "the training data carry a gap that the held-out data
  // do not confirm".
  DiagnosisOptions options;
  options.effects = {"torque_limit", "steering_friction", "road_friction"};
  options.closed_loop = false;
  for (const std::string id : {"torque_limit-start-minus2.5m-straight-100Hz", "none-start-minus2.5m-straight-100Hz"}) {
    const BenchmarkCase c = independentCase(id);
    const GapLog log = generateBenchmarkLog(c, SensorNoise{}, c.log_rate);
    const GapReport r = diagnoseGap(benchmarkCaseNominal(c), {log}, {}, options);
    std::printf("[ measured ] %s: %s, shrink %.3f (%s)\n", id.c_str(), r.verdict.effect.c_str(), r.verdict.shrink,
                r.verdict.reason.c_str());
    if (c.truth == "none") {
      EXPECT_EQ(r.verdict.effect, "unexplained") << r.verdict.reason;
    } else {
      EXPECT_EQ(r.verdict.effect, "torque_limit") << r.verdict.reason;
      EXPECT_GT(r.verdict.shrink, 0.8);
    }
  }
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
