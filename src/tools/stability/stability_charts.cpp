#include "stability_charts.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/analysis/stability_chart.h"
#include "lane_keeping/common/child_process.h"
#include "lane_keeping/common/errors.h"
#include "build_paths.h"

namespace lane_keeping {
namespace stability_cli {
namespace {

constexpr const char* kPython = "/usr/bin/python3";  // Debian's: has matplotlib (the pyenv one does not)

ChartAxis parseAxis(const std::string& spec, const std::string& what) {
  // KEY:MIN:MAX:N
  std::vector<std::string> parts;
  std::stringstream in(spec);
  for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
  if (parts.size() != 4) badArguments(what + " '" + spec + "' must be KEY:MIN:MAX:N");
  configParameterInfo(parts[0]);
  return ChartAxis::linear(parts[0], parseNumber(parts[1], what), parseNumber(parts[2], what),
                           parseInt(parts[3], what + " N", 2, 1000000));
}

struct Layer {
  std::string key;
  std::vector<double> values;
};

Layer parseLayer(const std::string& spec, const std::string& what) {
  Layer layer;
  if (spec.empty()) return layer;
  const auto eq = spec.find('=');
  if (eq == std::string::npos) badArguments(what + " '" + spec + "' must be KEY=v1,v2,...");
  layer.key = spec.substr(0, eq);
  configParameterInfo(layer.key);
  std::stringstream in(spec.substr(eq + 1));
  for (std::string v; std::getline(in, v, ',');) layer.values.push_back(parseNumber(v, what));
  if (layer.values.empty()) badArguments(what + " '" + spec + "' lists no values");
  return layer;
}

struct ChartSpec {
  ChartAxis x, y;
  Layer series, panels;
  std::string title;
  json markers = json::array();  ///< points to mark: {x, y, label}
};

json axisJson(const std::string& key) {
  const ConfigParameterInfo info = configParameterInfo(key);
  return json{{"key", key}, {"unit", info.unit}, {"doc", info.doc}};
}

/// Computes every panel x series chart, writes PREFIX.csv and PREFIX.json, runs the plotter.
int writeChart(const Args& a, const SimConfig& base, const ChartSpec& spec, const std::string& prefix) {
  ChartOptions options;
  if (a.degree > 0) options.spectrum.degree = a.degree;
  options.threads = a.threads;
  if (!a.reading.empty()) {
    const EquationReading reading = readingByName(a.reading);
    options.linearize = [reading](const SimConfig& c) { return linearizeUnderReading(c, reading); };
  }
  const std::vector<double> panel_values = spec.panels.key.empty() ? std::vector<double>{NAN} : spec.panels.values;
  const std::vector<double> series_values = spec.series.key.empty() ? std::vector<double>{NAN} : spec.series.values;
  {
    // The whole chart's cost, before its first point (stability_budget.h).
    const double points = static_cast<double>(spec.x.values.size()) * static_cast<double>(spec.y.values.size());
    const int threads = a.threads > 0 ? a.threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    const std::string option = a.command == "chart" ? "--x, --y N and --degree" : "--n and --degree";
    checkBudget(a, systemOf(a, base), options.spectrum.degree,
                points * static_cast<double>(panel_values.size() * series_values.size()), threads, points, option);
  }
  std::ofstream csv(prefix + ".csv");
  if (!csv) throw InputError("cannot write " + prefix + ".csv");
  csv << "panel,series,x,y,abscissa,frequency_hz,unstable_roots,stable,contour_field\n";
  csv << std::setprecision(10);
  double seconds = 0.0;
  int points = 0, threads = 1;
  for (double pv : panel_values) {
    for (double sv : series_values) {
      SimConfig c = base;
      if (!spec.panels.key.empty()) setConfigNumber(c, spec.panels.key, pv);
      if (!spec.series.key.empty()) setConfigNumber(c, spec.series.key, sv);
      const StabilityChart chart = computeStabilityChart(c, spec.x, spec.y, options);
      seconds += chart.wall_seconds;
      threads = chart.threads;
      for (const ChartPoint& p : chart.points) {
        csv << pv << "," << sv << "," << p.x << "," << p.y << "," << p.abscissa << "," << p.frequency_hz << ","
            << p.unstable << "," << (p.stable() ? 1 : 0) << "," << p.contour_field << "\n";
        ++points;
      }
      std::cerr << "lk_stability: " << prefix << ": chart " << (spec.panels.key.empty() ? "" : spec.panels.key + "=" + std::to_string(pv) + " ")
                << (spec.series.key.empty() ? "" : spec.series.key + "=" + std::to_string(sv) + " ") << chart.x.values.size()
                << "x" << chart.y.values.size() << " in " << chart.wall_seconds << " s (" << chart.threads << " threads)\n";
    }
  }
  csv.close();
  json meta{{"title", spec.title},
            {"csv", prefix + ".csv"},
            {"png", prefix + ".png"},
            {"x", axisJson(spec.x.key)},
            {"y", axisJson(spec.y.key)},
            {"n", {spec.x.values.size(), spec.y.values.size()}},
            {"series", spec.series.key.empty() ? json(nullptr) : json{{"key", spec.series.key}, {"values", spec.series.values}, {"unit", configParameterInfo(spec.series.key).unit}}},
            {"panels", spec.panels.key.empty() ? json(nullptr) : json{{"key", spec.panels.key}, {"values", spec.panels.values}, {"unit", configParameterInfo(spec.panels.key).unit}}},
            {"markers", spec.markers},
            {"point", pointJson(base)},
            {"equations", a.reading.empty() ? "printed" : a.reading},
            {"degree_per_delay_line", options.spectrum.degree},
            {"points", points},
            {"wall_s", seconds},
            {"threads", threads}};
  std::ofstream(prefix + ".json") << meta.dump(2) << "\n";
  std::cerr << "lk_stability: wrote " << prefix << ".csv and " << prefix << ".json (" << points << " points, " << seconds << " s)\n";
  if (!a.plot) return 0;
  const std::string script = std::string(build_paths::sourceDir()) + "/scripts/plot_stability.py";
  // Its argument vector, no shell: a prefix with a quote in it is a name like any other.
  const ChildResult plot = runChild({kPython, script, prefix + ".json"});
  if (!plot.ok()) {
    std::cerr << "lk_stability: plotting failed (" << kPython << " " << script << " " << prefix
              << ".json: " << plot.failure() << "); the CSV and JSON are written\n";
    return 1;
  }
  std::cerr << "lk_stability: wrote " << prefix << ".png\n";
  return 0;
}

std::string outputDir(const Args& a) {
  if (a.out.empty()) badArguments(a.command + " needs --out DIR");
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) throw InputError("--out " + a.out + ": cannot create the directory (" + ec.message() + ")");
  return a.out;
}

}  // namespace

int commandChart(const Args& a, const SimConfig& c) {
  if (a.x.empty() || a.y.empty() || a.out.empty()) badArguments("chart needs --x, --y and --out");
  ChartSpec spec{parseAxis(a.x, "--x"), parseAxis(a.y, "--y"), parseLayer(a.series, "--series"),
                 parseLayer(a.panels, "--panels"), a.title};
  return writeChart(a, c, spec, a.out);
}

/// Beregi Fig 3: tau1 in panels, p in series, tau2 = 0.1 ms.
int commandFig3(const Args& a, SimConfig c) {
  setConfigNumber(c, "tau2", 1e-4);
  ChartSpec spec{ChartAxis::linear("tracker.k_psi", 0.0, 2.5, a.n), ChartAxis::linear("tracker.k_y", 0.0, 0.3, a.n),
                 Layer{"actuator.p", {500, 1000, 2000, 8000}}, Layer{"delays.pose_to_tracker", {0.1, 0.15, 0.2, 0.3}},
                 "Beregi Fig 3: stable (k_psi, k_y) for tau1 (panels) and p (colours), tau2 = 0.1 ms"};
  spec.markers.push_back({{"x", 0.8}, {"y", 0.01}, {"label", "Fig 6"}, {"panel", 0.2}});
  spec.markers.push_back({{"x", 0.8}, {"y", 0.15}, {"label", "Figs 7-8"}, {"panel", 0.2}});
  return writeChart(a, c, spec, outputDir(a) + "/fig3");
}

/// Beregi Fig 4: several tau2, tau1 = 0.2 s, p = 4000. The lower-level boundary hardly depends on
/// (k_psi, k_y) (Beregi §3), so the region vanishes within a few 1e-4 of the critical tau2: the
/// series are 0.1 ms, 0.95 tau2c and tau2c (1 + 5e-5, 1e-4, 1.5e-4), tau2c the critical delay at
/// k_psi = 0.5, k_y = 0.01 1/m.
int commandFig4(const Args& a, SimConfig c) {
  setConfigNumber(c, "delays.pose_to_tracker", 0.2);
  setConfigNumber(c, "actuator.p", 4000);
  SimConfig centre = c;
  setConfigNumber(centre, "tracker.k_psi", 0.5);
  setConfigNumber(centre, "tracker.k_y", 0.01);
  ScanOptions scan;
  scan.end = a.tau2_max;
  if (!(scan.end > scan.start)) badArguments("--tau2-max must exceed 1e-5 s");
  const Crossing cross = findFirstCrossing(familyOf(a, centre, "tau2"), scan);
  if (!cross.found) throw LaneKeepingError("fig4: no critical tau2 at k_psi = 0.5, k_y = 0.01: " + cross.reason);
  const double tc = cross.parameter;
  std::cerr << "lk_stability: fig4: critical tau2 at k_psi = 0.5, k_y = 0.01 1/m: " << tc * 1e3 << " ms\n";
  ChartSpec spec{ChartAxis::linear("tracker.k_psi", 0.0, 2.5, a.n), ChartAxis::linear("tracker.k_y", 0.0, 0.3, a.n),
                 Layer{"tau2", {1e-4, 0.95 * tc, tc * (1 + 5e-5), tc * (1 + 1e-4), tc * (1 + 1.5e-4)}}, Layer{},
                 "Beregi Fig 4: stable (k_psi, k_y) for tau2 (colours), tau1 = 0.2 s, p = 4000"};
  spec.markers.push_back({{"x", 0.5}, {"y", 0.01}, {"label", "tau2c = " + std::to_string(tc * 1e3).substr(0, 7) + " ms"}});
  return writeChart(a, c, spec, outputDir(a) + "/fig4");
}

/// Beregi Fig 5: (p, tau2), k_psi = 0.5, k_y = 0.01 1/m, tau1 = 0.2 s.
int commandFig5(const Args& a, SimConfig c) {
  setConfigNumber(c, "tracker.k_psi", 0.5);
  setConfigNumber(c, "tracker.k_y", 0.01);
  setConfigNumber(c, "delays.pose_to_tracker", 0.2);
  ChartSpec spec{ChartAxis::linear("actuator.p", 0.0, 8000.0, a.n), ChartAxis::linear("tau2", 0.0, 7e-3, a.n),
                 Layer{}, Layer{}, "Beregi Fig 5: stable (p, tau2), k_psi = 0.5, k_y = 0.01 1/m, tau1 = 0.2 s"};
  spec.markers.push_back({{"x", 2000}, {"y", 1.9019505e-3}, {"label", "Fig 9"}});
  return writeChart(a, c, spec, outputDir(a) + "/fig5");
}

}  // namespace stability_cli
}  // namespace lane_keeping
