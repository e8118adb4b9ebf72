#pragma once
/// Headings that wrap at +-pi, unwrapped where the log is read (issue 46): a localisation or an INS
/// reports psi in (-pi, pi], and one wrap in a log read as it stands is a 2 pi step that the chassis
/// replay chases as a residual (one wrap was 92 % of a real log's residual).
#include <cstddef>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

/// Unwraps `angles` [rad] in place and returns the number of wraps removed. A wrap is a step between
/// consecutive samples within pi/2 of +-2 pi (a heading crossing +-pi turns by a fraction of a radian
/// per sample, so the step is 2 pi less that fraction); every later sample is shifted by -+2 pi. Only
/// single wraps are taken: a heading in degrees that wraps at +-180 steps by ~360, which is left as it
/// stands for the units check (input_checks.h) to name, rather than "unwrapped" into nonsense.
std::size_t unwrapAngle(std::vector<double>* angles);

/// Unwraps the log's psi column (if any) and says so in its notes, with the number of wraps and the
/// first sample's time.
void unwrapHeading(GapLog* log);

}  // namespace lane_keeping
