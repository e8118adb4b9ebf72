#pragma once
/// Lower-level controller: PID steering torque (Beregi eqs 12-16),
///   M_S(t) = k_p (delta_des - delta)(t - tau2) + k_d (delta_des_dot - delta_dot)(t - tau2) + k_i z(t - tau2),
///   dz/dt  = delta_des - delta,      k_{p,d,i} = p k_{p0,d0,i0}.
/// The actuator only ever sees its inputs delayed by tau2, so it integrates the delayed error and
/// holds z(t - tau2) directly (this is also what makes eq 20's delays {tau2, tau1 + tau2} exact).
/// The integral advances by the trapezoidal rule between consecutive samples, which is exact for
/// the piecewise-linear inputs that `linear` delay lines deliver.
#include "lane_keeping/control/actuator_params.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

class SteeringActuator {
 public:
  explicit SteeringActuator(const ActuatorParams& params, double initial_integral = 0.0)
      : params_(params), integral_(initial_integral) {}

  /// Torque at sample time t [s] from inputs already delayed by tau2; advances z.
  double update(double t, const SteeringCommand& desired, const SteeringMeasurement& measured);

  double integral() const { return integral_; }
  const ActuatorParams& params() const { return params_; }
  /// New gains from the next sample on (a runtime change). The integral z and the previous error
  /// carry over: z is the integral of the error (eq 13), which the gains do not touch, so the torque
  /// jumps by the gain change times the current error terms and nothing else.
  void setParams(const ActuatorParams& params) { params_ = params; }

  /// The law of eq 12 for given error, error rate and integral (shared with the linearisation).
  static double torque(const ActuatorParams& p, double error, double error_rate, double integral) {
    return p.kp() * error + p.kd() * error_rate + p.ki() * integral;
  }

 private:
  ActuatorParams params_;
  double integral_;
  bool has_previous_ = false;
  double previous_time_ = 0.0;
  double previous_error_ = 0.0;
};

}  // namespace lane_keeping
