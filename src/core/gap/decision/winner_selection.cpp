#include "lane_keeping/gap/decision/winner_selection.h"

#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {

WinnerSelection selectWinner(const std::vector<RankedEffect>& ranking,
                             const std::function<bool(const RankedEffect&)>& changes_where,
                             const std::set<std::string>& pinned, double min_shrink,
                             double min_evidence_per_parameter, const std::set<std::string>& never_win) {
  auto qualifies = [&](const RankedEffect& r) {
    return r.shrink >= min_shrink && r.score >= min_evidence_per_parameter * static_cast<double>(r.params.size());
  };
  WinnerSelection s;
  const RankedEffect* best_pinned = nullptr;
  const RankedEffect* best_sensor = nullptr;  // the best unpinned sensor error that qualifies
  for (const auto& r : ranking) {
    if (!changes_where(r) || !r.mayBeTheCause()) continue;
    if (s.top == nullptr) s.top = &r;
    if (!qualifies(r)) continue;
    if (pinned.count(r.label()) != 0) {
      if (best_pinned == nullptr && never_win.count(r.label()) == 0) best_pinned = &r;
    } else {
      if (s.winner == nullptr) s.winner = &r;
      if (best_sensor == nullptr && isSensorEffect(r.effect)) best_sensor = &r;
    }
  }
  if (s.winner == nullptr && best_pinned != nullptr) {
    s.winner = best_pinned;
    s.winner_pinned = true;
  }
  // Sensors before physics: a physical effect is named only where its held-out evidence beats the best
  // sensor explanation's by as much as a parameter has to earn, per parameter it fits.
  if (s.winner != nullptr && best_sensor != nullptr && s.winner != best_sensor && !isSensorEffect(s.winner->effect)) {
    const double needed = min_evidence_per_parameter * static_cast<double>(s.winner->params.size());
    if (s.winner->score - best_sensor->score < needed) {
      s.sensor_over = s.winner;
      s.winner = best_sensor;
      s.winner_pinned = false;
    }
  }
  for (const auto& r : ranking) {
    if (&r != s.winner && changes_where(r) && r.mayBeTheCause()) {
      s.runner_up = &r;
      break;
    }
  }
  return s;
}

}  // namespace lane_keeping
