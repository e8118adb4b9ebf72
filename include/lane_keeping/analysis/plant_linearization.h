#pragma once
/// Linearisation of the vehicle plant about straight-line motion, by automatic differentiation
/// (ceres::Jet) through the very SingleTrackModel::derivative the simulator integrates — any tire
/// model, any number of tire and steering-system states, no hand-typed matrices (Beregi eqs 2-8
/// linearised as in §3; Appendix B of the paper is garbled OCR and not used).
///
/// Equilibrium (Beregi eq 19): x = y = psi = delta = sigma_i = 0, tire and steering states relaxed
/// (zero), M_S = 0; the state derivative there is V along x and zero elsewhere.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

struct PlantLinearization {
  Eigen::VectorXd equilibrium;  ///< state of straight-line motion at x = 0
  Eigen::VectorXd drift;        ///< state derivative there: (V, 0, ..., 0)
  Eigen::MatrixXd a;            ///< d(state_dot)/d(state), full model state (x included)
  Eigen::VectorXd b;            ///< d(state_dot)/d(M_S) [per N m]
  Eigen::Matrix3d mass;         ///< generalised mass matrix of eq 4 at delta = 0
  std::vector<std::string> state_names;

  int size() const { return static_cast<int>(a.rows()); }
  /// Rows of the pose the tracker reads (VehiclePlant::pose(): x, y, psi, x_dot, y_dot, yaw_rate)
  /// as linear functions of the state (6 x size()).
  Eigen::MatrixXd poseJacobian() const;
};

/// Linearises `model` about straight-line motion. Throws ModelError if that is not an equilibrium
/// (e.g. a constant disturbance force is configured) or a derivative is not finite.
PlantLinearization linearizePlant(const SingleTrackModel& model);

/// Names of the model's states: x, y, psi, delta, sigma1..3, steering[i], front_tire[i], rear_tire[i].
std::vector<std::string> plantStateNames(const SingleTrackModel& model);

}  // namespace lane_keeping
