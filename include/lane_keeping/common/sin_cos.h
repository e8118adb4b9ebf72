#pragma once
/// sin and cos of one angle together, for the model's hot path (the steering angle and the yaw of
/// every derivative: 8 calls per RK4 step).
///
/// Why not std::sin / std::cos: glibc's sincos (below 1 ulp) took ~10 ns per call for small
/// arguments on this machine, and sincos of delta and psi was 13-20 % of a closed-loop step with
/// LuGre tires (perf, issue #2). The version below takes ~4 ns for |x| <= pi/4 — the steering angle
/// always, the yaw on a straight road — and is within 4 ulp of the exact value (the test checks
/// against long double over several ranges; measured 1.5-3.0 ulp).
///
/// Method: reduce x by k pi/2 (k = nearest integer of 2x/pi; pi/2 split into three parts with
/// trailing zeros so that k times each part is exact — Cody and Waite), then polynomials for sin
/// and cos on |r| <= pi/4 (below). Beyond |x| = 1e5 the three-part reduction loses digits: fall back
/// to the library (also for NaN and Inf, which it propagates).
///
/// Non-double scalars (ceres::Jet) use their own sin and cos.
#include <cmath>
#include <cstdint>

namespace lane_keeping {

template <typename T>
void sinCos(const T& x, T* s, T* c) {
  using std::cos;
  using std::sin;
  *s = sin(x);
  *c = cos(x);
}

namespace sin_cos_detail {
/// sin(r)/r and cos(r) on |r| <= pi/4 as polynomials of degree 6 and 7 in u = r^2: interpolation at
/// the Chebyshev points in 40-digit arithmetic by scripts/fit_polynomials.py, which measures the
/// largest relative error in double: 2.4e-16 (sin) and 2.5e-16 (cos). Estrin's scheme.
inline void kernel(double r, double* s, double* c) {
  constexpr double s1 = -0.16666666666666616, s2 = 0.008333333333320363, s3 = -0.000198412698286503,
                   s4 = 2.755731337640013e-06, s5 = -2.5050716974102745e-08, s6 = 1.5894736651849094e-10;
  constexpr double c1 = -0.5, c2 = 0.04166666666666645, c3 = -0.0013888888888861095, c4 = 2.4801587283881152e-05,
                   c5 = -2.7557313097790086e-07, c6 = 2.0875582380663952e-09, c7 = -1.1353379638297575e-11;
  const double u = r * r;
  const double u2 = u * u;
  const double u4 = u2 * u2;
  *s = r * (((1.0 + s1 * u) + (s2 + s3 * u) * u2) + ((s4 + s5 * u) + s6 * u2) * u4);
  *c = ((1.0 + c1 * u) + (c2 + c3 * u) * u2) + ((c4 + c5 * u) + (c6 + c7 * u) * u2) * u4;
}
}  // namespace sin_cos_detail

inline void sinCos(double x, double* s, double* c) {
  constexpr double kQuarterPi = 0.78539816339744830962;
  if (std::fabs(x) <= kQuarterPi) {
    sin_cos_detail::kernel(x, s, c);
    return;
  }
  if (!(std::fabs(x) < 1e5)) {
    *s = std::sin(x);
    *c = std::cos(x);
    return;
  }
  constexpr double kTwoOverPi = 0.63661977236758134308;
  constexpr double kShifter = 6755399441055744.0;  // 1.5 * 2^52: adding it rounds to an integer
  const double k = (x * kTwoOverPi + kShifter) - kShifter;
  // pi/2 = p1 + p2 + p3, p1 and p2 with 33 significant bits (k p1, k p2 exact for |k| < 2^20).
  constexpr double p1 = 1.57079632673412561417e+00;
  constexpr double p2 = 6.07710050630396597660e-11;
  constexpr double p3 = 2.02226624879595063154e-21;
  const double r = ((x - k * p1) - k * p2) - k * p3;
  double sr, cr;
  sin_cos_detail::kernel(r, &sr, &cr);
  switch (static_cast<std::int64_t>(k) & 3) {
    case 0: *s = sr; *c = cr; break;
    case 1: *s = cr; *c = -sr; break;
    case 2: *s = -sr; *c = -cr; break;
    default: *s = -cr; *c = sr; break;
  }
}

}  // namespace lane_keeping
