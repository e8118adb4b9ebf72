#pragma once
/// The logged speed as the model needs it. The single-track model's speed is V of Beregi eq 1, the front
/// axle's speed along its wheel; a log's `v` column holds the speed of the centre of gravity G unless its
/// mapping says otherwise (`v: {column: ..., speed_of: front_axle}`, log_mapping.h): that is what lk_simulate and the nodes
/// write, and what a vehicle bus (wheel speeds) or a GNSS receiver gives. So the diagnosis converts it,
/// once per run where its configuration is known (diagnosis_data.cpp prepareRuns), and its closed-loop
/// runs follow the logged speed as a profile in time (vehicle.speed_profile, speed_profile.h).

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

/// V of eq 1 from the speed of G: rows 1-2 of eq 1 give G's velocity in the body frame (u, sigma1), and
/// the front axle's wheel-direction speed is V = u cos(delta) + (sigma1 + b sigma2) sin(delta), with
/// u = sqrt(v_G^2 - sigma1^2) (0 if sigma1 exceeds v_G, a noisy standstill). [m/s]
/// @param cg_speed |velocity of G| [m/s]; @param sigma1 lateral velocity of G, body frame [m/s];
/// @param yaw_rate sigma2 [rad/s]; @param delta steering angle [rad]; @param cg_to_front_axle b = l - d [m].
double frontAxleSpeed(double cg_speed, double sigma1, double yaw_rate, double delta, double cg_to_front_axle);

/// Whether the log's v is a centre-of-gravity speed that the replays must convert (it has v, of G).
bool holdsCentreOfGravitySpeed(const GapLog& log);

/// The log with v converted to V (and GapLog::speed_of kFrontAxle), sample by sample with frontAxleSpeed: the
/// logged steering angle and yaw rate (0 where the log lacks them), the lateral velocity from the pose
/// (LogSignals::kSigma1; 0 without a pose: a bus log's speed is then taken as u), b of `vehicle`. Sensor
/// biases are not removed: a heading mount of 1 deg turns sigma1 by u sin(1 deg), which moves V by
/// sigma1^2 / (2 v) (millimetres per second). A log that holdsCentreOfGravitySpeed() denies comes back as it is.
GapLog withFrontAxleSpeed(const LogSignals& signals, const VehicleParams& vehicle);

/// The logged speed (LogSignals::kSpeed, V once prepared) as a profile in time for vehicle.speed_profile:
/// smoothed (local quadratic over +-`half_width` s, zero lag) and sampled at `rate` Hz from the log's start,
/// which is the closed loop's t = 0, to its end (the last point at the end). Throws InputError if the log
/// has no speed.
PointList speedProfileFromLog(const LogSignals& log, double rate = 10.0, double half_width = 0.1);

/// `config` driving as the logged car drove: when the log's speed varies (LogSignals::speedVaries), its
/// speedProfileFromLog as vehicle.speed_profile (and no speed varying along the road); otherwise `config`
/// as it is (its constant speed, or its own profile). For every closed loop simulated over a log.
SimConfig withLoggedSpeed(SimConfig config, const LogSignals& log);

}  // namespace lane_keeping
