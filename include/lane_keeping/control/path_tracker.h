#pragma once
/// Higher-level controller (Beregi eq 11, generalised to any path through e_y, e_psi):
///   delta_des(t)     = -k_psi sin(e_psi(t - tau1)) - k_y e_y(t - tau1)
///   delta_des_dot(t) = -k_psi cos(e_psi) e_psi_dot - k_y e_y_dot      (all at t - tau1)
/// The rate is the exact derivative from the delayed velocities, not a finite difference.
/// The delay itself is the input delay line's business; this class maps one pose to a command.
#include <memory>
#include <vector>

#include "lane_keeping/control/path.h"
#include "lane_keeping/control/tracker_params.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

class PathTracker {
 public:
  PathTracker(const TrackerParams& params, std::shared_ptr<const Path> path);

  /// Command from the (already delayed) vehicle state; `errors` receives e_y, e_psi if non-null.
  SteeringCommand command(const PoseSample& pose, PathErrors* errors = nullptr) const;
  /// Same, plus the identification excitation at time t [s] (tracker.excitation_*; 0 when off).
  SteeringCommand command(const PoseSample& pose, double t, PathErrors* errors = nullptr) const;
  /// The excitation multisine and its exact rate at time t [rad, rad/s].
  SteeringCommand excitation(double t) const;
  /// The multisine's sines (empty when the excitation is off): excitation(t) is the sum over them of
  /// amplitude sin(2 pi frequency t + phase).
  struct ExcitationComponent {
    double frequency;  ///< [Hz]
    double phase;      ///< [rad]
    double amplitude;  ///< [rad]
  };
  std::vector<ExcitationComponent> excitationComponents() const;

  const TrackerParams& params() const { return params_; }
  const Path& path() const { return *path_; }
  /// New gains, bias or excitation from the next command on (a runtime change). The tracker has no
  /// state of its own: the next command is the one a tracker built with `params` would give.
  void setParams(const TrackerParams& params);

 private:
  void buildExcitation();
  TrackerParams params_;
  std::shared_ptr<const Path> path_;
  std::vector<double> excitation_frequency_, excitation_phase_, excitation_amplitude_;
};

}  // namespace lane_keeping
