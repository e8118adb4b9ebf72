#pragma once
/// The steering angle at which the car goes straight: the second thing a vehicle-dynamics engineer reads off a
/// bus log before any model (after the gyro against the heading, heading_agreement.h). Where the car holds a
/// straight line — yaw rate and lateral acceleration near zero for at least 2 s above 5 m/s — the road-wheel
/// angle less the little the path's curvature asks for (l r / V, the kinematic steer; the understeer term
/// vanishes with a_y) is what the single-track model would need to be zero. A logged value away from zero is a
/// steering sensor's zero, or a pull the model lacks (tire conicity, an alignment's toe or camber split): the
/// model reads either as a steering offset, and a log mapping's offset corrects either. A crosswind asks for
/// steer at zero a_y too, but turns its sign with the direction of travel: the straights' courses are listed.
/// (On the race car's laps: +4.5 to +5.6 mrad at the road wheel on each, the main straight and the short
/// straight 169 degrees apart alike; docs/real_logs/super_fj_fuji.md.) Model-free but for the wheelbase.
#include <string>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/input_checks.h"

namespace lane_keeping {

/// One stretch the car drove straight.
struct StraightStretch {
  double t0 = 0.0, t1 = 0.0;   ///< [s] in the log's own time
  double offset = 0.0;         ///< [rad] mean road-wheel angle less the kinematic steer l r / V
  double sigma = 0.0;          ///< [rad] its standard error (effective sample count, as heading_agreement.h)
  double course = 0.0;         ///< [rad] mean psi over it (a course or a heading), to tell directions apart
};

struct StraightLineSteering {
  std::vector<StraightStretch> stretches;
  double offset = 0.0, sigma = 0.0;  ///< [rad] inverse-variance mean over the stretches, its standard error
  /// The offset differs from 0 by more than 3 sigma and kSteeringZeroTolerance, and no stretch contradicts the
  /// mean (beyond 3 of its sigma and the tolerance).
  bool found = false;
};

/// [rad] road-wheel angle below which a zero offset is not reported (0.06 degrees; 1 degree at a 17:1 wheel).
constexpr double kSteeringZeroTolerance = 1e-3;

/// The straight stretches of `log` (yaw rate, speed and the road-wheel angle needed; ay used where logged) on a
/// car of wheelbase `wheelbase`; the gyro's drift `yaw_rate_bias` [rad/s] taken out first (heading_agreement.h
/// measures it).
StraightLineSteering straightLineSteering(const GapLog& log, double wheelbase, double yaw_rate_bias = 0.0);

/// The finding as an input check of kind `offset` on `delta` (none where nothing is found).
std::vector<InputCheck> straightLineSteeringChecks(const GapLog& log, double wheelbase, double yaw_rate_bias = 0.0);

}  // namespace lane_keeping
