#include "lane_keeping/gap/fit/evaluation_budget.h"

#include <algorithm>
#include <string>

namespace lane_keeping {
namespace diagnosis {

using namespace search;

// Brent starts at the end of its bracket, a grid point the objective remembers.
std::size_t lineSearchReplays(int points) { return static_cast<std::size_t>(points + kBrentIterations); }

std::size_t constrainedLineSearchPoints(int points, int threads) {
  const std::size_t p = static_cast<std::size_t>(points);
  const std::size_t ahead = static_cast<std::size_t>(std::max(1, threads) - 1);
  // With a bounded grid point: the grid, Brent's minimum, `points` bisections; the points run ahead
  // beside Brent's minimum, each bisection step and each of the (at most points - 1) neighbours checked.
  const std::size_t steps = p * kBoundaryBisections;
  const std::size_t bounded = p + 1 + steps + ahead * (1 + steps + (p - 1));
  // Without one: the grid, then Brent on the constrained loss.
  const std::size_t unbounded = p + kBrentIterations;
  return std::max(bounded, unbounded);
}

std::size_t coordinateSearchReplays(std::size_t params) {
  // Its start, then the lines.
  return 1 + params * lineSearchReplays(kFirstRoundGrid) +
         (params > 1 ? params * lineSearchReplays(kSecondRoundGrid) : 0);
}

std::size_t polishReplays(std::size_t params, int steps) {
  // Its start twice where fit space does not give it back bit for bit (exp(log(v)) != v), its Jacobian,
  // the steps, and its result's loss.
  return 2 + params + static_cast<std::size_t>(steps) * (1 + kPolishLineSearchTrials + params) + 1;
}

EvaluationBudget fitSearchBudget(std::size_t params, bool profile) {
  EvaluationBudget budget;
  budget.replays = coordinateSearchReplays(params) + (profile ? 0 : polishReplays(params, kSearchPolishSteps));
  budget.closed_loops = 0;  // a least-squares fit runs none
  return budget;
}

EvaluationBudget fitFinalStepBudget(std::size_t params) {
  EvaluationBudget budget;
  budget.replays = polishReplays(params, kFinalPolishSteps);
  budget.closed_loops = 0;
  return budget;
}

EvaluationBudget refitSearchBudget(std::size_t params, std::size_t requirements, int threads) {
  const std::size_t wide = constrainedLineSearchPoints(kFirstRoundGrid, threads);
  const std::size_t narrow = constrainedLineSearchPoints(kSecondRoundGrid, threads);
  const std::size_t second_round = params > 1 ? params : 0;
  // A search (holdStable's `search`): its start, the first move, the coordinate search.
  const std::size_t search_points = 1 + params * wide + params * wide + second_round * narrow;
  const std::size_t search_lines = params + params + second_round;
  // The whole-log check and the narrowed lines (their start and each line's check), and on two or more
  // threads the first narrowed line's grid run ahead beside the check.
  const std::size_t ahead = threads > 1 ? static_cast<std::size_t>(kSecondRoundGrid) : 0;
  const std::size_t narrowed_points = 1 + 1 + params * narrow + params + ahead;
  const std::size_t points = 2 * search_points + narrowed_points + 1;
  const std::size_t lines = 2 * search_lines + params;
  EvaluationBudget budget;
  budget.replays = points + lines * static_cast<std::size_t>(kBrentIterations);
  budget.closed_loops = points * requirements;
  return budget;
}

std::string budgetSpentNote(const std::string& search, const EvaluationBudget& budget) {
  std::string note = search + " stopped at its evaluation budget (" + std::to_string(budget.replays) + " replays";
  if (budget.closed_loops != EvaluationBudget::kUnlimited && budget.closed_loops > 0) {
    note += ", " + std::to_string(budget.closed_loops) + " closed-loop runs";
  }
  return note + ") and kept the best point it had found";
}

}  // namespace diagnosis
}  // namespace lane_keeping
