#pragma once
/// A closed-loop effect moves the whole loop, and with it the replays of subsystems it does not change.
/// A localisation latency of 0.1 s makes the lane keeping ring; the actuator replay (the PID torque from
/// the logged, noisy angles) then leaves more excess than on the nominal loop's noise-only draws, whose
/// motion is calmer. Measured on the independent family's localisation_latency-large-bend: actuator excess
/// 0.039, against a largest of 0 over the nominal's 19 draws and of 0.063 over 19 draws of the true model
/// (the true model's own test: p = 0.75). That excess is the effect's knock-on, not a second gap, and it
/// made the diagnosis place the gap in the actuator ("no candidate changes it") or call the right
/// candidate a partial explanation (a third of the gap "in subsystems it does not change").
///
/// For the best candidates that leave excess in subsystems they do not change, the noise-only draws are
/// made again of each one's own closed loop (a parametric bootstrap under the candidate: Davison and
/// Hinkley, Bootstrap Methods, §4.2), and those subsystems are netted of its draws' largest excess where
/// that is above the nominal's. A candidate whose own draws leave as much there has explained it.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// A candidate's own noise-only reference for the subsystems it does not change.
struct KnockOn {
  std::map<std::string, double> reference;  ///< per subsystem: the largest held-out excess over its draws
  int draws = 0;                            ///< draws of its closed loop that ran
};

/// The knock-on reference of `fit` on the held-out data sets, over `subsystems`: `draws` noise-only draws
/// of each run's closed loop with the fit's change (noise_null.h).
KnockOn knockOnReference(const CandidateFit& fit, const std::vector<Dataset>& held, const std::set<std::string>& subsystems,
                         const DiagnosisOptions& options);

/// The held-out gap `ranked` leaves with its untouched subsystems netted of `knock_on` (where above the
/// nominal's reference): sqrt(gap_after^2 - sum over them of (net_nominal^2 - net_knock_on^2)).
double gapAfterKnockOn(const RankedEffect& ranked, const CandidateFit& fit, const Evaluation& nominal_held,
                       const KnockOn& knock_on);

/// For the best `options.knock_on_candidates` candidates (by held-out evidence, bounded, with positive
/// evidence) that leave net excess in subsystems they do not change: their knock-on references, and
/// their ranking entries' held-out gap after and shrink netted of them (the ranking is sorted again).
/// Returns the knock-on references by candidate label; says what it did in `notes`.
std::map<std::string, KnockOn> netKnockOn(std::vector<RankedEffect>* ranking, const std::vector<CandidateFit>& fits,
                                          const Evaluation& nominal_held, const std::vector<Dataset>& held,
                                          double gap_before, const DiagnosisOptions& options,
                                          std::vector<std::string>* notes);

}  // namespace diagnosis
}  // namespace lane_keeping
