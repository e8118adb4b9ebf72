#include "lane_keeping/sim/vehicle_plant.h"

#include <algorithm>
#include <cmath>

namespace lane_keeping {

VehiclePlant::VehiclePlant(SingleTrackModel model, const InitialState& initial, Nanoseconds step,
                           Nanoseconds torque_delay, Hold hold, Nanoseconds actuator_period, const SensorParams& sensors)
    : model_(std::move(model)),
      x_(model_.initialState(initial)),
      h_(step),
      hold_(hold),
      torque_line_("steering torque -> plant", torque_delay, hold, actuator_period),
      rk4_(model_.stateSize()),
      x_dot_at_sample_(model_.stateSize()),
      sensors_(sensors, model_.steering().columnSensor()) {
  if (step <= 0 || step % 2 != 0) throw ConfigError("simulation.step must be a positive, even number of nanoseconds");
  refresh(0.0);
}

void VehiclePlant::refresh(double torque) {
  model_.followSpeedProfile(nanosecondsToSeconds(t_));  // (nothing without vehicle.speed_profile)
  model_.derivative(x_.data(), torque, x_dot_at_sample_.data(), &outputs_);
  sample_torque_ = torque;
  if (!sensors_.passThrough()) {
    sensors_.record(t_, truePose(), wheel(), column(),
                    outputs_.lateral_acceleration - model_.unsensedLateralForce(x_.data()) / model_.params().mass);
  }
}

VehicleStateSample VehiclePlant::sample() const {
  return sensors_.sample(t_, truth(), model_.unsensedLateralForce(x_.data()), model_.params().mass);
}

VehicleStateSample VehiclePlant::truth() const {
  VehicleStateSample s;
  s.x = x_[kX];
  s.y = x_[kY];
  s.psi = x_[kPsi];
  s.delta = x_[kDelta];
  s.sigma1 = x_[kSigma1];
  s.sigma2 = x_[kSigma2];
  s.sigma3 = x_[kSigma3];
  s.x_dot = outputs_.x_dot;
  s.y_dot = outputs_.y_dot;
  s.speed = std::hypot(outputs_.longitudinal_velocity, x_[kSigma1]);
  s.lateral_acceleration = outputs_.lateral_acceleration;
  s.slip_angle_front = std::atan(outputs_.tan_slip_front);
  s.slip_angle_rear = std::atan(outputs_.tan_slip_rear);
  s.force_front = outputs_.front.lateral_force;
  s.force_rear = outputs_.rear.lateral_force;
  s.moment_front = outputs_.front.aligning_moment;
  s.moment_rear = outputs_.rear.aligning_moment;
  s.torque = sample_torque_;
  return s;
}

void VehiclePlant::step() {
  const Nanoseconds half = h_ / 2;
  const double u0 = torque_line_.at(t_).torque;
  double um = u0, u1 = u0;
  if (hold_ == Hold::kLinear) {
    um = torque_line_.at(t_ + half).torque;
    u1 = torque_line_.at(t_ + h_).torque;
  }
  const double inputs[4] = {u0, um, um, u1};
  // A speed profile in time (vehicle.speed_profile) gives V and dV/dt at each stage's time, as the torque
  // line gives the torque: the plant is the one that knows the time.
  const bool profiled = model_.followsSpeedProfile();
  const double times[4] = {nanosecondsToSeconds(t_), nanosecondsToSeconds(t_ + half), nanosecondsToSeconds(t_ + half),
                           nanosecondsToSeconds(t_ + h_)};
  auto f = [&](int stage, const Eigen::VectorXd& x, Eigen::VectorXd& x_dot) {
    if (profiled) model_.followSpeedProfile(times[stage]);
    model_.derivative(x.data(), inputs[stage], x_dot.data());
  };
  // f(x_, u0) is already known when the torque at t equals the one the sample was refreshed with.
  const Eigen::VectorXd* k1 = (u0 == sample_torque_) ? &x_dot_at_sample_ : nullptr;
  rk4_.step(f, nanosecondsToSeconds(h_), x_, k1);
  t_ += h_;
  // A change due at the new time acts from here: the sample at t_ (outputs, what the sensors record)
  // already comes from the new model, and so does the next step.
  while (!pending_.empty() && pending_.front().stamp <= t_) {
    model_ = std::move(pending_.front().model);
    pending_.erase(pending_.begin());
  }
  refresh(u1);
  torque_line_.discardBefore(t_);
}

void VehiclePlant::scheduleChange(Nanoseconds stamp, SingleTrackModel model, Nanoseconds torque_delay) {
  if (stamp <= t_) {
    throw ScheduleError("vehicle plant: a change at t = " + formatSeconds(nanosecondsToSeconds(stamp)) +
                        " s is not after the plant's time " + formatSeconds(nanosecondsToSeconds(t_)) + " s");
  }
  if (model.stateSize() != model_.stateSize() || model.frontTireOffset() != model_.frontTireOffset() ||
      model.rearTireOffset() != model_.rearTireOffset()) {
    throw ScheduleError("vehicle plant: a change of the model's state layout cannot happen during a run");
  }
  torque_line_.scheduleDelay(stamp, torque_delay);
  const auto at = std::upper_bound(pending_.begin(), pending_.end(), stamp,
                                   [](Nanoseconds t, const Pending& p) { return t < p.stamp; });
  pending_.insert(at, Pending{stamp, std::move(model)});
}

void VehiclePlant::clearChangesFrom(Nanoseconds from) {
  torque_line_.clearDelaysFrom(from);
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(), [from](const Pending& p) { return p.stamp >= from; }),
                 pending_.end());
}

}  // namespace lane_keeping
