#pragma once
/// The motor side of a compliant steering column (steering.angle_sensor = column), which a log does not
/// hold: the column driven by the applied torque (the logged command delayed by delays.torque_to_plant,
/// through the dead band and the torque limit) and by the logged road wheel through the torsion bar and
/// its damper (the column equations of SingleTrackModel::steeringSystem),
///   J_c q'' = T_applied - k (q - delta) - c (q' - delta'),
/// started twisted by the first torque at the logged wheel rate.
///
/// A linear column (no stiffening angle) is stepped from sample to sample by its exact discretisation
/// with a first-order hold on the three inputs (T_applied, delta, delta'), which the replays
/// interpolate linearly between samples anyway: one 2x2 update per sample whatever the stiffness. RK4
/// needed a step below 0.5 / (sqrt(k / J_c) + c / J_c): 2.5e-5 s at the fit's bounds (k = 1e6, J_c = 0.01,
/// c = 100), 2.4 million steps for a 60 s log, so the motor-side column was the diagnosis's slowest fit
/// (147-181 s of a 206-320 s lk_bench_gap). A progressive column (stiffening angle > 0) is nonlinear and
/// keeps RK4.
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

class ColumnObserver {
 public:
  ColumnObserver(const SimConfig& config, const LogSignals& log);

  /// The column's angle and rate at t (linear between log samples; clamped outside the log).
  SteeringMeasurement at(double t) const;

  /// At the log's samples.
  const std::vector<double>& angles() const { return angle_; }
  const std::vector<double>& rates() const { return rate_; }

 private:
  void exact(const SteeringParams& p, const std::vector<double>& applied);
  void rk4(const SteeringParams& p, double tau);

  const LogSignals& log_;
  std::vector<double> angle_, rate_;
};

}  // namespace lane_keeping
