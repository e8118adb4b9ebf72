#include "lane_keeping/control/path_tracker.h"

#include <cmath>

namespace lane_keeping {

SteeringCommand PathTracker::command(const PoseSample& pose, PathErrors* errors) const {
  // The tracker sees the pose through its localisation, with the configured bias (0 by default).
  const PathErrors e = path_->errors(pose.x, pose.y + params_.pose_bias_y, pose.psi + params_.pose_bias_psi, pose.x_dot,
                                     pose.y_dot, pose.yaw_rate);
  if (errors != nullptr) *errors = e;
  SteeringCommand command;
  command.delta_des = -params_.k_psi * std::sin(e.heading) - params_.k_y * e.lateral;                            // eq 11
  command.delta_des_rate = -params_.k_psi * std::cos(e.heading) * e.heading_rate - params_.k_y * e.lateral_rate;  // d/dt eq 11
  return command;
}

}  // namespace lane_keeping
