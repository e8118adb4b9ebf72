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
///   steering_compliance  stiffness (N m/rad), damping (N m s/rad), steering.column_stiffness, .column_damping,
///                        inertia (kg m^2)                          .column_inertia
///     (motor_sensor)     the same                                + steering.angle_sensor = column
///   lateral_disturbance (road_bank): the same as lateral_disturbance + disturbance.kind = road_bank
///   inertia              yaw_scale, mass_scale (1)               vehicle.yaw_inertia, vehicle.mass (x scale)
/// and the sensor and data errors every real log carries (sim/sensor_params.h; the replays undo them,
/// log/sensor_correction.h), each named by its channel (the form):
///   sensor_offset        bias (rad/s | rad | rad | m/s^2)        sensors.{yaw_rate_bias, steering_angle_bias,
///     (yaw_rate | steering_angle | heading | lateral_acceleration)          pose_bias_psi, lateral_acceleration_bias} (+)
///   sensor_scale         scale (1)                               sensors.{yaw_rate_scale, steering_angle_scale} (x)
///     (yaw_rate | steering_angle: a steering ratio other than the log's conversion)
///   sensor_latency       latency (s)                             sensors.{yaw_rate_latency, steering_angle_latency,
///     (yaw_rate | steering_angle | pose | lateral_acceleration)           pose_latency, lateral_acceleration_latency} (+)
/// A heading mount offset is sensor_offset (heading): the localisation bias the log records (until this
/// round the `localisation` form of pose_bias; pose_bias now names the offset only the tracker sees).
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

struct EffectParameter {
  EffectParameter() = default;
  EffectParameter(std::string name_, std::string unit_, double initial_, double lower_, double upper_, bool log_scale_ = false,
                  std::function<double(const SimConfig&)> nominal_ = {})
      : name(std::move(name_)), unit(std::move(unit_)), initial(initial_), lower(lower_), upper(upper_), log_scale(log_scale_),
        nominal(std::move(nominal_)) {}

  std::string name;
  std::string unit;
  double initial = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool log_scale = false;
  /// The value the nominal configuration holds for the parameter, where that may lie at or beyond a bound
  /// of the range (a steering without viscous friction: 0, below the range's 0.01 N m s/rad). A fit left at
  /// that bound keeps the part as the nominal has it, none of it, while the effect's other parameters place
  /// it: not a fit stretching to imitate something else (pinnedParameterCount). Empty: not compared.
  std::function<double(const SimConfig&)> nominal;
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
  /// A sensor or data error (sensor_offset, sensor_scale, sensor_latency), not physics: a physical effect
  /// is named only where it beats the sensor explanations by its evidence (winner_selection.h).
  bool sensor = false;
  /// The logged column the effect acts on ("" = none in particular): without it in the log (or with it
  /// in unknown units) the effect cannot be tested.
  std::string channel;

  /// "steering_compliance (motor_sensor)", or the bare name for an effect with one form.
  std::string label() const { return form.empty() ? name : name + " (" + form + ")"; }
  /// Whether this form changes the replay of `subsystem`.
  bool changes(const std::string& subsystem) const;
};

/// The eleven physical candidates, in DESIGN §5 order, with the further forms of steering_compliance and
/// lateral_disturbance after their first; then the sensor errors, one form per channel.
const std::vector<CandidateEffect>& candidateEffects();
/// Whether the named effect is a sensor or data error (sensor_offset, sensor_scale, sensor_latency).
bool isSensorEffect(const std::string& name);
/// The first form of the named effect.
const CandidateEffect& candidateEffect(const std::string& name);
/// Whether the named effect, in its form `form` (any of its forms when "") changes the replay of
/// `subsystem` (a candidate can be the cause of a gap only in a subsystem it changes).
bool effectChangesSubsystem(const std::string& effect, const std::string& subsystem, const std::string& form = "");

/// The form a fit stands for when the report names several it cannot tell apart ("aerodynamic or
/// road_bank" -> "aerodynamic": the one fitted).
std::string primaryForm(const std::string& form);

/// Pairs the data of a lane-keeping run cannot always tell apart (reported as such when both score
/// close to the winner): each effect's known look-alikes.
const std::vector<std::string>& knownLookAlikes(const std::string& effect);

/// The keys whose values differ between two configurations, as "key" -> "value" text (the overlay
/// a user adds to the nominal configuration).
std::map<std::string, std::string> configDifference(const SimConfig& nominal, const SimConfig& changed);

}  // namespace lane_keeping
