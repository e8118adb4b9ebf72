// Evaluations over data sets (gap/evaluation/evaluation.h): the evaluation of two data-set lists is the
// concatenation of theirs.
#include <gtest/gtest.h>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/log/gap_run.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

TEST(Evaluation, ConcatenatedIsTheEvaluationOfBothListsInOne) {
  // The diagnosis's "where" report takes the evaluation of training and held-out data from the two it
  // already has: each trace, break, start, sigma1 estimate and score must be the one evaluate() gives
  // the joined list (four runs of other manoeuvres and noise seeds, two data sets in each list).
  std::vector<GapRun> runs;
  for (unsigned seed : {11u, 12u, 13u, 14u}) {
    BenchmarkCase c;
    c.id = "concatenated";
    c.manoeuvre = seed % 2 ? "lane_change" : "sinusoid";
    c.seed = seed;
    c.truth_overlay = {"simulation.duration=8", "steering.coulomb_friction=3"};
    SimConfig nominal = benchmarkNominal(c.manoeuvre);
    nominal.simulation.duration = 8.0;
    runs.push_back(gapRun(generateBenchmarkLog(c, SensorNoise{}, 100.0), nominal));
  }
  DiagnosisOptions options;
  const DataSplit split = splitData(prepareRuns(runs), {}, options);
  std::vector<Dataset> both = split.train;
  both.insert(both.end(), split.held.begin(), split.held.end());
  ASSERT_GE(both.size(), 4u);
  const std::vector<Dataset> first(both.begin(), both.begin() + 2), second(both.begin() + 2, both.end());
  const auto all = allSubsystems();
  const Evaluation joined = evaluate(nullptr, both, all, options.replay);
  const Evaluation parts =
      concatenated(evaluate(nullptr, first, all, options.replay), evaluate(nullptr, second, all, options.replay));
  ASSERT_EQ(parts.replays.size(), joined.replays.size());
  for (const auto& [name, replay] : joined.replays) {
    const SubsystemReplay& other = parts.replays.at(name);
    EXPECT_EQ(other.diverged_intervals, replay.diverged_intervals) << name;
    EXPECT_EQ(other.sigma1_estimate, replay.sigma1_estimate) << name;
    ASSERT_EQ(other.traces.size(), replay.traces.size()) << name;
    for (std::size_t k = 0; k < replay.traces.size(); ++k) {
      EXPECT_EQ(other.traces[k].t, replay.traces[k].t) << name;
      EXPECT_EQ(other.traces[k].measured, replay.traces[k].measured) << name;
      EXPECT_EQ(other.traces[k].predicted, replay.traces[k].predicted) << name;
      EXPECT_EQ(other.traces[k].breaks, replay.traces[k].breaks) << name;
      EXPECT_EQ(other.traces[k].scale, replay.traces[k].scale) << name;
    }
    EXPECT_EQ(parts.starts.at(name), joined.starts.at(name)) << name;
    EXPECT_EQ(parts.scores.at(name).nrmse, joined.scores.at(name).nrmse) << name;
    EXPECT_EQ(parts.scores.at(name).excess, joined.scores.at(name).excess) << name;
    EXPECT_EQ(joined.starts.at(name).size(), both.size()) << name;
  }
  EXPECT_EQ(parts.sigma1, joined.sigma1);
  EXPECT_EQ(fitResiduals(parts), fitResiduals(joined));
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
