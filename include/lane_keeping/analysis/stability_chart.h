#pragma once
/// Stability chart over a grid of two configuration parameters (Beregi Figs 3-5): at every grid
/// point the loop is linearised (closed_loop_linearization.h) and its rightmost characteristic
/// roots computed (dde_spectrum.h). Grid points are spread over worker threads.
#include <functional>
#include <string>
#include <vector>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {

struct ChartAxis {
  std::string key;             ///< configuration key (config_parameter.h), e.g. "tracker.k_psi" or "tau2"
  std::vector<double> values;  ///< grid values, in order

  /// n >= 2 values from min to max inclusive. Throws ConfigError for n < 2 or non-finite bounds.
  static ChartAxis linear(const std::string& key, double min, double max, int n);
};

struct ChartPoint {
  double x = 0.0, y = 0.0;
  double abscissa = 0.0;      ///< largest real part of the characteristic roots [1/s]
  double frequency_hz = 0.0;  ///< |Im|/(2 pi) of the rightmost root
  int unstable = 0;           ///< roots in the right half plane (a complex pair counts 2)
  bool refined = true;        ///< the rightmost root was Newton-refined
  Complex rightmost;          ///< the rightmost root itself (Im >= 0)
  /// For contouring: the abscissa, except at a stable point next to an unstable one, where it is the
  /// real part of that neighbour's rightmost root continued here by Newton (the same mode). The
  /// abscissa alone has a kink there (a slow stable root is rightmost until the crossing mode
  /// overtakes it), so its zero contour would hug the stable grid points; this field is smooth
  /// across the boundary and its zero contour interpolates the crossing mode.
  double contour_field = 0.0;
  bool stable() const { return abscissa < 0.0; }
};

struct ChartOptions {
  SpectrumOptions spectrum = [] {
    SpectrumOptions o;
    o.degree = 20;
    o.seeds = 6;
    return o;
  }();
  LinearizationOptions linearization;
  /// Optional replacement of linearizeClosedLoop(config, linearization).dde (e.g. an equation
  /// reading of equation_readings.h). Must be thread-safe.
  std::function<LinearDelaySystem(const SimConfig&)> linearize;
  int threads = 0;  ///< 0: std::thread::hardware_concurrency()
};

struct StabilityChart {
  ChartAxis x, y;
  std::vector<ChartPoint> points;  ///< y outer, x inner: points[j * x.values.size() + i]
  double wall_seconds = 0.0;
  int threads = 1;
  const ChartPoint& at(std::size_t i, std::size_t j) const { return points[j * x.values.size() + i]; }
};

/// Computes the chart. Checks the configuration at the four corners first (throws ConfigError
/// naming the key and value); errors at a grid point are rethrown with the point's coordinates.
StabilityChart computeStabilityChart(const SimConfig& base, const ChartAxis& x, const ChartAxis& y,
                                     const ChartOptions& options = {});

}  // namespace lane_keeping
