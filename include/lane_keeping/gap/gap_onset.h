#pragma once
/// A gap that sets in mid-run (a crosswind past a cutting, a banked section, a fault): a candidate with
/// constant parameters, fitted over the whole log, meets data where the effect is absent and explains a
/// fraction of it (a crosswind from x = 200 m of 300 m: 19 %). When the where-analysis finds that one
/// run's excess accrues only after an onset (GapWhere::onset) and no candidate explains the whole log,
/// the diagnosis runs again on the log from just before the onset and, if that names an effect, reports
/// it with the onset in its reason.
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {

/// [s] of log kept before the onset: the replays' lead-in, and the ramp of an effect that sets in.
constexpr double kOnsetLeadIn = 1.0;

/// Whether `report` (of `training`, with no held-out runs) calls for the diagnosis from the onset: a
/// detected gap, left `unexplained`, in one run whose where-analysis found an onset with at least 5 s
/// of log after it.
bool diagnoseFromOnsetApplies(const GapReport& report, const std::vector<GapRun>& training,
                              const std::vector<GapRun>& heldout, const DiagnosisOptions& options);

/// The run from kOnsetLeadIn before `onset` to its end, its initial state taken from the log there.
GapRun runFromOnset(const GapRun& run, double onset);

/// Diagnoses `training` again from the onset. Returns that report (its reason and notes say so) when it
/// names an effect; otherwise `whole` with a note of what the retry found.
GapReport diagnoseFromOnset(const SimConfig& nominal, const std::vector<GapRun>& training, GapReport whole,
                            const DiagnosisOptions& options, DiagnosisArtifacts* artifacts);

}  // namespace lane_keeping
