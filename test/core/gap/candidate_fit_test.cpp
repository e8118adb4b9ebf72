// A fit coarse to fine (candidate_fit.h): the search on a third of the data and a polish on all of it
// must reach the optimum a search over all the data reaches; else the speed is bought with verdicts.
#include <gtest/gtest.h>

#include <cmath>

#include "benchmark_objective_fixture.h"
#include "lane_keeping/gap/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

TEST(LeastSquaresFit, CoarseToFineReachesTheOptimumOfAllTheData) {
  // A 20 s lane change with LuGre friction in the column (the benchmark's case), at 100 Hz; the
  // candidate's Coulomb + viscous friction fits it without a true value, so the reference is the fit
  // whose search saw all the data.
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 20.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  CandidateObjective objective(friction, f.config, f.data, ReplayOptions{}, f.nominal.sigma1, f.available);

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
