#pragma once
/// The unmodelled effects the diagnosis can name (DESIGN §5), each a parametric change of the
/// nominal configuration that the simulator runs as it is (so a user adds the diagnosed effect to
/// their config and sees the gap close). Parameters are SI; `log_scale` ones are fitted in log space.
///
///   effect               parameters (units)                      config keys it changes
///   tire_lag             relaxation_length (m)                   tire.{front,rear}.relaxation_length
///   sensing_delay        extra_delay (s)                         delays.pose_to_tracker (+)
///   actuation_delay      extra_delay (s)                         delays.torque_to_plant (+)
///   steering_friction    coulomb (N m), viscous (N m s/rad)      steering.coulomb_friction, .viscous_friction
///   torque_limit         limit (N m)                             steering.torque_limit
///   road_friction        scale (1)                               tire.*.mu, tire.*.mu0 (x scale)
///   cornering_stiffness  front_scale, rear_scale (1)             tire.{front,rear}.lateral_stiffness (x scale)
///   lateral_disturbance  force (N), moment (N m)                 disturbance.lateral_force, .yaw_moment
///   pose_bias            y (m), psi (rad)                        tracker.pose_bias_y, .pose_bias_psi (+)
///     (localisation)     psi (rad)                               sensors.pose_bias_psi (+): tracker and log
///   steering_compliance  stiffness (N m/rad), damping (N m s/rad), steering.column_stiffness, .column_damping,
///                        inertia (kg m^2)                          .column_inertia
///     (motor_sensor)     the same                                + steering.angle_sensor = column
///   lateral_disturbance (road_bank): the same as lateral_disturbance + disturbance.kind = road_bank
///   inertia              yaw_scale, mass_scale (1)               vehicle.yaw_inertia, vehicle.mass (x scale)
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

struct EffectParameter {
  std::string name;
  std::string unit;
  double initial = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool log_scale = false;
};

struct CandidateEffect {
  std::string name;
  std::string description;
  std::vector<EffectParameter> params;
  /// Replays whose prediction the effect changes directly ("steering" also follows from "chassis":
  /// the steering replay takes its lateral velocity from the chassis replay).
  std::vector<std::string> subsystems;
  /// One parameter whose loss is not smooth (a delay, a saturation): fitted by a grid and golden
  /// section instead of Gauss-Newton.
  bool profile = false;
  /// Writes the effect with parameters `theta` into `config` (a copy of the nominal one).
  std::function<void(const std::vector<double>& theta, SimConfig& config)> apply;
  /// Where the effect sits, for effects with several placements (docs/gap.md, "Where each candidate
  /// acts"): each form is fitted, the one that fits the training data best stands for the effect.
  std::string form;

  /// "pose_bias (localisation)", or the bare name for an effect with one form.
  std::string label() const { return form.empty() ? name : name + " (" + form + ")"; }
};

/// The eleven candidates, in DESIGN §5 order, with the further forms of pose_bias, steering_compliance
/// and lateral_disturbance after their first.
const std::vector<CandidateEffect>& candidateEffects();
/// The first form of the named effect.
const CandidateEffect& candidateEffect(const std::string& name);
/// Whether the named effect, in any of its forms, changes the replay of `subsystem` (a candidate can be
/// the cause of a gap only in a subsystem it changes).
bool effectChangesSubsystem(const std::string& effect, const std::string& subsystem);

/// Pairs the data of a lane-keeping run cannot always tell apart (reported as such when both score
/// close to the winner): each effect's known look-alikes.
const std::vector<std::string>& knownLookAlikes(const std::string& effect);

/// The keys whose values differ between two configurations, as "key" -> "value" text (the overlay
/// a user adds to the nominal configuration).
std::map<std::string, std::string> configDifference(const SimConfig& nominal, const SimConfig& changed);

}  // namespace lane_keeping
