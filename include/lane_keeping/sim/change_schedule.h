#pragma once
/// The configuration changes of one run (runtime tuning; docs/ros.md "Runtime tuning"): the
/// configuration the run starts with, and changes that each hold from a stamp on.
///
/// A change is validated when it is added, by the rules a configuration file obeys — the key is read
/// by the configuration's reader and the result passes validate() (config_assignments.h), and a
/// change of a delay leaves a lockstep schedule that can advance (checkLockstepFeasible) — plus two
/// that a running loop adds: the key is one a component can change mid-run (change_owner.h), and a
/// plant change keeps the model's state layout (the state carries over; at t = 0 anything goes: that
/// is the starting configuration). Each change is checked on the configuration in force when it takes
/// effect: the initial one with every change requested before it (changes with equal times in the
/// order they were added), and the changes after it are checked again on the result.
///
/// Time: a change requested for t takes effect at its owner's first sample stamped >= t — its stamp,
/// on the owner's grid (path tracker: 1 / tracker.rate, actuator: 1 / actuator.rate, plant:
/// simulation.step; all grids start at 0). Every sample its owner computes at or after the stamp uses
/// the new value, earlier ones the old: for the plant, the sample at the stamp (state outputs, the log
/// row) and every step from it; for a delay tau, tau(t) is a right-continuous step function of the
/// consumer's time and the value for time t is its input at t - tau(t) (delay_line.h). Changes at
/// stamp 0 form the configuration the run starts with (start()).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/common/time.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/sim/change_owner.h"

namespace lane_keeping {

/// The record of one scheduled change (what the summary lists and msg/ParameterChange.msg carries).
struct ScheduledChange {
  Nanoseconds stamp = 0;   ///< effective time [ns], on the owner's grid
  std::string key;         ///< full dotted configuration key
  std::string old_value;   ///< in force just before `stamp` (as the configuration prints it)
  std::string new_value;   ///< from `stamp` on
  LoopRole owner = LoopRole::kPlant;
  std::string origin;      ///< where it came from: "--change", "~changes", "reconfigure", ...

  /// "T:key=value" with T = stamp in seconds: the lk_simulate --change argument that reproduces it.
  std::string argument() const;
  /// "t = 10 s: steering.coulomb_friction 0 -> 3 (vehicle_plant)".
  std::string describe() const;
};

/// Sorted by stamp, then key (stable): the order a summary lists them in, whatever runner made them.
void sortForSummary(std::vector<ScheduledChange>& changes);

class ChangeSchedule {
 public:
  struct Entry {
    ScheduledChange change;
    std::shared_ptr<const SimConfig> after;  ///< the configuration with this change and every one before it
    Nanoseconds order = 0;                   ///< requested time [ns] (not before `earliest`): the order of checks
    int group = 0;                           ///< changes added together share a group
    std::string assignment;                  ///< "key=value" as given
  };

  /// @param initial the run's configuration before any change (valid: the caller validated it).
  explicit ChangeSchedule(SimConfig initial);

  /// Adds the changes of a list ("T:key=value" parsed; lk_simulate --change, a node's ~changes),
  /// the ones with equal T together. Throws ConfigError naming the change and the key.
  void addAll(const std::vector<TimedChange>& list, const std::string& origin);
  /// Adds assignments ("key" -> "value" text) requested for time t [s] that are checked and take
  /// effect together (e.g. both tau2 delays), none before `earliest` [ns] (a running component's next
  /// sample). Returns their records. Throws ConfigError naming the key and why; then nothing is added.
  std::vector<ScheduledChange> add(double t, const std::vector<std::pair<std::string, std::string>>& assignments,
                                   const std::string& origin, Nanoseconds earliest = 0);

  bool empty() const { return entries_.empty(); }
  const std::vector<Entry>& entries() const { return entries_; }
  /// Every record, in the order of the checks.
  std::vector<ScheduledChange> changes() const;
  /// The configuration before any change.
  const SimConfig& initial() const { return initial_; }
  /// The configuration the run starts with: initial() with the changes at stamp 0.
  const SimConfig& start() const;
  /// The configuration whose `role` keys are in force at stamp t [ns] (other keys may be ahead).
  const SimConfig& configFor(LoopRole role, Nanoseconds t) const;
  /// The grid period of a role [ns] (the stamps of its changes are multiples of it).
  Nanoseconds gridOf(LoopRole role) const;

 private:
  /// Checks the entries from `first` on against the chain before them; throws ConfigError.
  void recheck(std::vector<Entry>& entries, std::size_t first) const;
  void checkEntryGroup(const SimConfig& before, const SimConfig& after,
                       const std::vector<const Entry*>& group) const;

  SimConfig initial_;
  std::vector<Entry> entries_;
  int next_group_ = 0;
};

}  // namespace lane_keeping
