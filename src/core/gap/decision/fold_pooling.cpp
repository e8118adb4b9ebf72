#include "lane_keeping/gap/decision/fold_pooling.h"

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

}  // namespace

void poolFolds(GapVerdict* verdict, const GapDetection& detection, const std::vector<GapFold>& folds) {
  if (folds.size() != 2) return;
  const GapFold& first = folds[0];
  const GapFold& second = folds[1];
  std::ostringstream why;
  why << "the held-out data alone do not detect the gap (p = " << briefNumber(detection.heldout.p_value)
      << ", training p = " << briefNumber(detection.training.p_value) << "); both sides together do (p = "
      << briefNumber(detection.pooled.p_value) << " among " << detection.draws
      << " noise-only draws), so each side was held out in turn: fold 1 " << figures(first) << "; fold 2 (sides swapped) "
      << figures(second);
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

}  // namespace diagnosis
}  // namespace lane_keeping
