#include "lane_keeping/sim/divergence_monitor.h"

#include "lane_keeping/vehicle/single_track_model.h"

#include <cmath>
#include <sstream>

namespace lane_keeping {

std::string DivergenceMonitor::describeStep(const Eigen::VectorXd& state) const {
  static_assert(kDelta == 3, "checkStep reads the steering angle at index 3");
  if (!state.allFinite()) return "the state became non-finite (NaN/Inf)";
  const double delta = state[kDelta];
  std::ostringstream out;
  out << "|steering angle| = " << std::fabs(delta) << " rad exceeds simulation.divergence.max_steering_angle = "
      << limits_.max_steering_angle << " rad (steering oscillation out of bounds)";
  return out.str();
}

std::optional<std::string> DivergenceMonitor::check(const VehicleStateSample& s, const PathErrors& e) const {
  if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(s.psi) || !std::isfinite(s.delta)) {
    return std::string("the state became non-finite (NaN/Inf)");
  }
  if (std::fabs(s.delta) > limits_.max_steering_angle) {
    std::ostringstream out;
    out << "|steering angle| = " << std::fabs(s.delta) << " rad exceeds simulation.divergence.max_steering_angle = "
        << limits_.max_steering_angle << " rad (steering oscillation out of bounds)";
    return out.str();
  }
  if (std::fabs(e.heading) > limits_.max_heading_error) {
    std::ostringstream out;
    out << "|heading error| = " << std::fabs(e.heading) << " rad exceeds simulation.divergence.max_heading_error = "
        << limits_.max_heading_error << " rad (the car is spinning out)";
    return out.str();
  }
  if (std::fabs(e.lateral) > limits_.max_lateral_offset) {
    std::ostringstream out;
    out << "|lateral offset| = " << std::fabs(e.lateral) << " m exceeds simulation.divergence.max_lateral_offset = "
        << limits_.max_lateral_offset << " m (the car left the road)";
    return out.str();
  }
  return std::nullopt;
}

}  // namespace lane_keeping
