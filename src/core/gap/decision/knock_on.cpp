#include "lane_keeping/gap/decision/knock_on.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "lane_keeping/gap/decision/verdict.h"
#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// Whether the fit changes `subsystem`'s replay (directly, or the steering's through the chassis): the
/// others are where a knock-on shows.
bool changes(const CandidateFit& fit, const std::string& subsystem) { return fit.effect->changes(subsystem); }

double square(double x) { return x * x; }

/// Net excess of `score` against the larger of its own reference and `other`.
double netAgainst(const SubsystemScore& score, double other) {
  SubsystemScore s = score;
  s.reference = std::max(s.reference, other);
  return netExcess(s);
}

}  // namespace

KnockOn knockOnReference(const CandidateFit& fit, const std::vector<Dataset>& held, const std::set<std::string>& subsystems,
                         const DiagnosisOptions& options) {
  KnockOn out;
  std::vector<Dataset> changed_held;
  for (const Dataset& set : held) {
    changed_held.push_back({set.log, std::make_shared<const SimConfig>(changed(*set.config, fit.change)), set.segments});
  }
  const NoiseNull null = noiseNull({}, changed_held, subsystems, options.replay, options.noise_reference_draws, options.threads);
  out.reference = null.largestHeldExcess();
  out.draws = null.draws();
  return out;
}

double gapAfterKnockOn(const RankedEffect& ranked, const CandidateFit& fit, const Evaluation& nominal_held,
                       const KnockOn& knock_on) {
  double after2 = square(ranked.heldout_gap_after);
  for (const auto& [name, nominal] : nominal_held.scores) {
    if (changes(fit, name)) continue;
    const auto it = knock_on.reference.find(name);
    if (it == knock_on.reference.end()) continue;
    // The score the fit's gap holds for it (its own replay where it made one, as gapOf takes it), with
    // the nominal's reference.
    const auto own = fit.heldout_scores.find(name);
    SubsystemScore score = own != fit.heldout_scores.end() ? own->second : nominal;
    score.reference = nominal.reference;
    after2 -= square(netExcess(score)) - square(netAgainst(score, it->second));
  }
  return std::sqrt(std::max(0.0, after2));
}

std::map<std::string, KnockOn> netKnockOn(std::vector<RankedEffect>* ranking, const std::vector<CandidateFit>& fits,
                                          const Evaluation& nominal_held, const std::vector<Dataset>& held,
                                          double gap_before, const DiagnosisOptions& options,
                                          std::vector<std::string>* notes) {
  std::map<std::string, KnockOn> out;
  if (options.noise_reference_draws <= 0 || options.knock_on_candidates <= 0 || !(gap_before > 0.0)) return out;
  // The candidates by held-out evidence: bounded, with evidence for them, and excess left where they
  // do not act.
  std::vector<std::pair<RankedEffect*, const CandidateFit*>> chosen;
  for (RankedEffect& r : *ranking) {
    if (!r.mayBeTheCause() || !(r.score > 0.0)) continue;
    const CandidateFit* fit = nullptr;
    for (const auto& f : fits) {
      if (f.ok && f.effect->name == r.effect && f.effect->form == primaryForm(r.form)) fit = &f;
    }
    if (fit == nullptr) continue;
    double untouched = 0.0;
    for (const auto& [name, score] : nominal_held.scores) {
      if (!changes(*fit, name)) untouched += square(netExcess(score));
    }
    if (untouched > 0.0) chosen.emplace_back(&r, fit);
  }
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.first->score > b.first->score; });
  if (chosen.size() > static_cast<std::size_t>(options.knock_on_candidates)) {
    chosen.resize(static_cast<std::size_t>(options.knock_on_candidates));
  }
  for (auto& [ranked, fit] : chosen) {
    std::set<std::string> untouched;
    for (const auto& [name, score] : nominal_held.scores) {
      if (!changes(*fit, name) && netExcess(score) > 0.0) untouched.insert(name);
    }
    const KnockOn k = knockOnReference(*fit, held, untouched, options);
    if (k.draws == 0) continue;
    const double after = gapAfterKnockOn(*ranked, *fit, nominal_held, k);
    std::string what;
    for (const auto& name : untouched) {
      const auto it = k.reference.find(name);
      if (it == k.reference.end()) continue;
      const SubsystemScore& score = nominal_held.scores.at(name);
      what += (what.empty() ? "" : ", ") + name + " " + briefNumber(score.excess) + " (nominal draws up to " +
              briefNumber(score.reference) + ", its own up to " + briefNumber(it->second) + ")";
    }
    notes->push_back("knock-on of " + ranked->label() + ": held-out excess where it does not act, " + what +
                     "; its held-out gap after " + briefNumber(ranked->heldout_gap_after) + " -> " + briefNumber(after) +
                     " net of its own " + std::to_string(k.draws) + " noise-only draws");
    ranked->heldout_gap_after = after;
    ranked->shrink = 1.0 - after / gap_before;
    out[ranked->label()] = k;
  }
  std::stable_sort(ranking->begin(), ranking->end(), [](const RankedEffect& a, const RankedEffect& b) {
    if (a.mayBeTheCause() != b.mayBeTheCause()) return a.mayBeTheCause();
    return a.heldout_gap_after < b.heldout_gap_after;
  });
  return out;
}

}  // namespace diagnosis
}  // namespace lane_keeping
