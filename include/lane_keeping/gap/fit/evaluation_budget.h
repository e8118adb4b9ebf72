#pragma once
/// How much a fit may evaluate (issue 18: no stage of a diagnosis unbounded). Every search of the
/// diagnosis is a fixed number of line searches and Levenberg-Marquardt steps, each a bounded number of
/// evaluations, and an evaluation replays the objective's data or runs its closed loop over (at most)
/// the log: a fit's time is its number of evaluations times one pass over its data. The budgets below
/// are the most evaluations the searches can make, counted from the constants the searches themselves
/// use (candidate_fit.cpp, bounded_refit.cpp), the same for a 10 s log as for a 10-minute drive: each
/// fit's work is bounded and proportional to its data.
///
/// CandidateObjective::limit holds a search to its budget: a new point past it costs nothing and ranks
/// last (an infinite loss, a closed loop counted as leaving the bounds), so the search ends at the best
/// point it had, and the fit's note says the budget was spent. The searches as written never reach it
/// (docs/gap.md, "Evaluation budgets", gives the benchmark's largest use of each); it is there so that a
/// change to a search cannot make a stage run away again, as a bounded refit once did (218 s of a 238 s
/// diagnosis, issue 18).
#include <cstddef>
#include <limits>
#include <string>

namespace lane_keeping {
namespace diagnosis {

/// The searches' constants (one definition for the searches and their budgets).
namespace search {
/// Grid points of a coordinate search's line: the whole range in the first round, the narrowed range
/// (narrowedRange) in the second, and a bounded refit's narrowed lines.
constexpr int kFirstRoundGrid = 13;
constexpr int kSecondRoundGrid = 7;
/// Brent's most iterations in the bracket around a line's best grid point (Boost.Math: one evaluation
/// at its start, then one per iteration).
constexpr int kBrentIterations = 10;
/// Brent's relative tolerance on a line's axis, 2^(1 - bits) = 2^-10 ~ 1e-3.
constexpr int kLineSearchBits = 11;
/// Most bisection steps (closed-loop runs) a constrained line search spends locating a boundary of the
/// bounded region: 1/16 of a grid spacing, 2.3 % of a log-scale parameter on the narrowed second round's
/// grid (7 points over a factor of 9), which sets the fit's final precision. (Six steps cost the column's
/// refit on the benchmark's small logs ~20 more closed-loop runs, for the same shrinks.)
constexpr int kBoundaryBisections = 4;
/// Levenberg-Marquardt steps: the polish after the search (on its coarse data) and the step on all the
/// data after it.
constexpr int kSearchPolishSteps = 4;
constexpr int kFinalPolishSteps = 1;
/// The leader's other form (leader_forms.h), warm-started from the leader: at most this many steps on all
/// the data, ending where Ceres converges. It stands for the verdict and every further effect is fitted on
/// top of it, so what an unconverged step leaves is its own misfit, which the further candidates are then
/// fitted to imitate (lk_bench_gap's 1 kHz LuGre form: one step 0.03013 -> 0.006685 on the training data,
/// up to four 0.005824, within the draws of its own model, forward_selection.h).
constexpr int kLeaderFormPolishSteps = 4;
/// Most trial points of the line search along a projected Levenberg-Marquardt step (Ceres, under the
/// parameters' bounds).
constexpr int kPolishLineSearchTrials = 6;
}  // namespace search

/// A search's allowance on one objective: replays of its data (CandidateObjective::replayLoss and
/// residuals) and closed-loop runs (bounds checks). Unlimited by default.
struct EvaluationBudget {
  static constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();
  std::size_t replays = kUnlimited;
  std::size_t closed_loops = kUnlimited;
};

/// Most replays of a line search over `points` grid points without a stability requirement: the grid,
/// then Brent's iterations (its start is a grid point, remembered).
std::size_t lineSearchReplays(int points);

/// Most points a line search over `points` grid points evaluates under a stability requirement (each at
/// most one replay and one closed-loop run per required log): the grid; Brent's minimum of the replay
/// loss; a bisection of at most kBoundaryBisections steps for the bracket's boundary and for each of the
/// other boundaries between neighbouring grid points (at most points - 1 of them, so `points` bisections
/// in all); and, on `threads` threads, up to threads - 1 points run ahead beside each point asked for
/// next (each bisection step, Brent's minimum, each neighbour of a diverging grid point).
std::size_t constrainedLineSearchPoints(int points, int threads);

/// Most replays of a coordinate search (coordinateFit) of `params` parameters without a stability
/// requirement: its start, a line per parameter over its whole range, and a second round over narrowed
/// ranges when there are two or more.
std::size_t coordinateSearchReplays(std::size_t params);

/// Most replays of a Levenberg-Marquardt polish (polish) of `params` parameters and `steps` steps: its
/// start (twice where fit space does not give it back bit for bit) and forward-difference Jacobian, per
/// step the trial point, the line search's trials and the Jacobian at the point taken, and its result's
/// loss.
std::size_t polishReplays(std::size_t params, int steps);

/// The budget of a least-squares fit's search (leastSquaresFit) on the data it searches (the coarse data,
/// or all of it for a profile effect or coarse_stride 1): the coordinate search, then (not for a profile
/// effect) the polish of kSearchPolishSteps.
EvaluationBudget fitSearchBudget(std::size_t params, bool profile);

/// The budget of a coarse-to-fine fit's step on all the data: a polish of kFinalPolishSteps.
EvaluationBudget fitFinalStepBudget(std::size_t params);

/// The budget of a bounded refit's search (holdStable) with `requirements` logs required to stay bounded
/// and `threads` threads: its start; the first move (one line per parameter over its range) and a
/// coordinate search under the short-horizon requirements; the whole-log check (with two or more threads,
/// the first narrowed line's grid run ahead beside it); one narrowed line per
/// parameter under the whole-log requirements, each checked; and, if none of those lines gets the loop
/// bounded, the first move and coordinate search again under them. Each point runs at most one closed
/// loop per required log and horizon (two horizons per log).
EvaluationBudget refitSearchBudget(std::size_t params, std::size_t requirements, int threads);

/// "<search> stopped at its evaluation budget (...) and kept the best point it had found": the note of
/// a fit whose search spent its budget.
std::string budgetSpentNote(const std::string& search, const EvaluationBudget& budget);

}  // namespace diagnosis
}  // namespace lane_keeping
