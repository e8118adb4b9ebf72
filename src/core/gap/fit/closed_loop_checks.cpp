#include "lane_keeping/gap/fit/closed_loop_checks.h"

#include <algorithm>
#include <exception>

#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/bounded_refit.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {

bool checkedAsFitted(const CandidateFit& fit, const std::string& where_subsystem, double min_shrink) {
  if (!fit.ok || !fit.effect->changes(where_subsystem)) return false;
  // The shrink as rankFits computes it (fit.heldout_before is its gap_before: the same scores' gap).
  const double shrink = fit.heldout_before > 0.0 ? 1.0 - fit.heldout_after / fit.heldout_before : 0.0;
  return shrink >= min_shrink - 1e-12;
}

std::vector<std::size_t> checkUntilTopTwoKnown(const std::vector<double>& heldout_after,
                                               const std::vector<bool>& changes_where, std::vector<LoopCheck>* state,
                                               const std::function<bool(std::size_t)>& check) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < heldout_after.size(); ++i) {
    if (changes_where[i]) order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return heldout_after[a] < heldout_after[b]; });
  std::vector<std::size_t> checked;
  int bounded = 0;
  for (std::size_t i : order) {
    if (bounded == 2) break;
    LoopCheck& s = (*state)[i];
    if (s == LoopCheck::kNotChecked) {
      s = check(i) ? LoopCheck::kBounded : LoopCheck::kUnbounded;
      checked.push_back(i);
    }
    if (s == LoopCheck::kBounded) ++bounded;
  }
  return checked;
}

void checkClosedLoop(const CandidateObjective& objective, const FitContext& context, CandidateFit* fit) {
  fit->unbounded_on =
      stabilityRequirements(objective, fit->theta, *context.train, &fit->stability_note, context.nominal_bounds);
  fit->loop_checked = true;
}

std::vector<std::size_t> checkWhatTheVerdictReads(std::vector<CandidateFit>* fits_out, const std::string& where_subsystem,
                                                  double gap_before, const std::function<void(CandidateFit*)>& check) {
  std::vector<CandidateFit>& fits = *fits_out;
  std::vector<std::size_t> checked;
  // A check that throws fails its fit, which then ranks at the gap before: the visit stops there and
  // starts again in the new order (each fit fails at most once).
  struct Reorder {};
  for (bool again = true; again;) {
    again = false;
    std::vector<double> heldout_after(fits.size());
    std::vector<bool> changes_where(fits.size());
    std::vector<LoopCheck> state(fits.size());
    for (std::size_t i = 0; i < fits.size(); ++i) {
      const CandidateFit& fit = fits[i];
      // As rankFits ranks them: a failed fit at the gap before, bounded.
      heldout_after[i] = fit.ok ? fit.heldout_after : gap_before;
      changes_where[i] = fit.effect->changes(where_subsystem);
      state[i] = !fit.ok || (fit.loop_checked && fit.unbounded_on.empty()) ? LoopCheck::kBounded
                 : fit.loop_checked                                      ? LoopCheck::kUnbounded
                                                                         : LoopCheck::kNotChecked;
    }
    auto checkOne = [&](std::size_t i) {
      CandidateFit& fit = fits[i];
      checked.push_back(i);
      try {
        check(&fit);
      } catch (const std::exception& e) {
        fit.ok = false;
        fit.note = std::string("fit failed: ") + e.what();
        throw Reorder{};
      }
      return fit.unbounded_on.empty();
    };
    try {
      checkUntilTopTwoKnown(heldout_after, changes_where, &state, checkOne);
    } catch (const Reorder&) {
      again = true;
    }
  }
  return checked;
}

std::vector<std::string> checkWhatTheVerdictReads(const FitContext& context, const DiagnosisOptions& options,
                                                  std::vector<CandidateFit>* fits) {
  const std::string& where_subsystem = context.where_subsystem;
  std::vector<std::string> checked;
  if (!context.closed_loop_checks) return checked;
  const double gap_before = gapOf(context.nominal_held->scores, {});
  const double bar = refitBar(*fits, gap_before, where_subsystem, options);
  auto check = [&](CandidateFit* fit) {
    if (options.progress) options.progress("checking the closed loop of " + fit->effect->label());
    const CandidateObjective objective(*fit->effect, *context.nominal, *context.train, options.replay,
                                       context.nominal_train->sigma1, context.available);
    checkClosedLoop(objective, context, fit);
    if (!fit->unbounded_on.empty()) noteNotRefitted(bar, fit);
  };
  for (std::size_t i : checkWhatTheVerdictReads(fits, where_subsystem, gap_before, check)) {
    checked.push_back((*fits)[i].effect->label());
  }
  return checked;
}

}  // namespace diagnosis
}  // namespace lane_keeping
