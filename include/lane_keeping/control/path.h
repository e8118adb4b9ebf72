#pragma once
/// Reference paths (lane centres) as graphs y = f(x) in the map frame, and the path errors the
/// tracker needs: signed lateral offset e_y of G (left positive), heading error e_psi, and their
/// exact time derivatives from the velocity of G (Frenet frame):
///   s_dot = (v . t) / (1 - kappa e_y),  e_y_dot = v . n,  e_psi_dot = psi_dot - kappa s_dot.
/// For the straight road (f = 0) these reduce to e_y = y, e_psi = psi (Beregi eq 11).
#include <memory>
#include <vector>

#include "lane_keeping/control/path_params.h"

namespace lane_keeping {

struct PathErrors {
  double lateral = 0.0;        ///< e_y [m], signed distance of G from the path, left positive
  double heading = 0.0;        ///< e_psi [rad], psi - path heading, wrapped to (-pi, pi]
  double lateral_rate = 0.0;   ///< de_y/dt [m/s]
  double heading_rate = 0.0;   ///< de_psi/dt [rad/s]
  double foot_x = 0.0;         ///< x of the closest path point [m]
  double curvature = 0.0;      ///< path curvature there [1/m], left turn positive
};

class Path {
 public:
  virtual ~Path() = default;
  /// f(x), f'(x), f''(x).
  virtual void evaluate(double x, double* y, double* slope, double* second) const = 0;

  /// Errors of a body at (px, py) with yaw psi, moving with velocity (vx, vy) and yaw rate psi_dot.
  PathErrors errors(double px, double py, double psi, double vx, double vy, double psi_dot) const;

  /// Closest point on the path to (px, py): its x. Safeguarded Newton on
  /// (x - px) + (f(x) - py) f'(x) = 0.
  double project(double px, double py) const;

 private:
  /// project(), with f, f', f'' at the returned x (errors() needs them: not evaluated twice).
  double foot(double px, double py, double* f, double* f1, double* f2) const;
};

/// Builds the path of the configuration (type = straight | lane_change | sinusoid | waypoints).
std::shared_ptr<const Path> createPath(const PathParams& params);

}  // namespace lane_keeping
