#pragma once
/// Higher-level controller: desired steering angle from the delayed path errors (Beregi eq 11).
#include <string>

#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct TrackerParams {
  double k_psi = 0.8;    ///< heading gain [1] (Beregi eq 11; Fig 6 value)
  double k_y = 0.01;     ///< lateral-offset gain [1/m] (Beregi eq 11; Fig 6 value)
  double rate = 1000.0;  ///< output sample rate [Hz]
  double pose_bias_y = 0.0;    ///< [m] added to the y the tracker sees (localisation bias); 0 = none
  double pose_bias_psi = 0.0;  ///< [rad] added to the yaw the tracker sees; 0 = none
  double pose_bias_variation = 0.0;    ///< fraction: biases scale with (1 + a sin(2 pi x / wavelength))
  double pose_bias_wavelength = 200.0; ///< [m]
  // Identification excitation: a multisine added to delta_des (a known test signal; 0 = off).
  double excitation_amplitude = 0.0;       ///< RMS of the multisine [rad]
  double excitation_min_frequency = 1.0;   ///< [Hz]
  double excitation_max_frequency = 15.0;  ///< [Hz]
  int excitation_components = 12;         ///< sines, log-spaced in frequency
  int excitation_seed = 1;                ///< seed of the random phases
  /// [s] Not a configuration key (set by code): the excitation runs on t + offset. A simulation that
  /// starts at a log's time t0 rather than 0 (the gap diagnosis' noise reference and closed-loop replays of
  /// a log cut mid-run) sets it to t0, so that it meets the test signal at the phase the log recorded.
  double excitation_clock_offset = 0.0;

  void visit(ParamVisitor& v, const std::string& prefix) {
    v.number(prefix + "k_psi", k_psi, "", Range::any(), "k_psi, heading-error gain (Beregi eq 11)");
    v.number(prefix + "k_y", k_y, "1/m", Range::any(), "k_y, lateral-offset gain (Beregi eq 11)");
    v.number(prefix + "rate", rate, "Hz", Range::closed(1.0, 1e7), "sample rate of the desired steering angle");
    v.number(prefix + "pose_bias_y", pose_bias_y, "m", Range::any(),
             "bias added to the lateral position the tracker sees (localisation error); 0 = none");
    v.number(prefix + "pose_bias_psi", pose_bias_psi, "rad", Range::closed(-1.0, 1.0),
             "bias added to the yaw angle the tracker sees; 0 = none");
    v.number(prefix + "pose_bias_variation", pose_bias_variation, "", Range::closed(0.0, 1.0),
             "bias varying along the road: scaled by (1 + a sin(2 pi x / pose_bias_wavelength))");
    v.number(prefix + "pose_bias_wavelength", pose_bias_wavelength, "m", Range::positive(),
             "wavelength of the bias variation");
    v.number(prefix + "excitation_amplitude", excitation_amplitude, "rad", Range::closed(0.0, 0.1),
             "identification test signal: RMS of a multisine added to delta_des; 0 = off");
    v.number(prefix + "excitation_min_frequency", excitation_min_frequency, "Hz", Range::positive(),
             "lowest frequency of the multisine");
    v.number(prefix + "excitation_max_frequency", excitation_max_frequency, "Hz", Range::positive(),
             "highest frequency of the multisine");
    v.integer(prefix + "excitation_components", excitation_components, Range::closed(1, 200), "sines in the multisine");
    v.integer(prefix + "excitation_seed", excitation_seed, Range::closed(0, 1000000), "seed of the random phases");
  }
};

}  // namespace lane_keeping
