#pragma once
/// The sliding window of the live gap monitor (gap_monitor.h): the last `length` seconds of the three
/// streams a lane-keeping car publishes, assembled on demand into a GapLog for the subsystem replays.
///  * the vehicle state (pose, yaw rate, steering angle and rate, speed, lateral acceleration, and the
///    torque acting on the wheel), thinned to one sample per `sample_period` — the replays' rate;
///  * the desired steering angle (the tracker's output), and the steering torque command (the actuator's
///    output), interpolated to the state's stamps. A stream that has sent nothing in the window leaves
///    its column out (a real car rarely logs delta_des: the replays that need it are then skipped); without
///    the torque command, the acting torque of the state stands in for it, as the bag reader does.
/// Samples are keyed by the instant their values hold at (DESIGN §4), not by when they arrive: the
/// actuator's torque for t reaches the monitor after the state at t, so the newest state rows may wait
/// for it (rows with no bracketing desired/torque samples are left out, and counted).
///
/// Stamps: a sample not after the last one of its stream is rejected and counted (duplicates, reordered
/// messages); a state stamp more than `jump_back` seconds before the last one is a clock that jumped
/// backwards (a bag played in a loop, a restarted simulation): the window starts again from it.
#include <cstddef>
#include <deque>
#include <string>
#include <utility>

#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {

/// What vehicle_state carries that the replays use (SI units, angles in rad).
struct MonitorStateSample {
  double t = 0.0;
  double x = 0.0, y = 0.0, psi = 0.0;
  double yaw_rate = 0.0;
  double delta = 0.0, delta_rate = 0.0;
  double speed = 0.0, lateral_acceleration = 0.0;
  double torque_applied = 0.0;  ///< the torque acting on the wheel (the command's stand-in)
};

class MonitorWindow {
 public:
  enum class Added { kAccepted, kThinned, kRejected, kRestarted };

  /// Throws std::invalid_argument unless 0 < sample_period < length (the caller validates options).
  MonitorWindow(double length, double sample_period, double jump_back = 1.0);

  Added addState(const MonitorStateSample& sample);
  Added addDesired(double t, double delta_des);
  Added addTorque(double t, double torque);
  void clear();

  bool empty() const { return states_.empty(); }
  double latest() const;  ///< the newest state stamp (NaN when empty)
  double span() const;    ///< newest - oldest state stamp held
  std::size_t stateSamples() const { return states_.size(); }

  /// The newest stamp every stream that has sent anything covers (NaN when empty).
  double coveredUntil() const;
  /// The state rows in [until - length, until] that every present stream covers (until may lie up to
  /// kSlack before latest()). A short window gives a short log: the caller decides if it is enough.
  GapLog log(const std::string& source, double until) const;
  GapLog log(const std::string& source) const { return log(source, latest()); }
  static constexpr double kSlack = 2.0;  ///< [s] held beyond the window

  struct Counts {
    std::size_t rejected = 0;   ///< non-finite values or stamps not after the last of their stream
    std::size_t restarts = 0;   ///< clock jumps backwards
    std::size_t uncovered = 0;  ///< state rows left out of the last log() for want of desired/torque samples
  };
  const Counts& counts() const { return counts_; }
  double length() const { return length_; }
  double samplePeriod() const { return sample_period_; }

 private:
  void trim();
  double length_, sample_period_, jump_back_;
  std::deque<MonitorStateSample> states_;
  std::deque<std::pair<double, double>> desired_, torque_;
  mutable Counts counts_;
};

}  // namespace lane_keeping
