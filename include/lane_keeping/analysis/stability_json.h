#pragma once
/// The JSON renderings of the stability analysis: what `lk_stability critical|roots|boundary` print and
/// the Python module's critical_delay, rightmost_roots and stability_boundary return (src/python), made
/// by the same functions so that the two cannot differ.
#include <string>

#include <nlohmann/json.hpp>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/critical_delay.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

using StabilityJson = nlohmann::ordered_json;

/// {re, im, frequency_hz, refined}.
StabilityJson rootJson(Complex root, bool refined = true);
/// The first `count` roots, rightmost first.
StabilityJson spectrumJson(const Spectrum& spectrum, int count);
/// States, dropped states, delays and gains of the linearised loop; with `spectrum`, its discretisation.
StabilityJson ddeJson(const ClosedLoopLinearization& linearization, const Spectrum* spectrum, int degree);
/// The configuration point: gains, delays, tire models.
StabilityJson pointJson(const SimConfig& config);
/// "printed" or the reading's name.
std::string equationsName(const std::string& reading);

/// `lk_stability critical` without its wall time: the critical tau2, its crossing, the margin, the
/// `count` rightmost roots at the configured point, the point, the equations, the DDE and the scan.
StabilityJson criticalDelayJson(const SimConfig& config, const CriticalDelay& critical,
                                const CriticalDelayOptions& options, int count);
/// `lk_stability roots`: stability, abscissa and the `count` rightmost roots at the configured point.
StabilityJson rootsJson(const SimConfig& config, const Spectrum& spectrum, const std::string& reading, int count,
                        int degree);
/// `lk_stability boundary`: the first loss of stability along `param` (a scan of findFirstCrossing).
StabilityJson boundaryJson(const SimConfig& config, const std::string& param, const Crossing& crossing,
                           const std::string& reading);

}  // namespace lane_keeping
