// lk_gap: sim-to-real gap diagnosis.
//   lk_gap --config nominal.yaml [--set key=value ...] --log run.csv [--scenario run.yaml] [--log more.csv ...]
//          [--holdout other.csv [--scenario other.yaml] ...] --report DIR [--effects a,b,...] [--threads N]
//          [--no-plots] [--quiet]
// Writes DIR/report.json (DESIGN §5 fields), DIR/report.md and plots (residuals, spectra, overlays,
// ranking). Exit status: 0 ok, 2 bad configuration, 4 bad input data, 1 other error.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_reader.h"
#include "lane_keeping/gap/report/gap_report_markdown.h"
#include "bag_log_reader.h"

namespace {

void usage(std::ostream& out) {
  out << "usage: lk_gap --config nominal.yaml [--set key=value ...] --log run.csv|run.bag [--scenario run.yaml]\n"
         "              [--log ...] [--holdout other.csv|other.bag [--scenario other.yaml] ...] --report DIR\n"
         "              [--effects a,b] [--threads N] [--coarse-fit-stride K] [--no-plots] [--quiet]\n"
         "  --config   the nominal configuration (the same YAML lk_simulate and the nodes use): the car, its\n"
         "             controllers and delays, shared by every run\n"
         "  --log      a log of a real run (CSV with DESIGN §5 columns, or a bag of the suite's topics)\n"
         "  --scenario right after a --log or --holdout: that run's own settings (path, initial state, duration,\n"
         "             speed, test signal) overlaid on the nominal; without one the run uses the shared\n"
         "             configuration; an initial state configured nowhere is taken from the log's first samples\n"
         "  --log-map  right after a --log or --holdout: a file whose log: section maps that log's columns\n"
         "             (names, scale and offset, time unit, unscaled columns); a log: section may also stand in\n"
         "             the nominal configuration (every log) or in a scenario (its log)\n"
         "  --holdout  held-out runs for scoring; without them, blocks of the logs are held out\n"
         "  --report   output directory: report.json, report.md, *.csv, *.png\n"
         "  --noise-reference-draws N   draws of the noise-only null: the detection test's tail, and the largest\n"
         "             is the noise reference the gap is net of (default 19: a test at 5 %; 0 = raw excess, no test)\n"
         "  --coarse-fit-stride K   fit each candidate coarse to fine: search on every K-th 2 s piece of the\n"
         "             training data, finish on all of it (default 3; 1: search all the data; docs/gap.md)\n";
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lane_keeping;
  std::vector<std::string> configs, sets;
  struct RunArgument {
    std::string log, scenario, log_map;
  };
  std::vector<RunArgument> logs, heldout;
  std::vector<RunArgument>* last_run = nullptr;  // the run a following --scenario belongs to
  std::string report_dir;
  DiagnosisOptions options;
  bool plots = true, quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "lk_gap: " << arg << " needs a value\n";
        usage(std::cerr);
        std::exit(2);
      }
      return argv[++i];
    };
    std::vector<RunArgument>* const previous_run = last_run;
    last_run = nullptr;
    if (arg == "--config") configs.push_back(value());
    else if (arg == "--set") sets.push_back(value());
    else if (arg == "--log" || arg == "--holdout") {
      last_run = arg == "--log" ? &logs : &heldout;
      last_run->push_back({value(), "", ""});
    } else if (arg == "--scenario" || arg == "--log-map") {
      const std::string file = value();
      if (previous_run == nullptr) {
        std::cerr << "lk_gap: " << arg << " " << file << " must follow the --log or --holdout it belongs to\n";
        return 2;
      }
      (arg == "--scenario" ? previous_run->back().scenario : previous_run->back().log_map) = file;
      last_run = previous_run;  // --log a.csv --scenario a.yaml --log-map m.yaml
    }
    else if (arg == "--report") report_dir = value();
    else if (arg == "--effects") options.effects = split(value());
    else if (arg == "--threads") options.threads = std::atoi(value().c_str());
    else if (arg == "--noise-reference-draws") options.noise_reference_draws = std::atoi(value().c_str());
    else if (arg == "--coarse-fit-stride") {
      options.coarse_fit_stride = static_cast<std::size_t>(std::max(1, std::atoi(value().c_str())));
    }
    else if (arg == "--no-plots") plots = false;
    else if (arg == "--quiet") quiet = true;
    else if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return 0;
    } else {
      std::cerr << "lk_gap: unknown argument '" << arg << "'\n";
      usage(std::cerr);
      return 2;
    }
  }
  if (configs.empty() || logs.empty() || report_dir.empty()) {
    std::cerr << "lk_gap: --config, --log and --report are required\n";
    usage(std::cerr);
    return 2;
  }
  if (options.noise_reference_draws < 0 || options.noise_reference_draws > 100) {
    std::cerr << "lk_gap: --noise-reference-draws must be between 0 and 100\n";
    return 2;
  }
  registerBagLogReader([](const std::string& path) { return readBagLog(path); });
  try {
    FlatParams nominal_params;
    LogMapping shared_mapping;  // a log: section of the nominal configuration applies to every log
    for (const auto& file : configs) {
      nominal_params.overlayFile(file);
      const LogMapping m = readLogMapping(file);
      if (!m.source.empty()) shared_mapping = m;
    }
    for (const auto& assignment : sets) nominal_params.overlayAssignment(assignment);
    nominal_params.erasePrefix("log.");
    const SimConfig nominal = simConfigFromFlat(nominal_params);
    auto runsOf = [&](const std::vector<RunArgument>& arguments) {
      std::vector<GapRun> runs;
      for (const auto& a : arguments) {
        // The log's mapping: its own file, else its scenario's log: section, else the nominal's.
        LogMapping mapping = shared_mapping;
        if (!a.scenario.empty()) {
          const LogMapping m = readLogMapping(a.scenario);
          if (!m.source.empty()) mapping = m;
        }
        if (!a.log_map.empty()) {
          mapping = readLogMapping(a.log_map);
          if (mapping.source.empty()) throw ConfigError("--log-map " + a.log_map + ": the file has no log: section");
        }
        GapLog log = readLog(a.log, mapping);
        runs.push_back(a.scenario.empty() ? gapRun(std::move(log), nominal_params, FlatParams{}, "")
                                          : gapRun(std::move(log), nominal_params, a.scenario));
      }
      return runs;
    };
    const std::vector<GapRun> training = runsOf(logs), held = runsOf(heldout);
    for (const auto& effect : options.effects) {
      bool known = false;
      for (const auto& name : candidateEffectNames()) known = known || name == effect;
      if (!known) throw ConfigError("--effects: '" + effect + "' is not a candidate effect");
    }
    if (!quiet) options.progress = [](const std::string& m) { std::cerr << "[lk_gap] " << m << "\n"; };
    // Created up front (with parents): a long diagnosis must not end on "cannot open for writing".
    std::error_code mkdir_error;
    std::filesystem::create_directories(report_dir, mkdir_error);
    if (mkdir_error) throw InputError("--report " + report_dir + ": cannot create the directory (" + mkdir_error.message() + ")");
    DiagnosisArtifacts artifacts;
    const GapReport report = diagnoseGap(nominal, training, held, options, &artifacts);
    writeGapReportJson(report_dir + "/report.json", report);
    writeDiagnosisArtifacts(report_dir, artifacts);
    if (plots) {
      const std::string command = "/usr/bin/python3 " + std::string(LANE_KEEPING_SOURCE_DIR) +
                                  "/scripts/gap_report_plots.py '" + report_dir + "' >/dev/null 2>&1";
      if (std::system(command.c_str()) != 0) std::cerr << "lk_gap: plotting failed (python3-matplotlib?); report.md has no figures\n";
    }
    writeGapReportMarkdown(report_dir, report);
    const GapVerdict& v = report.verdict;
    for (const auto& s : report.skipped_subsystems) std::cout << "skipped: the " << s.name << " replay (" << s.reason << ")\n";
    for (const auto& e : report.not_testable) std::cout << "not testable: " << e.effect << " (" << e.reason << ")\n";
    std::cout << "verdict: " << v.effect << (v.form.empty() ? "" : " (" + v.form + ")") << " (confidence "
              << v.confidence << ")\n"
              << "held-out gap: " << v.gap_before << " -> " << v.gap_after << " (shrink " << 100.0 * v.shrink << " %)\n"
              << "where: " << report.where.subsystem << "\n"
              << "reason: " << v.reason << "\n"
              << "report: " << report_dir << "/report.md\n";
    return 0;
  } catch (const ConfigError& e) {
    std::cerr << "lk_gap: " << e.what() << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "lk_gap: " << e.what() << "\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "lk_gap: " << e.what() << "\n";
    return 1;
  }
}
