#pragma once
/// A log seen through the inverse of its sensors (sim/sensor_params.h): the true motion the physics
/// replays (steering, chassis) compare their model with.
///
/// A real log records what the car's sensors report: a steering angle through an offset and a gain (a
/// steering ratio other than the one the log was converted with), a gyro with a bias, a gain and a
/// latency, an accelerometer with an offset and a latency, a localisation with a mounting offset in
/// heading and a latency. The controllers read the same sensors, so the tracker and actuator replays
/// take the log as it is; the steering and chassis replays need the truth:
///   channel_true(t) = (channel_logged(t + latency) - bias) / scale
/// (the localisation's bias at the reported x, optionally varying along the road). Undoing a sensor on
/// the log instead of simulating it in every replay keeps one implementation for every replay and every
/// sensor, and leaves each replay's noise model intact:
///  * a latency reads each raw sample at t + L as LogSignals::nearestAlongSmoothed does (the nearest
///    sample carried along the smoothed curve: the noise stays one white sample's, so the replays' noise
///    floor, estimated from second differences, still holds); the smooth derived channels (rates,
///    accelerations, velocities of G) are interpolated. The log ends L earlier: its last samples would
///    read past the end.
///  * an offset and a gain act linearly, and so on every derived channel (the Savitzky-Golay filters are
///    linear): values (v - b) / s, rates and accelerations / s, noise levels / s. Nothing is smoothed
///    again, so a candidate's evaluation pays a copy of the log, not a filter.
/// With exact sensors the log is returned as it is (the same object).
#include <memory>

#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/sim/sensor_params.h"

namespace lane_keeping {

/// Whether `sensors` change what the log records (anything but the exact sensors).
bool sensorsChangeTheLog(const SensorParams& sensors);

/// `log` with `sensors` undone (see above); `log` itself when sensorsChangeTheLog is false.
std::shared_ptr<const LogSignals> correctedForSensors(const std::shared_ptr<const LogSignals>& log,
                                                     const SensorParams& sensors);

}  // namespace lane_keeping
