#pragma once
/// Dominant oscillation of a uniformly sampled signal and whether it grows or decays.
///
/// The signal is analysed as is (no detrending): the channels of interest settle to zero.
/// Regular oscillation (>= 3 zero crossings whose spacing varies by less than 50 %): the frequency
/// is 1 / (2 x mean half-period); the growth rate sigma [1/s] (amplitude ~ exp(sigma t)) is the
/// least-squares slope of log(peak |value|) of each half-cycle over the peak times (the
/// logarithmic decrement), which works for growing and decaying runs alike.
/// Otherwise: the frequency is the peak of the Hann-windowed spectrum (parabolic refinement), and
/// sigma the slope of log(RMS) over four equal windows.
#include <string>
#include <vector>

namespace lane_keeping {

struct OscillationEstimate {
  bool valid = false;          ///< enough samples and a non-zero signal
  double frequency_hz = 0.0;   ///< dominant frequency
  double growth_rate = 0.0;    ///< sigma [1/s]
  double rms_first = 0.0;      ///< RMS of the first window
  double rms_last = 0.0;       ///< RMS of the last window
  int cycles = 0;              ///< dominant periods within the analysed span
  bool regular = false;        ///< frequency from zero crossings (true) or the spectrum (false)
  /// "grows", "decays" or "steady" (|sigma| below `steady_rate`).
  std::string trend(double steady_rate = 0.02) const;
};

/// @param dt sample spacing [s]; @param values signal samples.
OscillationEstimate analyzeOscillation(const std::vector<double>& values, double dt);

}  // namespace lane_keeping
