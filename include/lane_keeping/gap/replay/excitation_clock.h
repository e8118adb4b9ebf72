#pragma once
/// The clock of the identification excitation in a log. The path tracker adds a known multisine e(tau)
/// to its output (tracker.excitation_*, path_tracker.h), tau being the tracker's own clock; the diagnosis
/// evaluates it at the log's t + `tracker.excitation_clock_offset`, in the tracker's replay (pose ->
/// delta_des) and in every simulation of the logged run (the noise-only draws, the closed-loop replays).
/// With the offset 0 that assumes the log's clock is the tracker's, which a log whose t was shifted does
/// not keep (rebased to 0, a logger with another origin): shifted by +0.5 s, a no-effect log was
/// "detected at p = 0.05" with a tracker gap; by 1000 s, a steering-friction log lost its verdict.
///
/// The offset is found from the log: delta_des minus the tracker's law (Beregi eq 11) on the logged pose
/// is the multisine plus noise; least squares give each of its sines' phase, and the offset is where the
/// multisine's own phases agree with them best (coherence 1 = every sine in phase), searched around
/// the two origins a log has (its own clock and the time since its first sample, +-60 s each). The log's
/// own clock is kept when it fits (coherence >= 0.9), when no offset fits well (< 0.7, the excitation not
/// found), and when the whole delta_des channel, the tracker's law included, looks late by the offset:
/// that is a channel logged late, left to the candidates to explain.
#include <string>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

struct ExcitationClock {
  double offset = 0.0;                  ///< [s] the excitation runs on the log's t + offset
  double coherence_at_log_clock = 0.0;  ///< in [-1, 1], at offset 0
  double coherence = 0.0;               ///< in [-1, 1], at the best offset found
  double best_offset = 0.0;             ///< [s] where the coherence is largest
  std::string note;                     ///< what was found, for the report ("" when the log's clock fits)
};

/// The excitation's clock in `log` under `config` (offset 0 without an excitation or a tracker replay).
ExcitationClock estimateExcitationClock(const SimConfig& config, const LogSignals& log);

}  // namespace lane_keeping
