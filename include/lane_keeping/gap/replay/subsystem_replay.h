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
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/actuator_replay.h"
#include "lane_keeping/gap/replay/chassis_replay.h"
#include "lane_keeping/gap/replay/replay_trace.h"
#include "lane_keeping/gap/replay/steering_replay.h"
#include "lane_keeping/gap/replay/tracker_replay.h"

namespace lane_keeping {

/// The names, in report order.
const std::vector<std::string>& subsystemNames();

/// Why `log` cannot feed the replay of `subsystem` ("" when it can): the columns it needs (inputs and
/// outputs) that are absent, or present in unknown units.
///   tracker  x, y, psi, yaw_rate -> delta_des     actuator  delta_des, delta -> torque
///   steering torque, yaw_rate -> delta            chassis   delta -> yaw_rate (x, y, psi, ay if present)
std::string replayUnavailable(const std::string& subsystem, const GapLog& log);
SubsystemReplay replaySubsystem(const std::string& name, const SimConfig& config, const LogSignals& log,
                                const std::vector<TimeSegment>& segments, const ReplayOptions& options = {});

}  // namespace lane_keeping
