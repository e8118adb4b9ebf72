#pragma once
/// The steering loop's ringing in a log that the nominal loop does not have (issue 47, kind 3): evidence
/// the replays cannot weigh. Near its stability margin the steering loop's lower-level mode (Beregi's
/// ~130 Hz with p = 2000) decays slowly and rings; a 100 Hz log aliases it into its upper half band
/// (129.5 Hz to 29.5 Hz), where the replays, stepping between samples 10 ms apart, cannot follow it: on the
/// independent family's +1.7 ms actuation delay (0.03 ms from the margin) the log's held-out excess was the
/// same whatever delay the model had (0.0795-0.0878 from 1.60 to 1.72 ms). Its spectrum shows it plainly:
/// the torque's upper band holds a bin 3,000 times the band's median level there, its no-effect twin none.
///
/// Here: the upper half band (band_noise.h) of a channel in the log and in the nominal closed loop simulated
/// over it (nominalReferenceLog, noise-free), per bin the mean over the segments (a ringing after a step
/// lasts a second or two: a median over the segments would not see it). The log's largest bin is a ringing
/// when it stands at least kRingingProminence times the log's noise level (the median of the bins' medians,
/// over ln 2) and kRingingNarrowness times the band's median bin (narrow), and the nominal's same bin holds
/// at most kRingingNominalShare of it (a start transient the nominal loop makes too is no evidence). Said in a note, with the frequencies the peak may alias
/// (f, rate - f, rate + f). A delay or gain candidate is scored on it against the linearised loop's roots
/// (modal_evidence.h).
#include <optional>
#include <string>
#include <vector>

#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {

/// A bin's mean this many times the noise level: white noise's bin means over 30 segments scatter by ~0.2
/// of it.
constexpr double kRingingProminence = 30.0;
/// The peak bin at least this many times the band's median bin's mean: a narrow peak. A broadband burst
/// fills every bin (the torque limit the independent family's -2.5 m start reaches: its largest bin 3,659
/// times the noise level, its median bin 310 times; the +1.7 ms log's ringing: 49,650 against 4).
constexpr double kRingingNarrowness = 30.0;
/// The nominal's level in that bin, as a share of the log's, at most.
constexpr double kRingingNominalShare = 0.1;

struct LoopRinging {
  std::string source;         ///< the log's source (file name)
  std::string column;         ///< "torque" or "delta"
  double frequency = 0.0;     ///< [Hz] the peak bin's centre, as sampled
  double rate = 0.0;          ///< [Hz] the log's sample rate
  double prominence = 0.0;    ///< the peak bin's mean level over the log's noise level
  double nominal_share = 0.0; ///< the nominal's level in that bin over the log's
  double bin_width = 0.0;     ///< [Hz] of the band's bins (rate over the segment length)
};

/// The ringing of `column` (the LogSignals channel `channel`) in `log` that `nominal` (the noise-free nominal
/// closed loop over the log's span) lacks; nullopt where there is none, the channel is missing, or the log
/// is too short for the band (upperBandMedians).
std::optional<LoopRinging> loopRinging(const LogSignals& log, const GapLog& nominal, LogSignals::Channel channel,
                                       const char* column);

/// The note a report carries for it, naming the log's source.
std::string ringingNote(const std::string& source, const LoopRinging& ringing);

}  // namespace lane_keeping
