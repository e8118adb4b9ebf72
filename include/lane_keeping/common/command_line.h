#pragma once
/// Strict reading of the tools' numeric options (lk_simulate, lk_gap, lk_stability, lk_gap_benchmark and
/// the bench programs). std::atoi read `--threads abc` as 0 (then one thread) and `--noise-reference-draws
/// abc` as 0, which switched the detection test off: here a value is the whole text, finite and within
/// its range, or a UsageError that names the option, the value and what it takes (the tools exit 2).
#include <string>

namespace lane_keeping {

/// `text` as a finite number in [min, max]. `unit` (e.g. "Hz", "s") is named in the message.
double numberOption(const std::string& option, const std::string& text, double min, double max,
                    const std::string& unit = "");

/// `text` as a whole number in [min, max] ("12", "1e3"; not "2.5", "12abc", "").
long long wholeNumberOption(const std::string& option, const std::string& text, long long min, long long max);

}  // namespace lane_keeping
