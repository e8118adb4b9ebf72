// A fit coarse to fine (candidate_fit.h): the search on a third of the data and a polish on all of it
// must reach the optimum a search over all the data reaches; else the speed is bought with verdicts.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/candidate_fit.h"
#include "lane_keeping/gap/diagnosis_data.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

const CandidateEffect& effectNamed(const std::string& name) {
  for (const auto& e : candidateEffects()) {
    if (e.name == name) return e;
  }
  throw std::runtime_error("no candidate " + name);
}

TEST(LeastSquaresFit, CoarseToFineReachesTheOptimumOfAllTheData) {
  // A 20 s lane change with LuGre friction in the column (the benchmark's case), at 100 Hz; the
  // candidate's Coulomb + viscous friction fits it without a true value, so the reference is the fit
  // whose search saw all the data.
  BenchmarkCase c = benchmarkCase("steering_friction-large-lane_change");
  c.truth_overlay.push_back("simulation.duration=20");
  GapRun run;
  run.log = generateBenchmarkLog(c, SensorNoise{}, 100.0);
  run.config = benchmarkNominal(c.manoeuvre);
  run.config.simulation.duration = 20.0;
  const std::vector<RunData> runs = prepareRuns({run});
  const std::vector<Dataset> data = wholeLogs(runs, 0.6);
  const std::set<std::string> available = availableSubsystems(runs);
  const Evaluation nominal = evaluate(nullptr, data, available, ReplayOptions{});
  const CandidateEffect& friction = effectNamed("steering_friction");
  CandidateObjective objective(friction, run.config, data, ReplayOptions{}, nominal.sigma1, available);

  const std::vector<double> full = leastSquaresFit(objective, 1);
  const std::vector<double> coarse = leastSquaresFit(objective, 3);
  const double initial = objective.loss({friction.params[0].initial, friction.params[1].initial});
  const double full_loss = objective.loss(full), coarse_loss = objective.loss(coarse);
  ASSERT_LT(full_loss, 0.5 * initial) << "the reference fit found nothing to fit";
  EXPECT_LE(coarse_loss, full_loss * 1.01) << "coarse to fine stopped short of the optimum of all the data";
  // The Coulomb level is what the data pin down (the viscous term is small at these rates).
  EXPECT_NEAR(std::log(coarse[0] / full[0]), 0.0, 0.05) << coarse[0] << " N m against " << full[0];
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
