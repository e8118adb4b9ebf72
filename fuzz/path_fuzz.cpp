// Fuzz target: waypoint paths, createPath (control/path.h) for path.type = waypoints (control/path_params.h),
// with the points given inline (as YAML lists reach it) or read by readPointsCsv (config/points_file.h)
// from a points file (path.waypoints: lane.csv). Feeds: first byte even -> the rest as raw pairs of doubles
// (any bit pattern: NaN, Inf, duplicates, 1e308), odd -> the rest as a points CSV file. Then queries a car
// near the lane makes: at and between waypoints, 1 m to either side, and before the first one.
// Asserts: readPointsCsv fails with an error naming the file or returns finite points; createPath throws a
// ConfigError naming path.waypoints or builds a path whose nearest point (project), height, slope,
// curvature and errors() (lateral offset, heading, curvature) are finite at every query.
#include <cmath>
#include <cstring>

#include "fuzz_support.h"
#include "lane_keeping/config/points_file.h"
#include "lane_keeping/control/path.h"

using namespace lane_keeping;

namespace {

void query(const Path& path, double px, double py) {
  if (!std::isfinite(px) || !std::isfinite(py)) return;  // a car is somewhere
  const double foot = path.project(px, py);
  double f, slope, second;
  path.evaluate(foot, &f, &slope, &second);
  const PathErrors e = path.errors(px, py, 0.1, 0.0, 0.0, 0.0);
  const double values[] = {foot, f, slope, second, e.lateral, e.heading, e.curvature, e.foot_x};
  for (double v : values) {
    if (!std::isfinite(v)) {
      fuzz::finding("non-finite path query at (" + std::to_string(px) + ", " + std::to_string(py) + ")");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  PathParams params;
  params.type = "waypoints";
  std::vector<Point2> points;
  if (data[0] % 2 == 0) {
    for (size_t at = 1; at + 16 <= size && points.size() < 256; at += 16) {
      Point2 p;
      std::memcpy(&p[0], data + at, 8);
      std::memcpy(&p[1], data + at + 8, 8);
      points.push_back(p);
    }
  } else {
    const std::string file =
        fuzz::writeFile("lane.csv", std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
    std::string error;
    if (!readPointsCsv(file, &points, &error)) {
      if (error.find(file) == std::string::npos) fuzz::finding("readPointsCsv error without the file: " + error);
      return 0;
    }
    for (const Point2& p : points) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) fuzz::finding("readPointsCsv returned a non-finite point");
    }
  }
  params.waypoints = std::move(points);
  std::shared_ptr<const Path> path;
  fuzz::expectResultOrSuiteError([&] { path = createPath(params); }, "path.waypoints");
  if (!path) return 0;
  const std::vector<Point2>& w = params.waypoints;
  const std::size_t n = w.size();
  for (std::size_t i : {std::size_t{0}, n / 2, n - 1}) {
    query(*path, w[i][0], w[i][1] + 1.0);
    query(*path, w[i][0], w[i][1] - 1.0);
    if (i + 1 < n) query(*path, 0.5 * (w[i][0] + w[i + 1][0]), 0.5 * (w[i][1] + w[i + 1][1]));
  }
  query(*path, w[0][0] - 10.0, w[0][1]);
  return 0;
}
