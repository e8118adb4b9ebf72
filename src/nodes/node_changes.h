#pragma once
/// The runtime changes of one node (docs/ros.md, "Runtime tuning") — the ROS side only; parsing,
/// validation and stamping are the core's (config/timed_change.h, sim/change_schedule.h):
///  * the private parameter ~changes, a list of "T:key=value", read into the core ChangeSchedule. Every
///    node checks the whole list (each entry on the configuration in force at its time), so a bad entry
///    stops every node with the same message naming it; each node applies the keys it owns.
///  * live requests (dynamic_reconfigure) added to the same schedule, no earlier than the node's next
///    sample;
///  * each of the node's changes announced on `parameter_changes` (msg/ParameterChange) as soon as its
///    stamp is fixed — ~changes entries when the run starts, a live request when it is accepted — and
///    logged (ROS_INFO: key, old, new, stamp) when scheduled and when it takes effect.
/// Shared by the three roles.
#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/change_schedule.h"

namespace lane_keeping {

class NodeChanges {
 public:
  /// Reads ~changes from `pnh` and advertises parameter_changes on `nh`. Throws ConfigError naming the
  /// entry and the key.
  NodeChanges(ros::NodeHandle nh, const ros::NodeHandle& pnh, const SimConfig& config, LoopRole role, std::string name);

  const ChangeSchedule& schedule() const { return schedule_; }
  /// The configuration the run starts with (the changes at stamp 0 applied).
  const SimConfig& start() const { return schedule_.start(); }
  LoopRole role() const { return role_; }

  /// Announces the node's own ~changes entries (once; when the run has started, so that the plant and
  /// a recorder are connected).
  void announceConfigured();
  /// A live request for the node's keys ("key" -> value text), taking effect together at the node's
  /// first sample at or after `apply_at` [s] (0: the next sample) and not before `earliest` [ns] (its
  /// next sample). Logs, announces and returns the records. Throws ConfigError naming the key and why.
  std::vector<ScheduledChange> request(double apply_at, const std::vector<std::pair<std::string, std::string>>& assignments,
                                       Nanoseconds earliest);
  /// The node's changes stamped at or before `reached` [ns] (the latest sample it has computed) not
  /// returned before: each logged as having taken effect.
  std::vector<ScheduledChange> takeEffective(Nanoseconds reached);
  /// ~changes as given (for the startup log).
  const std::vector<std::string>& configured() const { return configured_; }

 private:
  void announce(const ScheduledChange& change);

  std::string name_;
  LoopRole role_;
  ChangeSchedule schedule_;
  ros::Publisher publisher_;
  std::vector<std::string> configured_;
  std::vector<ScheduledChange> waiting_;  // own changes not yet in effect, by stamp
  bool announced_configured_ = false;
};

}  // namespace lane_keeping
