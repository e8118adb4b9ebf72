#include "lane_keeping/gap/decision/verdict.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/decision/fold_pooling.h"
#include "lane_keeping/gap/decision/winner_selection.h"
#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

GapVerdict unexplainedVerdict(double gap_before, const std::string& reason) {
  GapVerdict v;
  v.effect = "unexplained";
  v.gap_before = gap_before;
  v.gap_after = gap_before;
  v.shrink = 0.0;
  v.confidence = 0.5;
  v.combined_gap_after = gap_before;
  v.reason = reason;
  return v;
}

std::vector<RankedEffect> rankFits(const std::vector<CandidateFit>& fits, const SimConfig& nominal, double gap_before,
                                   std::vector<std::string>* notes) {
  std::vector<RankedEffect> ranking;
  for (const auto& fit : fits) {
    RankedEffect r;
    r.effect = fit.effect->name;
    r.form = fit.effect->form;
    for (const auto& f : fit.tied_forms) r.form += " or " + f;  // forms the logs cannot tell apart
    r.heldout_gap_before = gap_before;
    if (!fit.ok) {
      r.heldout_gap_after = gap_before;
      r.shrink = 0.0;
      notes->push_back(fit.effect->label() + ": " + fit.note);
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
    r.closed_loop_checked = !fit.ok || fit.loop_checked;
    r.implausible = fit.ok ? fit.implausible : "";
    if (fit.ok && !fit.note.empty()) notes->push_back(fit.effect->label() + ": " + fit.note);
    if (fit.ok && fit.at_bound) notes->push_back(fit.effect->label() + ": a fitted parameter is pinned at a bound of its range");
    if (fit.ok && !fit.implausible.empty()) notes->push_back(fit.effect->label() + ": " + fit.implausible + " (ranked last)");
    if (fit.ok && !fit.stability_note.empty()) notes->push_back(fit.effect->label() + ": " + fit.stability_note);
    ranking.push_back(r);
  }
  std::sort(ranking.begin(), ranking.end(), [](const RankedEffect& a, const RankedEffect& b) {
    if (a.mayBeTheCause() != b.mayBeTheCause()) return a.mayBeTheCause();
    return a.heldout_gap_after < b.heldout_gap_after;
  });
  return ranking;
}

std::set<std::string> pinnedEffects(const std::vector<CandidateFit>& fits) {
  std::set<std::string> pinned;
  for (const auto& fit : fits) {
    if (fit.ok && fit.at_bound) pinned.insert(fit.effect->label());
  }
  return pinned;
}

std::set<std::string> pinnedWithinNoise(const std::vector<RankedEffect>& ranking, const std::set<std::string>& pinned,
                                        const NoiseNull& null, double gap_before) {
  std::set<std::string> out;
  const double spread = heldSpread(null);
  for (const auto& r : ranking) {
    if (!pinned.count(r.label())) continue;
    if (gap_before * gap_before - r.heldout_gap_after * r.heldout_gap_after <= spread) out.insert(r.label());
  }
  return out;
}

namespace {

const SubsystemGap* subsystemGap(const GapWhere* where, const std::string& name) {
  if (where == nullptr) return nullptr;
  for (const auto& s : where->subsystems) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

std::string pValue(const DetectionTest& test, int draws) {
  // Without draws (the nominal closed loop could not be simulated over the log) nothing is calibrated:
  // detection falls back to the net gap's threshold, and the words must not suggest a test was made.
  if (draws == 0) return "no noise-only draws, so no calibrated test: see the notes";
  return "p = " + formatNumber(std::round(1000.0 * test.p_value) / 1000.0) + " among " + std::to_string(draws) +
         " noise-only draws";
}

}  // namespace

const ModalSupport* modalWinner(const std::vector<ModalSupport>& modal) {
  return modal.size() == 1 ? &modal.front() : nullptr;
}

GapVerdict decideVerdict(const std::vector<RankedEffect>& ranking, const VerdictContext& context,
                         const DiagnosisOptions& options) {
  const std::string where_subsystem = context.where ? context.where->subsystem : "";
  const double gap_before = context.gap_before;
  auto changesWhere = [&](const RankedEffect& r) {
    return effectChangesSubsystem(r.effect, where_subsystem, r.form) || context.where_by_knock_on.count(r.label()) != 0;
  };
  GapVerdict v;
  v.gap_before = gap_before;
  std::set<std::string> never_win = context.pinned_within_noise;
  for (const auto& [label, fitted] : context.pinned_everywhere) never_win.insert(label);
  const WinnerSelection selection = selectWinner(ranking, changesWhere, context.pinned, options.min_shrink,
                                                 options.min_evidence_per_parameter, never_win);
  const RankedEffect* top = selection.top;
  const RankedEffect* best = selection.winner;
  const RankedEffect* second = selection.runner_up;
  const bool pinned_winner = selection.winner_pinned;
  // On the pooled test (fold_pooling.h) it stands in for the held-out test; the loop's modes are still
  // read where the held-out test alone does not see the gap.
  const GapDetection detection = decisiveDetection(context.detection, options);
  std::ostringstream reason;
  auto unexplained = [&](double confidence) {
    v.effect = "unexplained";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    v.confidence = confidence;
  };
  // Named on the loop's modes (modal_evidence.h): where the replays name nothing, because their test does not
  // see the gap or no candidate earns its parameters on them, and one candidate alone gives the loop the
  // mode a log rings at. The ringing is its own test: a narrow peak 30 times the band's noise level that the
  // nominal loop lacks. The replays do not measure how far it goes: the held-out gap stays as it was.
  const ModalSupport* modal =
      best == nullptr || !context.detection.heldout.detected ? modalWinner(context.modal) : nullptr;
  auto namedOnModes = [&](const ModalSupport& m) {
    v.effect = m.effect;
    v.form = m.form;
    v.basis = "modal";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    v.confidence = 0.5;
    reason << "a gap of " << briefNumber(gap_before) << " (mostly in the " << where_subsystem << " subsystem; "
           << pValue(detection.heldout, detection.draws) << ")";
    if (!detection.heldout.detected) {
      reason << " that the replays' test does not detect on held-out data (training "
             << pValue(detection.training, detection.draws) << ")";
    } else {
      reason << " that no candidate explains by the replays";
      if (top != nullptr) {
        reason << " (the best, " << top->label() << ", removes " << briefNumber(100.0 * std::max(0.0, top->shrink))
               << " % of it on held-out data)";
      }
    }
    for (const auto& r : ranking) {
      if (r.label() != m.label()) continue;
      reason << "; " << m.label() << "'s held-out replay: " << briefNumber(gap_before) << " -> "
             << briefNumber(r.heldout_gap_after) << ", training " << briefNumber(r.train_gap_before) << " -> "
             << briefNumber(r.train_gap_after);
      if (!r.closed_loop_bounded) reason << " (its least-squares fit's closed loop leaves the logged bounds)";
      if (!r.implausible.empty()) reason << " (" << r.implausible << ")";
    }
    reason << ". Named on the loop's modes: " << modalReason(m) << ". The replays, stepping between samples "
           << briefNumber(1.0 / m.ringing.rate) << " s apart, do not weigh a mode at " << briefNumber(m.mode.frequency)
           << " Hz: the held-out gap is left as it was, confidence 0.5";
  };
  if (modal != nullptr) {
    namedOnModes(*modal);
  } else if (!detection.heldout.detected) {
    // Not detected on held-out data. Never "nothing to explain" beside a gap in the training data.
    const double p = std::isfinite(detection.heldout.p_value) ? detection.heldout.p_value : 1.0;  // NaN: not tested
    unexplained(0.5 + 0.5 * std::clamp(p, 0.0, 1.0));
    if (detection.training.detected) {
      v.confidence = 0.5;
      reason << "the training data carry a gap that the held-out data do not confirm: training excess "
             << briefNumber(detection.training.value) << " (" << pValue(detection.training, detection.draws)
             << ")";
      if (const SubsystemGap* s = subsystemGap(context.where, where_subsystem)) {
        reason << ", mostly in the " << where_subsystem << " subsystem (nrmse " << briefNumber(s->nrmse)
               << " against a noise floor of " << briefNumber(s->noise_floor) << " over all data)";
      }
      reason << "; held-out excess " << briefNumber(detection.heldout.value) << " ("
             << pValue(detection.heldout, detection.draws) << ", net gap " << briefNumber(gap_before)
             << "). The effect shows in a part of the run the held-out data do not cover, or the training data "
                "hold a rare noise draw: not diagnosed";
    } else if (detection.draws > 0) {
      reason << "the nominal model matches the held-out and the training data to within the noise-only spread "
                "(held-out "
             << pValue(detection.heldout, detection.draws) << ", training " << pValue(detection.training, detection.draws)
             << "; net held-out gap " << briefNumber(gap_before) << "): nothing to explain";
    } else {
      reason << "the nominal model matches the held-out data to within noise (gap " << briefNumber(gap_before)
             << " < detection threshold " << briefNumber(options.detection_gap) << "): nothing to explain";
    }
  } else if (best == nullptr) {
    const double s = top ? std::max(0.0, top->shrink) : 0.0;
    unexplained(std::clamp(1.0 - s / options.min_shrink, 0.0, 1.0) * 0.5 + 0.5);
    reason << "a gap of " << briefNumber(gap_before) << " (mostly in the " << where_subsystem << " subsystem; "
           << pValue(detection.heldout, detection.draws) << ") that no candidate explains: ";
    if (top == nullptr) {
      reason << "no candidate changes the " << where_subsystem << " subsystem";
    } else {
      reason << "the best candidate that changes it, " << top->effect << ", removes " << briefNumber(100.0 * s)
             << " % of it on held-out data with evidence " << briefNumber(top->score) << " (needs "
             << briefNumber(100.0 * options.min_shrink) << " % and " << briefNumber(options.min_evidence_per_parameter)
             << " per parameter)";
      if (context.pinned_within_noise.count(top->label())) {
        reason << "; its fit is pinned at a bound of its range and improves the gap by less than the noise-only spread";
      }
      const auto everywhere = context.pinned_everywhere.find(top->label());
      if (everywhere != context.pinned_everywhere.end()) {
        reason << "; its fit runs to a bound of the range of every parameter it fits (" << everywhere->second
               << "): the data place none of them, and a candidate stretched so far stands in for something it is not";
      }
    }
  } else {
    const PartialExplanation partial = context.partial_of ? context.partial_of(*best) : PartialExplanation{};
    if (!partial.effect.empty()) {
      // What it leaves is more than noise, in subsystems it cannot change or as structure after less
      // than half of the gap: half an explanation is not a diagnosis.
      unexplained(0.5);
      v.partial = partial;
      reason << "a gap of " << briefNumber(gap_before) << " (mostly in the " << where_subsystem
             << " subsystem) that " << best->effect << (best->form.empty() ? "" : " (" + best->form + ")")
             << " explains only in part: it removes " << briefNumber(std::round(1000.0 * best->shrink) / 10.0)
             << " % of the held-out gap and "
             << briefNumber(std::round(1000.0 * (best->train_gap_before > 0.0
                                                      ? 1.0 - best->train_gap_after / best->train_gap_before
                                                      : 0.0)) /
                             10.0)
             << " % of the training gap it was fitted to, and what it leaves is structured beyond the noise (";
      if (partial.untouched_share >= options.untouched_share) {
        reason << briefNumber(std::round(1000.0 * partial.untouched_share) / 10.0)
               << " % of the gap lies in subsystems it does not change";
      } else {
        reason << "residual whiteness p = " << briefNumber(std::round(1000.0 * partial.whiteness_p) / 1000.0)
               << ", correlation with the input p = "
               << briefNumber(std::round(1000.0 * partial.input_correlation_p) / 1000.0);
      }
      reason << "): a partial explanation, not the cause";
    } else {
      v.effect = best->effect;
      v.form = best->form;
      v.gap_after = best->heldout_gap_after;
      v.shrink = best->shrink;
      // Confidence: how much of the gap it explains, times how clearly it beats the runner-up.
      const double margin = second ? (best->shrink - second->shrink) / std::max(1e-9, best->shrink) : 1.0;
      v.confidence = std::clamp(best->shrink, 0.0, 1.0) * (0.5 + 0.5 * std::clamp(margin / 0.3, 0.0, 1.0));
      if (pinned_winner) v.confidence *= 0.5;
      for (const auto& r : ranking) {
        if (&r != best && changesWhere(r) && r.mayBeTheCause() && r.shrink >= options.min_shrink &&
            best->shrink - r.shrink < 0.1) {
          // A sensor error is named with its channel: sensor_offset of the heading is not of the gyro.
          v.confusable_with.push_back(isSensorEffect(r.effect) ? r.label() : r.effect);
        }
      }
      reason << best->effect << (best->form.empty() ? "" : " (" + best->form + ")") << " removes "
             << briefNumber(100.0 * best->shrink) << " % of the held-out gap (" << briefNumber(gap_before) << " -> "
             << briefNumber(best->heldout_gap_after) << "; the gap: " << pValue(detection.heldout, detection.draws)
             << ")";
      if (second) reason << "; next best " << second->effect << " removes " << briefNumber(100.0 * second->shrink) << " %";
      if (pinned_winner) {
        reason << "; a fitted parameter sits at a bound of its range (the effect's form differs from the candidate's, "
                  "or the data fix only a combination of its parameters): confidence halved";
      }
      const auto& known = knownLookAlikes(best->effect);
      for (const auto& c : v.confusable_with) {
        const std::string name = c.substr(0, c.find(' '));
        if (std::find(known.begin(), known.end(), name) != known.end()) reason << "; " << c << " is a known look-alike";
      }
      if (selection.sensor_over != nullptr) {
        reason << "; " << selection.sensor_over->label() << " removes " << briefNumber(100.0 * selection.sensor_over->shrink)
               << " % with held-out evidence " << briefNumber(selection.sensor_over->score) << " against "
               << briefNumber(best->score)
               << " of this sensor error: a physical effect must beat the sensor explanations by "
               << briefNumber(options.min_evidence_per_parameter) << " per parameter it fits";
      }
    }
  }
  if (v.effect == "unexplained" && context.modal.size() > 1) {
    reason << "; the logged ringing is a lightly damped mode of the loop under each of";
    for (const auto& m : context.modal) reason << " " << m.label() << " (" << m.parameter << " " << briefNumber(m.modal) << ")";
    reason << ": the loop's modes cannot tell them apart";
  }
  v.reason = reason.str();
  return v;
}

}  // namespace diagnosis
}  // namespace lane_keeping
