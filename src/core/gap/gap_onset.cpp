#include "lane_keeping/gap/gap_onset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "lane_keeping/gap/diagnosis.h"

namespace lane_keeping {
namespace {

constexpr double kMinAfterOnset = 5.0;  ///< [s] of log after the onset for a diagnosis worth the name

std::string seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", t);
  return text;
}

}  // namespace

bool diagnoseFromOnsetApplies(const GapReport& report, const std::vector<GapRun>& training,
                              const std::vector<GapRun>& heldout, const DiagnosisOptions& options) {
  if (!options.from_onset || training.size() != 1 || !heldout.empty()) return false;
  if (report.verdict.effect != "unexplained" || !report.detection.heldout.detected) return false;
  const double onset = report.where.onset;
  return std::isfinite(onset) && training[0].log.t.back() - onset >= kMinAfterOnset;
}

GapRun runFromOnset(const GapRun& run, double onset) {
  const std::vector<double>& t = run.log.t;
  const std::size_t begin =
      static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), onset - kOnsetLeadIn) - t.begin());
  GapRun out = run;
  out.log = run.log.slice(begin, t.size());
  out.initial_from_log = true;  // the state at the cut, not the configured start
  return out;
}

GapReport diagnoseFromOnset(const SimConfig& nominal, const std::vector<GapRun>& training, GapReport whole,
                            const DiagnosisOptions& options, DiagnosisArtifacts* artifacts) {
  const double onset = whole.where.onset;
  DiagnosisOptions again = options;
  again.from_onset = false;
  again.effect_onset = onset;  // how far switches the effect on where the gap sets in
  GapReport part = diagnoseGap(nominal, {runFromOnset(training[0], onset)}, {}, again, artifacts);
  const std::string sets_in = "the gap sets in at t = " + seconds(onset) + " (before it the nominal model matches the "
                              "log within noise)";
  if (part.verdict.effect == "unexplained") {
    whole.notes.push_back(sets_in + "; diagnosed again on the log from t = " + seconds(onset - kOnsetLeadIn) +
                          ": still unexplained (" + part.verdict.reason + ")");
    return whole;
  }
  part.verdict.reason = sets_in + "; over the whole log no candidate explains it (" + whole.verdict.reason +
                        "); on the log from t = " + seconds(onset - kOnsetLeadIn) + ": " + part.verdict.reason;
  part.notes.insert(part.notes.begin(), sets_in + ": diagnosed on the log from t = " + seconds(onset - kOnsetLeadIn));
  part.where.onset = onset;
  part.where.onsets = whole.where.onsets;  // in the whole log's time, as `onset`
  std::vector<std::pair<std::string, double>> stages;
  for (const auto& [stage, secs] : whole.wall_seconds) stages.emplace_back("whole log: " + stage, secs);
  stages.insert(stages.end(), part.wall_seconds.begin(), part.wall_seconds.end());
  part.wall_seconds = std::move(stages);
  return part;
}

}  // namespace lane_keeping
