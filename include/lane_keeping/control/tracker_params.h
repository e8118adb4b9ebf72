#pragma once
/// Higher-level controller: desired steering angle from the delayed path errors (Beregi eq 11).
#include <string>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct TrackerParams {
  double k_psi = 0.8;    ///< heading gain [1] (Beregi eq 11; Fig 6 value)
  double k_y = 0.01;     ///< lateral-offset gain [1/m] (Beregi eq 11; Fig 6 value)
  double rate = 1000.0;  ///< output sample rate [Hz]
  double pose_bias_y = 0.0;    ///< [m] added to the y the tracker sees (localisation bias); 0 = none
  double pose_bias_psi = 0.0;  ///< [rad] added to the yaw the tracker sees; 0 = none

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "k_psi", k_psi, "", Range::any(), "k_psi, heading-error gain (Beregi eq 11)");
    v.number(prefix + "k_y", k_y, "1/m", Range::any(), "k_y, lateral-offset gain (Beregi eq 11)");
    v.number(prefix + "rate", rate, "Hz", Range::closed(1.0, 1e7), "sample rate of the desired steering angle");
    v.number(prefix + "pose_bias_y", pose_bias_y, "m", Range::any(),
             "bias added to the lateral position the tracker sees (localisation error); 0 = none");
    v.number(prefix + "pose_bias_psi", pose_bias_psi, "rad", Range::closed(-1.0, 1.0),
             "bias added to the yaw angle the tracker sees; 0 = none");
  }
};

}  // namespace lane_keeping
