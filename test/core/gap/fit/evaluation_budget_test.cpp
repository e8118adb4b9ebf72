// Evaluation budgets (evaluation_budget.h): the most replays and closed-loop runs each search of a fit may
// make, counted from the searches' constants. A search must stay within its budget on a short log and on a
// long one (else the count is wrong, and a fit would be cut short where it should not); a budget not
// reached must change nothing; a search that reaches it must stop there, keep its best point, and leave
// nothing false remembered.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "benchmark_objective_fixture.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/fit/bounded_refit.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/fit/evaluation_budget.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(EvaluationBudget, EachSearchOfAFitStaysWithinItsBudgetOnAShortAndALongLog) {
  // The fit's phases run one by one, unheld, counting their replays: the coordinate search and first
  // polish on the coarse data, the step on all of it (a profile effect: the search on all of it). Then
  // leastSquaresFit, which holds each phase to its budget, must return the same point bit for bit with no
  // note. The heaviest searches: the column (three parameters), friction (two), the torque limit (a
  // profile). The budget depends on the parameters alone; the log's length only sets what each replay
  // costs.
  const ReplayOptions replay;
  for (double duration : {8.0, 20.0}) {
    const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", duration, 100.0, 0.6);
    for (const auto& [name, form] : std::vector<std::pair<std::string, std::string>>{
             {"steering_compliance", "wheel_sensor"}, {"steering_friction", ""}, {"torque_limit", ""}}) {
      SCOPED_TRACE(name + " on " + std::to_string(duration) + " s");
      const CandidateEffect& effect = candidateNamed(name, form);
      const std::size_t p = effect.params.size();
      std::vector<double> unheld;
      {
        CandidateObjective objective = f.objective(effect, replay);
        if (effect.profile) {
          unheld = coordinateFit(objective);
          EXPECT_LE(objective.evaluations(), fitSearchBudget(p, true).replays);
        } else {
          const std::vector<Dataset> coarse = coarseFitData(f.data, replay.chassis_horizon, 3);
          ASSERT_LT(pieceCount(coarse, replay.chassis_horizon), pieceCount(f.data, replay.chassis_horizon));
          const CandidateObjective coarse_objective = objective.on(coarse);
          const std::vector<double> searched =
              polish(coarse_objective, coordinateFit(coarse_objective), search::kSearchPolishSteps);
          EXPECT_LE(coarse_objective.evaluations(), fitSearchBudget(p, false).replays);
          unheld = polish(objective, searched, search::kFinalPolishSteps);
          EXPECT_LE(objective.evaluations(), fitFinalStepBudget(p).replays);
          EXPECT_GT(objective.evaluations(), p) << "the step on all the data replayed nothing: nothing counted";
        }
      }
      CandidateObjective objective = f.objective(effect, replay);
      std::string note;
      EXPECT_EQ(leastSquaresFit(objective, 3, &note), unheld);
      EXPECT_EQ(note, "");
    }
  }
}

TEST(EvaluationBudget, ASearchThatSpendsItsBudgetKeepsItsBestPointAndRemembersNothingFalse) {
  const BenchmarkObjectiveFixture f("steering_friction-large-lane_change", 10.0, 100.0, 0.6);
  const CandidateEffect& friction = candidateNamed("steering_friction");
  CandidateObjective objective = f.objective(friction);
  const std::vector<double> start{friction.params[0].initial, friction.params[1].initial};
  EvaluationBudget budget;
  budget.replays = 9;  // the start and 8 of the first line's 13 grid points
  objective.limit(budget);
  const std::vector<double> held = coordinateFit(objective, start);
  EXPECT_TRUE(objective.budgetSpent());
  EXPECT_EQ(objective.evaluations(), budget.replays) << "the search replayed past its budget";
  // A point not evaluated before the budget ran out: no replay, an infinite loss.
  const std::vector<double> unseen{3.7, 0.37};
  EXPECT_EQ(objective.loss(unseen), kInf);
  EXPECT_EQ(objective.evaluations(), budget.replays);

  objective.limit({});
  EXPECT_FALSE(objective.budgetSpent());
  CandidateObjective fresh = f.objective(friction);
  // Its true loss once the budget is lifted (the stand-in was not remembered) ...
  EXPECT_EQ(objective.loss(unseen), fresh.loss(unseen));
  // ... and the point kept is the best of those the search could evaluate: the start or a grid point.
  const double kept = fresh.loss(held);
  EXPECT_LE(kept, fresh.loss(start));
  const EffectParameter& coulomb = friction.params[0];
  for (int i = 0; i < static_cast<int>(budget.replays) - 1; ++i) {
    const double u = std::log(coulomb.lower) + (std::log(coulomb.upper) - std::log(coulomb.lower)) * i /
                                                   (search::kFirstRoundGrid - 1);
    EXPECT_LE(kept, fresh.loss({std::exp(u), start[1]})) << "grid point " << i;
  }
  EXPECT_LT(kept, fresh.loss(start)) << "no grid point beat the start: the kept point was not compared";
}

TEST(EvaluationBudget, ABoundedRefitWithinItsBudgetIsUnchangedAndOneHeldToAFewClosedLoopsStops) {
  // The column fitted with too little damping: its closed loop leaves the logged bounds over the log, and
  // holdStable fits it again under them, as refitBounded does (its budget from refitSearchBudget).
  const ColumnLaneChangeFixture f(0.0);  // bounds over the whole log
  const std::vector<BoundedLoopRequirement> required{f.required};
  const std::vector<double> start{4000.0, 0.5, f.column.params[2].initial};
  {
    CandidateObjective check = f.objective(f.column);
    ASSERT_TRUE(check.bounds(start, required[0]).diverged) << "the start's loop stays bounded: nothing to refit";
  }
  struct Refit {
    std::vector<double> theta;
    bool bounded = false, spent = false;
    std::size_t closed_loops = 0;
    std::string note;
  };
  auto refit = [&](const EvaluationBudget& budget) {
    CandidateObjective objective = f.objective(f.column);
    objective.limit(budget);
    Refit r;
    r.theta = holdStable(objective, start, required, &r.note, &r.bounded, 2);
    r.spent = objective.budgetSpent();
    r.closed_loops = objective.closedLoopRuns();
    return r;
  };
  const Refit unheld = refit({});
  const EvaluationBudget derived = refitSearchBudget(start.size(), required.size(), 2);
  const Refit held = refit(derived);
  ASSERT_TRUE(unheld.bounded) << unheld.note;
  EXPECT_FALSE(held.spent);
  EXPECT_EQ(held.theta, unheld.theta);
  EXPECT_EQ(held.bounded, unheld.bounded);
  EXPECT_LE(unheld.closed_loops, derived.closed_loops);
  EXPECT_GT(unheld.closed_loops, 5u) << "the refit ran almost no closed loops: the small budget below tests nothing";

  EvaluationBudget few = derived;
  few.closed_loops = 5;
  const Refit stopped = refit(few);
  EXPECT_TRUE(stopped.spent);
  EXPECT_LE(stopped.closed_loops, few.closed_loops);
  EXPECT_FALSE(stopped.bounded) << "a refit that could not check its result called it bounded";
}

TEST(HoldStable, OnTwoThreadsIsTheRefitOnOne) {
  // On two threads the refit runs closed loops ahead (beside a grid's point, beside Brent's minimum and
  // each bisection step, and the first narrowed line's first points beside the whole-log check): the
  // objective remembers them, so the refit must end where one thread's does, bit for bit. The column
  // fitted with too little damping, its closed loop required to stay bounded over the whole 8 s log (the
  // short-horizon search's result passes the whole-log check here, so what ran beside the check is not
  // used; LineSearch.UnderAStabilityRequirementPointsCheckedAhead... covers a line that uses it).
  const ColumnLaneChangeFixture f(0.0);  // bounds over the whole log
  const std::vector<BoundedLoopRequirement> required{f.required};
  const std::vector<double> start{4000.0, 0.5, f.column.params[2].initial};
  std::vector<std::vector<double>> found;
  std::vector<std::size_t> loops;
  for (int threads : {1, 2}) {
    CandidateObjective objective = f.objective(f.column);
    std::string note;
    bool bounded = false;
    found.push_back(holdStable(objective, start, required, &note, &bounded, threads));
    EXPECT_TRUE(bounded) << note;
    loops.push_back(objective.closedLoopRuns());
  }
  EXPECT_EQ(found[0], found[1]);
  EXPECT_NE(found[0], start) << "the refit did not move: nothing compared";
  EXPECT_GT(loops[1], loops[0]) << "two threads ran nothing ahead: the comparison tests nothing";
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
