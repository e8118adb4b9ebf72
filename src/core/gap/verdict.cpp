#include "lane_keeping/gap/verdict.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/candidate_effects.h"
#include "lane_keeping/gap/winner_selection.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

std::vector<RankedEffect> rankFits(const std::vector<CandidateFit>& fits, const SimConfig& nominal, double gap_before,
                                   std::vector<std::string>* notes) {
  std::vector<RankedEffect> ranking;
  for (const auto& fit : fits) {
    RankedEffect r;
    r.effect = fit.effect->name;
    r.heldout_gap_before = gap_before;
    if (!fit.ok) {
      r.heldout_gap_after = gap_before;
      r.shrink = 0.0;
      notes->push_back(fit.effect->name + ": " + fit.note);
    } else {
      for (std::size_t i = 0; i < fit.theta.size(); ++i) {
        r.params[fit.effect->params[i].name] = fit.theta[i];
        r.param_sigma[fit.effect->params[i].name] = i < fit.sigma.size() ? fit.sigma[i] : kNaN;
      }
      r.config = configDifference(nominal, fit.corrected);
      r.train_gap_before = fit.train_before;
      r.train_gap_after = fit.train_after;
      r.heldout_gap_after = fit.heldout_after;
      r.shrink = gap_before > 0.0 ? 1.0 - fit.heldout_after / gap_before : 0.0;
    }
    r.score = fit.ok ? fit.evidence : 0.0;
    r.closed_loop_bounded = !fit.ok || fit.unbounded_on.empty();
    if (fit.ok && fit.at_bound) notes->push_back(fit.effect->name + ": a fitted parameter is pinned at a bound of its range");
    if (fit.ok && !fit.stability_note.empty()) notes->push_back(fit.effect->name + ": " + fit.stability_note);
    ranking.push_back(r);
  }
  std::sort(ranking.begin(), ranking.end(), [](const RankedEffect& a, const RankedEffect& b) {
    if (a.closed_loop_bounded != b.closed_loop_bounded) return a.closed_loop_bounded;
    return a.heldout_gap_after < b.heldout_gap_after;
  });
  return ranking;
}

std::set<std::string> pinnedEffects(const std::vector<CandidateFit>& fits) {
  std::set<std::string> pinned;
  for (const auto& fit : fits) {
    if (fit.ok && fit.at_bound) pinned.insert(fit.effect->name);
  }
  return pinned;
}

GapVerdict decideVerdict(const std::vector<RankedEffect>& ranking, const std::set<std::string>& pinned,
                         const std::string& where_subsystem, double gap_before, const DiagnosisOptions& options) {
  auto changesWhere = [&](const std::string& effect) { return effectChangesSubsystem(effect, where_subsystem); };
  GapVerdict v;
  v.gap_before = gap_before;
  const WinnerSelection selection =
      selectWinner(ranking, changesWhere, pinned, options.min_shrink, options.min_evidence_per_parameter);
  const RankedEffect* top = selection.top;
  const RankedEffect* best = selection.winner;
  const RankedEffect* second = selection.runner_up;
  const bool pinned_winner = selection.winner_pinned;
  std::ostringstream reason;
  if (gap_before < options.detection_gap) {
    v.effect = "unexplained";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    v.confidence = std::clamp(1.0 - gap_before / options.detection_gap, 0.0, 1.0) * 0.5 + 0.5;
    reason << "the nominal model matches the held-out data to within noise (gap " << formatNumber(gap_before)
           << " < detection threshold " << formatNumber(options.detection_gap) << "): nothing to explain";
  } else if (best == nullptr) {
    v.effect = "unexplained";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    const double s = top ? std::max(0.0, top->shrink) : 0.0;
    v.confidence = std::clamp(1.0 - s / options.min_shrink, 0.0, 1.0) * 0.5 + 0.5;
    reason << "a gap of " << formatNumber(gap_before) << " (mostly in the " << where_subsystem
           << " subsystem) that no candidate explains: ";
    if (top == nullptr) {
      reason << "no candidate changes the " << where_subsystem << " subsystem";
    } else {
      reason << "the best candidate that changes it, " << top->effect << ", removes " << formatNumber(100.0 * s)
             << " % of it on held-out data with evidence " << formatNumber(top->score) << " (needs "
             << formatNumber(100.0 * options.min_shrink) << " % and " << formatNumber(options.min_evidence_per_parameter)
             << " per parameter)";
    }
  } else {
    v.effect = best->effect;
    v.gap_after = best->heldout_gap_after;
    v.shrink = best->shrink;
    // Confidence: how much of the gap it explains, times how clearly it beats the runner-up.
    const double margin = second ? (best->shrink - second->shrink) / std::max(1e-9, best->shrink) : 1.0;
    v.confidence = std::clamp(best->shrink, 0.0, 1.0) * (0.5 + 0.5 * std::clamp(margin / 0.3, 0.0, 1.0));
    if (pinned_winner) v.confidence *= 0.5;
    for (const auto& r : ranking) {
      if (&r != best && changesWhere(r.effect) && r.closed_loop_bounded && r.shrink >= options.min_shrink &&
          best->shrink - r.shrink < 0.1) {
        v.confusable_with.push_back(r.effect);
      }
    }
    reason << best->effect << " removes " << formatNumber(100.0 * best->shrink) << " % of the held-out gap ("
           << formatNumber(gap_before) << " -> " << formatNumber(best->heldout_gap_after) << ")";
    if (second) reason << "; next best " << second->effect << " removes " << formatNumber(100.0 * second->shrink) << " %";
    if (pinned_winner) {
      reason << "; a fitted parameter sits at a bound of its range (the effect's form differs from the candidate's, "
                "or the data fix only a combination of its parameters): confidence halved";
    }
    const auto& known = knownLookAlikes(best->effect);
    for (const auto& c : v.confusable_with) {
      if (std::find(known.begin(), known.end(), c) != known.end()) reason << "; " << c << " is a known look-alike";
    }
  }
  v.reason = reason.str();
  return v;
}

}  // namespace diagnosis
}  // namespace lane_keeping
