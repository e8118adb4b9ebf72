#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

SingleTrackModel::SingleTrackModel(const VehicleParams& params, Tire front, Tire rear)
    : SingleTrackModel(params, SteeringParams{}, DisturbanceParams{}, std::move(front), std::move(rear)) {}

SingleTrackModel::SingleTrackModel(const VehicleParams& params, const SteeringParams& steering,
                                   const DisturbanceParams& disturbance, Tire front, Tire rear)
    : p_(params),
      steering_(steering),
      disturbance_(disturbance),
      plain_steering_(steering.torque_limit == 0.0 && steering.dead_band == 0.0 && !steering.hasFriction() &&
                      !steering.compliant()),
      soft_saturation_(steering.softSaturation()),
      lugre_friction_(steering.lugreFriction()),
      unsensed_disturbance_(disturbance.active() && !disturbance.sensedByAccelerometer()),
      front_(std::move(front)),
      rear_(std::move(rear)),
      inv_V_(1.0 / params.speed),
      inv_JF_(1.0 / params.steering_inertia),
      speed_k_(2.0 * M_PI / params.speed_wavelength),
      front_offset_(kRigidStateSize + steering.stateSize()),
      rear_offset_(front_offset_ + front_.stateSize()),
      state_size_(rear_offset_ + rear_.stateSize()),
      front_half_length_(front_.contactHalfLength()),
      rear_half_length_(rear_.contactHalfLength()) {
  if (!params.speed_profile.empty()) {
    speed_profile_ = std::make_shared<const SpeedProfile>(params.speed_profile.points());
    followSpeedProfile(0.0);
  }
}

Eigen::VectorXd SingleTrackModel::initialState(const InitialState& initial) const {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(stateSize());
  x[kX] = initial.x;
  x[kY] = initial.y;
  x[kPsi] = initial.psi;
  x[kDelta] = initial.delta;
  x[kSigma1] = initial.sigma1;
  x[kSigma2] = initial.sigma2;
  x[kSigma3] = initial.sigma3;
  if (steering_.compliant()) x[steeringStateOffset()] = initial.delta;  // relaxed column
  return x;
}

Eigen::Matrix3d SingleTrackModel::massMatrix(double delta) const {
  // Beregi eq 4.
  const double b = p_.cgToFrontAxle(), m = p_.mass, mF = p_.steering_mass;
  const double c = std::cos(delta), s = std::sin(delta);
  const double mixed = (mF + m * s * s) / (c * c);
  Eigen::Matrix3d M;
  M << (mF + m) / (c * c), mixed * b, 0.0,
       mixed * b, p_.steering_inertia + p_.yaw_inertia + mixed * b * b, p_.steering_inertia,
       0.0, p_.steering_inertia, p_.steering_inertia;
  return M;
}

SingleTrackModel createVehicleModel(const VehicleParams& vehicle, const TireParams& front, const TireParams& rear) {
  return createVehicleModel(vehicle, SteeringParams{}, DisturbanceParams{}, front, rear);
}

SingleTrackModel createVehicleModel(const VehicleParams& vehicle, const SteeringParams& steering,
                                    const DisturbanceParams& disturbance, const TireParams& front,
                                    const TireParams& rear) {
  return SingleTrackModel(vehicle, steering, disturbance, createTire(front, vehicle.frontAxleLoad()),
                          createTire(rear, vehicle.rearAxleLoad()));
}

}  // namespace lane_keeping
