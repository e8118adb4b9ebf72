// The identification excitation's clock (gap/replay/excitation_clock.h) found from the log, so that a log
// whose t is shifted by a constant is diagnosed as the same log: shifted by +0.5 s a no-effect log was a
// false alarm with a tracker gap, by 1000 s a friction log lost its verdict.
#include <gtest/gtest.h>

#include <cmath>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/excitation_clock.h"

namespace lane_keeping {
namespace {

/// A benchmark case's log (the benchmark's nominal has the tracker's multisine on), `duration` s at 200 Hz.
GapLog caseLog(const std::string& id, double duration) {
  BenchmarkCase c = benchmarkCase(id);
  c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
  return generateBenchmarkLog(c, SensorNoise{}, 200.0);
}

GapLog shifted(GapLog log, double by) {
  for (double& t : log.t) t += by;
  return log;
}

SimConfig nominalOf(const std::string& id, double duration) {
  SimConfig nominal = benchmarkNominal(benchmarkCase(id).manoeuvre);
  nominal.simulation.duration = duration;
  return nominal;
}

TEST(ExcitationClock, FoundFromTheLogWhateverItsClocksOrigin) {
  const std::string id = "steering_friction-large-lane_change";
  const GapLog log = caseLog(id, 12.0);
  const SimConfig nominal = nominalOf(id, 12.0);
  ASSERT_GT(nominal.tracker.excitation_amplitude, 0.0);
  const ExcitationClock own = estimateExcitationClock(nominal, LogSignals(log));
  EXPECT_EQ(own.offset, 0.0);
  EXPECT_GT(own.coherence_at_log_clock, 0.95);
  EXPECT_EQ(own.note, "");
  for (const double by : {0.5, 1000.0, -3.25, 1.7e9}) {
    SCOPED_TRACE(by);
    const ExcitationClock c = estimateExcitationClock(nominal, LogSignals(shifted(log, by)));
    EXPECT_LT(c.coherence_at_log_clock, 0.8);
    EXPECT_GT(c.coherence, 0.95);
    EXPECT_EQ(c.offset, -by);  // the time since the log's first sample: snapped to it exactly
    EXPECT_NE(c.note.find("its clock's origin is not the log's"), std::string::npos) << c.note;
  }
  // An offset that is no origin of the log (a logger started 2.3 s after the tracker) is found too.
  const ExcitationClock c = estimateExcitationClock(nominal, LogSignals(shifted(log, 102.3)));
  EXPECT_NEAR(c.offset, -102.3, 1e-4);
}

TEST(ExcitationClock, AWholeChannelLoggedLateIsLeftToTheDiagnosis) {
  // delta_des logged 30 ms late, the tracker's law with it: a latency, not a clock.
  const std::string id = "steering_friction-large-lane_change";
  GapLog log = caseLog(id, 12.0);
  const GapLog original = log;
  const std::size_t lag = 6;  // samples at 200 Hz
  for (std::size_t i = 0; i < log.size(); ++i) log.delta_des[i] = original.delta_des[i >= lag ? i - lag : 0];
  const ExcitationClock c = estimateExcitationClock(nominalOf(id, 12.0), LogSignals(log));
  EXPECT_EQ(c.offset, 0.0);
  EXPECT_NEAR(c.best_offset, -0.03, 2e-3);
  EXPECT_NE(c.note.find("delta_des looks logged 0.0299 s late"), std::string::npos) << c.note;
}

GapReport diagnose(const std::string& id, const GapLog& log, const std::vector<std::string>& effects) {
  DiagnosisOptions options;
  options.effects = effects;
  return diagnoseGap(nominalOf(id, 12.0), {log}, {}, options);
}

TEST(ExcitationClock, AShiftedLogGetsTheSameVerdictAndShrink) {
  const std::vector<std::string> effects{"steering_friction", "sensing_delay"};
  {
    const std::string id = "none-1-lane_change";
    const GapLog log = caseLog(id, 12.0);
    const GapReport a = diagnose(id, log, effects), b = diagnose(id, shifted(log, 0.5), effects);
    EXPECT_EQ(a.verdict.effect, "unexplained");
    EXPECT_EQ(b.verdict.effect, a.verdict.effect) << b.verdict.reason;
    EXPECT_EQ(b.detection.heldout.detected, a.detection.heldout.detected);  // no false alarm
    EXPECT_EQ(b.where.subsystem, a.where.subsystem);
  }
  {
    const std::string id = "steering_friction-large-lane_change";
    const GapLog log = caseLog(id, 12.0);
    const GapReport a = diagnose(id, log, effects), b = diagnose(id, shifted(log, 1000.0), effects);
    EXPECT_EQ(a.verdict.effect, "steering_friction") << a.verdict.reason;
    EXPECT_EQ(b.verdict.effect, a.verdict.effect) << b.verdict.reason;
    EXPECT_NEAR(b.verdict.shrink, a.verdict.shrink, 0.02);
    // Within 5 %: t + 1000 rounds differently, so a held-out block's edge on the 0.1 s grid takes or leaves
    // a sample (the steering replay, which the excitation does not reach, moves by 2.3 %: 0.1511 -> 0.1476).
    EXPECT_NEAR(b.verdict.gap_before, a.verdict.gap_before, 0.05 * a.verdict.gap_before);
  }
}

}  // namespace
}  // namespace lane_keeping
