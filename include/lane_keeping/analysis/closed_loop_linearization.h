#pragma once
/// The closed loop linearised about straight-line motion as a delay-differential system
/// (Beregi §3, eqs 17-20, generalised to per-hop delays):
///
///   plant      X'(t)   = A X(t) + b M_S(t - tau_T)                          (eqs 2-8, autodiff)
///   tracker    c(t)    = K P X(t - tau_1)          c = (delta_des, delta_des_dot)       (eq 11)
///   actuator   e(t)    = c_0(t - tau_des) - delta(t - tau_meas),
///              e'(t)   = c_1(t - tau_des) - delta_dot(t - tau_meas),
///              z'(t)   = e(t),   M_S(t) = k_p e(t) + k_d e'(t) + k_i z(t)             (eqs 12-16)
///
/// P maps the state to the pose the tracker reads, K is the tracker's Jacobian (central differences
/// of PathTracker::command on a straight lane) and (k_p, k_d, k_i) are read off
/// SteeringActuator::torque: every coefficient comes from the code the simulator runs. The actuator
/// integrates the error it receives, so z is Beregi's z(t - tau_2) and, with tau_T = 0 and
/// tau_des = tau_meas = tau_2, the delays are exactly eq 20's {tau_2, tau_1 + tau_2}. In general they
/// are {tau_T, tau_meas, tau_T + tau_meas, tau_1 + tau_des, tau_T + tau_1 + tau_des} (merged when equal).
///
/// State: the plant states except x, then z. x is the neutral direction of the paper ("lambda = 0 is
/// always a solution corresponding to the 'neutral' direction x", §3): on a straight lane nothing
/// depends on x (its column is zero) and, at straight-line motion, x' = V has no linear part (its row
/// is zero), so keeping x would only add the trivial root 0 (D(lambda) = lambda D~(lambda)). Any other
/// state whose row and column are both identically zero in every matrix (a state a model holds fixed
/// at straight-line motion) adds a trivial root 0 the same way and is dropped too; the names of all
/// dropped states are reported.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lane_keeping/analysis/linear_delay_system.h"
#include "lane_keeping/analysis/plant_linearization.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

struct LinearizationOptions {
  /// Eq 12 as printed: the derivative term acts on (delta_des_dot - delta_dot). false: on
  /// -delta_dot only (a common PID variant; one of the readings checked against Fig 9).
  bool derivative_on_desired_rate = true;
};

struct ClosedLoopLinearization {
  LinearDelaySystem dde;                    ///< over the kept plant states, then "z"
  std::vector<std::string> dropped_states;  ///< "x" and any frozen states, each adds the root 0
  Eigen::MatrixXd tracker_jacobian;         ///< K: d(delta_des, delta_des_dot)/d(pose), 2 x 6
  double k_p = 0.0, k_d = 0.0, k_i = 0.0;   ///< as SteeringActuator::torque applies them
  double tau_tracker = 0.0, tau_desired = 0.0, tau_measured = 0.0, tau_torque = 0.0;  ///< hop delays [s]
};

/// Linearises the configured closed loop (any tire model). The `path` section is not used: the
/// equilibrium is straight-line motion along a straight lane (Beregi eq 19). Throws ConfigError for
/// an invalid configuration or one without that equilibrium (tracker pose bias), ModelError if the
/// plant has none (disturbance).
ClosedLoopLinearization linearizeClosedLoop(const SimConfig& config, const LinearizationOptions& options = {});

/// Same from an already linearised plant (used by the equation-reading study to swap terms).
ClosedLoopLinearization assembleClosedLoop(const SimConfig& config, const PlantLinearization& plant,
                                           const LinearizationOptions& options = {});

}  // namespace lane_keeping
