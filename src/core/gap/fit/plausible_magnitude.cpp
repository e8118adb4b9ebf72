// Fitted magnitudes beyond what the world makes (plausible_magnitude.h).
#include "lane_keeping/gap/fit/plausible_magnitude.h"

#include <cmath>
#include <cstdio>

namespace lane_keeping {
namespace diagnosis {

std::string implausibleMagnitude(const CandidateEffect& effect, const std::vector<double>& theta,
                                 const SimConfig& config, double max_side_force) {
  if (effect.name != "lateral_disturbance" || theta.empty() || !(max_side_force > 0.0)) return "";
  constexpr double kGravity = 9.80665;
  const double weight = config.vehicle.mass * kGravity;
  const double force = std::fabs(theta[0]);
  if (!(weight > 0.0) || force <= max_side_force * weight) return "";
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "a side force of %.0f N is %.2f g on this car (%.0f kg): beyond %.2f g, no road's bank or storm's "
                "crosswind makes it; it stands in for what the model lacks",
                force, force / weight, config.vehicle.mass, max_side_force);
  return buffer;
}

}  // namespace diagnosis
}  // namespace lane_keeping
