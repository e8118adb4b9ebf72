#include "lane_keeping/gap/replay/subsystem_replay.h"

#include <map>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

const std::vector<std::string>& subsystemNames() {
  static const std::vector<std::string> names{"steering", "chassis", "tracker", "actuator"};
  return names;
}

SubsystemReplay replaySubsystem(const std::string& name, const SimConfig& config, const LogSignals& log,
                                const std::vector<TimeSegment>& segments, const ReplayOptions& options) {
  if (name == "tracker") return replayTracker(config, log, segments);
  if (name == "actuator") return replayActuator(config, log, segments);
  if (name == "steering") return replaySteering(config, log, segments, options, nullptr);
  if (name == "chassis") return replayChassis(config, log, segments, options);
  throw LaneKeepingError("unknown subsystem '" + name + "'");
}

std::string replayUnavailable(const std::string& subsystem, const GapLog& log) {
  static const std::map<std::string, std::vector<std::string>> needs{
      {"tracker", {"x", "y", "psi", "yaw_rate", "delta_des"}},
      {"actuator", {"delta_des", "delta", "torque"}},
      // The steering replay's lateral velocity comes from the chassis replay, which needs no pose: a
      // vehicle bus's speed, steering angle and yaw rate (and a_y) are enough (chassis_replay.h).
      {"steering", {"torque", "delta", "yaw_rate"}},
      {"chassis", {"delta", "yaw_rate"}}};
  const auto it = needs.find(subsystem);
  if (it == needs.end()) throw LaneKeepingError("unknown subsystem '" + subsystem + "'");
  std::vector<std::string> absent, unscaled;
  for (const auto& column : it->second) {
    if (!log.has(column)) absent.push_back(column);
    else if (!log.has(column, true)) unscaled.push_back(column);
  }
  std::string why;
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
    return s;
  };
  if (!absent.empty()) why = "the log has no " + list(absent);
  if (!unscaled.empty()) why += (why.empty() ? "" : "; ") + list(unscaled) + " in unknown units (log mapping: unscaled)";
  return why;
}

}  // namespace lane_keeping
