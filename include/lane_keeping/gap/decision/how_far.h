#pragma once
/// How far the gap shrinks once the winning effect is added (diagnosis.h, step 4; DESIGN §5 question 3):
/// the held-out excess of every subsystem before and after, and the closed-loop replay of whole runs
/// with the nominal and the corrected configuration.
#include <memory>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// Fills report->how_far: per-subsystem held-out excess before (`nominal_held`) and after (`winner`'s
/// held-out scores; the nominal's when there is no winner), and — if options.closed_loop — the RMS over
/// `runs` of the closed-loop replay gap with each run's configuration and with the winner added. Notes on
/// failed or diverged replays go to report->notes; the first run's overlays to `artifacts` (may be null).
void howFar(const CandidateFit* winner, const Evaluation& nominal_held, const std::vector<RunData>& runs,
            const DiagnosisOptions& options,
            GapReport* report, DiagnosisArtifacts* artifacts);

}  // namespace diagnosis
}  // namespace lane_keeping
