#pragma once
/// Detects a run that has left the model's domain or the road, so that it is reported and not
/// integrated on: non-finite state, |delta| beyond the limit (eqs 2-5 are singular at pi/2),
/// |e_psi| beyond the limit (spinning out), |e_y| beyond the limit (off the road).
#include <optional>
#include <string>

#include <Eigen/Core>

#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/signals.h"
#include "lane_keeping/sim/simulation_params.h"

namespace lane_keeping {

class DivergenceMonitor {
 public:
  explicit DivergenceMonitor(const DivergenceLimits& limits) : limits_(limits) {}

  /// Cheap per-step check (finite rigid state, steering angle).
  std::optional<std::string> checkStep(const Eigen::VectorXd& state) const;
  /// Full check including the path errors of the actual state.
  std::optional<std::string> check(const VehicleStateSample& s, const PathErrors& errors) const;

 private:
  DivergenceLimits limits_;
};

}  // namespace lane_keeping
