#include "lane_keeping/gap/fit/candidate_forms.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "lane_keeping/common/brief_number.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// Whether fit a describes the training data better than fit b.
bool fitsBetter(const CandidateFit& a, const CandidateFit& b) {
  if (a.ok != b.ok) return a.ok;
  return a.ok && a.train_after < b.train_after;
}

/// The fits that compete as forms of one effect: a physical effect's placements. A sensor error's forms
/// are its channels: errors of different sensors, each its own explanation (a log can carry several).
std::string formGroup(const CandidateEffect& effect) { return effect.sensor ? effect.label() : effect.name; }

}  // namespace

void keepBestForms(std::vector<CandidateFit>* fits, std::vector<std::string>* notes) {
  std::map<std::string, std::size_t> best;  // effect -> index of its best form so far
  std::map<std::string, std::string> compared;
  for (std::size_t i = 0; i < fits->size(); ++i) {
    const CandidateFit& fit = (*fits)[i];
    const std::string name = formGroup(*fit.effect);
    const std::string gap = fit.ok ? briefNumber(fit.train_after) : "failed";
    std::string& list = compared[name];
    list += (list.empty() ? "" : ", ") + (fit.effect->form.empty() ? name : fit.effect->form) + " " + gap;
    const auto it = best.find(name);
    if (it == best.end()) {
      best[name] = i;
    } else if (fitsBetter(fit, (*fits)[it->second])) {
      it->second = i;
    }
  }
  // Forms the data cannot tell apart: the same training gap to rounding (a crosswind and a road bank
  // differ only in what the accelerometer senses: without a_y in the logs their replays are the same).
  std::map<std::string, std::vector<std::string>> tied;
  for (std::size_t i = 0; i < fits->size(); ++i) {
    const CandidateFit& fit = (*fits)[i];
    const std::size_t b = best[formGroup(*fit.effect)];
    const CandidateFit& kept_fit = (*fits)[b];
    if (b == i || !fit.ok || !kept_fit.ok) continue;
    if (std::fabs(fit.train_after - kept_fit.train_after) <= 1e-9 * std::max(1e-12, std::fabs(kept_fit.train_after))) {
      tied[formGroup(*fit.effect)].push_back(fit.effect->form);
    }
  }
  std::vector<CandidateFit> kept;
  for (std::size_t i = 0; i < fits->size(); ++i) {
    CandidateFit fit = (*fits)[i];
    if (best[formGroup(*fit.effect)] != i) continue;
    fit.tied_forms = tied[formGroup(*fit.effect)];
    if (!fit.tied_forms.empty()) {
      std::string forms = fit.effect->form;
      for (const auto& f : fit.tied_forms) forms += " and " + f;
      notes->push_back(fit.effect->name + ": the logs cannot tell the forms " + forms +
                       " apart (the same fit to rounding; for a crosswind and a road bank only a logged lateral "
                       "acceleration would): the verdict names them all");
    }
    const std::string& list = compared[formGroup(*fit.effect)];
    if (list.find(", ") != std::string::npos) {
      notes->push_back(fit.effect->name + ": form " + fit.effect->form +
                       " chosen by the training gap after each form's fit (" + list + ")");
    }
    kept.push_back(fit);
  }
  *fits = std::move(kept);
}

}  // namespace diagnosis
}  // namespace lane_keeping
