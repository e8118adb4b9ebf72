#include "lane_keeping/control/path.h"

#include <cmath>

#include <algorithm>
#include <array>
#include <atomic>
#include <deque>
#include <limits>
#include <mutex>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/fresh_memory.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace {

double wrapAngle(double angle) {
  double wrapped = std::remainder(angle, 2.0 * M_PI);
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

/// Quintic smoothstep on [0, 1] (C2: position, slope and curvature continuous) and derivatives.
void smoothstep(double u, double* value, double* d1, double* d2) {
  if (u <= 0.0) {
    *value = 0.0; *d1 = 0.0; *d2 = 0.0;
    return;
  }
  if (u >= 1.0) {
    *value = 1.0; *d1 = 0.0; *d2 = 0.0;
    return;
  }
  const double u2 = u * u, u3 = u2 * u;
  *value = u3 * (10.0 - 15.0 * u + 6.0 * u2);
  *d1 = 30.0 * u2 * (1.0 - u) * (1.0 - u);
  *d2 = 60.0 * u * (1.0 - u) * (1.0 - 2.0 * u);
}

class StraightPath : public Path {
 public:
  void evaluate(double, double* y, double* slope, double* second) const override {
    *y = 0.0; *slope = 0.0; *second = 0.0;
  }
};

class LaneChangePath : public Path {
 public:
  LaneChangePath(double start, double length, double offset) : start_(start), length_(length), offset_(offset) {}
  void evaluate(double x, double* y, double* slope, double* second) const override {
    double s, d1, d2;
    smoothstep((x - start_) / length_, &s, &d1, &d2);
    *y = offset_ * s;
    *slope = offset_ * d1 / length_;
    *second = offset_ * d2 / (length_ * length_);
  }

 private:
  double start_, length_, offset_;
};

class SinusoidPath : public Path {
 public:
  SinusoidPath(double amplitude, double wavelength, double start)
      : amplitude_(amplitude), wavelength_(wavelength), start_(start) {}
  void evaluate(double x, double* y, double* slope, double* second) const override {
    // y = A w(x) sin(k (x - x0)), w = smoothstep((x - x0) / wavelength) fades the amplitude in.
    const double k = 2.0 * M_PI / wavelength_;
    double w, w1, w2;
    smoothstep((x - start_) / wavelength_, &w, &w1, &w2);
    w1 /= wavelength_;
    w2 /= wavelength_ * wavelength_;
    const double phase = k * (x - start_);
    const double sn = std::sin(phase), cs = std::cos(phase);
    *y = amplitude_ * w * sn;
    *slope = amplitude_ * (w1 * sn + w * k * cs);
    *second = amplitude_ * (w2 * sn + 2.0 * w1 * k * cs - w * k * k * sn);
  }

 private:
  double amplitude_, wavelength_, start_;
};

/// Natural cubic spline y(x) through the waypoints; straight lines along the end tangents beyond.
/// Holds the configuration's points themselves (shared, point_list.h) and one second derivative per
/// point: a lane from a map has 10^5 points, and every megabyte of fresh memory costs ~3 ms of page
/// faults on the 2-core machine (issue 18, fresh_memory.h), more than building the spline.
class WaypointPath : public Path {
 public:
  explicit WaypointPath(const PointList& points) : points_(points), p_(points.points().data()) {
    const int n = static_cast<int>(points.size());
    // Second derivatives M_i: tridiagonal system with M_0 = M_(n-1) = 0 (natural spline).
    m_ = populatedVector<double>(n);
    if (n > 2) {
      // Rows i = 1 .. n-2: h0/6 M_(i-1) + (h0+h1)/3 M_i + h1/6 M_(i+1) = slope difference. Tridiagonal and
      // strictly diagonally dominant, so the Thomas algorithm (Gaussian elimination without pivoting) is
      // stable and solves it in O(n) with one scratch vector (the eliminated right side is kept in m_ and
      // overwritten by the back substitution). (A dense LU took O(n^3): 0.7 s for 1,080 waypoints,
      // std::bad_alloc for 100,000; Eigen's sparse LDL^T, 0.1 s and 10 MB of triplets and factors for
      // 100,000 - most of a 20 s run's start-up.)
      std::vector<double> upper = populatedVector<double>(n);  // the eliminated system's super-diagonal
      for (int i = 1; i < n - 1; ++i) {
        const double h0 = x(i) - x(i - 1), h1 = x(i + 1) - x(i);
        const double lower = i > 1 ? h0 / 6.0 : 0.0;  // M_0 = 0: no term for row 1
        const double pivot = (h0 + h1) / 3.0 - lower * upper[i - 1];
        upper[i] = i < n - 2 ? h1 / 6.0 / pivot : 0.0;  // M_(n-1) = 0: no term for row n-2
        m_[i] = ((y(i + 1) - y(i)) / h1 - (y(i) - y(i - 1)) / h0 - lower * m_[i - 1]) / pivot;
      }
      for (int i = n - 2; i >= 1; --i) m_[i] -= upper[i] * m_[i + 1];
    }
    segments_per_metre_ = (n - 1) / (x(n - 1) - x(0));
    // Beyond the ends: the end tangents (the natural spline's curvature is 0 there).
    double unused;
    segment(0, x(0), &y_front_, &slope_front_, &unused);
    segment(n - 2, x(n - 1), &y_back_, &slope_back_, &unused);
  }

  void evaluate(double at, double* y, double* slope, double* second) const override {
    const int n = static_cast<int>(m_.size());
    if (at <= x(0) || at >= x(n - 1)) {
      const bool front = at <= x(0);
      const double se = front ? slope_front_ : slope_back_;
      *y = (front ? y_front_ : y_back_) + se * (at - (front ? x(0) : x(n - 1)));
      *slope = se;
      *second = 0.0;
      return;
    }
    segment(segmentOf(at), at, y, slope, second);
  }

 private:
  double x(int i) const { return p_[i][0]; }
  double y(int i) const { return p_[i][1]; }

  /// The cubic of segment i at `at` (Numerical Recipes section 3.3, eqs. 3.3.3 and 3.3.5), with one
  /// division: the queries (several per projection, two projections per millisecond of a run)
  /// are the lane's running cost.
  void segment(int i, double at, double* f, double* f1, double* f2) const {
    const double h = x(i + 1) - x(i), inverse = 1.0 / h;
    const double a = (x(i + 1) - at) * inverse, b = (at - x(i)) * inverse;
    const double m0 = m_[i], m1 = m_[i + 1];
    *f = a * y(i) + b * y(i + 1) + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * (h * h / 6.0);
    *f1 = (y(i + 1) - y(i)) * inverse - (3.0 * a * a - 1.0) / 6.0 * h * m0 + (3.0 * b * b - 1.0) / 6.0 * h * m1;
    *f2 = a * m0 + b * m1;
  }

  /// The segment [x_i, x_(i+1)) holding `at` (inside the waypoints), searched from the last query's:
  /// queries walk along the lane, several per projection, most within a few segments of the last
  /// one, so a galloping search (steps 1, 2, 4, ... away from the hint, then bisection of the last step)
  /// costs O(log d) for a query d segments away and stays in the cache, where a bisection of the whole
  /// lane cost O(log n) scattered reads on every bracket end the projection evaluates (±1 m: 170
  /// segments of a 100,000-point lane). A projection away from the lane scans a window of it (up to its
  /// distance either side: 0.2 m is 33 segments of a lane sampled every 6 mm), and each scan point
  /// galloped away from the hint and back; so the search starts from the segment the lane's mean
  /// spacing puts `at` in when that lies closer than the hint's - O(1) on a lane sampled evenly, as maps'
  /// lanes often are, and never worse than the hint on an uneven one. Either start changes only the
  /// cost, never the segment found (the hint is a relaxed atomic: a path is shared read-only).
  int segmentOf(double at) const {
    const int last = static_cast<int>(m_.size()) - 2;  // the last segment
    const int hint = std::clamp(hint_.load(std::memory_order_relaxed), 0, last);
    int h = hint;
    if (!(x(h) <= at && at < x(h + 1))) {
      const double even = (at - x(0)) * segments_per_metre_;  // in [0, last + 1) but for a NaN
      if (even >= 0.0 && even < last + 1.0) {
        const int i = static_cast<int>(even);
        if (std::fabs(x(i) - at) < std::fabs(x(h) - at)) h = i;
      }
    }
    int lo, hi;  // x(lo) <= at < x(hi)
    if (x(h) <= at) {
      lo = h;
      hi = h + 1;
      for (int step = 1; x(hi) <= at; step *= 2) {
        lo = hi;
        hi = std::min(hi + step, last + 1);
      }
    } else {
      hi = h;
      lo = h - 1;
      for (int step = 1; at < x(lo); step *= 2) {
        hi = lo;
        lo = std::max(lo - step, 0);
      }
    }
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (x(mid) <= at ? lo : hi) = mid;
    }
    if (lo != hint) hint_.store(lo, std::memory_order_relaxed);
    return lo;
  }

  PointList points_;       // the waypoints (shared with the configuration)
  const Point2* p_;        // their first: points_ holds them
  std::vector<double> m_;  // M_i = f''(x_i)
  double segments_per_metre_ = 0.0;  // (n - 1) / (x_(n-1) - x_0): where an evenly sampled lane puts x
  double y_front_ = 0.0, slope_front_ = 0.0, y_back_ = 0.0, slope_back_ = 0.0;  // the ends and their tangents
  mutable std::atomic<int> hint_{0};
};

}  // namespace

namespace {

/// Newton on g from x, kept inside [lo, hi] where g(lo) <= 0 <= g(hi) (bisection when Newton leaves it).
/// With `verified` false g has not been evaluated at lo and hi, so they are no bracket: NaN where a
/// verified search would bisect (or had not converged after its iterations).
template <typename G>
double refineRoot(const G& g, double x, double lo, double hi, bool verified = true) {
  for (int iteration = 0; iteration < 100; ++iteration) {
    double dg;
    const double gx = g(x, &dg);
    if (gx == 0.0) return x;
    if (gx < 0.0) lo = x; else hi = x;
    const double tolerance = 1e-13 * (1.0 + std::fabs(x));
    double next = dg > 0.0 ? x - gx / dg : 0.5 * (lo + hi);
    // Converged: the root is within Newton's step of x, and x is evaluated (its values are at hand:
    // another evaluation at `next` would move the foot by less than the tolerance). Tested before the
    // bracket: a step below rounding lands on x itself, which is a bracket end - taken for Newton leaving
    // the bracket, it made every converged search bisect (a dozen evaluations more per query).
    if (dg > 0.0 && std::fabs(next - x) <= tolerance) return x;
    if (!(dg > 0.0 && next > lo && next < hi)) {
      if (!verified) return std::numeric_limits<double>::quiet_NaN();
      next = 0.5 * (lo + hi);
      if (std::fabs(next - x) <= tolerance) return x;  // the bracket is that narrow
    }
    x = next;
  }
  return verified ? x : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double Path::project(double px, double py) const {
  double f, f1, f2;
  return foot(px, py, &f, &f1, &f2);
}

double Path::foot(double px, double py, double* foot_f, double* foot_f1, double* foot_f2) const {
  // g(x) = (x - px) + (f - py) f' is the derivative of half the squared distance. Newton from
  // x = px, kept inside a bracket where g changes sign (bisection when Newton leaves it).
  // The last point evaluated and f, f', f'' there: Newton's first point is px (evaluated for the reach
  // below), and a converged search returns the point it evaluated last, whose values errors() needs.
  double memo_x = px;
  std::array<double, 3> memo;
  evaluate(px, &memo[0], &memo[1], &memo[2]);
  const double f0 = memo[0];
  auto at = [&](double x, double* f, double* f1, double* f2) {
    if (x != memo_x) {
      memo_x = x;
      evaluate(x, &memo[0], &memo[1], &memo[2]);
    }
    *f = memo[0];
    *f1 = memo[1];
    *f2 = memo[2];
  };
  auto g = [&](double x, double* dg) {
    double f, f1, f2;
    at(x, &f, &f1, &f2);
    if (dg) *dg = 1.0 + f1 * f1 + (f - py) * f2;
    return (x - px) + (f - py) * f1;
  };
  // The squared distance of (x, f(x)), and f, f', f'' there in `values` (the foot's are returned).
  auto distance2 = [&](double x, std::array<double, 3>* values) {
    double& f = (*values)[0];
    at(x, &f, &(*values)[1], &(*values)[2]);
    return (x - px) * (x - px) + (f - py) * (f - py);
  };
  // The closest point lies within |py - f(px)| of px in x (the point above px is that close).
  const double reach = std::fabs(py - f0) + 1.0;
  double lo = px - reach, hi = px + reach;
  // Near the lane Newton converges without a step leaving [lo, hi]: then it took the steps it takes
  // inside the verified bracket, one for one (a bracket only acts on a step that leaves it), and the
  // bracket's two evaluations are saved. Else the bracket is verified (widened until g changes sign
  // across it) and the search runs again from px.
  double best = refineRoot(g, px, lo, hi, false);
  if (std::isnan(best)) {
    double glo = g(lo, nullptr), ghi = g(hi, nullptr);
    for (int widen = 0; glo > 0.0 && widen < 40; ++widen) glo = g(lo -= reach, nullptr);
    for (int widen = 0; ghi < 0.0 && widen < 40; ++widen) ghi = g(hi += reach, nullptr);
    best = refineRoot(g, px, lo, hi);
  }
  // On a winding lane g has several roots in the bracket and Newton may settle on a farther one (a
  // local minimum of the distance, or a maximum). A closer point (x, f(x)) than Newton's, at distance d,
  // has |x - px| < d: scan that window on a grid finer than a lane's bends (0.25 m; at most 400 pieces)
  // for the sign changes of g that bracket a minimum, and keep the closest. Near the lane the window is
  // one piece, which holds Newton's root: nothing to scan - the common case returns the root untouched.
  std::array<double, 3> best_values;
  double best_d = distance2(best, &best_values);
  auto found = [&] {
    *foot_f = best_values[0];
    *foot_f1 = best_values[1];
    *foot_f2 = best_values[2];
    return best;
  };
  const double d = std::sqrt(best_d);
  const double w0 = std::max(lo, px - d), w1 = std::min(hi, px + d);
  const int pieces = std::clamp(static_cast<int>(std::ceil((w1 - w0) / 0.25)), 1, 400);
  if (pieces == 1 && best >= w0 && best <= w1) return found();
  double a = w0, ga = g(w0, nullptr);
  for (int k = 1; k <= pieces; ++k) {
    const double b = w0 + (w1 - w0) * k / pieces;
    const double gb = g(b, nullptr);
    if (ga <= 0.0 && gb >= 0.0 && !(best >= a && best <= b)) {
      const double root = refineRoot(g, 0.5 * (a + b), a, b);
      std::array<double, 3> values;
      const double d = distance2(root, &values);
      if (d < best_d) {
        best = root;
        best_d = d;
        best_values = values;
      }
    }
    a = b;
    ga = gb;
  }
  return found();
}

PathErrors Path::errors(double px, double py, double psi, double vx, double vy, double psi_dot) const {
  PathErrors e;
  double f, f1, f2;  // at the foot: the projection evaluated them last
  const double xf = foot(px, py, &f, &f1, &f2);
  const double norm = std::sqrt(1.0 + f1 * f1);
  const double tx = 1.0 / norm, ty = f1 / norm;  // unit tangent
  const double nx = -ty, ny = tx;                 // unit normal, to the left
  e.foot_x = xf;
  e.curvature = f2 / (norm * norm * norm);
  e.lateral = (px - xf) * nx + (py - f) * ny;
  e.heading = wrapAngle(psi - std::atan(f1));
  const double s_dot = (vx * tx + vy * ty) / (1.0 - e.curvature * e.lateral);
  e.lateral_rate = vx * nx + vy * ny;
  e.heading_rate = psi_dot - e.curvature * s_dot;
  return e;
}

std::shared_ptr<const Path> createPath(const PathParams& params) {
  if (params.type == "straight") return std::make_shared<StraightPath>();
  if (params.type == "lane_change") {
    return std::make_shared<LaneChangePath>(params.lane_change_start, params.lane_change_length,
                                            params.lane_change_offset);
  }
  if (params.type == "sinusoid") {
    return std::make_shared<SinusoidPath>(params.sinusoid_amplitude, params.sinusoid_wavelength,
                                          params.sinusoid_start);
  }
  if (params.type == "waypoints") {
    // One run builds its lane several times (the lockstep feasibility probe, the plant, the tracker; the
    // gap diagnosis once per replay): a lane from a map of 100,000 points costs ~5 ms and 4 MB of fresh
    // pages each time, most of a short run's start-up. Lanes are immutable, so the last few are kept and
    // shared, found by their points: at once when the configuration is a copy of the one that built the
    // lane (they share the points, point_list.h), else by comparing them (~0.1 ms on 100,000 points).
    static std::mutex cache_mutex;
    static std::deque<std::pair<PointList, std::shared_ptr<const Path>>> cache;
    {
      std::lock_guard<std::mutex> lock(cache_mutex);
      for (const auto& [points, path] : cache) {
        if (points == params.waypoints) return path;
      }
    }
    // The same checks as SimConfig::problems(): finite values (RangeChecker), then the shape rules.
    PathParams copy = params;  // visit() takes non-const references (the copy shares the points)
    RangeChecker checker;
    copy.visit(checker, "path.");
    std::vector<ConfigProblem> problems = checker.problems();
    params.validate("path.", problems);
    if (!problems.empty()) throw ConfigError(problems);
    std::shared_ptr<const Path> path = std::make_shared<WaypointPath>(params.waypoints);
    std::lock_guard<std::mutex> lock(cache_mutex);
    cache.emplace_front(params.waypoints, path);
    if (cache.size() > 4) cache.pop_back();
    return path;
  }
  throw ConfigError("path.type '" + params.type + "' is unknown; allowed: straight, lane_change, sinusoid, waypoints");
}

}  // namespace lane_keeping
