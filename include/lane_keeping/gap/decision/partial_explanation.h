#pragma once
/// What the best candidate leaves (diagnosis.h, step 3), as system identification validates a model
/// (Ljung, System Identification, §16.6): is the remaining residual more than noise, and where? A
/// candidate that removes half of a gap and leaves structure is half an explanation, not the cause —
/// a varying speed fitted as steering friction (47 % of the gap), a delay on the steering-angle sensor
/// fitted as cornering stiffness (50 %). Two signs, each measured against the noise-only null:
///  * untouched share: the share of the held-out gap^2 that lies in subsystems the candidate does not
///    change (it cannot explain that part, whatever its parameters);
///  * residual structure: the whiteness and input-correlation statistics (residual_structure.h) of the
///    candidate's held-out residual in the subsystem carrying the gap, as Monte Carlo p-values among the
///    null draws' statistics.
/// A winner is a partial explanation when the untouched share reaches options.untouched_share, or when it
/// removes less than options.half_explanation of the gap — on held-out data and on the training data it
/// was fitted to — and its residual is structured at the false-alarm rate. (Measured on the benchmark:
/// the residual of every real effect's winner is structured, p = 1 / (B + 1); the share decides.)
#include <map>
#include <string>
#include <vector>

#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// The analysis of `fit` (ranked as `ranked`, the gap located in `where_subsystem`); the returned
/// effect is empty when the fit explains the gap, else it names the partial candidate. The untouched
/// subsystems are netted of `knock_on_reference` where it is above their own reference (knock_on.h).
/// Whether `p` (its untouched share, share and residual p-values set) is a partial explanation: sets
/// p->effect to `effect` if so (the rule above).
void judgePartial(PartialExplanation* p, const std::string& effect, const DiagnosisOptions& options);

PartialExplanation partialExplanation(const CandidateFit& fit, const RankedEffect& ranked, const std::string& where_subsystem,
                                      const Evaluation& nominal_held, const std::vector<Dataset>& held,
                                      const NoiseNull& null, double gap_before, const DiagnosisOptions& options,
                                      const std::map<std::string, double>& knock_on_reference = {});

}  // namespace diagnosis
}  // namespace lane_keeping
