#pragma once
/// The white-noise level of a logged channel from the upper half of its band, robust to a fast ringing
/// and to a transient (issue 47, kind 3).
///
/// Why not fourth differences alone (LogSignals::noise): var(d4 x) = 70 sigma^2 holds for white noise, but
/// d4 passes the top of the band with a gain up to 16, so whatever the signal itself does there counts as
/// noise. A steering loop near its stability margin rings at ~130 Hz (Beregi's lower-level mode; at
/// +1.7 ms of actuation delay it decays at only 7 1/s), which a 100 Hz log aliases to ~30 Hz; the 1 m
/// start correction's first samples swing the torque by hundreds of N m. Both were read as sensor noise:
/// 132x the true torque noise on the +1.7 ms log, 12x on its no-effect twin (the start alone), 3.1x on a
/// 1 kHz +0.9 ms log. The noise-only draws then carried that "noise", and the delay's changed ringing
/// stayed under their floor.
///
/// Here: the fourth differences (they flatten the signal's slow content, so none leaks into the band),
/// in Welch segments of kBandSegment samples (Hann window), each cell's periodogram at the bins of
/// [1/4, 1/2) cycles per sample divided by d4's power gain (2 sin pi f)^8. For white noise every cell is
/// exponentially distributed with mean sigma^2, so its median is sigma^2 ln 2. A transient holds a few
/// segments: each bin's median over the segments does not move with it. A ringing holds a few bins (a
/// tone, with the Hann window's leakage, up to 7 of the 16): the median over the bins' medians does not
/// move with it. Tried on the benchmark's margin logs and on a sustained tone 50x the noise's amplitude:
/// the median over all cells read the tone at 1.53x the noise; this reads it at 1.09 +- 0.04x (30 draws of
/// the noise; white noise alone 1.01 +- 0.03x), and every
/// channel of the margin logs at 0.96-1.13x of its true level (the +1.7 ms torque at 1.00x).
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

namespace lane_keeping {

/// Samples per Welch segment: 16 bins in the upper half band, a transient confined to a few segments.
constexpr std::size_t kBandSegment = 64;
/// At least this many segments (~4.5 segment lengths of samples) for an estimate.
constexpr std::size_t kBandMinimumSegments = 8;

/// The upper half band's bins (kBandSegment / 4 of them, from 1/4 cycle per sample up), each over the
/// segments: the median of its cells (white noise: sigma^2 ln 2 in every bin; a ringing that lasts: more in
/// its bins) and their mean (white noise: sigma^2; a ringing, lasting or not, adds its power over the log).
/// Both empty where upperBandNoise gives nullopt. For the loop's ringing (loop_ringing.h).
struct UpperBand {
  std::vector<double> median, mean;
};
UpperBand upperBand(const std::vector<double>& values,
                    const std::vector<std::pair<std::size_t, std::size_t>>& stretches = {});

/// [Hz] the centre of the upper band's bin `bin` in a series sampled at `rate` [Hz].
double upperBandFrequency(std::size_t bin, double rate);

/// sigma of the white noise in `values` from the upper half of the band (the median of upperBand's medians over
/// ln 2), within each [begin, end) of
/// `stretches` (a log's hole-free stretches, time_holes.h; empty: the whole series); nullopt where the
/// stretches hold fewer than kBandMinimumSegments segments, where the caller keeps
/// the fourth differences' estimate.
std::optional<double> upperBandNoise(const std::vector<double>& values,
                                     const std::vector<std::pair<std::size_t, std::size_t>>& stretches = {});

}  // namespace lane_keeping
