#include "lane_keeping/sim/change_owner.h"

#include <vector>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

[[noreturn]] void fixed(const std::string& key, const std::string& why) {
  throw ConfigError(std::vector<ConfigProblem>{{key, "", "cannot change during a run: " + why}});
}

}  // namespace

const char* roleName(LoopRole role) {
  switch (role) {
    case LoopRole::kTracker:
      return "path_tracking";
    case LoopRole::kActuator:
      return "steering_actuator";
    case LoopRole::kPlant:
      return "vehicle_plant";
  }
  return "?";
}

LoopRole changeOwner(const std::string& key) {
  if (key == "tracker.rate" || key == "actuator.rate" || key == "simulation.step") {
    fixed(key, "it sets a sample grid, on which every stamp of the run lies");
  }
  if (key == "delays.hold") fixed(key, "it sets how every delay line reads between samples");
  if (startsWith(key, "simulation.")) {
    fixed(key, "simulation.* describes the run itself (duration, log, initial state, divergence limits)");
  }
  if (startsWith(key, "path.")) fixed(key, "the lane is what the tracker follows and the log measures against");
  if (startsWith(key, "sensors.") || key == "steering.angle_sensor") {
    fixed(key, "the sensor model keeps a history of the motion shaped by it");
  }
  if (startsWith(key, "tracker.") || key == "delays.pose_to_tracker") return LoopRole::kTracker;
  if (startsWith(key, "actuator.") || key == "delays.desired_steering_to_actuator" ||
      key == "delays.steering_angle_to_actuator") {
    return LoopRole::kActuator;
  }
  if (startsWith(key, "vehicle.") || startsWith(key, "steering.") || startsWith(key, "disturbance.") ||
      startsWith(key, "tire.") || key == "delays.torque_to_plant") {
    return LoopRole::kPlant;
  }
  fixed(key, "no component of the loop owns it");
}

}  // namespace lane_keeping
