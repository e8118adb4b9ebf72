#pragma once
/// How a logged channel departs from "truth plus white Gaussian noise": what a car's bus does to a
/// signal, estimated from the log so that the noise-only null (noise_null.h) draws noise of the same
/// kind as the log's, and the detection test is calibrated on real data.
///
///  * quantisation: a CAN signal is an integer times a factor (the RAV4's yaw rate moves in steps);
///    its values lie on a grid, its differences are multiples of the step;
///  * hold: a message slower than the log's rows, resampled by repeating it, holds each reading for
///    several rows (runs of equal values of one length);
///  * coloured noise: a sensor's filter, or vibration, correlates its noise from one reading to the next
///    (AR(1), lag-one correlation `ar`).
/// White noise at the estimated level is what a channel without any of them gets (as before: the draws
/// of a white channel are the same to the last bit).
///
/// The estimate: the hold from where the value changes (the largest h of 2 to 100 on whose one residue of
/// the row index modulo h 95 % of the changes fall); the readings (one per hold); the step from the
/// smallest non-zero difference between readings, kept if at least 90 % of the non-zero differences are
/// within 5 % of a multiple of it; the level and correlation from the second differences of the readings
/// — or of the readings less the noise-free nominal's, where that is smaller (estimateCharacter) —
/// trimmed to their smallest 90 % against transients. For an AR(1) noise of correlation rho the lag-one
/// autocorrelation of second differences is -(4 - 3 rho + rho^2) / (2 (3 - rho)), -2/3 for white noise,
/// and their variance sigma^2 (6 - 8 rho + 2 rho^2); the rounding onto a grid adds 6 q^2 / 12 and
/// -4 q^2 / 12, taken out before the colour is read. The colour is kept if |rho| >= 0.3 on a quantised
/// or held channel, or on a continuous one whose fast content is noise: a body sensor (yaw rate, lateral
/// acceleration: the body filters the steering loop's fast content out of them). On a continuous channel of
/// the steering loop a fast signal (the loop ringing at 120 Hz in a 1 kHz log) reads as colour: such
/// channels stay white. A quantised channel's level is found by simulation (the
/// sigma whose noise, rounded, gives the observed variance), as the rounding is not independent of the
/// noise where the step is not well below it.
#include <random>
#include <vector>

namespace lane_keeping {

struct ChannelCharacter {
  double quantum = 0.0;  ///< step between the values the channel takes (0: continuous)
  double offset = 0.0;   ///< the grid's offset: values are offset + k * quantum
  int hold = 1;          ///< log rows each reading is held for (1: a new reading every row)
  double ar = 0.0;       ///< lag-one correlation of the noise between readings (0: white)
  double sigma = 0.0;    ///< std of the noise before quantisation

  /// White noise only: the draws take the plain white-noise path.
  bool plain() const { return quantum == 0.0 && hold == 1 && ar == 0.0; }
};

/// The character of a channel's samples (see above); `white_sigma` is its fourth-difference noise level,
/// the level a plain channel keeps. `nominal`, if given, is the channel as the noise-free nominal model
/// gives it at the same rows: the level and colour are then taken from the second differences of the
/// readings less the nominal's where those are the smaller. Each is the noise's plus a part of a signal
/// (on average), so the smaller is the tighter bound; without it a signal that moves fast between
/// readings reads as noise. Measured on the independent family's no-effect log through a full bus
/// (500 Hz, torque held 5 rows, 0.5 N m steps, AR 0.5, sigma 0.2 N m): the readings alone gave the torque
/// sigma 33.7 N m and AR 0.9 (the PID torque's own motion between 100 Hz readings), the draws' excess
/// median 13.7 against the log's 0.04, and every effect on such a bus came out "nothing to explain".
/// `colour_where_continuous`: the channel's fast content is its noise's (a body sensor: yaw rate, lateral
/// acceleration), so its colour is read also where it is continuous (see above).
ChannelCharacter estimateCharacter(const std::vector<double>& values, double white_sigma,
                                   const std::vector<double>& nominal = {}, bool colour_where_continuous = false);

/// `truth` with noise of character `c` added: AR(1) noise at sigma (one unit normal per row from `unit`,
/// consumed as the white path consumes them, so a plain character adds the same values as white noise of
/// level c.sigma), held for c.hold rows, quantised onto the grid.
void addCharacterisedNoise(std::vector<double>& truth, const ChannelCharacter& c, std::mt19937& rng,
                           std::normal_distribution<double>& unit);

}  // namespace lane_keeping
