#pragma once
/// Sensors before physics, for several sensor errors at once. winner_selection.h compares one physical
/// effect with one sensor error; a real log usually carries two or three sensor errors, and together
/// they can explain what one physical effect imitates. The race car's log (docs/real_logs/super_fj_fuji.md)
/// is the case: a steering-wheel zero offset (+5.2 mrad, measured on the straights) and a gyro reading
/// 0.85 of the true yaw rate; each alone removes 25 % and 19 % of the held-out gap, a 3.2 kN "aerodynamic"
/// side force 51 %, and the two measured errors together leave nothing beyond the noise-only draws. A
/// forward selection from the physical leader tries the sensor errors only on top of the side force, which
/// has absorbed them already.
///
/// So, when the first-round winner is physical, a second forward selection (forward_selection.h) starts
/// from the best sensor error (the unpinned, bounded sensor fit with the largest held-out evidence that
/// earns its parameters and changes the subsystem carrying the gap); physical effects may join it on top,
/// by the same rules. The two chains are compared by their penalised held-out evidence, E − m·k (E the
/// summed evidence of the chain's effects, which telescopes to the evidence of all of them over the
/// nominal; k their parameters; m = min_evidence_per_parameter). The physical-led chain keeps the lead only
/// where its penalised evidence beats the sensor-led chain's by m per parameter of its leader, as a single
/// physical effect must beat a single sensor error (winner_selection.h); the sensor-led chain must
/// remove at least min_shrink of the held-out gap, as a leader must, and its first sensor error alone at
/// least min_further_shrink (10 %), as an effect added on top of others must remove of what is left; and
/// it must be a complete explanation where the physical chain is not: its net held-out gap 0 (what it
/// leaves lies within the noise-only reference), the physical chain's above 0.
#include <string>
#include <vector>

#include "lane_keeping/gap/decision/forward_selection.h"

namespace lane_keeping {
namespace diagnosis {

/// Held-out evidence of a chain of effects, penalised by `per_parameter` for each parameter it fits.
double penalisedEvidence(const ForwardSelection& chain, double per_parameter);

/// The sensor fit a sensor-led chain starts from, or nullptr: among `fits`, ok, a sensor error, no parameter
/// at a bound, its closed loop not contradicted by the logs, changing `where`, with at least
/// min_evidence_per_parameter per parameter; the largest held-out evidence.
const CandidateFit* sensorLeader(const std::vector<CandidateFit>& fits, const std::string& where,
                                 const DiagnosisOptions& options);

/// What sensorsLead asks that is known before the sensor-led chain is fitted: a physical chain that leaves a
/// gap beyond the noise-only reference, and a first sensor error that removes, alone, `first_share` of the
/// held-out gap of at least min_further_shrink (and min_effect_share). Where it does not hold no sensor chain
/// can lead, whatever is fitted on top of its first error, so none is fitted (diagnosis.cpp: at 1 kHz such a
/// chain took a third of lk_bench_gap's time). `why_not`, if given, gets the reason where it does not hold.
bool sensorChainMayLead(const ForwardSelection& physical, double first_share, double gap_before,
                        const DiagnosisOptions& options, std::string* why_not = nullptr);

/// Whether the sensor-led chain `sensors` takes the lead from the physical-led chain `physical` (see above).
/// `why` gets the sentence the verdict's reason adds.
bool sensorsLead(const ForwardSelection& physical, const ForwardSelection& sensors, double gap_before,
                 const DiagnosisOptions& options, std::string* why);

/// The verdict rewritten for a sensor-led chain that took the lead: `first` (the chain's first effect as
/// ranked) becomes the verdict's effect, the physical leader a look-alike, `why` the reason; the
/// confidence is the chain's combined shrink, halved where the physical chain comes within 30 % of it
/// (as decideVerdict weighs a runner-up).
void leadWithSensors(GapVerdict* verdict, const RankedEffect& first, const ForwardSelection& sensors,
                     const ForwardSelection& physical, const std::string& why);

}  // namespace diagnosis
}  // namespace lane_keeping
