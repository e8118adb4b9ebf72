#pragma once
/// The logged runs stayed bounded, so a fitted effect under which the closed loop of a log diverges
/// contradicts that log, however well it fits the open-loop replays. Requirement, check, and which
/// training logs a fit violates.
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/closed_loop_replay.h"

namespace lane_keeping {
namespace diagnosis {

class CandidateObjective;

/// The closed loop of a fit must stay bounded on `log` over `horizon` seconds from its start, its
/// steering angle within `max_steering_angle` and its torque command within `max_torque`.
struct BoundedLoopRequirement {
  const LogSignals* log;
  const SimConfig* config;  ///< the run's own configuration (before the change under test)
  double horizon;
  double max_steering_angle;
  double max_torque;
};

/// Whether the closed loop of `config` leaves requirement `r`'s bounds on its log: the divergence
/// monitor with its steering-angle limit lowered to r.max_steering_angle, and the torque command.
LoopDivergence boundsCheck(const ConfigChange& change, const BoundedLoopRequirement& r);

/// Whether the nominal's closed loop leaves a requirement's bounds (boundsCheck without a change), run once
/// per requirement and shared by every fit's check (each fit whose loop leaves the bounds compares with it: a 60 s
/// closed loop each, the same every time). Thread-safe.
class NominalBounds {
 public:
  bool leaves(const BoundedLoopRequirement& r);

 private:
  struct Entry {
    std::once_flag once;
    bool leaves = false;
  };
  std::mutex mutex_;
  using Key = std::tuple<const LogSignals*, const SimConfig*, double, double, double>;
  std::map<Key, std::unique_ptr<Entry>> entries_;
};

/// The logged runs stayed bounded, so a fitted effect under which the closed loop of the log diverges
/// contradicts the log, however well it fits the open-loop replays (a column fitted with too little
/// damping does: the steering replay hardly sees the damping, the actuator's PD loop does). Bounded
/// means within the simulator's divergence limits, with the steering angle within 1.5 times the logged
/// range (+ 0.02 rad) and the torque command within twice the logged range (+ 5 N m): a column fitted at
/// the edge of stability kept a 69 Hz oscillation that grew at 0.2 1/s to 0.93 rad and 40 kN m within
/// the log's 30 s, under the monitor's 1.2 rad; one at 0.05 1/s reached 480 N m (logged: 35 N m).
/// Returns the training logs on which the closed loop of theta leaves those bounds where the nominal's
/// does not (empty: theta is consistent with the logs), and says so in `note`.
/// `nominal` (optional) remembers the nominal's loops across fits.
std::vector<BoundedLoopRequirement> stabilityRequirements(const CandidateObjective& objective, const std::vector<double>& theta,
                                                          const std::vector<Dataset>& train, std::string* note,
                                                          NominalBounds* nominal = nullptr);

}  // namespace diagnosis
}  // namespace lane_keeping
