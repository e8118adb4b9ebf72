// Benchmark of the lane queries (issue 18 item 1): Path::errors - the projection onto the lane and the
// Frenet errors at the foot - on a straight lane and on waypoint lanes of 10, 1,000 and 100,000 points
// (the gentle S of bench/lane_length.py), at points 0.45 mm apart along 450 m of the lane that weave
// +-0.2 m about it: successive queries close to each other, as the plant's and the tracker's are. Prints ns per query, the best
// of three passes of 10^6 queries, and a checksum (the same on every build that computes the same errors).
//   lk_bench_path
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "lane_keeping/control/path.h"

using namespace lane_keeping;

namespace {

constexpr int kQueries = 1000000;

PathParams lane(int points) {
  PathParams p;
  if (points == 0) return p;  // straight
  p.type = "waypoints";
  std::vector<Point2> waypoints;
  for (int i = 0; i < points; ++i) {
    const double x = -50.0 + 600.0 * i / (points - 1);
    waypoints.push_back({x, 1.5 * std::sin(2.0 * M_PI * x / 300.0)});
  }
  p.waypoints = std::move(waypoints);
  return p;
}

}  // namespace

int main() {
  std::printf("lane_keeping lane-query benchmark: Path::errors, %d queries per pass, best of 3\n\n", kQueries);
  std::printf("%-22s %12s %16s\n", "lane", "ns / query", "checksum");
  for (const int points : {0, 10, 1000, 100000}) {
    const auto path = createPath(lane(points));
    double best = 1e300, checksum = 0.0;
    for (int pass = 0; pass < 3; ++pass) {
      double sum = 0.0;
      const auto start = std::chrono::steady_clock::now();
      for (int k = 0; k < kQueries; ++k) {
        const double x = 4.5e-4 * k;
        const double y = 1.5 * std::sin(2.0 * M_PI * x / 300.0) + 0.2 * std::sin(0.01 * k);
        sum += path->errors(x, y, 0.01, 15.0, 0.1, 0.01).lateral;
      }
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      checksum = sum;
    }
    const std::string name = points == 0 ? "straight" : std::to_string(points) + " waypoints";
    std::printf("%-22s %12.1f %16.9g\n", name.c_str(), best * 1e9 / kQueries, checksum);
  }
  return 0;
}
