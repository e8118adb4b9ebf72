#pragma once
/// Which fits' closed loops are checked against the logs (bounded_loop.h): those whose boundedness the
/// verdict reads, no others.
///
/// A check runs the fitted closed loop over each training log (0.3-0.5 s for a 60 s log at 100 Hz); with
/// every fit checked they were a third of the fits' CPU time (4.9 of 15.2 s on lk_bench_gap's 60 s log).
/// The verdict reads a fit's boundedness only where the fit changes the subsystem carrying the gap
/// (winner_selection.h), and there only
///  - for the fits that remove at least min_shrink of the held-out gap: the candidates for the verdict,
///    for a bounded refit (bounded_refit.h) and for a look-alike (verdict.h). Those are checked as they
///    are fitted (checkedAsFitted);
///  - for the first two bounded fits in order of held-out gap, `top` and the runner-up: the fits in that
///    order are checked one by one until two are known bounded (checkUntilTopTwoKnown).
/// So the verdict, its shrink and confidence, its look-alikes and every refit are those of checking every
/// fit (where no check throws: closed_loop_checks_test.cpp). The other fits rank as if bounded (nothing
/// contradicts them) and are reported as not checked.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {

/// What is known of a fit's closed loop.
enum class LoopCheck { kNotChecked, kBounded, kUnbounded };

/// Whether `fit`'s closed loop is checked as soon as it is fitted: it changes `where_subsystem` and
/// removes at least min_shrink of the held-out gap (within 1e-12, so that no fit the verdict or the
/// refits' bar could read is left out by rounding).
bool checkedAsFitted(const CandidateFit& fit, const std::string& where_subsystem, double min_shrink);

/// Visits the fits that change the "where" subsystem (`changes_where`) in ascending `heldout_after`
/// (index order among equals), and checks (`check(i)`: whether fit i's loop stays bounded) each one not
/// yet checked, until two are known bounded or none is left. `state` holds what is known before and
/// after. Returns the fits checked, in the order checked.
std::vector<std::size_t> checkUntilTopTwoKnown(const std::vector<double>& heldout_after,
                                               const std::vector<bool>& changes_where, std::vector<LoopCheck>* state,
                                               const std::function<bool(std::size_t)>& check);

/// The checks the verdict still reads once every fit and refit is done: checkUntilTopTwoKnown over the
/// fits, a failed fit counting as bounded at `gap_before`, as rankFits ranks it. `check` runs one fit's
/// check and records it in the fit (checkClosedLoop); one that throws fails its fit, as it would have
/// within fitCandidate, and the fits are visited again in the new order. Returns the indices of the fits
/// checked, in the order checked.
std::vector<std::size_t> checkWhatTheVerdictReads(std::vector<CandidateFit>* fits, const std::string& where_subsystem,
                                                  double gap_before, const std::function<void(CandidateFit*)>& check);

/// The same with the diagnosis's checks (checkClosedLoop), run one after the other (the result does not
/// depend on the threads). A fit found unbounded here removes less than min_shrink of the gap, so it
/// could not have become the verdict: its note says so, as refitWhereTheyCouldWin's does. Nothing when
/// context.closed_loop_checks is false. The subsystem is context.where_subsystem. Returns the labels of
/// the fits checked.
std::vector<std::string> checkWhatTheVerdictReads(const FitContext& context, const DiagnosisOptions& options,
                                                  std::vector<CandidateFit>* fits);

/// Runs `fit`'s closed-loop check (stabilityRequirements) and records it in the fit.
void checkClosedLoop(const CandidateObjective& objective, const FitContext& context, CandidateFit* fit);

}  // namespace diagnosis
}  // namespace lane_keeping
