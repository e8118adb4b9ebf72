#pragma once
/// The sensor errors the input checks measure before any model (log/heading_agreement.h: a gyro that turns
/// 0.84 of the course and of ay / V, a gyro drifting from the heading) against the verdict's effects. A
/// model-based verdict that does not name an error measured so may have let other effects stand in for it
/// (on the race car's three laps: a steering ratio of 20.1 where the gyro reads 0.84; docs/real_logs/
/// super_fj_fuji.md), and the engineer reading it is told so, with the way to correct the log and diagnose
/// again. Said, not decided: the checks' findings do not change the verdict.
#include <string>
#include <vector>

#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/log/heading_agreement.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// One note per channel and kind of the `scale` and `bias` input checks whose sensor error the verdict's
/// effects (`sensor_scale` / `sensor_offset` of that channel) do not hold; none where they do or where
/// nothing was measured.
std::vector<std::string> measuredSensorErrorNotes(const GapReport& report);

/// The configuration change that corrects `measured` (each value into its key: the measured gain or bias
/// replaces the configured one).
ConfigChange correctionOf(const std::vector<MeasuredSensorError>& measured);

/// `report`, diagnosed with `measured` corrected, told about them: each becomes an effect of the verdict
/// (basis "measured", `VerdictEffect::measured`), its share the held-out gap it removes, gap_as_logged ->
/// gap_corrected (the nominal as configured against it corrected, on the same noise-only reference); the
/// effects the diagnosis then named keep their order, their shares rescaled to the gap as logged. The leader is
/// the effect with the largest share; where the diagnosis named nothing, the measured errors are the verdict.
void withMeasuredErrors(GapReport* report, const std::vector<MeasuredSensorError>& measured, double gap_as_logged,
                        double gap_corrected);

}  // namespace diagnosis
}  // namespace lane_keeping
