#include "node_changes.h"

#include <algorithm>

#include <xmlrpcpp/XmlRpcValue.h>

#include "conversions.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/ParameterChange.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

/// ~changes: absent -> none; otherwise a list of strings.
std::vector<std::string> readChangeList(const ros::NodeHandle& pnh) {
  const std::string key = pnh.resolveName("changes");
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam("changes", value)) return {};
  std::vector<std::string> out;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {  // one change given as a plain string
    out.push_back(static_cast<std::string>(value));
    return out;
  }
  if (value.getType() != XmlRpc::XmlRpcValue::TypeArray) {
    throw ConfigError(std::vector<ConfigProblem>{
        {key, "ROS parameter", "must be a list of \"T:key=value\" strings, e.g. ['10:steering.coulomb_friction=3']"}});
  }
  for (int i = 0; i < value.size(); ++i) {
    if (value[i].getType() != XmlRpc::XmlRpcValue::TypeString) {
      throw ConfigError(std::vector<ConfigProblem>{
          {key + "[" + std::to_string(i) + "]", "ROS parameter", "must be a \"T:key=value\" string (quote it in YAML)"}});
    }
    out.push_back(static_cast<std::string>(value[i]));
  }
  return out;
}

std::string seconds(Nanoseconds t) { return formatNumber(nanosecondsToSeconds(t)) + " s"; }

}  // namespace

NodeChanges::NodeChanges(ros::NodeHandle nh, const ros::NodeHandle& pnh, const SimConfig& config, LoopRole role,
                         std::string name)
    : name_(std::move(name)), role_(role), schedule_(config) {
  configured_ = readChangeList(pnh);
  std::vector<TimedChange> list;
  for (const auto& text : configured_) list.push_back(parseTimedChange(text));
  schedule_.addAll(list, pnh.resolveName("changes"));
  for (const ScheduledChange& change : schedule_.changes()) {
    if (change.owner == role_) waiting_.push_back(change);
  }
  publisher_ = nh.advertise<ParameterChange>(topics::kParameterChanges, 100);
}

void NodeChanges::announce(const ScheduledChange& change) { publisher_.publish(toParameterChangeMsg(change, name_)); }

void NodeChanges::announceConfigured() {
  if (announced_configured_) return;
  announced_configured_ = true;
  for (const ScheduledChange& change : schedule_.changes()) {
    if (change.owner != role_) continue;
    announce(change);
    ROS_INFO("%s: %s %s -> %s from t = %s (%s)", name_.c_str(), change.key.c_str(), change.old_value.c_str(),
             change.new_value.c_str(), seconds(change.stamp).c_str(), change.origin.c_str());
  }
}

std::vector<ScheduledChange> NodeChanges::request(double apply_at,
                                                 const std::vector<std::pair<std::string, std::string>>& assignments,
                                                 Nanoseconds earliest) {
  const std::string origin = "reconfigure (apply_at " + formatNumber(apply_at) + " s, next sample at " +
                             seconds(earliest) + ")";
  std::vector<ScheduledChange> records = schedule_.add(apply_at, assignments, origin, earliest);
  for (const ScheduledChange& change : records) {
    waiting_.insert(std::upper_bound(waiting_.begin(), waiting_.end(), change.stamp,
                                     [](Nanoseconds t, const ScheduledChange& c) { return t < c.stamp; }),
                    change);
    announce(change);
    const bool late = apply_at > 0.0 && change.stamp > secondsToNanoseconds(apply_at) &&
                      earliest > secondsToNanoseconds(apply_at);
    ROS_INFO("%s: %s %s -> %s from t = %s (%s%s); reproduce with lk_simulate --change %s", name_.c_str(),
             change.key.c_str(), change.old_value.c_str(), change.new_value.c_str(), seconds(change.stamp).c_str(),
             origin.c_str(), late ? ": apply_at had passed, so the next sample" : "", change.argument().c_str());
  }
  return records;
}

std::vector<ScheduledChange> NodeChanges::takeEffective(Nanoseconds reached) {
  std::vector<ScheduledChange> out;
  while (!waiting_.empty() && waiting_.front().stamp <= reached) {
    const ScheduledChange& change = waiting_.front();
    ROS_INFO("%s: %s = %s in effect at t = %s (was %s)", name_.c_str(), change.key.c_str(), change.new_value.c_str(),
             seconds(change.stamp).c_str(), change.old_value.c_str());
    out.push_back(change);
    waiting_.erase(waiting_.begin());
  }
  return out;
}

}  // namespace lane_keeping
