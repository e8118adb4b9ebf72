#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

VehicleStateSample VehicleStateSample::interpolate(const VehicleStateSample& a, const VehicleStateSample& b,
                                                   double w) {
  auto mix = [w](double p, double q) { return p + w * (q - p); };
  VehicleStateSample s;
  s.x = mix(a.x, b.x);
  s.y = mix(a.y, b.y);
  s.psi = mix(a.psi, b.psi);
  s.delta = mix(a.delta, b.delta);
  s.sigma1 = mix(a.sigma1, b.sigma1);
  s.sigma2 = mix(a.sigma2, b.sigma2);
  s.sigma3 = mix(a.sigma3, b.sigma3);
  s.x_dot = mix(a.x_dot, b.x_dot);
  s.y_dot = mix(a.y_dot, b.y_dot);
  s.speed = mix(a.speed, b.speed);
  s.lateral_acceleration = mix(a.lateral_acceleration, b.lateral_acceleration);
  s.slip_angle_front = mix(a.slip_angle_front, b.slip_angle_front);
  s.slip_angle_rear = mix(a.slip_angle_rear, b.slip_angle_rear);
  s.force_front = mix(a.force_front, b.force_front);
  s.force_rear = mix(a.force_rear, b.force_rear);
  s.moment_front = mix(a.moment_front, b.moment_front);
  s.moment_rear = mix(a.moment_rear, b.moment_rear);
  s.torque = mix(a.torque, b.torque);
  return s;
}

}  // namespace lane_keeping
