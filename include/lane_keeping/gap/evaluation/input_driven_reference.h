#pragma once
/// The noise-free truth of the noise-only reference (noise_reference.h) for a log the suite's own loop
/// does not describe: a real car's log (a driver or another controller steered, the desired angle and
/// the torque in N m are not on the bus) or a vehicle bus's (no pose). The nominal closed loop on the
/// scenario's road steers as the suite's controllers would, not as the car was steered: on comma2k19's
/// RAV4 its draws' chassis excess was 1e-7 to 1e-4 against the log's 0.01 to 18 — the draws did not
/// carry the log's excitation, so every real log came out "detected".
///
/// Here the nominal chassis is driven by the log's own steering (the logged angle smoothed, with its
/// rate and acceleration) and speed, from the log's first state, over the log's span: the draws then
/// see the excitation the log saw, and the noise added to them (sensor_character.h) propagates through
/// the replays as the log's noise does. The steering is prescribed, so only the chassis replay of such a
/// reference means anything (noise_null.cpp uses it where the chassis is the only replay the logs feed).
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

/// The nominal chassis under the log's smoothed steering and speed, at the log's sample times, with the
/// log's columns only (pose and a_y from the model, steering smoothed, the rest copied). Throws
/// LaneKeepingError if the simulation leaves the model's domain.
GapLog inputDrivenReferenceLog(const SimConfig& nominal, const LogSignals& log);

}  // namespace lane_keeping
