#pragma once
/// What is odd about a log before it is diagnosed (issue 48): holes in its time axis, stuck channels,
/// a sample rate too low for a subsystem's band, units that look wrong, a speed that is not what the
/// configuration says. Each finding names the log, the channel, its kind and the numbers, and says what
/// the diagnosis does about it; report.json carries them as `input_checks` (docs/gap.md, "Inputs", gives
/// every threshold and why). Without these, each of them ended in a confident wrong verdict or in
/// "nothing to explain" with no word about the log: a 5 s hole lost a steering-friction verdict, a
/// steering angle stuck at 0 gave `steering_friction` with a gap of 3.7e7, a 500 Hz log decimated to
/// 10 Hz read a steering noise floor of 0, and time in milliseconds made the noise-only null simulate
/// 30,000 s.
///
/// A pure function of the log and the run's configuration; the diagnosis (diagnosis_data.h) acts on
/// the findings: it cuts the replays' segments at holes, skips the replays that read a stuck channel or
/// that the rate cannot resolve (listing them in skipped_subsystems), and refuses a log whose time axis
/// would make it simulate hours.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/time_holes.h"

namespace lane_keeping {

struct InputCheck {
  std::string log;      ///< the log's source
  std::string channel;  ///< the schema column ("t" for the time axis)
  std::string kind;     ///< hole | stuck | rate | units | speed | span | scale | bias (heading_agreement.h) | offset (straight_line_steering.h)
  std::string detail;   ///< one sentence: what was found, with its numbers, and what the diagnosis does
  /// [s] a hole's first and last sample around it, in the log's own time (NaN for other kinds)
  double t0 = std::numeric_limits<double>::quiet_NaN();
  double t1 = std::numeric_limits<double>::quiet_NaN();
  bool refuse = false;    ///< the log cannot be diagnosed as it stands (refuseImplausibleLog)
  bool unusable = false;  ///< `channel` cannot be used: every replay that reads it is skipped (stuck)
  std::vector<std::string> skip;  ///< replays the log's rate cannot feed meaningfully (rate)
};

/// A finding of `kind` on `channel` of the log `log` (the other fields as declared).
InputCheck inputCheck(const std::string& log, const std::string& channel, const std::string& kind,
                      const std::string& detail);

/// The steering loop's modes [Hz]: the roots of J_F s^2 + k_d s + k_p = 0 (the PID of Beregi eqs 12-13
/// closed on the front axle's inertia; the aligning moment and the delay tau2 are small beside k_p), the
/// slower and the faster (equal for a complex pair: the natural frequency). Zero without a loop (p = 0).
struct Modes {
  double slow = 0.0, fast = 0.0;
};
Modes steeringLoopModes(const SimConfig& config);
/// The chassis' modes [Hz] at speed `speed`: the eigenvalues of the linear single-track model (lateral
/// velocity and yaw rate of Beregi eqs 1-3 with the axles' small-slip cornering stiffnesses).
Modes chassisModes(const SimConfig& config, double speed);

/// The findings on `log` under `config` (the run's configuration: vehicle, controller gains, speed).
/// Empty for a log with nothing odd.
std::vector<InputCheck> inputChecks(const GapLog& log, const SimConfig& config);

/// Throws InputError with the detail of the first check that refuses the log (a time axis that looks like
/// milliseconds over a span that would make every noise-only draw simulate hours).
void refuseImplausibleLog(const std::vector<InputCheck>& checks);

}  // namespace lane_keeping
