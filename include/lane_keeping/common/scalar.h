#pragma once
/// Helpers that let model code be templated on the scalar type (double, or ceres::Jet for
/// automatic differentiation) without including Ceres here.
#include <cmath>

namespace lane_keeping {

/// Value part of a scalar: the double itself, or a Jet's `.a`.
inline double toDouble(double x) { return x; }
template <typename T>
double toDouble(const T& jet) {
  return jet.a;
}

/// sqrt(a^2 + b^2) that stays differentiable at (0, 0): returns an exact zero (with zero
/// derivative parts) there instead of sqrt(0), whose derivative is infinite. Used for the
/// slip speed |v_r| (Deur eq 4), which multiplies bristle states that vanish with it.
template <typename T>
T slipSpeedNorm(const T& a, const T& b) {
  using std::sqrt;
  if (toDouble(a) == 0.0 && toDouble(b) == 0.0) return T(0.0);
  return sqrt(a * a + b * b);
}

/// sgn with sgn(0) = 0.
template <typename T>
double sign(const T& x) {
  const double v = toDouble(x);
  return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
}

}  // namespace lane_keeping
