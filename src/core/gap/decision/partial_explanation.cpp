#include "lane_keeping/gap/decision/partial_explanation.h"

#include <algorithm>
#include <set>

#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {
namespace diagnosis {

void judgePartial(PartialExplanation* p, const std::string& effect, const DiagnosisOptions& options) {
  const bool structured = std::min(p->whiteness_p, p->input_correlation_p) <= options.false_alarm_rate;
  p->effect.clear();
  if (p->untouched_share >= options.untouched_share || (p->share < options.half_explanation && structured)) {
    p->effect = effect;
  }
}

PartialExplanation partialExplanation(const CandidateFit& fit, const RankedEffect& ranked, const std::string& where_subsystem,
                                      const Evaluation& nominal_held, const std::vector<Dataset>& held,
                                      const NoiseNull& null, double gap_before, const DiagnosisOptions& options,
                                      const std::map<std::string, double>& knock_on_reference) {
  PartialExplanation out;
  out.form = ranked.form;
  const std::vector<std::string>& changes = fit.effect->subsystems;
  auto changed = [&](const std::string& s) { return std::find(changes.begin(), changes.end(), s) != changes.end(); };
  double untouched = 0.0;
  for (const auto& [name, score] : nominal_held.scores) {
    if (changed(name)) continue;
    SubsystemScore netted = score;
    const auto it = knock_on_reference.find(name);
    if (it != knock_on_reference.end()) netted.reference = std::max(netted.reference, it->second);
    untouched += netExcess(netted) * netExcess(netted);
  }
  out.untouched_share = gap_before > 0.0 ? untouched / (gap_before * gap_before) : 0.0;

  // The residual it leaves in the subsystem carrying the gap (or the first it changes).
  const std::string subsystem = changed(where_subsystem) ? where_subsystem : changes.front();
  const bool reuse = !changed("chassis");
  const Evaluation ev = evaluate(fit.change, held, {subsystem}, options.replay, reuse ? &nominal_held.sigma1 : nullptr);
  const auto structures = residualStructures(ev, held);
  const auto it = structures.find(subsystem);
  if (it != structures.end() && null.draws() > 0) {
    std::vector<double> whiteness, input;
    for (const auto& draw : null.held_structure) {
      const auto d = draw.find(subsystem);
      if (d == draw.end()) continue;
      whiteness.push_back(d->second.whiteness);
      input.push_back(d->second.input_correlation);
    }
    out.whiteness_p = monteCarloPValue(it->second.whiteness, whiteness);
    out.input_correlation_p = monteCarloPValue(it->second.input_correlation, input);
  }
  // Its share of the gap on the data it was fitted to as well as on held-out data: held-out data can hold
  // a noise realisation beyond the null's draws that no model removes (the benchmark's small actuation
  // delay on a sinusoid: 100 % of the training gap, 36 % of the held-out one, as much as the truth model
  // itself), while a candidate that cannot reach half of the gap even where it was fitted is half an
  // explanation by construction.
  const double train_share =
      ranked.train_gap_before > 0.0 ? 1.0 - ranked.train_gap_after / ranked.train_gap_before : 0.0;
  out.share = std::max(ranked.shrink, train_share);
  judgePartial(&out, ranked.effect, options);
  return out;
}

}  // namespace diagnosis
}  // namespace lane_keeping
