#pragma once
/// Which ranked candidate the gap diagnosis names as the cause (DESIGN §5 verdict), separated from the
/// fitting so that the rule can be tested on its own.
///
/// A candidate qualifies when it changes the subsystem carrying the gap, removes at least `min_shrink`
/// of the held-out gap and has at least `min_evidence_per_parameter` held-out evidence per fitted
/// parameter. A fit with a parameter pinned at a bound of its range is stretching to imitate something
/// else, or the data fix only a combination of its parameters: it ranks below every unpinned candidate
/// that qualifies, and wins only when none does. A candidate whose fitted closed loop leaves the logged
/// bounds (RankedEffect::closed_loop_bounded false) is contradicted by the logs: it is never picked.
/// Sensors before physics: every real log carries sensor and data errors (an offset, a gain, a latency),
/// and a physical effect fitted to one absorbs it (a heading mount read as a side force, a gyro's gain as
/// soft tires). A physical winner keeps the verdict only where its held-out evidence exceeds the best
/// qualifying sensor error's by min_evidence_per_parameter per parameter it fits; else the sensor error
/// is named (and the physical effect can still earn its place on top of it: several effects at once).
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {

struct WinnerSelection {
  const RankedEffect* top = nullptr;     ///< best-ranked candidate that changes the "where" subsystem
  const RankedEffect* winner = nullptr;  ///< the cause, or nullptr: unexplained
  const RankedEffect* runner_up = nullptr;  ///< best-ranked candidate after the winner that changes "where"
  bool winner_pinned = false;            ///< the winner has a parameter at a bound (confidence halved)
  /// The physical candidate that ranked first but did not beat the best sensor error by its evidence.
  const RankedEffect* sensor_over = nullptr;
};

/// `ranking` is sorted best first; `changes_where(effect)` says whether an effect (in its form) changes
/// the subsystem carrying the gap; `pinned` names (RankedEffect::label) the candidates with a parameter
/// pinned at a bound; those also in `never_win` (pinned with an improvement inside the noise-only spread,
/// or pinned on every parameter: verdict.h) never win.
WinnerSelection selectWinner(const std::vector<RankedEffect>& ranking,
                             const std::function<bool(const RankedEffect&)>& changes_where,
                             const std::set<std::string>& pinned, double min_shrink,
                             double min_evidence_per_parameter, const std::set<std::string>& never_win = {});

}  // namespace lane_keeping
