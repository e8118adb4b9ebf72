#include "lane_keeping/gap/subsystem_replay.h"

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

}  // namespace lane_keeping
