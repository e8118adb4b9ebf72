#include "lane_keeping/analysis/stability_chart.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <thread>

#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/common/errors.h"

namespace lane_keeping {

ChartAxis ChartAxis::linear(const std::string& key, double min, double max, int n) {
  if (n < 2) throw ConfigError("chart axis " + key + ": needs at least 2 points, got " + std::to_string(n));
  if (!std::isfinite(min) || !std::isfinite(max) || !(max > min)) {
    throw ConfigError("chart axis " + key + ": range [" + std::to_string(min) + ", " + std::to_string(max) +
                      "] must be finite with max > min");
  }
  ChartAxis axis;
  axis.key = key;
  for (int i = 0; i < n; ++i) axis.values.push_back(min + (max - min) * i / (n - 1));
  return axis;
}

namespace {

SimConfig configAt(const SimConfig& base, const ChartAxis& x, double xv, const ChartAxis& y, double yv) {
  SimConfig c = base;
  setConfigNumber(c, x.key, xv);
  setConfigNumber(c, y.key, yv);
  return c;
}

}  // namespace

StabilityChart computeStabilityChart(const SimConfig& base, const ChartAxis& x, const ChartAxis& y,
                                     const ChartOptions& options) {
  if (x.values.empty() || y.values.empty()) throw ConfigError("chart: an axis has no values");
  if (x.key == y.key) throw ConfigError("chart: both axes are " + x.key);
  for (double xv : {x.values.front(), x.values.back()}) {
    for (double yv : {y.values.front(), y.values.back()}) configAt(base, x, xv, y, yv).validate();
  }
  StabilityChart chart;
  chart.x = x;
  chart.y = y;
  const std::size_t nx = x.values.size(), total = nx * y.values.size();
  chart.points.resize(total);
  int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min<int>(threads, static_cast<int>(total)));
  chart.threads = threads;

  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::string first_error;
  auto work = [&] {
    for (std::size_t k = next++; k < total; k = next++) {
      const double xv = x.values[k % nx], yv = y.values[k / nx];
      ChartPoint& p = chart.points[k];
      p.x = xv;
      p.y = yv;
      try {
        const SimConfig c = configAt(base, x, xv, y, yv);
        const LinearDelaySystem dde =
            options.linearize ? options.linearize(c) : linearizeClosedLoop(c, options.linearization).dde;
        const Spectrum s = computeSpectrum(dde, options.spectrum);
        p.abscissa = s.abscissa();
        p.frequency_hz = s.roots.front().frequencyHz();
        p.unstable = s.unstableCount();
        p.refined = s.roots.front().refined;
        p.rightmost = s.roots.front().value;
        p.contour_field = p.abscissa;
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (first_error.empty()) {
          std::ostringstream message;
          message << "chart point " << x.key << " = " << xv << ", " << y.key << " = " << yv << ": " << e.what();
          first_error = message.str();
        }
        next = total;  // stop the other workers
      }
    }
  };
  // Second pass: contour field at stable points next to unstable ones (see ChartPoint).
  const std::size_t ny = y.values.size();
  std::atomic<std::size_t> next_edge{0};
  auto edges = [&] {
    for (std::size_t k = next_edge++; k < total && first_error.empty(); k = next_edge++) {
      ChartPoint& p = chart.points[k];
      if (!p.stable()) continue;
      const std::size_t i = k % nx, j = k / nx;
      const std::size_t neighbours[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
      for (const auto& nb : neighbours) {
        if (nb[0] >= nx || nb[1] >= ny) continue;  // i - 1 of i = 0 wraps to a huge value
        const ChartPoint& q = chart.points[nb[1] * nx + nb[0]];
        if (q.stable()) continue;
        try {
          // Continue q's rightmost root to p in small steps, so Newton stays on the same mode.
          Complex root = q.rightmost;
          bool ok = true;
          constexpr int kSteps = 4;
          for (int step = 1; step <= kSteps && ok; ++step) {
            const double w = static_cast<double>(step) / kSteps;
            const SimConfig c = configAt(base, x, q.x + w * (p.x - q.x), y, q.y + w * (p.y - q.y));
            const LinearDelaySystem dde =
                options.linearize ? options.linearize(c) : linearizeClosedLoop(c, options.linearization).dde;
            ok = refineRoot(dde, &root);
          }
          if (ok && root.real() < 0.0) {
            p.contour_field = p.contour_field == p.abscissa ? root.real() : std::max(p.contour_field, root.real());
          }
        } catch (const std::exception&) {
          // keep the abscissa for this point
        }
      }
    }
  };
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  pool.clear();
  if (first_error.empty()) {
    for (int t = 1; t < threads; ++t) pool.emplace_back(edges);
    edges();
    for (auto& t : pool) t.join();
  }
  chart.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!first_error.empty()) throw LaneKeepingError(first_error);
  return chart;
}

}  // namespace lane_keeping
