#pragma once
/// Where the gap lies (diagnosis.h, step 2; DESIGN §5 question 1): the subsystem carrying most excess
/// beyond the noise-only reference, and within it the time windows, frequency bands and operating
/// regimes (slip angle, lateral acceleration, steering rate) where the excess concentrates.
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// `ev` holds the nominal replays and scores (with their references) over `data`; `artifacts` (may be
/// null) receives the residual and spectrum series of every subsystem. Each run whose dominant-subsystem
/// excess sets in mid-run gets an onset (GapWhere::onsets; `onset` too when the data hold one run).
GapWhere whereAnalysis(const Evaluation& ev, const std::vector<Dataset>& data, double upstream_share,
                       DiagnosisArtifacts* artifacts);

}  // namespace diagnosis
}  // namespace lane_keeping
