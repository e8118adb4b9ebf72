// Lane queries: the closest point equals a brute-force search on random poses, also on winding lanes
// where a local search settles on a farther root; long lanes (100,000 waypoints) build in linear time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/control/path.h"
#include "lane_keeping/control/path_params.h"

namespace lane_keeping {
namespace {

std::shared_ptr<const Path> waypointLane(const std::vector<Point2>& points) {
  PathParams p;
  p.type = "waypoints";
  p.waypoints = points;
  return createPath(p);
}

/// The closest point by brute force: the squared distance sampled every millimetre over a window wider
/// than any candidate, then refined by golden section around the best sample.
double bruteForceDistance(const Path& path, double px, double py, double window) {
  auto d2 = [&](double x) {
    double f, f1, f2;
    path.evaluate(x, &f, &f1, &f2);
    return (x - px) * (x - px) + (f - py) * (f - py);
  };
  double best_x = px, best = d2(px);
  for (double x = px - window; x <= px + window; x += 1e-3) {
    const double d = d2(x);
    if (d < best) {
      best = d;
      best_x = x;
    }
  }
  double a = best_x - 1e-3, b = best_x + 1e-3;
  for (int i = 0; i < 60; ++i) {
    const double m1 = a + 0.382 * (b - a), m2 = a + 0.618 * (b - a);
    (d2(m1) < d2(m2) ? b : a) = d2(m1) < d2(m2) ? m2 : m1;
  }
  return std::sqrt(d2(0.5 * (a + b)));
}

double projectedDistance(const Path& path, double px, double py) {
  const double x = path.project(px, py);
  double f, f1, f2;
  path.evaluate(x, &f, &f1, &f2);
  return std::hypot(x - px, f - py);
}

TEST(Path, ClosestPointEqualsBruteForceOnAWindingLane) {
  // Hairpin-like zig-zags: y = 6 sin(x / 2) has slopes up to 3 (72 degrees) and lobes 6.3 m apart, so that
  // from many poses the nearest lobe is not the one above the car and Newton from x = px can stop on a
  // farther root of the distance's derivative.
  std::vector<Point2> points;
  for (double x = -10.0; x <= 60.0; x += 0.5) points.push_back({x, 6.0 * std::sin(0.5 * x)});
  const auto lane = waypointLane(points);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> along(0.0, 50.0), off(-8.0, 8.0);
  int farther_root_cases = 0;
  for (int i = 0; i < 400; ++i) {
    const double px = along(random);
    double f, f1, f2;
    lane->evaluate(px, &f, &f1, &f2);
    const double py = f + off(random);
    const double truth = bruteForceDistance(*lane, px, py, std::fabs(py - f) + 1.0);
    const double found = projectedDistance(*lane, px, py);
    ASSERT_NEAR(found, truth, 1e-6) << "pose (" << px << ", " << py << ")";
    if (std::fabs(py - f) > 2.0) ++farther_root_cases;
  }
  EXPECT_GT(farther_root_cases, 100);  // the poses do reach beyond the neighbouring lobes
}

TEST(Path, ClosestPointEqualsBruteForceOnAnAnalyticLane) {
  PathParams p;
  p.type = "sinusoid";
  p.sinusoid_amplitude = 4.0;
  p.sinusoid_wavelength = 20.0;
  p.sinusoid_start = 0.0;
  const auto lane = createPath(p);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> along(20.0, 200.0), off(-6.0, 6.0);
  for (int i = 0; i < 300; ++i) {
    const double px = along(random), py = off(random);
    double f, f1, f2;
    lane->evaluate(px, &f, &f1, &f2);
    ASSERT_NEAR(projectedDistance(*lane, px, py), bruteForceDistance(*lane, px, py, std::fabs(py - f) + 1.0), 1e-6)
        << "pose (" << px << ", " << py << ")";
  }
}

TEST(Path, AHundredThousandWaypointsBuildAndMatchTheSplineThroughThem) {
  // A lane from a map: 100,000 points at 0.5 m (50 km). The spline passes through every point, and
  // queries far along it find the point below the car.
  std::vector<Point2> points;
  for (int i = 0; i < 100000; ++i) {
    const double x = 0.5 * i;
    points.push_back({x, 3.0 * std::sin(x / 80.0) + 0.5 * std::sin(x / 13.0)});
  }
  const auto lane = waypointLane(points);
  for (int i : {1, 777, 50000, 99998}) {
    double f, f1, f2;
    lane->evaluate(points[i][0], &f, &f1, &f2);
    ASSERT_NEAR(f, points[i][1], 1e-9);
  }
  EXPECT_NEAR(projectedDistance(*lane, 30000.0, points[60000][1] + 0.7), 0.7, 0.05);
}

/// A lane that counts the evaluations the queries make of the one it wraps.
class CountingPath : public Path {
 public:
  explicit CountingPath(std::shared_ptr<const Path> lane) : lane_(std::move(lane)) {}
  void evaluate(double x, double* y, double* slope, double* second) const override {
    ++evaluations;
    lane_->evaluate(x, y, slope, second);
  }
  mutable long evaluations = 0;

 private:
  std::shared_ptr<const Path> lane_;
};

TEST(Path, AQueryNearTheLaneTakesNewtonsFewEvaluations) {
  // The lane's running cost is its evaluations per query (two queries per millisecond of a run). Near the
  // lane Newton converges in two or three steps and the foot's evaluation serves errors() too. A step
  // below rounding once landed on the bracket's end, was taken for Newton leaving it, and every converged
  // search bisected: 23.6 evaluations per query on this sweep.
  std::vector<Point2> points;
  for (int i = 0; i < 1000; ++i) {
    const double x = -50.0 + 0.6 * i;
    points.push_back({x, 1.5 * std::sin(2.0 * M_PI * x / 300.0)});
  }
  const CountingPath lane(waypointLane(points));
  const int queries = 20000;
  for (int k = 0; k < queries; ++k) {
    const double x = 0.02 * k;
    const double offset = 0.1 * std::sin(0.01 * k);  // within 0.1 m: the scan window is Newton's piece
    lane.errors(x, 1.5 * std::sin(2.0 * M_PI * x / 300.0) + offset, 0.01, 15.0, 0.1, 0.01);
  }
  const double per_query = static_cast<double>(lane.evaluations) / queries;
  EXPECT_LE(per_query, 3.5) << per_query << " evaluations per query";
  EXPECT_GE(per_query, 1.0);
}

TEST(Path, AWaypointLaneSharesTheConfigurationsPoints) {
  // A copy of the configuration shares the points (point_list.h), so createPath finds the lane it built
  // by the points' identity; equal points given anew find it too, by value.
  PathParams params;
  params.type = "waypoints";
  params.waypoints = std::vector<Point2>{{0, 0}, {10, 1}, {20, 0}};
  const PathParams copy = params;
  EXPECT_EQ(&copy.waypoints.points(), &params.waypoints.points());
  const auto lane = createPath(params);
  EXPECT_EQ(createPath(copy), lane);
  PathParams anew;
  anew.type = "waypoints";
  anew.waypoints = std::vector<Point2>{{0, 0}, {10, 1}, {20, 0}};
  EXPECT_NE(&anew.waypoints.points(), &params.waypoints.points());
  EXPECT_EQ(createPath(anew), lane);
  anew.waypoints = std::vector<Point2>{{0, 0}, {10, 1}, {20, 0.5}};
  EXPECT_NE(createPath(anew), lane);
  EXPECT_EQ(params.waypoints[2][1], 0.0);  // a change replaces the list: the copies keep theirs
}

TEST(Path, WaypointLaneIsTheNaturalCubicSpline) {
  // What makes the spline the spline (the tridiagonal system the constructor solves): slope and curvature
  // continuous at every knot, zero curvature at both ends. Uneven spacing, so that no row is like another.
  std::vector<Point2> points;
  double x = 0.0;
  for (int i = 0; i < 2000; ++i) {
    points.push_back({x, 2.0 * std::sin(x / 40.0) + 0.3 * std::cos(x / 7.0) + 0.1 * (i % 3)});
    x += 0.3 + 0.9 * std::fabs(std::sin(1.7 * i));
  }
  const auto lane = waypointLane(points);
  double worst_slope = 0.0, worst_second = 0.0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const double xi = points[i][0], eps = 1e-7;
    double f_left, s_left, c_left, f_right, s_right, c_right;
    lane->evaluate(xi - eps, &f_left, &s_left, &c_left);
    lane->evaluate(xi + eps, &f_right, &s_right, &c_right);
    worst_slope = std::max(worst_slope, std::fabs(s_left - s_right));
    worst_second = std::max(worst_second, std::fabs(c_left - c_right));
  }
  EXPECT_LT(worst_slope, 1e-6);   // a kink would show as the jump in slope, O(0.1) here
  EXPECT_LT(worst_second, 1e-5);
  double f, s, c;
  lane->evaluate(points.front()[0] + 1e-9, &f, &s, &c);
  EXPECT_NEAR(c, 0.0, 1e-6);
  lane->evaluate(points.back()[0] - 1e-9, &f, &s, &c);
  EXPECT_NEAR(c, 0.0, 1e-6);
}

}  // namespace
}  // namespace lane_keeping

namespace lane_keeping {
namespace {

std::string pathError(const std::vector<Point2>& points) {
  try {
    waypointLane(points);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Found by fuzzing (fuzz/regressions/path/denormal_spacing.bin): waypoints 3.5e-310 m apart passed the
// "x increases" check and made a NaN lane (and an undefined int conversion of NaN in project()).
TEST(PathFuzzRegressions, WaypointsCloserThanAMillimetreAreRefusedNamingThePoint) {
  const std::string error = pathError({{0.0, 0.0}, {3.47328271065196e-310, 1.0156250001164153}, {2.0, 2.0}, {3.0, 3.0}});
  EXPECT_TRUE(has(error, "path.waypoints") && has(error, "[1]") && has(error, "0.001 m apart")) << error;
  // 1 mm apart is a lane, and its queries are finite.
  const auto lane = waypointLane({{0.0, 0.0}, {1e-3, 1.0}, {2.0, 2.0}, {3.0, 3.0}});
  const PathErrors e = lane->errors(1e-3, 2.0, 0.1, 0.0, 0.0, 0.0);
  EXPECT_TRUE(std::isfinite(e.lateral) && std::isfinite(e.heading) && std::isfinite(e.curvature)) << e.lateral;
}

TEST(PathFuzzRegressions, NonFiniteAndHugeWaypointsAreRefusedByCreatePath) {
  const double nan = std::nan("");
  std::string error = pathError({{0.0, 0.0}, {1.0, nan}, {2.0, 0.0}});
  EXPECT_TRUE(has(error, "path.waypoints") && has(error, "[1] is not finite")) << error;
  error = pathError({{-1e300, 0.0}, {1e300, 0.0}});
  EXPECT_TRUE(has(error, "path.waypoints") && has(error, "beyond 1e8 m")) << error;
}

}  // namespace
}  // namespace lane_keeping
