// The stability analysis (lane_keeping_stability) as lk_stability runs it: critical_delay, rightmost
// roots and boundary return the JSON lk_stability prints (stability_json.h), parsed by the Python side;
// stability_chart returns the chart's fields as arrays (rows: y values, columns: x values).
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "config_input.h"
#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/critical_delay.h"
#include "lane_keeping/analysis/stability_chart.h"
#include "lane_keeping/analysis/stability_json.h"
#include "lane_keeping/common/errors.h"

namespace py = pybind11;

namespace lane_keeping {
namespace python {
namespace {

/// lk_stability's spectrum options: degree (0: the default), seeds = max(seeds, count + 4).
SpectrumOptions spectrumOptions(int degree, int default_degree, int count, int seeds) {
  SpectrumOptions o;
  o.degree = degree > 0 ? degree : default_degree;
  o.seeds = std::max(seeds, count + 4);
  return o;
}

std::string criticalDelayText(py::handle layers, double tau2_max, int steps, int degree, int count, const std::string& reading) {
  const SimConfig config = simConfigOf(layers);
  CriticalDelayOptions options;
  options.tau2_to = tau2_max;
  options.steps = steps;
  options.spectrum = spectrumOptions(degree, 24, count, 10);
  options.reading = reading;
  py::gil_scoped_release release;
  return criticalDelayJson(config, criticalDelay(config, options), options, count).dump();
}

std::string rootsText(py::handle layers, int degree, int count, const std::string& reading) {
  const SimConfig config = simConfigOf(layers);
  const SpectrumOptions options = spectrumOptions(degree, 24, count, 10);
  py::gil_scoped_release release;
  return rootsJson(config, computeSpectrum(loopDelaySystem(config, reading), options), reading, count, options.degree).dump();
}

std::string boundaryText(py::handle layers, const std::string& param, double from, double to, int steps, bool uniform,
                         int degree, const std::string& reading) {
  const SimConfig config = simConfigOf(layers);
  configParameterInfo(param);
  ScanOptions scan;
  scan.start = from;
  scan.end = to;
  scan.steps = steps;
  scan.geometric = !uniform;
  scan.spectrum = spectrumOptions(degree, 24, 6, 10);
  if (scan.geometric && !(from > 0 && to > 0)) throw ConfigError("a geometric scan needs from, to > 0 (or uniform=True)");
  if (!(from != to) || steps < 1) throw ConfigError("boundary: need from != to and steps >= 1");
  py::gil_scoped_release release;
  return boundaryJson(config, param, findFirstCrossing(loopFamily(config, param, reading), scan), reading).dump();
}

/// (key, min, max, n): ChartAxis::linear, as lk_stability chart's --x KEY:MIN:MAX:N; (key, [values]).
ChartAxis axisOf(py::handle spec) {
  const py::tuple axis = spec.cast<py::tuple>();
  const std::string key = axis[0].cast<std::string>();
  configParameterInfo(key);
  if (axis.size() == 4) return ChartAxis::linear(key, axis[1].cast<double>(), axis[2].cast<double>(), axis[3].cast<int>());
  ChartAxis out{key, axis[1].cast<std::vector<double>>()};
  if (out.values.empty()) throw ConfigError("stability_chart: the axis " + key + " has no values");
  return out;
}

py::dict chart(py::handle layers, py::handle x_axis, py::handle y_axis, int degree, int threads, const std::string& reading) {
  const SimConfig config = simConfigOf(layers);
  const ChartAxis x = axisOf(x_axis), y = axisOf(y_axis);
  const std::string &x_key = x.key, &y_key = y.key;
  const std::vector<double>&x_values = x.values, &y_values = y.values;
  ChartOptions options;
  if (degree > 0) options.spectrum.degree = degree;
  options.threads = threads;
  if (!reading.empty()) {
    loopDelaySystem(config, reading);  // an unknown reading fails here, naming the known ones
    options.linearize = [reading](const SimConfig& c) { return loopDelaySystem(c, reading); };
  }
  StabilityChart result;
  {
    py::gil_scoped_release release;
    result = computeStabilityChart(config, x, y, options);
  }
  const py::ssize_t nx = static_cast<py::ssize_t>(x_values.size()), ny = static_cast<py::ssize_t>(y_values.size());
  py::array_t<double> abscissa({ny, nx}), frequency({ny, nx}), contour({ny, nx});
  py::array_t<int> unstable({ny, nx});
  py::array_t<bool> stable({ny, nx}), refined({ny, nx});
  py::array_t<std::complex<double>> rightmost({ny, nx});
  for (py::ssize_t j = 0; j < ny; ++j) {
    for (py::ssize_t i = 0; i < nx; ++i) {
      const ChartPoint& p = result.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
      abscissa.mutable_at(j, i) = p.abscissa;
      frequency.mutable_at(j, i) = p.frequency_hz;
      contour.mutable_at(j, i) = p.contour_field;
      unstable.mutable_at(j, i) = p.unstable;
      stable.mutable_at(j, i) = p.stable();
      refined.mutable_at(j, i) = p.refined;
      rightmost.mutable_at(j, i) = p.rightmost;
    }
  }
  py::dict d;
  d["x_key"] = x_key;
  d["y_key"] = y_key;
  d["x"] = py::array_t<double>(nx, x_values.data());
  d["y"] = py::array_t<double>(ny, y_values.data());
  d["x_unit"] = configParameterInfo(x_key).unit;
  d["y_unit"] = configParameterInfo(y_key).unit;
  d["abscissa"] = abscissa;
  d["frequency_hz"] = frequency;
  d["unstable_roots"] = unstable;
  d["stable"] = stable;
  d["contour_field"] = contour;
  d["refined"] = refined;
  d["rightmost"] = rightmost;
  d["degree_per_delay_line"] = options.spectrum.degree;
  d["equations"] = equationsName(reading);
  d["wall_seconds"] = result.wall_seconds;
  d["threads"] = result.threads;
  return d;
}

}  // namespace

void bindStability(py::module_& m) {
  m.def("critical_delay", &criticalDelayText, py::arg("layers"), py::arg("tau2_max"), py::arg("steps"), py::arg("degree"),
        py::arg("count"), py::arg("reading"));
  m.def("rightmost_roots", &rootsText, py::arg("layers"), py::arg("degree"), py::arg("count"), py::arg("reading"));
  m.def("stability_boundary", &boundaryText, py::arg("layers"), py::arg("param"), py::arg("start"), py::arg("stop"),
        py::arg("steps"), py::arg("uniform"), py::arg("degree"), py::arg("reading"));
  m.def("stability_chart", &chart, py::arg("layers"), py::arg("x"), py::arg("y"), py::arg("degree"), py::arg("threads"),
        py::arg("reading"));
}

}  // namespace python
}  // namespace lane_keeping
