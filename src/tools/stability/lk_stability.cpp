// lk_stability: linear stability of the delayed lane-keeping loop about straight-line motion
// (Beregi et al. §3): critical delays, rightmost characteristic roots, stability charts.
//
//   lk_stability critical  --config FILE [--set key=value ...]   one JSON object on stdout
//   lk_stability roots     --config FILE ...                      rightmost roots (JSON)
//   lk_stability boundary  --config FILE ... --param KEY --from A --to B [--steps N] [--uniform]
//   lk_stability linearize --config FILE ...                      the DDE matrices (JSON)
//   lk_stability readings  --config FILE ...                      critical tau2 per equation reading (JSON)
//   lk_stability chart     --config FILE ... --x KEY:MIN:MAX:N --y KEY:MIN:MAX:N
//                          [--series KEY=v1,v2,..] [--panels KEY=v1,v2,..] --out PREFIX
//   lk_stability fig3|fig4|fig5 --config FILE ... --out DIR [--n N]   the paper's charts
// Charts: PREFIX.csv, PREFIX.json (axes, units, series), PREFIX.png (scripts/plot_stability.py
// with Debian's /usr/bin/python3 + matplotlib).
// Exit status: 0 ok, 2 bad arguments or configuration, 1 other error (plotting included).
#include <chrono>
#include <cmath>
#include <iostream>
#include <malloc.h>
#include <string>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/critical_delay.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/analysis/stability_json.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "stability_charts.h"
#include "stability_cli.h"

namespace {

using namespace lane_keeping;
using namespace lane_keeping::stability_cli;

/// Spectra a scan of `steps` intervals computes: one per step and the bisection's and secant's (at most
/// about 60; stability_boundary.h).
double scanSpectra(int steps) { return steps + 61.0; }

int commandCritical(const Args& a, const SimConfig& c) {
  const auto start = std::chrono::steady_clock::now();
  CriticalDelayOptions options;
  options.tau2_to = a.tau2_max;
  options.steps = a.steps;
  options.spectrum = spectrumOptions(a, 24, 10);
  options.reading = a.reading;
  checkBudget(a, systemOf(a, c), options.spectrum.degree, scanSpectra(a.steps), 1, 0, "--degree and --steps");
  if (!(options.tau2_to > options.tau2_from)) badArguments("--tau2-max must exceed 1e-5 s");
  json j = criticalDelayJson(c, criticalDelay(c, options), options, a.count);
  j["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  printJson(j);
  return 0;
}

int commandRoots(const Args& a, const SimConfig& c) {
  const SpectrumOptions so = spectrumOptions(a, 24, 10);
  checkBudget(a, systemOf(a, c), so.degree, 1, 1, 0, "--degree");
  printJson(rootsJson(c, computeSpectrum(systemOf(a, c), so), a.reading, a.count, so.degree));
  return 0;
}

int commandBoundary(const Args& a, const SimConfig& c) {
  if (a.param.empty() || std::isnan(a.from) || std::isnan(a.to)) badArguments("boundary needs --param KEY --from A --to B");
  if (a.from == a.to) badArguments("--from and --to are both " + std::to_string(a.from) + ": the scan needs two ends");
  configParameterInfo(a.param);
  ScanOptions scan;
  scan.start = a.from;
  scan.end = a.to;
  scan.steps = a.steps;
  scan.geometric = !a.uniform;
  scan.spectrum = spectrumOptions(a, 24, 10);
  if (scan.geometric && !(a.from > 0 && a.to > 0)) badArguments("a geometric scan needs --from, --to > 0 (or --uniform)");
  checkBudget(a, systemOf(a, c), scan.spectrum.degree, scanSpectra(a.steps), 1, 0, "--degree and --steps");
  printJson(boundaryJson(c, a.param, findFirstCrossing(familyOf(a, c, a.param), scan), a.reading));
  return 0;
}

int commandLinearize(const Args&, const SimConfig& c) {
  const ClosedLoopLinearization lin = linearizeClosedLoop(c);
  auto matrix = [](const Eigen::MatrixXd& m) {
    json rows = json::array();
    for (int i = 0; i < m.rows(); ++i) {
      json row = json::array();
      for (int k = 0; k < m.cols(); ++k) row.push_back(m(i, k));
      rows.push_back(row);
    }
    return rows;
  };
  json terms = json::array();
  for (const auto& t : lin.dde.delayed) terms.push_back({{"delay_s", t.delay}, {"matrix", matrix(t.matrix)}});
  json j = ddeJson(lin, nullptr, 0);
  j["a0"] = matrix(lin.dde.a0);
  j["delayed"] = terms;
  j["tracker_jacobian"] = matrix(lin.tracker_jacobian);
  j["point"] = pointJson(c);
  printJson(j);
  return 0;
}

int commandReadings(const Args& a, const SimConfig& c) {
  ScanOptions scan;
  scan.start = 1e-5;
  scan.end = a.tau2_max;
  scan.steps = a.steps;
  scan.spectrum = spectrumOptions(a, 24, 10);
  checkBudget(a, systemOf(a, c), scan.spectrum.degree, scanSpectra(a.steps) * candidateReadings().size(), 1, 0,
              "--degree and --steps");
  json rows = json::array();
  double printed = NAN;
  for (const auto& reading : candidateReadings()) {
    const Crossing cross = findFirstCrossing(readingFamily(c, reading), scan);
    if (reading.name == "printed") printed = cross.parameter;
    json row{{"reading", reading.name}, {"description", reading.description}, {"found", cross.found},
             {"tau2_critical_s", cross.found ? json(cross.parameter) : json(nullptr)},
             {"frequency_hz", cross.found ? json(cross.frequencyHz()) : json(nullptr)}};
    if (cross.found && std::isfinite(printed)) row["change_vs_printed"] = cross.parameter / printed - 1.0;
    if (cross.found) row["paper_fig9_over_critical"] = 1.9019505e-3 / cross.parameter - 1.0;
    rows.push_back(row);
  }
  printJson(json{{"point", pointJson(c)}, {"paper_fig9_tau2_s", 1.9019505e-3}, {"readings", rows}});
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Chart points allocate and free ~100 kB matrices; without this glibc returns the heap top to the
  // kernel after every point and half the run is spent in brk and page faults.
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  const Args args = parseArgs(argc, argv);
  try {
    const SimConfig config = loadSimConfig(args.files, args.sets);
    if (config.path.type != "straight") {
      std::cerr << "lk_stability: note: path.type = " << config.path.type
                << " is not used; the analysis linearises about straight-line motion on a straight lane\n";
    }
    if (args.command == "critical") return commandCritical(args, config);
    if (args.command == "roots") return commandRoots(args, config);
    if (args.command == "boundary") return commandBoundary(args, config);
    if (args.command == "linearize") return commandLinearize(args, config);
    if (args.command == "readings") return commandReadings(args, config);
    if (args.command == "chart") return commandChart(args, config);
    if (args.command == "fig3") return commandFig3(args, config);
    if (args.command == "fig4") return commandFig4(args, config);
    if (args.command == "fig5") return commandFig5(args, config);
    badArguments("unknown command '" + args.command + "'");
  } catch (const UsageError& e) {
    badArguments(e.what());
  } catch (const ConfigError& e) {
    std::cerr << "lk_stability: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lk_stability: " << e.what() << "\n";
    return 1;
  }
}
