#pragma once
/// The critical lower-level delay tau2 of the loop (Beregi §3, Figs 5 and 9): the rightmost roots at
/// the configured point and the first loss of stability along tau2 (both actuator delays moved
/// together), under the printed equations or an alternative reading (equation_readings.h). What
/// `lk_stability critical` prints and the Python module's `critical_delay` returns; also the loop's
/// delay system and parameter family under a reading, which every lk_stability command uses.
#include <string>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

/// The loop's delay system: the printed equations (`reading` empty) or the named reading. Throws
/// ConfigError for an unknown reading (listing the known ones) or an invalid configuration.
LinearDelaySystem loopDelaySystem(const SimConfig& config, const std::string& reading = "");
/// The family along configuration key `key` (config_parameter.h; "tau2" moves both actuator delays),
/// printed equations or the named reading. Throws ConfigError for an unknown key or reading.
SystemFamily loopFamily(const SimConfig& config, const std::string& key, const std::string& reading = "");

struct CriticalDelayOptions {
  double tau2_from = 1e-5;  ///< [s] first tau2 of the scan
  double tau2_to = 0.05;    ///< [s] last tau2 of the scan (lk_stability --tau2-max)
  int steps = 300;          ///< geometric scan intervals
  SpectrumOptions spectrum; ///< degree 24, 10 seeds (lk_stability: seeds = max(10, count + 4))
  std::string reading;      ///< "" = the printed equations
};

struct CriticalDelay {
  Crossing crossing;                      ///< along tau2; crossing.parameter is the critical tau2 [s]
  Spectrum configured;                    ///< rightmost roots at the configured tau2
  ClosedLoopLinearization linearization;  ///< the printed equations' loop at the configured point
  ScanOptions scan;                       ///< the scan that found it
};

/// Throws ConfigError for an invalid configuration, an unknown reading, or tau2_to <= tau2_from.
CriticalDelay criticalDelay(const SimConfig& config, const CriticalDelayOptions& options = {});

}  // namespace lane_keeping
