#pragma once
// Command-line plumbing shared by lk_stability's sub-commands: arguments, printing JSON (the renderings
// are the core's: stability_json.h), and the loop's delay system under the printed equations or an
// alternative reading (--reading; critical_delay.h).
#include <iosfwd>
#include <string>
#include <vector>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/stability_boundary.h"
#include "lane_keeping/analysis/stability_json.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {
namespace stability_cli {

using json = StabilityJson;  // rootJson, pointJson, ...: lane_keeping/analysis/stability_json.h

struct Args {
  std::string command;
  std::vector<std::string> files, sets;
  int degree = 0, count = 6, n = 100, threads = 0, steps = 300;
  double tau2_max = 0.05;
  double time_budget_hours = 4.0;  ///< --time-budget: refuse work estimated to take longer
  std::string out, x, y, series, panels, title, param, reading;
  double from = NAN, to = NAN;
  bool uniform = false, plot = true;
};

void usage(std::ostream& out);
/// Prints the message and the usage to stderr and exits with status 2.
[[noreturn]] void badArguments(const std::string& message);
double parseNumber(const std::string& text, const std::string& what);
int parseInt(const std::string& text, const std::string& what, int min, int max);
Args parseArgs(int argc, char** argv);

SpectrumOptions spectrumOptions(const Args& a, int default_degree, int seeds);
void printJson(const json& j);

/// The budget check before the work (stability_budget.h): `spectra` spectra of `system` at `degree` on
/// `threads` threads, `points` chart points held. Exits 2 (badArguments) naming `option` and the
/// estimate if they need more memory than the machine has or more time than --time-budget; prints the
/// estimate when it exceeds a minute.
void checkBudget(const Args& a, const LinearDelaySystem& system, int degree, double spectra, int threads,
                 double points, const std::string& option);

/// The loop's delay system: the printed equations, or --reading.
LinearDelaySystem systemOf(const Args& a, const SimConfig& c);
/// Parameter family along `key` (tau2: both actuator delays), printed equations or --reading.
SystemFamily familyOf(const Args& a, const SimConfig& c, const std::string& key);

}  // namespace stability_cli
}  // namespace lane_keeping
