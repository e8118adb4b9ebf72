#pragma once
/// Open-loop replays of each subsystem with its logged inputs (DESIGN §5, "where"):
///  * tracker   pose -> delta_des        Beregi eq 11 on the logged pose delayed by tau1 (algebraic)
///  * actuator  delta_des, delta -> M_S  eqs 12-13 on the logged inputs delayed by tau2 (the unknown
///                                       initial integral is a constant offset, removed by least squares)
///  * steering  M_S -> delta             the steering degree of freedom (row 3 of eq 3, the front tire's
///                                       aligning moment, the steering system) driven by the logged torque,
///                                       with the logged chassis motion (sigma1, sigma2, sigma2') as input
///  * chassis   delta -> yaw rate, psi, y, ay   rows 1-2 of eq 3 and eq 2 with the logged steering motion
/// Steering and chassis are integrated by multiple shooting: every `horizon` seconds the state is
/// re-initialised from the log, so that an unstable open-loop mode (the brush model's steering alone
/// grows at ~18 1/s) or a drifting integral (y) does not wreck the comparison. The initial conditions
/// the log measures poorly are nuisance parameters of each interval, estimated by one Gauss-Newton
/// step on finite-difference sensitivities (the model is near linear in them over an interval):
/// (delta, delta_dot) for the steering, (sigma1, psi, y) for the chassis. Without this, the noise of
/// a differentiated log would set an error floor larger than the effects sought; with it, what
/// remains is what initial conditions cannot explain (forces: friction, limits, disturbances...).
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log_signals.h"

namespace lane_keeping {

struct TimeSegment {
  double t0 = 0.0, t1 = 0.0;  ///< [s], half-open [t0, t1)
};

/// One compared output of a replay.
struct ReplayTrace {
  std::string name;                     ///< e.g. "delta", "yaw_rate"
  std::vector<double> t, measured, predicted;
  double scale = 1.0;                   ///< normalisation: RMS of the measured output over the whole log
  std::vector<std::size_t> breaks;      ///< indices where a new shooting interval (or log) starts
  std::vector<double> residual() const;  ///< (measured - predicted) / scale
  /// Appends another trace of the same output (another log or segment set); keeps the breaks.
  void append(const ReplayTrace& other);
};

struct SubsystemReplay {
  std::string name;                  ///< tracker | actuator | steering | chassis
  std::vector<ReplayTrace> traces;
  int diverged_intervals = 0;        ///< shooting intervals that left the model's domain
  /// chassis only: the model's estimate of sigma1 (lateral velocity of G) at the compared times,
  /// fitted through the interval's initial conditions — the steering replay's best sigma1 input.
  std::vector<std::pair<double, double>> sigma1_estimate;
};

struct ReplayOptions {
  double steering_horizon = 0.15;    ///< [s]
  double steering_step = 2e-3;       ///< RK4 step [s] (reduced automatically for stiff steering systems)
  double chassis_horizon = 2.0;      ///< [s]
  double chassis_step = 4e-3;        ///< RK4 step [s] (reduced automatically for fast tire dynamics)
  double chassis_compare_period = 0.01;  ///< compare the chassis outputs at most at 100 Hz [s]
  bool estimate_initial_conditions = true;  ///< project out the nuisance initial conditions
};

SubsystemReplay replayTracker(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments);
SubsystemReplay replayActuator(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments);
/// @param sigma1 the chassis replay's sigma1_estimate (recommended), or nullptr to differentiate positions.
SubsystemReplay replaySteering(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                               const ReplayOptions& options = {},
                               const std::vector<std::pair<double, double>>* sigma1 = nullptr);
SubsystemReplay replayChassis(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                              const ReplayOptions& options = {});

/// The names, in report order.
const std::vector<std::string>& subsystemNames();
SubsystemReplay replaySubsystem(const std::string& name, const SimConfig& config, const LogSignals& log,
                                const std::vector<TimeSegment>& segments, const ReplayOptions& options = {});

}  // namespace lane_keeping
