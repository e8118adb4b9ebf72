#pragma once
/// Sensor noise on a log, and the noise-only reference of a log for the gap diagnosis.
///
/// A replay driven by measured inputs carries their noise into its prediction: the chassis replay
/// filters the noise of the logged steering angle, the steering replay that of the logged torque and
/// yaw acceleration. That part of the residual is smooth, so the white-noise floor of gap_metrics.h
/// does not remove it, and no model change can: it is there even when the model is exactly right.
/// The reference measures it on the log's own terms: the nominal closed loop simulated over the log's
/// span at the log's sampling, with white noise at the levels estimated from the log (the upper half of
/// each channel's band, band_noise.h), replayed exactly like the log. Its excess per subsystem is the part of the gap a
/// perfect model would leave (the diagnosis takes the largest of a few draws: the excess of a noise-only
/// replay is 0 or a few thousandths, depending on the draw). Measured on the gap benchmark's 12 no-effect logs: steering excess
/// 0.0018-0.0035 (the reference gives 0.0022-0.0035 for the same manoeuvres), chassis 0-0.003 (a
/// trace crossing the noise threshold or not), against 0.006-0.05 for the hidden effects.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/evaluation/sensor_character.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

/// 1-sigma white noise per logged channel, and where a channel's sensor does more than add white noise
/// (quantises, holds, colours: sensor_character.h), its character.
struct SensorNoise {
  double position = 0.01;     ///< x, y [m]
  double heading = 5e-4;      ///< psi [rad]
  double yaw_rate = 2e-3;     ///< [rad/s]
  double steering = 2e-4;     ///< delta [rad]
  double steering_rate = 5e-3;  ///< [rad/s]
  double torque = 0.2;        ///< [N m]
  double lateral_acceleration = 0.02;  ///< [m/s^2]
  double speed = 0.02;        ///< [m/s]
  /// Per schema column ("yaw_rate", "delta", ...): its character where not plain white noise.
  std::map<std::string, ChannelCharacter> character{};
};

/// Adds noise (reproducible from `seed`) to every measured column present: Gaussian white noise at the
/// channel's level, or noise of its character (quantised, held, coloured) where it has one.
void addSensorNoise(GapLog& log, const SensorNoise& noise, unsigned seed);

/// The noise a log shows: white levels from the upper half of each channel's band (upperBandNoise, robust
/// to a loop's fast ringing and a start transient; LogSignals::noise where a channel is too short), and each channel's
/// character (estimateCharacter) where it is more than white noise. `nominal`, if given, is the noise-free
/// nominal run over the log's span (nominalReferenceLog): its columns, at the log's times, take the
/// nominal motion out of a characterised channel's level and colour. Give it only the columns the model
/// simulates (not ones copied or smoothed from the log itself). The colour of a continuous channel is read on
/// the body's sensors only (yaw rate, lateral acceleration; sensor_character.h).
SensorNoise estimatedNoise(const LogSignals& log, const GapLog* nominal = nullptr);

/// The white level of one channel as estimatedNoise reads it (without the character), within `stretches`
/// (the log's hole-free stretches, time_holes.h).
double whiteNoiseLevel(const LogSignals& log, LogSignals::Channel channel,
                       const std::vector<std::pair<std::size_t, std::size_t>>& stretches);

/// The nominal closed loop over the span of `log` (times shifted to the log's start), sampled at its
/// median rate, with `log`'s optional columns only, without noise: the noise is added to the record,
/// not fed back (the controller of the simulated loop sees the noise-free state), so this is the same
/// for every draw and a null of B draws simulates it once (noise_null.h).
/// Throws LaneKeepingError if the nominal run diverges before the log's end.
GapLog nominalReferenceLog(const SimConfig& nominal, const LogSignals& log);

/// nominalReferenceLog with noise at estimatedNoise(log), reproducible from `seed`.
GapLog noiseReferenceLog(const SimConfig& nominal, const LogSignals& log, unsigned seed);

}  // namespace lane_keeping
