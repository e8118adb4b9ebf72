#pragma once
/// Fitting one candidate effect (diagnosis.h, step 3): a robust coordinate search (grid + Brent's
/// minimisation per parameter), polished by Levenberg-Marquardt (Ceres) for smooth parameters, then the
/// fit's parameters, uncertainty, bound flag and training / held-out scores.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/bounded_loop.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {

/// What every candidate is fitted and scored on.
struct FitContext {
  const SimConfig* nominal = nullptr;           ///< the shared nominal configuration
  const std::vector<Dataset>* train = nullptr;  ///< training data
  const std::vector<Dataset>* held = nullptr;   ///< held-out data
  const Evaluation* nominal_train = nullptr;    ///< the nominal's replays and scores on them
  const Evaluation* nominal_held = nullptr;
  std::set<std::string> available;              ///< the subsystems the logs can feed
  /// The logs carry what the whole loop needs (the tracker's inputs and output): a fit's closed loop can
  /// then be checked against them (bounded_loop.h).
  bool closed_loop_checks = true;
  /// The subsystem carrying the gap: a fit that changes it and removes at least min_shrink of the gap has
  /// its closed loop checked as it is fitted (closed_loop_checks.h); the others' checks wait until the
  /// verdict needs them.
  std::string where_subsystem;
  NominalBounds* nominal_bounds = nullptr;  ///< the nominal's closed loops, shared by the fits' checks
  /// Where a fit may start near its optimum (a further effect fitted on top of others, whose parameters
  /// alone are known: forward_selection.h), by CandidateEffect::label: warmStartFit instead of the search.
  const std::map<std::string, std::vector<double>>* warm_start = nullptr;
  /// A warm-started fit's Levenberg-Marquardt steps on all the data (warmStartFit).
  int warm_final_steps = search::kFinalPolishSteps;
};

struct CandidateFit {
  const CandidateEffect* effect = nullptr;
  bool ok = false;
  std::string note;
  /// Why its magnitude is beyond what the world makes ("": plausible; fit/plausible_magnitude.h).
  std::string implausible;
  std::vector<double> theta, sigma;
  bool at_bound = false;  ///< a fitted parameter is pinned at a bound of its range (pinnedAtBound)
  bool at_bound_everywhere = false;  ///< every fitted parameter is (pinnedParameterCount)
  std::string stability_note;  ///< set when the least-squares fit's closed loop leaves the logged bounds
  /// Logs on which the fit's closed loop leaves the bounds (empty: it stays bounded, also after a
  /// bounded refit that succeeded).
  std::vector<BoundedLoopRequirement> unbounded_on;
  bool loop_checked = false;  ///< the closed loop was checked (unbounded_on is known; closed_loop_checks.h)
  SimConfig corrected;  ///< the shared nominal configuration with the fitted effect (the report's overlay)
  ConfigChange change;  ///< the fitted effect, as a change of each run's own configuration
  double train_before = 0.0, train_after = 0.0;
  double heldout_before = 0.0, heldout_after = 0.0;
  double evidence = 0.0;  ///< held-out reduction of the noise-normalised squared residual (see evidenceOf)
  /// Other forms of the effect whose fit the data cannot tell from this one's (keepBestForms).
  std::vector<std::string> tied_forms;
  std::map<std::string, SubsystemScore> heldout_scores;
  /// The replays behind the scores (of the subsystems the effect changes): on top of them a further effect
  /// is fitted without replaying the data again (forward_selection.h).
  std::shared_ptr<const Evaluation> train_evaluation, heldout_evaluation;
};

/// Minimises the loss over parameter j with the others fixed: a grid over [lo, hi] (log-spaced for
/// log-scale parameters), then Brent's method (parabolic and golden-section steps, Boost.Math) in the
/// bracket around the best grid point, at most 10 evaluations. The grid's points are evaluated on
/// `threads` threads (the result does not depend on it). Under a stability requirement
/// (CandidateObjective::constrained) with a bounded grid point, Brent minimises the replay loss alone
/// and the closed loop runs at its result, then, if that point leaves the bounds, at each step of a
/// bisection towards it from the bounded side (at most 4); each other boundary between a bounded grid
/// point and a diverging one of lower replay loss is bisected too.
double lineSearch(const CandidateObjective& objective, std::vector<double>& theta, std::size_t j, double lo, double hi,
                  int points, double current_loss, int threads = 1);

/// The points of lineSearch's grid over [lo, hi] along parameter j from theta, in the order in which it
/// checks their closed loops under a stability requirement: by replay loss, ties to the lower index (the
/// replays run on `threads` threads and are remembered by the objective). The bounded refit runs the
/// first of them ahead beside its whole-log check (bounded_refit.h).
std::vector<std::vector<double>> constrainedScanOrder(const CandidateObjective& objective, const std::vector<double>& theta,
                                                      std::size_t j, double lo, double hi, int points, int threads = 1);

/// The range coordinateFit's second round searches around `value`: a third to three times it for a
/// log-scale parameter, else +-15 % of the parameter's range; within its bounds.
std::pair<double, double> narrowedRange(const EffectParameter& p, double value);

/// Robust low-dimensional fit: coordinate-wise grid + Brent over the whole bounds, then a
/// second round in a narrowed range. (Gauss-Newton alone crawls here: stick-slip friction and
/// saturations make the residuals far from linear in the parameters.) The grids' points are evaluated
/// on `threads` threads.
std::vector<double> coordinateFit(const CandidateObjective& objective, std::vector<double> theta = {}, int threads = 1);

/// Levenberg-Marquardt (Ceres, forward differences) from theta, at most `iterations` steps, within the
/// parameters' ranges (one at a bound of its range held there); theta itself when no step lowers the loss.
std::vector<double> polish(const CandidateObjective& objective, std::vector<double> theta, int iterations);

/// Unconstrained least-squares fit: coordinate search, polished with Levenberg-Marquardt (forward
/// differences; parameters the search left at a bound held there). Coarse to fine when `coarse_stride`
/// > 1 (the default, 3): the search and a first polish run on every coarse_stride-th piece of the data,
/// or every sqrt(n)-th of a log's n pieces where that is sparser (coarseFitData, pieces of the chassis
/// horizon), one further step on all of it; else the search and
/// the polish on all of it. A profile effect (no polish: its loss is not smooth) searches
/// all the data. Each search is held to its evaluation budget (evaluation_budget.h); one that spends it
/// keeps its best point, and `note` (if given) says so.
std::vector<double> leastSquaresFit(const CandidateObjective& objective, std::size_t coarse_stride = 1,
                                    std::string* note = nullptr);

/// The fit from `theta`, a point near the optimum: a profile effect's line search over the narrowed range
/// of each parameter (narrowedRange), a smooth one's Levenberg-Marquardt polish on the coarse data and one
/// step on all of it (`final_steps` steps). A third to a half of leastSquaresFit's work.
std::vector<double> warmStartFit(const CandidateObjective& objective, std::vector<double> theta, std::size_t coarse_stride,
                                 int final_steps = search::kFinalPolishSteps);

/// Whether a fit `theta` of `effect` (standard errors `sigma`, NaN where unknown) has a parameter pinned at a
/// bound of its range: one within 1 % of the range of a bound (on the log axis for a log-scale parameter)
/// that the data do not place off it — within 3 standard errors of the bound, or within 0.1 % of the range
/// (Gauss-Newton's sigma is a lower bound where residuals are correlated, and says nothing of a fit the
/// search stopped at the bound). A pinned fit was stretching to imitate something else; a fit clearly off
/// its bound was not, however wide the range: a 2.8 ms steering-angle latency +- 0.07 ms lies within 1 %
/// of its 0-0.3 s range, and is 41 standard errors from a latency of nil.
bool pinnedAtBound(const CandidateEffect& effect, const std::vector<double>& theta, const std::vector<double>& sigma);
/// How many of the fit's parameters are pinned so (pinnedAtBound is this > 0). Given the `nominal`
/// configuration, a parameter at the bound its nominal value lies at or beyond (EffectParameter::nominal)
/// is not counted while another parameter of the fit lies off its bounds: the fit keeps that part as the
/// nominal has it and places the effect by the others (the independent family's LuGre kingpin friction on top
/// of a steering offset: Coulomb 3.01 N m for 3, the viscous part at the range's 0.01 for none). Where no
/// parameter lies off its bounds it is counted: such a fit is the nominal's corner of the range, not an effect.
std::size_t pinnedParameterCount(const CandidateEffect& effect, const std::vector<double>& theta,
                                 const std::vector<double>& sigma, const SimConfig* nominal = nullptr);

/// Parameters, bound flag, uncertainty and training / held-out scores of a fit at theta (`objective`
/// over `context.train`, its replays the training scores). Its p + 2 replays run on `threads` threads (the
/// scores do not depend on it).
void scoreFit(const CandidateObjective& objective, const std::vector<double>& theta, const FitContext& context,
              const DiagnosisOptions& options, CandidateFit* out, int threads = 1);

/// The least-squares fit of one candidate, scored; if checkedAsFitted (closed_loop_checks.h),
/// `unbounded_on` lists the training logs whose closed loop it makes leave the logged bounds
/// (refitBounded fits it again under them).
CandidateFit fitCandidate(const CandidateEffect& effect, const FitContext& context, const DiagnosisOptions& options);

}  // namespace diagnosis
}  // namespace lane_keeping
