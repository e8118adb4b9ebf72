#pragma once
/// The vehicle plant as a lockstep component: integrates the single-track model with RK4 at a
/// fixed step, reading the steering torque through its delay line at the stage times (linear
/// hold: t, t + h/2, t + h; zero-order hold: the value at t for the whole step). It may step only
/// when the torque line covers those times — the lockstep rule (DESIGN §4).
#include <Eigen/Core>

#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/sim/signals.h"
#include "lane_keeping/sim/simulation_params.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

class VehiclePlant {
 public:
  /// @param step plant step [ns] (even); @param torque_delay [ns]; @param actuator_period [ns].
  VehiclePlant(SingleTrackModel model, const InitialState& initial, Nanoseconds step, Nanoseconds torque_delay,
               Hold hold, Nanoseconds actuator_period);

  Nanoseconds time() const { return t_; }
  Nanoseconds stepSize() const { return h_; }
  /// Latest time the torque must be known at for the next step.
  Nanoseconds torqueNeededUntil() const { return hold_ == Hold::kLinear ? t_ + h_ : t_; }
  bool readyToStep() const { return torque_line_.covers(torqueNeededUntil()); }
  void pushTorque(Nanoseconds stamp, double torque) { torque_line_.push(stamp, TorqueCommand{torque}); }
  /// One RK4 step. Throws ScheduleError if !readyToStep().
  void step();

  /// Everything about the vehicle at time(): state, velocities, tire quantities, and the torque of
  /// the last RK4 stage (zero before the first step). Accelerations use that torque. Built on
  /// demand (it costs two atan and a hypot that a step does not need).
  VehicleStateSample sample() const;
  /// What the tracker reads, every step.
  PoseSample pose() const {
    return {x_[kX], x_[kY], x_[kPsi], x_dot_at_sample_[kX], x_dot_at_sample_[kY], x_[kSigma2]};
  }
  SteeringMeasurement measurement() const { return {x_[kDelta], x_[kSigma3]}; }
  const Eigen::VectorXd& state() const { return x_; }
  const SingleTrackModel& model() const { return model_; }
  const DelayLine<TorqueCommand>& torqueLine() const { return torque_line_; }
  /// True if every state is finite.
  bool finite() const { return x_.allFinite(); }

 private:
  void refresh(double torque);

  SingleTrackModel model_;
  Eigen::VectorXd x_;
  Nanoseconds t_ = 0;
  Nanoseconds h_;
  Hold hold_;
  DelayLine<TorqueCommand> torque_line_;
  Rk4 rk4_;
  VehicleOutputs<double> outputs_;  // of f(x_, sample_torque_)
  Eigen::VectorXd x_dot_at_sample_;  // f(x_, sample_torque_): reused as k1 when the torque matches
  double sample_torque_ = 0.0;
};

}  // namespace lane_keeping
