#pragma once
/// Bounded refits (diagnosis.h, step 3): a least-squares fit whose closed loop leaves the logged bounds
/// (bounded_loop.h) is fitted again with those bounds as a constraint, where that could change the
/// verdict.
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/bounded_loop.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {

/// Fits again from theta with the closed loop required to stay bounded on `requirements` (see
/// stabilityRequirements); *bounded_fit says whether the result does. The line searches' grids are
/// evaluated on `threads` threads (the result does not depend on it).
std::vector<double> holdStable(CandidateObjective& objective, std::vector<double> theta,
                               const std::vector<BoundedLoopRequirement>& requirements,
                               std::string* note, bool* bounded_fit, int threads = 1);

/// Fits `fit` again from its least-squares parameters with its closed loop required to stay bounded
/// on the logs in fit->unbounded_on, and scores it again (holdStable's grids on `threads` threads).
void refitBounded(const FitContext& context, const DiagnosisOptions& options, CandidateFit* fit, int threads = 1);

/// The held-out gap a refit must beat to become the verdict: the least of the bounded, unpinned fits
/// with enough evidence that change `where_subsystem`, and at most (1 - min_shrink) of gap_before.
double refitBar(const std::vector<CandidateFit>& fits, double gap_before, const std::string& where_subsystem,
                const DiagnosisOptions& options);

/// Appends to `fit`'s stability note why it is not fitted again under the logged bounds (its held-out
/// gap does not beat `bar`).
void noteNotRefitted(double bar, CandidateFit* fit);

/// Bounded refits where they could change the verdict. A least-squares fit whose closed loop leaves the
/// logged bounds is contradicted by the logs; fitting it again under those bounds costs a closed-loop run
/// per point visited (40-60 s on a 60 s log). It is worth that only if the refit could become the
/// verdict: the refit fits the training data no better than the unconstrained fit, so a candidate whose
/// unconstrained held-out gap already loses to the best qualifying bounded candidate (is larger: at a tie,
/// both nets at 0, the evidence decides) (or misses the
/// min_shrink needed), or that does not change the subsystem carrying the gap (`where_subsystem`), or a
/// gap the detection test does not confirm (`detected` false), keeps its unconstrained fit marked unbounded (a note says why),
/// and cannot be the verdict. Returns the wall time of each refit, named for the report.
std::vector<std::pair<std::string, double>> refitWhereTheyCouldWin(const FitContext& context, double gap_before,
                                                                   bool detected, const std::string& where_subsystem,
                                                                   const DiagnosisOptions& options,
                                                                   std::vector<CandidateFit>* fits);

}  // namespace diagnosis
}  // namespace lane_keeping
