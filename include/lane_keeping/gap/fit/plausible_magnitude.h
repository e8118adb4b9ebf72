#pragma once
/// A fitted effect whose magnitude no road or weather makes cannot be the cause, however well it fits: it is
/// standing in for what the model lacks. The steady side force (lateral_disturbance) is the one the diagnosis
/// reached for on both real cars — 2.4 kN on the RAV4's straight highway (0.14 g: a 27 m/s crosswind or an 8 degree
/// bank), 3.2 kN on the race car's hairpin (0.67 g) — so its size is bounded by the car's weight:
/// |F| <= max_side_force * m g, 0.1 g by default (a road's steepest superelevation, 8-12 %, or a storm's
/// crosswind, 0.5 rho C_y A v^2 = 0.5 * 1.2 * 0.8 * 6 m^2 * (27 m/s)^2 = 2.1 kN, on an SUV's side). Beyond it the
/// fit is listed with the reason and ranks last, as a fit whose closed loop leaves the logged bounds does.
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/fit/candidate_effects.h"

namespace lane_keeping {
namespace diagnosis {

/// Why `theta` of `effect` on a car configured as `config` is beyond what the world makes, or "" where it is
/// not (`max_side_force` in g).
std::string implausibleMagnitude(const CandidateEffect& effect, const std::vector<double>& theta,
                                 const SimConfig& config, double max_side_force);

}  // namespace diagnosis
}  // namespace lane_keeping
