#pragma once
/// Several effects at once (DESIGN §5: `verdict.effects`). A real car has several — a sensor's offset
/// and a crowned road, a compliant column and a torque limit — and a diagnosis that names one leaves the
/// others to be absorbed by it or left unsaid. After the leading effect, forward selection (Efroymson's
/// stepwise regression, forward only): the remaining candidates are fitted again on top of the effects
/// chosen so far — each run's configuration with those effects applied is the new nominal — and the best
/// one is added if it earns its place on held-out data, as the leader had to:
///  * what the effects so far leave is still a gap: its total excess lies above every noise-only draw's
///    (the Monte Carlo test of noise_null.h, at the same false-alarm rate), both the nominal's and those
///    of the model with the effects so far (what noise leaves through that model), else there is nothing
///    more to explain;
///  * the added effect removes at least `min_further_shrink` (10 %) of what is left and at least
///    `min_effect_share` (2 %) of the original gap, and lowers the total excess by more than the
///    noise-only draws' spread (noise_null.h heldSpread);
///  * its held-out evidence over the effects so far is at least min_evidence_per_parameter per
///    parameter; sensors before physics (winner_selection.h) as for the leader.
/// At most `max_effects` effects. Each is reported with its share of the original gap: (gap before it -
/// gap with it) / gap before any, so the shares add up to the combined shrink.
#include <string>
#include <vector>

#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

struct ForwardSelection {
  std::vector<VerdictEffect> effects;  ///< the leader first
  /// The fits of the effects named after the leader (their `change` is on top of those before them).
  std::vector<CandidateFit> added;
  double gap_after = 0.0;              ///< held-out gap with every named effect
  ConfigChange change;                 ///< all of them, as a change of any run's configuration
  SimConfig corrected;                 ///< the shared nominal with all of them
  /// What the effects leave is beyond the nominal's noise-only draws but within the draws of the model
  /// with them (a complete explanation, as a chain leaving no net gap is: sensor_led_selection.h).
  bool complete = false;
  std::vector<std::string> notes;      ///< why the selection stopped
  std::vector<std::pair<std::string, double>> wall_seconds;  ///< per round
};

/// Forward selection from `leader` (a fit of `context`, which holds the nominal's evaluations with the
/// noise reference set) among `candidates`. `gap_before` is the nominal's held-out gap.
/// `first_round` are the candidates' fits alone: each further fit starts from them (warmStartFit), and only
/// the candidates that change the subsystem carrying what is left are fitted again.
ForwardSelection forwardSelection(const CandidateFit& leader, const std::vector<const CandidateEffect*>& candidates,
                                  const std::vector<CandidateFit>& first_round, const FitContext& context,
                                  const NoiseNull& null, double gap_before, const DiagnosisOptions& options);

/// A fitted effect as the verdict names it (parameters, uncertainty, overlay against `nominal`).
VerdictEffect verdictEffect(const CandidateFit& fit, const SimConfig& nominal);

}  // namespace diagnosis
}  // namespace lane_keeping
