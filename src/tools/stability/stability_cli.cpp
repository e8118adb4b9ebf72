#include "stability_cli.h"

#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "lane_keeping/analysis/critical_delay.h"
#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/analysis/equation_readings.h"
#include "lane_keeping/analysis/stability_budget.h"
#include "lane_keeping/analysis/stability_chart.h"
#include "lane_keeping/common/command_line.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace stability_cli {

void usage(std::ostream& out) {
  out << "usage: lk_stability COMMAND --config FILE [--config FILE ...] [--set key=value ...] [--tire MODEL] [options]\n"
         "commands:\n"
         "  critical    critical lower-level delay tau2 (both actuator delays moved together) and the\n"
         "              crossing frequency, plus the rightmost roots at the configured tau2: one JSON object\n"
         "  roots       rightmost characteristic roots at the configured point (JSON)\n"
         "  boundary    first loss of stability along --param KEY from --from A to --to B (JSON)\n"
         "  linearize   the delay-differential system x' = A0 x + sum A_j x(t - tau_j) (JSON)\n"
         "  readings    critical tau2 under alternative readings of the paper's equations (JSON)\n"
         "  chart       stability chart over --x KEY:MIN:MAX:N and --y KEY:MIN:MAX:N, optional\n"
         "              --series KEY=v1,v2,... (one boundary per value) and --panels KEY=v1,v2,...\n"
         "  fig3        Beregi Fig 3: (k_psi, k_y) for tau1 in panels and p in series, tau2 = 0.1 ms\n"
         "  fig4        Beregi Fig 4: (k_psi, k_y) for several tau2, tau1 = 0.2 s, p = 4000\n"
         "  fig5        Beregi Fig 5: (p, tau2), k_psi = 0.5, k_y = 0.01 1/m, tau1 = 0.2 s\n"
         "options:\n"
         "  --tau2 S          shorthand for both actuator delays (delays.desired_steering_to_actuator and\n"
         "                    delays.steering_angle_to_actuator), in seconds\n"
         "  --degree M        Chebyshev degree per delay line (default 24; charts 20)\n"
         "  --count K         roots to report (default 6)\n"
         "  --tau2-max S      end of the tau2 scan of `critical` (default 0.05 s)\n"
         "  --out PREFIX|DIR  chart output prefix (chart) or directory (fig3-5)\n"
         "  --n N             grid points per axis for fig3-5 (default 100)\n"
         "  --threads T       worker threads for charts (default: all cores)\n"
         "  --title TEXT      chart title;  --no-plot  CSV and JSON only\n"
         "  --time-budget H   refuse work estimated to take longer than H hours (default 4; the estimate is\n"
         "                    printed above a minute, docs/reliability.md)\n"
         "  --reading NAME    use an alternative reading of the paper's equations (see `readings`)\n"
         "  KEY is a numeric configuration key (lk_simulate --print-config) or tau2.\n";
}


[[noreturn]] void badArguments(const std::string& message) {
  std::cerr << "lk_stability: " << message << "\n";
  usage(std::cerr);
  std::exit(2);
}

double parseNumber(const std::string& text, const std::string& what) {
  try {
    return numberOption(what, text, -1.7976931348623157e308, 1.7976931348623157e308);
  } catch (const UsageError& e) {
    badArguments(e.what());
  }
}

int parseInt(const std::string& text, const std::string& what, int min, int max) {
  try {
    return static_cast<int>(wholeNumberOption(what, text, min, max));
  } catch (const UsageError& e) {
    badArguments(e.what());
  }
}

void checkBudget(const Args& a, const LinearDelaySystem& system, int degree, double spectra, int threads,
                 double points, const std::string& option) {
  const SpectrumCost one = spectrumCost(system, degree);
  const double workers = std::max(1, threads);
  const double bytes = workers * one.bytes + points * sizeof(ChartPoint) + 50e6;
  const double seconds = spectra * one.seconds / workers;
  std::ostringstream estimate;
  estimate << formatNumber(spectra) << (spectra == 1 ? " spectrum" : " spectra") << " of order " << one.order
           << " (degree " << degree << " per delay line)" << (points > 0 ? ", " + formatNumber(points) + " chart points" : "")
           << ": about " << formatDuration(seconds) << " on " << workers << (workers == 1 ? " thread" : " threads")
           << " and " << formatBytes(bytes) << " of memory";
  const double memory = physicalMemoryBytes();
  if (memory > 0.0 && bytes > 0.8 * memory) {
    badArguments(option + ": " + estimate.str() + ", more than this machine's " + formatBytes(memory) +
                 "; lower it");
  }
  if (seconds > a.time_budget_hours * 3600.0) {
    badArguments(option + ": " + estimate.str() + ", more than --time-budget " + formatNumber(a.time_budget_hours) +
                 " h; lower it or raise --time-budget");
  }
  if (seconds > 60.0) std::cerr << "lk_stability: note: " << estimate.str() << "\n";
}

Args parseArgs(int argc, char** argv) {
  Args a;
  if (argc < 2) badArguments("missing command");
  a.command = argv[1];
  if (a.command == "--help" || a.command == "-h") {
    usage(std::cout);
    std::exit(0);
  }
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) badArguments(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--config") a.files.push_back(value());
    else if (arg == "--set") a.sets.push_back(value());
    else if (arg == "--tire") {
      const std::string model = value();
      a.sets.push_back("tire.front.model=" + model);
      a.sets.push_back("tire.rear.model=" + model);
    } else if (arg == "--tau2") {
      const std::string seconds = value();
      a.sets.push_back("delays.desired_steering_to_actuator=" + seconds);
      a.sets.push_back("delays.steering_angle_to_actuator=" + seconds);
    } else if (arg == "--degree") a.degree = parseInt(value(), "--degree", 2, 100000);
    else if (arg == "--count") a.count = parseInt(value(), "--count", 1, 10000);
    else if (arg == "--n") a.n = parseInt(value(), "--n", 2, 1000000);
    else if (arg == "--threads") a.threads = parseInt(value(), "--threads", 1, 1024);
    else if (arg == "--steps") a.steps = parseInt(value(), "--steps", 1, 10000000);
    else if (arg == "--tau2-max") a.tau2_max = parseNumber(value(), "--tau2-max");
    else if (arg == "--time-budget") {
      try {
        a.time_budget_hours = numberOption(arg, value(), 0.0, 1e4, "h");
      } catch (const UsageError& e) {
        badArguments(e.what());
      }
    }
    else if (arg == "--out") a.out = value();
    else if (arg == "--x") a.x = value();
    else if (arg == "--y") a.y = value();
    else if (arg == "--series") a.series = value();
    else if (arg == "--panels") a.panels = value();
    else if (arg == "--title") a.title = value();
    else if (arg == "--param") a.param = value();
    else if (arg == "--reading") a.reading = value();
    else if (arg == "--from") a.from = parseNumber(value(), "--from");
    else if (arg == "--to") a.to = parseNumber(value(), "--to");
    else if (arg == "--uniform") a.uniform = true;
    else if (arg == "--no-plot") a.plot = false;
    else if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      std::exit(0);
    } else badArguments("unknown argument '" + arg + "'");
  }
  return a;
}

SpectrumOptions spectrumOptions(const Args& a, int default_degree, int seeds) {
  SpectrumOptions o;
  o.degree = a.degree > 0 ? a.degree : default_degree;
  o.seeds = std::max(seeds, a.count + 4);
  return o;
}

void printJson(const json& j) { std::cout << j.dump(2) << "\n"; }

LinearDelaySystem systemOf(const Args& a, const SimConfig& c) { return loopDelaySystem(c, a.reading); }

SystemFamily familyOf(const Args& a, const SimConfig& c, const std::string& key) { return loopFamily(c, key, a.reading); }

}  // namespace stability_cli
}  // namespace lane_keeping
