#include "lane_keeping/vehicle/speed_profile.h"

#include <algorithm>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

SpeedProfile::SpeedProfile(const std::vector<Point2>& points) {
  if (points.empty()) throw ConfigError("vehicle.speed_profile: a profile needs at least one point [t, V]");
  for (const Point2& p : points) {
    t_.push_back(p[0]);
    v_.push_back(p[1]);
  }
  const std::size_t n = t_.size();
  slope_.assign(n, 0.0);  // the ends stay 0: the profile joins the holds before and after it smoothly
  // Interior slopes (Fritsch-Butland): 0 where the secants differ in sign or one is flat (a local
  // extremum or a plateau: no overshoot), else their harmonic mean weighted by the intervals' lengths.
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h0 = t_[k] - t_[k - 1], h1 = t_[k + 1] - t_[k];
    const double d0 = (v_[k] - v_[k - 1]) / h0, d1 = (v_[k + 1] - v_[k]) / h1;
    if (d0 * d1 <= 0.0) continue;
    const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
    slope_[k] = (w0 + w1) / (w0 / d0 + w1 / d1);
  }
}

SpeedProfile::Sample SpeedProfile::at(double t) const {
  if (!(t > t_.front())) return {v_.front(), 0.0};  // (a NaN time too: the first speed, not a NaN)
  if (t >= t_.back()) return {v_.back(), 0.0};
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  // Cubic Hermite on [t_k, t_k+1] with the values and slopes at its ends.
  const double h = t_[k + 1] - t_[k];
  const double s = (t - t_[k]) / h;
  const double s2 = s * s, s3 = s2 * s;
  const double dv = v_[k + 1] - v_[k];
  const double m0 = slope_[k] * h, m1 = slope_[k + 1] * h;  // slopes per unit s
  const double speed = v_[k] + m0 * (s3 - 2.0 * s2 + s) + dv * (3.0 * s2 - 2.0 * s3) + m1 * (s3 - s2);
  const double rate = (m0 * (3.0 * s2 - 4.0 * s + 1.0) + dv * (6.0 * s - 6.0 * s2) + m1 * (3.0 * s2 - 2.0 * s)) / h;
  return {speed, rate};
}

}  // namespace lane_keeping
