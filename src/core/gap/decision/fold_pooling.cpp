#include "lane_keeping/gap/decision/fold_pooling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lane_keeping/gap/decision/verdict.h"

namespace lane_keeping {
namespace diagnosis {

bool decidesOnPooledTest(const GapDetection& detection, const DiagnosisOptions& options) {
  return options.two_folds && detection.draws > 0 && !detection.heldout.detected && detection.pooled.detected;
}

GapDetection decisiveDetection(const GapDetection& detection, const DiagnosisOptions& options) {
  GapDetection out = detection;
  if (decidesOnPooledTest(detection, options)) out.heldout = detection.pooled;
  return out;
}

GapFold foldOf(const GapReport& report, const std::vector<std::string>& training) {
  GapFold f;
  f.training = training;
  f.heldout = report.heldout;
  f.effect = report.verdict.effect.empty() ? "unexplained" : report.verdict.effect;
  f.form = report.verdict.form;
  f.basis = report.verdict.basis;
  f.heldout_p = report.detection.heldout.p_value;
  f.gap_before = report.verdict.gap_before;
  f.gap_after = report.verdict.gap_after;
  for (const RankedEffect& r : report.ranking) {
    if (r.effect == report.verdict.effect && r.form == report.verdict.form) f.params = r.params;
  }
  return f;
}

namespace {

std::string named(const GapFold& f) {
  return f.effect + (f.form.empty() ? "" : " (" + f.form + ")");
}

std::string figures(const GapFold& f) {
  std::ostringstream s;
  s << named(f);
  if (f.effect != "unexplained") {
    s << ", held-out gap " << briefNumber(f.gap_before) << " -> " << briefNumber(f.gap_after);
    if (f.basis == "modal") s << " (on the loop's modes)";
  }
  return s.str();
}

/// Why the folds ran: the held-out test alone missed the gap, or they were asked for.
std::string whyFolds(const GapDetection& detection, const std::string& held_out_in_turn) {
  std::ostringstream why;
  if (detection.heldout.detected) {
    why << "the held-out data alone detect the gap (p = " << briefNumber(detection.heldout.p_value) << "), and "
        << held_out_in_turn;
  } else if (detection.pooled.detected) {
    why << "the held-out data alone do not detect the gap (p = " << briefNumber(detection.heldout.p_value)
        << ", training p = " << briefNumber(detection.training.p_value) << "); both sides together do (p = "
        << briefNumber(detection.pooled.p_value) << " among " << detection.draws << " noise-only draws), so "
        << held_out_in_turn;
  } else {  // a gap on the training side alone: the folds ran, the verdict says what the held-out data do not confirm
    why << "the training data alone show a gap (p = " << briefNumber(detection.training.p_value)
        << "; held-out p = " << briefNumber(detection.heldout.p_value) << ", both sides together p = "
        << briefNumber(detection.pooled.p_value) << "), and " << held_out_in_turn;
  }
  return why.str();
}

}  // namespace

void poolFolds(GapVerdict* verdict, const GapDetection& detection, const std::vector<GapFold>& folds) {
  if (folds.size() != 2) return;
  const GapFold& first = folds[0];
  const GapFold& second = folds[1];
  std::ostringstream why;
  why << whyFolds(detection, "each side was held out in turn") << ": fold 1 " << figures(first)
      << "; fold 2 (sides swapped) " << figures(second);
  const bool agree = first.effect != "unexplained" && first.effect == second.effect && first.form == second.form;
  if (agree) {
    verdict->reason = why.str() + ". Both folds name it. " + verdict->reason;
    // Pooled over the folds: each side's held-out gap, before and after its own fold's fit.
    const double before = std::hypot(first.gap_before, second.gap_before);
    const double after = std::hypot(first.gap_after, second.gap_after);
    if (before > 0.0 && verdict->basis != "modal") {
      verdict->reason += " (both folds' held-out gaps together: " + briefNumber(before) + " -> " + briefNumber(after) + ")";
    }
    return;
  }
  *verdict = unexplainedVerdict(verdict->gap_before, why.str() + ": the folds do not agree, not diagnosed");
}

std::vector<RankedEffect> pooledRanking(const std::vector<RankedEffect>& first,
                                        const std::vector<std::vector<RankedEffect>>& folds,
                                        std::vector<std::string>* notes) {
  std::vector<RankedEffect> pooled;
  for (const RankedEffect& r : first) {
    RankedEffect p = r;
    double before2 = 0.0, after2 = 0.0, evidence = 0.0;
    bool everywhere = true;
    for (const auto& ranking : folds) {
      const RankedEffect* same = nullptr;
      for (const RankedEffect& f : ranking) {
        if (f.label() == r.label()) same = &f;
      }
      if (same == nullptr) {
        everywhere = false;
        break;
      }
      before2 += same->heldout_gap_before * same->heldout_gap_before;
      after2 += same->heldout_gap_after * same->heldout_gap_after;
      evidence += same->score;
      p.closed_loop_bounded = p.closed_loop_bounded && same->closed_loop_bounded;
      if (p.implausible.empty()) p.implausible = same->implausible;  // implausible in any fold: in the pool
    }
    if (!everywhere) {
      if (notes != nullptr) notes->push_back(r.label() + ": not ranked in every fold, left out of the pooled ranking");
      continue;
    }
    p.heldout_gap_before = std::sqrt(before2);
    p.heldout_gap_after = std::sqrt(after2);
    p.shrink = p.heldout_gap_before > 0.0 ? 1.0 - p.heldout_gap_after / p.heldout_gap_before : 0.0;
    p.score = evidence;
    pooled.push_back(p);
  }
  std::stable_sort(pooled.begin(), pooled.end(), [](const RankedEffect& a, const RankedEffect& b) {
    if (a.mayBeTheCause() != b.mayBeTheCause()) return a.mayBeTheCause();
    return a.heldout_gap_after < b.heldout_gap_after;
  });
  return pooled;
}

double pooledUntouchedShare(const std::vector<std::string>& changes,
                            const std::vector<std::map<std::string, double>>& excess, double gap_before) {
  if (gap_before <= 0.0) return 0.0;
  double untouched = 0.0;
  for (const auto& fold : excess) {
    for (const auto& [name, e] : fold) {
      if (std::find(changes.begin(), changes.end(), name) == changes.end()) untouched += e * e;
    }
  }
  return untouched / (gap_before * gap_before);
}

void describeRunFolds(GapVerdict* verdict, const GapDetection& detection, const std::vector<GapFold>& folds) {
  std::ostringstream why;
  why << whyFolds(detection, "each of the " + std::to_string(folds.size()) +
                                 " runs was held out in turn, fitted on the others, and the verdict decided on the "
                                 "held-out evidence summed over them");
  for (std::size_t k = 0; k < folds.size(); ++k) {
    why << (k == 0 ? ": " : "; ") << "fold " << (k + 1) << " (" << (folds[k].heldout.empty() ? "?" : folds[k].heldout.front())
        << " held out) " << figures(folds[k]);
  }
  verdict->reason = why.str() + ". Pooled: " + verdict->reason;
}

}  // namespace diagnosis
}  // namespace lane_keeping
