#pragma once
/// How large a replay's mismatch is, and how much of it is more than sensor noise.
///  * nrmse: RMS of (measured - predicted) / scale  (scale = RMS of the measured output about its mean)
///  * floor: the white-noise part of that residual, from second differences within each shooting
///    interval: for white noise of std s, var(r[i-1] - 2 r[i] + r[i+1]) = 6 s^2, while a smooth model
///    error (what we look for) contributes almost nothing to second differences at the log's rate.
///  * excess = sqrt(max(0, nrmse^2 - 1.1 floor^2)): the mismatch that is not noise (a residual variance
///    within 10 % of the noise variance counts as noise: the floor estimate scatters, and filtered noise
///    is not quite white).
/// A subsystem's figures are the RMS over its outputs. `reference` is the largest excess the same
/// replay shows on the log's noise-only reference draws (noise_reference.h): what measurement noise
/// can leave through the replay's inputs even under a perfect model. The total gap is
/// sqrt(sum over subsystems of max(0, excess^2 - reference^2)). Shrink = 1 - gap_after / gap_before.
/// (Clipped per output on purpose: summing the signed nrmse^2 - 1.1 floor^2 was tried; the tracker's and
/// actuator's large floors then scatter more than a steering gap is worth — docs/gap.md.)
#include <string>
#include <vector>

#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {

struct TraceScore {
  std::string name;
  std::size_t samples = 0;
  double nrmse = 0.0, floor = 0.0, excess = 0.0;
};

struct SubsystemScore {
  std::string name;
  std::vector<TraceScore> traces;
  double nrmse = 0.0, floor = 0.0, excess = 0.0;
  double reference = 0.0;  ///< excess on the noise-only reference (0: none measured)
  int diverged_intervals = 0;
};

TraceScore scoreTrace(const ReplayTrace& trace);
SubsystemScore scoreReplay(const SubsystemReplay& replay);
/// sqrt(max(0, excess^2 - reference^2)): a subsystem's mismatch beyond what noise leaves through it.
double netExcess(const SubsystemScore& score);
/// sqrt(sum of netExcess^2) over the given subsystems.
double combinedGap(const std::vector<SubsystemScore>& scores);

}  // namespace lane_keeping
