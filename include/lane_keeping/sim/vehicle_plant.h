#pragma once
/// The vehicle plant as a lockstep component: integrates the single-track model with RK4 at a
/// fixed step, reading the steering torque through its delay line at the stage times (linear
/// hold: t, t + h/2, t + h; zero-order hold: the value at t for the whole step). It may step only
/// when the torque line covers those times — the lockstep rule (DESIGN §4).
///
/// Runtime changes (change_schedule.h): a model with new parameters and the same state layout takes
/// over at a plant time; the state carries over (nothing jumps but what the parameters drive), the
/// sample at that time and every step from it use the new model.
#include <vector>

#include <Eigen/Core>

#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/sim/sensor_model.h"
#include "lane_keeping/sim/signals.h"
#include "lane_keeping/sim/simulation_params.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

class VehiclePlant {
 public:
  /// @param step plant step [ns] (even); @param torque_delay [ns]; @param actuator_period [ns].
  /// @param sensors what the tracker, the actuator and the log receive (sensor_model.h).
  VehiclePlant(SingleTrackModel model, const InitialState& initial, Nanoseconds step, Nanoseconds torque_delay,
               Hold hold, Nanoseconds actuator_period, const SensorParams& sensors = {});

  Nanoseconds time() const { return t_; }
  Nanoseconds stepSize() const { return h_; }
  /// Latest time the torque must be known at for the next step.
  Nanoseconds torqueNeededUntil() const { return hold_ == Hold::kLinear ? t_ + h_ : t_; }
  bool readyToStep() const { return torque_line_.covers(torqueNeededUntil()); }
  void pushTorque(Nanoseconds stamp, double torque) { torque_line_.push(stamp, TorqueCommand{torque}); }
  /// One RK4 step. Throws ScheduleError if !readyToStep().
  void step();

  /// From plant time `stamp` [ns] (after time()) on, integrate `model` and read the torque
  /// `torque_delay` [ns] back. Throws ScheduleError if the model's state layout differs (the state
  /// must carry over) or `stamp` is not after time().
  void scheduleChange(Nanoseconds stamp, SingleTrackModel model, Nanoseconds torque_delay);
  /// Forgets the changes scheduled at `from` [ns] or later.
  void clearChangesFrom(Nanoseconds from);

  /// Everything about the vehicle at time() as its sensors report it (sensor_model.h: what the
  /// tracker and the log see): state, velocities, tire quantities, and the torque of the last RK4 stage
  /// (zero before the first step). Accelerations use that torque. Built on demand (it costs two atan and
  /// a hypot that a step does not need).
  VehicleStateSample sample() const;
  /// The same, true (for the errors from the lane, the divergence monitor, the log's *_true columns).
  VehicleStateSample truth() const;
  /// What the tracker reads, every step (the localisation's report).
  PoseSample pose() const { return sensors_.pose(t_, truePose()); }
  /// What the actuator's angle sensor reads, every step.
  SteeringMeasurement measurement() const { return sensors_.actuatorAngle(t_, wheel(), column()); }
  const Eigen::VectorXd& state() const { return x_; }
  const SingleTrackModel& model() const { return model_; }
  const DelayLine<TorqueCommand>& torqueLine() const { return torque_line_; }
  /// True if every state is finite.
  bool finite() const { return x_.allFinite(); }

 private:
  void refresh(double torque);
  PoseSample truePose() const {
    return {x_[kX], x_[kY], x_[kPsi], x_dot_at_sample_[kX], x_dot_at_sample_[kY], x_[kSigma2]};
  }
  SteeringMeasurement wheel() const { return {x_[kDelta], x_[kSigma3]}; }
  /// The motor side of a compliant column (the wheel's angle and rate with a rigid one).
  SteeringMeasurement column() const {
    return model_.steering().compliant() ? SteeringMeasurement{x_[model_.steeringStateOffset()],
                                                               x_[model_.steeringStateOffset() + 1]}
                                         : wheel();
  }

  struct Pending {
    Nanoseconds stamp;
    SingleTrackModel model;
  };

  SingleTrackModel model_;
  std::vector<Pending> pending_;  // by stamp
  Eigen::VectorXd x_;
  Nanoseconds t_ = 0;
  Nanoseconds h_;
  Hold hold_;
  DelayLine<TorqueCommand> torque_line_;
  Rk4 rk4_;
  VehicleOutputs<double> outputs_;  // of f(x_, sample_torque_)
  Eigen::VectorXd x_dot_at_sample_;  // f(x_, sample_torque_): reused as k1 when the torque matches
  double sample_torque_ = 0.0;
  SensorModel sensors_;
};

}  // namespace lane_keeping
