#pragma once
/// Detects a run that has left the model's domain or the road, so that it is reported and not
/// integrated on: non-finite state, |delta| beyond the limit (eqs 2-5 are singular at pi/2),
/// |e_psi| beyond the limit (spinning out), |e_y| beyond the limit (off the road).
#include <cmath>
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

  /// Cheap per-step check (finite state, steering angle). Inline, the message out of line: it runs after
  /// every plant step.
  std::optional<std::string> checkStep(const Eigen::VectorXd& state) const {
    const double* x = state.data();
    bool finite = true;
    for (Eigen::Index i = 0; i < state.size(); ++i) finite &= std::isfinite(x[i]);
    if (finite && std::fabs(x[3]) <= limits_.max_steering_angle) return std::nullopt;  // x[3]: delta (kDelta)
    return describeStep(state);
  }
  /// Full check including the path errors of the actual state.
  std::optional<std::string> check(const VehicleStateSample& s, const PathErrors& errors) const;

 private:
  /// Why the state fails checkStep (non-finite, or the steering angle beyond its limit).
  std::string describeStep(const Eigen::VectorXd& state) const;
  DivergenceLimits limits_;
};

}  // namespace lane_keeping
