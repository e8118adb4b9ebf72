#pragma once
/// In-process lockstep run of the three components over delay lines — the same stage classes the
/// ROS nodes drive, scheduled by the same rule: each computes its output for time t as soon as
/// all of its inputs cover t; the plant steps once the torque covers its step.
#include <functional>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/sim/change_schedule.h"
#include "lane_keeping/sim/log_row.h"

namespace lane_keeping {

struct RunResult {
  enum class Status { kCompleted, kDiverged };
  Status status = Status::kCompleted;
  std::string message;     ///< why a run diverged
  double end_time = 0.0;   ///< simulated time reached [s]
  std::vector<LogRow> rows;
  long plant_steps = 0;
  /// The runtime changes that took effect (stamped no later than the end), in the schedule's order.
  std::vector<ScheduledChange> changes;
  bool diverged() const { return status == Status::kDiverged; }
};

class ClosedLoop {
 public:
  /// Validates the configuration (throws ConfigError) and checks that the lockstep schedule can
  /// advance (throws ScheduleError naming the delays otherwise).
  explicit ClosedLoop(SimConfig config);
  /// With changes during the run ("T:key=value", lk_simulate --change): each is checked by the
  /// schedule's rules (change_schedule.h; throws ConfigError naming the change and the key).
  ClosedLoop(SimConfig config, const std::vector<TimedChange>& changes);

  /// Runs for simulation.duration. `on_row` sees each log row as it is recorded.
  RunResult run(const std::function<void(const LogRow&)>& on_row = nullptr) const;

  /// The configuration before any change.
  const SimConfig& config() const { return config_; }
  const ChangeSchedule& changes() const { return changes_; }

 private:
  SimConfig config_;
  ChangeSchedule changes_;
};

/// Throws ScheduleError if the loop's delays give the lockstep schedule no way to advance (e.g. a
/// linear torque hold needs the torque one step ahead, so tau2 + torque delay must cover a step).
void checkLockstepFeasible(const SimConfig& config);

}  // namespace lane_keeping
