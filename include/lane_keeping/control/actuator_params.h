#pragma once
/// Lower-level controller: PID steering torque (Beregi eqs 12-16), gains k = p k_0.
#include <string>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct ActuatorParams {
  double p = 2000.0;     ///< control strength (eqs 14-16)
  double k_p0 = 8.0;     ///< [N m/rad]
  double k_d0 = 0.1;     ///< [N m s/rad]
  double k_i0 = 0.5;     ///< [N m/(rad s)]
  double rate = 10000.0; ///< torque sample rate [Hz]

  double kp() const { return p * k_p0; }
  double kd() const { return p * k_d0; }
  double ki() const { return p * k_i0; }

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "p", p, "", Range::nonNegative(), "control strength p: k = p k_0 (Beregi eqs 14-16)");
    v.number(prefix + "k_p0", k_p0, "N m/rad", Range::any(), "proportional gain per unit p");
    v.number(prefix + "k_d0", k_d0, "N m s/rad", Range::any(), "derivative gain per unit p");
    v.number(prefix + "k_i0", k_i0, "N m/(rad s)", Range::any(), "integral gain per unit p");
    v.number(prefix + "rate", rate, "Hz", Range::closed(1.0, 1e7), "steering-torque sample rate");
  }
};

}  // namespace lane_keeping
