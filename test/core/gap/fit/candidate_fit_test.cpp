// The fit machinery (candidate_fit.h). A line search must find the minimum of its line that a brute-force
// scan finds; a fit coarse to fine (the search on a third of the data and a polish on all of it) must
// reach the optimum a search over all the data reaches; else the speed is bought with verdicts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "benchmark_objective_fixture.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// The column's damping line searched from `start` under `required` (as the bounded refit does), on one
/// and on two threads, each on a fresh objective (nothing remembered between): the points and losses found.
std::pair<std::vector<std::vector<double>>, std::vector<double>> dampingSearchesOnOneAndTwoThreads(
    const BenchmarkObjectiveFixture& f, const BoundedLoopRequirement& required, const std::vector<double>& start) {
  const CandidateEffect& column = candidateNamed("steering_compliance");
  const EffectParameter& damping = column.params[1];
  std::vector<std::vector<double>> found;
  std::vector<double> losses;
  for (int threads : {1, 2}) {
    CandidateObjective objective = f.objective(column);
    objective.requireStability({required});
    std::vector<double> theta = start;
    losses.push_back(lineSearch(objective, theta, 1, damping.lower, damping.upper, 13, objective.loss(theta), threads));
    found.push_back(theta);
  }
  return {found, losses};
}

TEST(LineSearch, FindsTheMinimumABruteForceScanOfTheLineFinds) {
  // The Coulomb level of the benchmark's friction case on a 10 s log: a loss with a clear minimum
  // inside the bounds, log-scaled. The grid (13 points) brackets it, Brent's method refines it.
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 10.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  CandidateObjective objective = f.objective(friction);
  const EffectParameter& p = friction.params[0];
  ASSERT_TRUE(p.log_scale);
  std::vector<double> theta{p.initial, friction.params[1].initial};
  const double start = objective.loss(theta);
  const double found = lineSearch(objective, theta, 0, p.lower, p.upper, 13, start);
  EXPECT_DOUBLE_EQ(found, objective.loss(theta)) << "the returned loss is not the loss at the returned point";

  double scanned = std::numeric_limits<double>::infinity(), at = 0.0;
  const int n = 241;  // 0.0125 decades apart over [lower, upper]
  for (int i = 0; i < n; ++i) {
    const double v = p.lower * std::pow(p.upper / p.lower, static_cast<double>(i) / (n - 1));
    const double l = objective.loss({v, friction.params[1].initial});
    if (l < scanned) scanned = l, at = v;
  }
  ASSERT_LT(scanned, 0.5 * start) << "the line has no minimum worth finding";
  // Between the scan's points the loss can dip below them: the search may beat the scan, by little.
  EXPECT_LE(found, scanned * 1.001) << "line search " << theta[0] << " N m, scan " << at << " N m";
  EXPECT_NEAR(std::log(theta[0] / at), 0.0, std::log(p.upper / p.lower) / (n - 1))
      << "line search " << theta[0] << " N m, scan " << at << " N m";
}

TEST(LineSearch, OnTwoThreadsIsTheSearchOnOne) {
  // The bounded refit evaluates its grids on the threads the other fits left idle: the points, and so
  // the result, must be those of one thread, bit for bit (two objectives: nothing remembered between).
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 10.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  std::vector<std::vector<double>> found;
  std::vector<double> losses;
  for (int threads : {1, 2}) {
    CandidateObjective objective = f.objective(friction);
    const EffectParameter& p = friction.params[0];
    std::vector<double> theta{p.initial, friction.params[1].initial};
    losses.push_back(lineSearch(objective, theta, 0, p.lower, p.upper, 13, objective.loss(theta), threads));
    found.push_back(theta);
  }
  EXPECT_EQ(found[0], found[1]);
  EXPECT_EQ(losses[0], losses[1]);
  EXPECT_NE(found[0][0], friction.params[0].initial) << "the search did not move: nothing compared";
}

TEST(LineSearch, UnderAStabilityRequirementNoGridPointBeatsIt) {
  // A column's damping searched with its closed loop required to stay bounded (as the bounded refit
  // does): the grid's closed loops run in order of replay loss until the first bounded point, taken as
  // the grid's best. No point of the grid may then have a lower loss than the search's result (each
  // point's loss on a fresh objective, closed loop and all), and one and two threads (checks one and
  // two at a time) must agree bit for bit. Low damping diverges, so both kinds of point are on the line.
  const ColumnLaneChangeFixture f(3.0);
  const EffectParameter& damping = f.column.params[1];
  const std::vector<double> start{4000, 0.5, f.column.params[2].initial};
  const auto [found, losses] = dampingSearchesOnOneAndTwoThreads(f, f.required, start);
  EXPECT_EQ(found[0], found[1]);
  EXPECT_EQ(losses[0], losses[1]);
  CandidateObjective fresh = f.objective(f.column);
  fresh.requireStability({f.required});
  int bounded = 0, diverging = 0;
  for (int i = 0; i < 13; ++i) {
    std::vector<double> point = start;
    const double ua = std::log(damping.lower), ub = std::log(damping.upper);
    point[1] = std::exp(ua + (ub - ua) * i / 12);  // lineSearch's grid
    const double loss = fresh.loss(point);
    (loss == fresh.replayLoss(point) ? bounded : diverging) += 1;
    EXPECT_GE(loss, losses[0]) << "grid point " << i << " (damping " << point[1] << ") beats the search";
  }
  EXPECT_GT(bounded, 0);
  EXPECT_GT(diverging, 0) << "no diverging point on the line: the ordering was not exercised";
}

TEST(LineSearch, UnderAStabilityRequirementFindsTheBoundedMinimumAScanFinds) {
  // The column's damping at 4,000 N m/rad, its closed loop required to stay bounded over the log's first
  // 3 s: the replay loss falls towards 0.75 N m s/rad, the loop diverges below ~6, so the bounded
  // minimum lies on that boundary, between two grid points (5.6: diverges; 10: bounded). The grid's
  // best bounded point is the far end, 100, by 1e-9 of the loss: a search confined to its bracket (as
  // this one was before the boundary pass) returned 100 and a loss 0.35 % above the scan's. The search
  // must find the bounded minimum a brute-force scan of the line's constrained loss finds, at most one
  // closed loop per grid point and 1 + 4 per boundary (Brent's replay minimum, the bisection).
  const ColumnLaneChangeFixture f(3.0);
  const EffectParameter& damping = f.column.params[1];
  const std::vector<double> start{4000, 2.0, f.column.params[2].initial};
  CandidateObjective objective = f.objective(f.column);
  objective.requireStability({f.required});
  std::vector<double> theta = start;
  const double found = lineSearch(objective, theta, 1, damping.lower, damping.upper, 13, objective.loss(theta));
  EXPECT_LE(objective.closedLoopRuns(), 13u + 2u * (1u + 4u));

  CandidateObjective fresh = f.objective(f.column);
  fresh.requireStability({f.required});
  EXPECT_EQ(fresh.loss(theta), fresh.replayLoss(theta)) << "the search's result leaves the bounds";
  EXPECT_EQ(fresh.loss(theta), found);
  const int n = 193;  // 1/16 of the grid's spacing apart
  double scanned = std::numeric_limits<double>::infinity(), unconstrained = scanned, at = 0.0;
  int diverging = 0;
  for (int i = 0; i < n; ++i) {
    std::vector<double> point = start;
    point[1] = damping.lower * std::pow(damping.upper / damping.lower, static_cast<double>(i) / (n - 1));
    const double l = fresh.loss(point), r = fresh.replayLoss(point);
    if (l != r) ++diverging;
    unconstrained = std::min(unconstrained, r);
    if (l < scanned) scanned = l, at = point[1];
  }
  ASSERT_GT(diverging, 0) << "the line has no diverging point";
  ASSERT_LT(unconstrained, 0.999 * scanned) << "the replay loss has its minimum in the bounded region: no boundary";
  EXPECT_LE(found, scanned * (1.0 + 1e-4)) << "search " << theta[1] << " N m s/rad, scan " << at;
}

TEST(LineSearch, UnderAStabilityRequirementTheClosedLoopsRunAheadChangeNothing) {
  // With a thread to spare, the constrained search runs the closed loops it may ask for next beside the
  // one it asks for now (the bisection's next midpoints if this one stays bounded, the neighbour of a
  // diverging grid point beside Brent's replay minimum). The objective remembers each point, so the
  // search must take one thread's path: the same point and loss, bit for bit, on the line above whose
  // bounded minimum lies on a boundary the search bisects.
  const ColumnLaneChangeFixture f(3.0);
  const EffectParameter& damping = f.column.params[1];
  const std::vector<double> start{4000, 2.0, f.column.params[2].initial};
  const auto [found, losses] = dampingSearchesOnOneAndTwoThreads(f, f.required, start);
  EXPECT_EQ(found[0], found[1]);
  EXPECT_EQ(losses[0], losses[1]);
  // The result lies between grid points (on the boundary the bisection found), not on the grid.
  const double u = std::log(found[0][1] / damping.lower) / std::log(damping.upper / damping.lower) * 12.0;
  EXPECT_GT(std::fabs(u - std::round(u)), 1e-6) << "the search stopped on a grid point: no bisection compared";
}

TEST(LineSearch, UnderAStabilityRequirementPointsCheckedAheadChangeNothingAndAreNotRunAgain) {
  // The bounded refit checks the first points of its first narrowed line ahead, in the line's own order
  // (constrainedScanOrder), beside its whole-log check. The line must then take the path of a line with
  // nothing run ahead (the same point and loss, bit for bit), must not run those points again, and must
  // not run a batch beside a remembered bounded point. The column's stiffness line at 5 N m s/rad: its
  // third point in replay-loss order is the first bounded one, so two threads checking two at a time with
  // nothing remembered would run the fourth beside it, and nothing later on this line needs the fourth.
  const ColumnLaneChangeFixture f(3.0);
  const EffectParameter& stiffness = f.column.params[0];
  const std::vector<double> start{8000, 5.0, f.column.params[2].initial};
  std::vector<double> plain = start;
  double plain_loss = 0.0;
  std::size_t plain_loops = 0;
  {
    CandidateObjective objective = f.objective(f.column);
    objective.requireStability({f.required});
    plain_loss = lineSearch(objective, plain, 0, stiffness.lower, stiffness.upper, 13, objective.loss(plain), 2);
    plain_loops = objective.closedLoopRuns();
  }
  CandidateObjective objective = f.objective(f.column);
  objective.requireStability({f.required});
  const double start_loss = objective.loss(start);
  const auto order = constrainedScanOrder(objective, start, 0, stiffness.lower, stiffness.upper, 13);
  ASSERT_EQ(order.size(), 13u);
  for (std::size_t k = 1; k < order.size(); ++k) {
    EXPECT_LE(objective.replayLoss(order[k - 1]), objective.replayLoss(order[k])) << "not ordered by replay loss";
  }
  std::size_t ahead = 0;  // checked ahead up to the first bounded point, as the refit does
  for (const auto& point : order) {
    ++ahead;
    if (!objective.bounds(point, f.required).diverged) break;
  }
  ASSERT_EQ(ahead, 3u) << "the line's first bounded point moved: the batch beside it is not exercised";
  const std::size_t before = objective.closedLoopRuns();
  std::vector<double> theta = start;
  const double loss = lineSearch(objective, theta, 0, stiffness.lower, stiffness.upper, 13, start_loss, 2);
  EXPECT_EQ(theta, plain);
  EXPECT_EQ(loss, plain_loss);
  EXPECT_FALSE(objective.remembersLoss(order[ahead])) << "a batch ran beside the remembered bounded point";
  EXPECT_LE(objective.closedLoopRuns() - before + ahead, plain_loops) << "points checked ahead were run again";
}

TEST(ScoreFit, OnTwoThreadsScoresAsOnOne) {
  // A bounded refit scores its result with the threads the other fits left idle: the training and
  // held-out replays and the uncertainty's p forward steps side by side. The scores and sigmas must be
  // those of one thread, bit for bit.
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 10.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  FitContext context;
  context.nominal = &f.config;
  context.train = &f.data;
  context.held = &f.data;
  context.nominal_train = &f.nominal;
  context.nominal_held = &f.nominal;
  context.available = f.available;
  const std::vector<double> theta{2.0, 0.5};
  std::vector<CandidateFit> fits(2);
  for (int threads : {1, 2}) {
    CandidateObjective objective = f.objective(friction);
    fits[threads - 1].effect = &friction;
    scoreFit(objective, theta, context, DiagnosisOptions{}, &fits[threads - 1], threads);
  }
  ASSERT_TRUE(fits[0].ok && fits[1].ok);
  ASSERT_EQ(fits[0].sigma.size(), 2u);
  for (double s : fits[0].sigma) EXPECT_TRUE(std::isfinite(s) && s > 0.0) << "no uncertainty: its replays not compared";
  EXPECT_EQ(fits[0].sigma, fits[1].sigma);
  EXPECT_EQ(fits[0].train_after, fits[1].train_after);
  EXPECT_EQ(fits[0].heldout_after, fits[1].heldout_after);
  EXPECT_EQ(fits[0].evidence, fits[1].evidence);
  EXPECT_LT(fits[0].train_after, fits[0].train_before) << "the point fits no better than the nominal: a weak check";
}

TEST(LeastSquaresFit, CoarseToFineReachesTheOptimumOfAllTheData) {
  // A 20 s lane change with LuGre friction in the column (the benchmark's case), at 100 Hz; the
  // candidate's Coulomb + viscous friction fits it without a true value, so the reference is the fit
  // whose search saw all the data.
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 20.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  CandidateObjective objective = f.objective(friction);

  const std::vector<double> full = leastSquaresFit(objective, 1);
  const std::vector<double> coarse = leastSquaresFit(objective, 3);
  const double initial = objective.loss({friction.params[0].initial, friction.params[1].initial});
  const double full_loss = objective.loss(full), coarse_loss = objective.loss(coarse);
  ASSERT_LT(full_loss, 0.5 * initial) << "the reference fit found nothing to fit";
  EXPECT_LE(coarse_loss, full_loss * 1.01) << "coarse to fine stopped short of the optimum of all the data";
  // The Coulomb level is what the data pin down (the viscous term is small at these rates).
  EXPECT_NEAR(std::log(coarse[0] / full[0]), 0.0, 0.05) << coarse[0] << " N m against " << full[0];
}

TEST(Polish, AStepCostsItsReplaysNotALineSearchOfJacobians) {
  // The motor-side column on the benchmark's sensing-delay case at 1 kHz, polished again from a polished
  // point: Levenberg-Marquardt's step there does not lower the loss enough. Under bounds Ceres searches
  // along the projected step (Armijo); with its default cubic interpolation every trial point cost the
  // forward-difference Jacobian too (p + 1 replays of all the data), the trials shrinking towards the
  // start: 45 replays for one step.
  const BenchmarkObjectiveFixture f("sensing_delay-large-sinusoid", 20.0, 1000.0, 0.6);
  const CandidateEffect& column = candidateNamed("steering_compliance", "motor_sensor");
  CandidateObjective objective = f.objective(column);
  const std::vector<double> polished = polish(objective, coordinateFit(objective), 4);
  const std::size_t before = objective.evaluations();
  const std::vector<double> again = polish(objective, polished, 1);
  // Its start and Jacobian (p + 1), a step and the Jacobian there (p + 1), at most 6 line-search trials.
  const std::size_t p = column.params.size();
  EXPECT_LE(objective.evaluations() - before, 2 * (p + 1) + 6);
  EXPECT_LE(objective.loss(again), objective.loss(polished)) << "a polish returned a worse point than its start";
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
