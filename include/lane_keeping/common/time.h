#pragma once
/// Time in the core: seconds as double for physics, integer nanoseconds for every
/// timestamp that crosses a component boundary (sample stamps, delays, grids).
///
/// Why nanoseconds: ROS stamps are integer nanoseconds. If both the in-process runner
/// and the ROS nodes key their delay lines on the same integers and convert them to
/// seconds through the same function, a lockstep ROS run reproduces the in-process run
/// bit for bit. A delay of 1.9019505 ms therefore becomes 1901951 ns (round half to
/// even is not used: std::llround rounds half away from zero) — documented in docs/configuration.md, Conventions.
#include <cstdint>
#include <string>

namespace lane_keeping {

using Nanoseconds = std::int64_t;

/// Rounds seconds to the nearest nanosecond. Throws std::invalid_argument on NaN/Inf or
/// values beyond +-292 years.
Nanoseconds secondsToNanoseconds(double seconds);

/// The one conversion from stamps to physics time (exact for |ns| < 2^53).
inline double nanosecondsToSeconds(Nanoseconds ns) { return static_cast<double>(ns) / 1e9; }

/// Period in nanoseconds of a rate in Hz (rounded). Throws on non-positive rates.
Nanoseconds periodFromRate(double rate_hz);

/// "1.234 ms" style rendering for messages.
std::string formatSeconds(double seconds);

}  // namespace lane_keeping
