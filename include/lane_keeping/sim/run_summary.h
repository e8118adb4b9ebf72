#pragma once
/// What a control engineer wants to know after a run: offsets, settling, peaks, the dominant
/// oscillation of the lateral (e_y) and steering (delta - delta_des) channels and whether each
/// grows or decays, and how the run ended.
#include <string>
#include <vector>

#include "lane_keeping/sim/oscillation.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"

namespace lane_keeping {

struct RunSummary {
  std::string scenario;
  bool diverged = false;
  std::string stop_message;
  double duration = 0.0;         ///< simulated time reached [s]
  double final_lateral_offset = 0.0;   ///< e_y at the end [m]
  double peak_lateral_offset = 0.0;    ///< max |e_y| [m]
  double peak_lateral_offset_time = 0.0;
  double settling_time = -1.0;         ///< [s]; < 0 if never settled within the run
  double settling_band = 0.0;          ///< [m]
  double peak_steering_angle = 0.0;    ///< max |delta| [rad]
  double peak_torque = 0.0;            ///< max |M_S| [N m]
  double peak_lateral_acceleration = 0.0;  ///< max |a_y| [m/s^2]
  double peak_slip_angle = 0.0;        ///< max(|alpha_F|, |alpha_R|) [rad]
  bool left_lane = false;              ///< |e_y| exceeded half the lane width at some time
  OscillationEstimate lateral;         ///< of e_y
  OscillationEstimate steering;        ///< of delta - delta_des
  /// The runtime changes that took effect, one line each (ScheduledChange::describe), by stamp then key.
  std::vector<std::string> changes;
};

/// The summary lines of runtime changes: sorted by stamp then key (sortForSummary), described.
std::vector<std::string> describeChanges(std::vector<ScheduledChange> changes);

RunSummary summarizeRun(const SimConfig& config, const RunResult& result);
/// Human-readable multi-line text.
std::string formatSummary(const RunSummary& summary);

}  // namespace lane_keeping
