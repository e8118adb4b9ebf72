#pragma once
/// Memory and time in the messages of the tools' budget checks (lk_gap's logs, lk_stability's spectra
/// and charts): the machine's memory, and sizes and durations as a person reads them.
#include <string>

namespace lane_keeping {

/// The machine's physical memory [bytes] (sysconf), or 0 if unknown.
double physicalMemoryBytes();

/// "3.2 GB", "450 MB", "12 kB".
std::string formatBytes(double bytes);
/// "3.5 days", "2 h 5 min", "12 min", "40 s".
std::string formatDuration(double seconds);

}  // namespace lane_keeping
