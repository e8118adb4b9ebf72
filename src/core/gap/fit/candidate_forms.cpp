#include "lane_keeping/gap/fit/candidate_forms.h"

#include <cstdio>
#include <map>

namespace lane_keeping {
namespace diagnosis {
namespace {

std::string formatGap(double gap) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", gap);
  return buffer;
}

/// Whether fit a describes the training data better than fit b.
bool fitsBetter(const CandidateFit& a, const CandidateFit& b) {
  if (a.ok != b.ok) return a.ok;
  return a.ok && a.train_after < b.train_after;
}

}  // namespace

void keepBestForms(std::vector<CandidateFit>* fits, std::vector<std::string>* notes) {
  std::map<std::string, std::size_t> best;  // effect -> index of its best form so far
  std::map<std::string, std::string> compared;
  for (std::size_t i = 0; i < fits->size(); ++i) {
    const CandidateFit& fit = (*fits)[i];
    const std::string& name = fit.effect->name;
    const std::string gap = fit.ok ? formatGap(fit.train_after) : "failed";
    std::string& list = compared[name];
    list += (list.empty() ? "" : ", ") + (fit.effect->form.empty() ? name : fit.effect->form) + " " + gap;
    const auto it = best.find(name);
    if (it == best.end()) {
      best[name] = i;
    } else if (fitsBetter(fit, (*fits)[it->second])) {
      it->second = i;
    }
  }
  std::vector<CandidateFit> kept;
  for (std::size_t i = 0; i < fits->size(); ++i) {
    const CandidateFit& fit = (*fits)[i];
    if (best[fit.effect->name] != i) continue;
    const std::string& list = compared[fit.effect->name];
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
