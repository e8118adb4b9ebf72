#pragma once
/// Alternative readings of Beregi's printed equations, to find which one puts the lower-level
/// stability boundary where the paper's Fig 9 value tau2 = 1.9019505 ms sits (just above it). The
/// default everywhere else is the equations as printed; these readings exist only for that study
/// (lk_stability readings, docs/stability.md).
///
/// Each switch edits the linearised plant derived from the model, never a hand-typed matrix: the
/// generalised forces of eq 3 are recovered as F = M(0) [sigma rows of A] (M of eq 4), edited, and
/// mapped back with the (possibly edited) mass matrix. Valid for Beregi's rigid, frictionless
/// steering (f3 = M_F + M_S, so d f3 / d state = d M_F / d state) and, for the leading-point switch,
/// a brush front tire (its forces depend on sigma3 only through a (sigma2 + sigma3) of eq 8).
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/plant_linearization.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {

struct EquationReading {
  std::string name;
  std::string description;
  bool front_leading_point = true;      ///< eq 8: a (sigma2 + sigma3) in tan(alpha_F); false: contact centre
  double aligning_moment_in_f3 = 1.0;   ///< f3 = c M_F + M_S (eq 5: c = 1; 0 drops M_F, -1 flips its sign)
  bool steering_inertia_coupled = true; ///< eq 3's J_F couplings; false: sigma3' = f3 / J_F
  bool derivative_on_desired_rate = true;  ///< eq 12: k_d (delta_des' - delta'); false: -k_d delta'
  std::vector<std::pair<std::string, double>> overrides;  ///< configuration values, e.g. {"vehicle.steering_mass", 0}
};

/// The printed equations, each switch alone, and the combinations discussed in docs/stability.md.
std::vector<EquationReading> candidateReadings();

/// The plant linearisation under `reading`. Throws ConfigError if the model is outside the
/// switches' validity (non-rigid or frictional steering; leading-point switch without a brush front).
PlantLinearization applyReading(const PlantLinearization& plant, const SingleTrackModel& model,
                                const EquationReading& reading);

/// The reading called `name`. Throws ConfigError listing the known names.
EquationReading readingByName(const std::string& name);

/// The closed loop of `config` under `reading`.
LinearDelaySystem linearizeUnderReading(const SimConfig& config, const EquationReading& reading);

/// tau2 -> the closed loop under `reading` (both actuator delays = tau2).
SystemFamily readingFamily(const SimConfig& config, const EquationReading& reading);

}  // namespace lane_keeping
