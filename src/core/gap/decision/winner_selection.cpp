#include "lane_keeping/gap/decision/winner_selection.h"

namespace lane_keeping {

WinnerSelection selectWinner(const std::vector<RankedEffect>& ranking,
                             const std::function<bool(const std::string&)>& changes_where,
                             const std::set<std::string>& pinned, double min_shrink,
                             double min_evidence_per_parameter, const std::set<std::string>& pinned_within_noise) {
  auto qualifies = [&](const RankedEffect& r) {
    return r.shrink >= min_shrink && r.score >= min_evidence_per_parameter * static_cast<double>(r.params.size());
  };
  WinnerSelection s;
  const RankedEffect* best_pinned = nullptr;
  for (const auto& r : ranking) {
    if (!changes_where(r.effect) || !r.closed_loop_bounded) continue;
    if (s.top == nullptr) s.top = &r;
    if (!qualifies(r)) continue;
    if (pinned.count(r.effect) != 0) {
      if (best_pinned == nullptr && pinned_within_noise.count(r.effect) == 0) best_pinned = &r;
    } else if (s.winner == nullptr) {
      s.winner = &r;
    }
  }
  if (s.winner == nullptr && best_pinned != nullptr) {
    s.winner = best_pinned;
    s.winner_pinned = true;
  }
  for (const auto& r : ranking) {
    if (&r != s.winner && changes_where(r.effect) && r.closed_loop_bounded) {
      s.runner_up = &r;
      break;
    }
  }
  return s;
}

}  // namespace lane_keeping
