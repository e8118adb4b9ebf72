// Fuzz target: the lane shapes, createPath (control/path.h) after the configuration's checks
// (SimConfig::problems: ranges, waypoints, the lane's bends against the car's turning radius). Feeds, by the
// first byte modulo 4: 0 -> the rest as raw pairs of doubles, waypoints as an inline list reaches them (any
// bit pattern: NaN, Inf, duplicates, 1e308); 1 -> the rest as a points CSV file read by readPointsCsv
// (config/points_file.h; path.waypoints: lane.csv); 2 -> a lane change, 3 -> a sinusoid, their three
// numbers (start, length and offset; amplitude, wavelength and start) the next 24 bytes as doubles. Then
// queries a car near the lane makes: at and between waypoints, 1 m to either side, before the first one;
// along the lane change or sinusoid at eight places from before its start to beyond its end.
// Asserts: readPointsCsv fails with an error naming the file or returns finite points; the configuration
// is refused with problems naming path.* keys, or createPath throws a ConfigError naming path.waypoints,
// or builds a path whose nearest point (project), height, slope, curvature and errors() (lateral offset,
// heading, curvature) are finite at every query.
#include <cmath>
#include <cstring>

#include "fuzz_support.h"
#include "lane_keeping/config/points_file.h"
#include "lane_keeping/config/sim_config.h"
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

/// A lane change or a sinusoid from three doubles; queried along x where the shape lives.
void shape(const uint8_t* data, size_t size, bool sinusoid) {
  double v[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < 3 && 1 + 8 * (i + 1) <= static_cast<int>(size); ++i) std::memcpy(&v[i], data + 1 + 8 * i, 8);
  SimConfig config;
  PathParams& params = config.path;
  if (sinusoid) {
    params.type = "sinusoid";
    params.sinusoid_amplitude = v[0];
    params.sinusoid_wavelength = v[1];
    params.sinusoid_start = v[2];
  } else {
    params.type = "lane_change";
    params.lane_change_start = v[0];
    params.lane_change_length = v[1];
    params.lane_change_offset = v[2];
  }
  const std::vector<ConfigProblem> problems = config.problems();
  if (!problems.empty()) {
    for (const ConfigProblem& p : problems) {
      if (p.key.rfind("path.", 0) != 0) fuzz::finding("a lane shape refused by a key that is not path.*: " + p.key);
    }
    return;
  }
  std::shared_ptr<const Path> path;
  fuzz::expectResultOrSuiteError([&] { path = createPath(params); }, "");
  if (!path) return;
  const double start = sinusoid ? params.sinusoid_start : params.lane_change_start;
  const double length = sinusoid ? 2.0 * params.sinusoid_wavelength : params.lane_change_length;
  for (double s : {-1.0, 0.0, 0.1, 0.25, 0.5, 0.75, 1.0, 1.5}) {
    const double x = start + s * length;
    if (!std::isfinite(x) || std::fabs(x) > 1e7) continue;  // a car on a road: within 10,000 km
    double y, slope, second;
    path->evaluate(x, &y, &slope, &second);
    if (!std::isfinite(y) || !std::isfinite(slope) || !std::isfinite(second)) {
      fuzz::finding("a non-finite " + params.type + " lane at x = " + std::to_string(x));
    }
    query(*path, x, y + 1.0);
    query(*path, x, y - 1.0);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  if (data[0] % 4 >= 2) {
    shape(data, size, data[0] % 4 == 3);
    return 0;
  }
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
