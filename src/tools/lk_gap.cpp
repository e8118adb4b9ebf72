// lk_gap: sim-to-real gap diagnosis.
//   lk_gap --config nominal.yaml [--set key=value ...] --log run.csv [--scenario run.yaml] [--log more.csv ...]
//          [--holdout other.csv [--scenario other.yaml] ...] --report DIR [--effects a,b,...] [--threads N]
//          [--no-plots] [--quiet]
// Writes DIR/report.json (DESIGN §5 fields), DIR/report.md and plots (residuals, spectra, overlays,
// ranking), all at once (report_directory.h). Exit status: 0 ok, 2 bad arguments or configuration,
// 4 bad input data, 1 other error.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "lane_keeping/common/child_process.h"
#include "lane_keeping/common/command_line.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/file_identity.h"
#include "lane_keeping/common/resources.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_reader.h"
#include "lane_keeping/gap/report/gap_report_markdown.h"
#include "lane_keeping/gap/report/report_directory.h"
#include "bag_log_reader.h"
#include "lk_gap_budget.h"
#include "build_paths.h"

namespace {

using namespace lane_keeping;

void usage(std::ostream& out) {
  out << "usage: lk_gap --config nominal.yaml [--set key=value ...] --log run.csv|run.bag [--scenario run.yaml]\n"
         "              [--log ...] [--holdout other.csv|other.bag [--scenario other.yaml] ...] --report DIR\n"
         "              [--effects a,b] [--threads N] [--coarse-fit-stride K] [--noise-reference-draws N]\n"
         "              [--one-fold] [--candidate-forms-only] [--no-closed-loop-placement] [--time-budget HOURS]\n"
         "              [--no-plots] [--quiet]\n"
         "  --config   the nominal configuration (the same YAML lk_simulate and the nodes use): the car, its\n"
         "             controllers and delays, shared by every run\n"
         "  --log      a log of a real run (CSV with DESIGN §5 columns, or a bag of the suite's topics)\n"
         "  --scenario right after a --log or --holdout: that run's own settings (path, initial state, duration,\n"
         "             speed, test signal) overlaid on the nominal; without one the run uses the shared\n"
         "             configuration; an initial state configured nowhere is taken from the log's first samples\n"
         "  --log-map  right after a --log or --holdout: a file whose log: section maps that log's columns\n"
         "             (names, scale and offset, time unit, unscaled columns); a log: section may also stand in\n"
         "             the nominal configuration (every log) or in a scenario (its log)\n"
         "  --holdout  held-out runs for scoring (other files than the --log ones); without them, blocks of the\n"
         "             logs are held out\n"
         "  --report   output directory: report.json, report.md, *.csv, *.png, written beside it and moved into\n"
         "             place when complete; it must be new, empty, or hold an earlier report\n"
         "  --threads N   candidates fitted in parallel (default 2; 1-256)\n"
         "  --noise-reference-draws N   draws of the noise-only null: the detection test's tail, and the largest\n"
         "             is the noise reference the gap is net of (default 19: a test at 5 %; fewer cannot detect a\n"
         "             gap and are refused; 0 = raw excess, no test; at most 1000)\n"
         "  --coarse-fit-stride K   fit each candidate coarse to fine: search on every K-th 2 s piece of the\n"
         "             training data, finish on all of it (default 3; 1: search all the data; docs/gap.md)\n"
         "  --one-fold   where the held-out test alone misses a gap both sides together show, say so and stop\n"
         "             (default: hold each side out in turn and name an effect both folds name; with three runs\n"
         "             or more, hold each run out in turn and decide on the held-out evidence summed over them)\n"
         "  --every-fold hold every run (or side) out in turn even where the held-out test alone detects the gap,\n"
         "             and list each fold in the report\n"
         "  --no-measured-corrections   report the gyro scale and drift the input checks measure against psi\n"
         "             and ay / V (with a note where the verdict does not hold them) but read the log as it is\n"
         "             (default: corrected before the fits and named among the verdict's effects)\n"
         "  --no-targeted-test   where the replays' test sees no gap, do not test the actuation delay's fit\n"
         "             against the same fit on the noise-only draws (default: named where it beats every draw on\n"
         "             both sides; docs/gap.md, \"A delay tested on its own fit\")\n"
         "  --max-side-force G   the largest steady side force a candidate may fit and still be the cause,\n"
         "             as a fraction of the car's weight (default 0.1: a road's steepest bank or a storm's\n"
         "             crosswind; 0 lifts the bound; a banked oval needs more)\n"
         "  --candidate-forms-only   do not fit the other forms of the leader and of further effects\n"
         "             (LuGre kingpin friction for steering_friction, a soft saturation for torque_limit,\n"
         "             the contact patch's length for cornering_stiffness; docs/gap.md, \"How far\")\n"
         "  --no-closed-loop-placement   keep one named effect at the replays' fit where its closed loop closes\n"
         "             clearly less than its replays (default: placed by the training runs' closed loop among the\n"
         "             values the replays cannot tell apart; docs/gap.md, \"Placed by the closed loop\")\n"
         "  --time-budget HOURS   refuse logs whose diagnosis is estimated to take longer (default 1; the\n"
         "             estimate is printed when it exceeds 10 minutes; docs/reliability.md)\n";
}

[[noreturn]] void badUsage(const std::string& message) { throw UsageError(message); }

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

struct RunArgument {
  std::string log, scenario, log_map;
};

struct Arguments {
  std::vector<std::string> configs, sets;
  std::vector<RunArgument> logs, heldout;
  std::string report_dir;
  DiagnosisOptions options;
  double time_budget_hours = 1.0;
  bool plots = true, quiet = false;
};

Arguments parseArguments(int argc, char** argv) {
  Arguments a;
  std::vector<RunArgument>* last_run = nullptr;  // the run a following --scenario belongs to
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) badUsage(arg + " needs a value");
      return argv[++i];
    };
    std::vector<RunArgument>* const previous_run = last_run;
    last_run = nullptr;
    if (arg == "--config") a.configs.push_back(value());
    else if (arg == "--set") a.sets.push_back(value());
    else if (arg == "--log" || arg == "--holdout") {
      last_run = arg == "--log" ? &a.logs : &a.heldout;
      last_run->push_back({value(), "", ""});
    } else if (arg == "--scenario" || arg == "--log-map") {
      const std::string file = value();
      if (previous_run == nullptr) badUsage(arg + " " + file + " must follow the --log or --holdout it belongs to");
      (arg == "--scenario" ? previous_run->back().scenario : previous_run->back().log_map) = file;
      last_run = previous_run;  // --log a.csv --scenario a.yaml --log-map m.yaml
    }
    else if (arg == "--report") a.report_dir = value();
    else if (arg == "--effects") a.options.effects = split(value());
    else if (arg == "--threads") a.options.threads = static_cast<int>(wholeNumberOption(arg, value(), 1, 256));
    else if (arg == "--noise-reference-draws") {
      const std::string text = value();
      const int draws = static_cast<int>(wholeNumberOption(arg, text, 0, 1000));
      const int least = diagnosis::minimumNoiseDraws(a.options.false_alarm_rate);
      if (draws > 0 && draws < least) {
        badUsage(arg + ": " + text + " draws cannot detect a gap: the test's smallest p-value is 1 / (draws + 1) = " +
                 std::to_string(1.0 / (draws + 1)).substr(0, 5) + ", above its level " +
                 std::to_string(a.options.false_alarm_rate).substr(0, 4) + "; give at least " + std::to_string(least) +
                 " (ceil(1 / level) - 1), or 0 to turn the test off");
      }
      a.options.noise_reference_draws = draws;
    }
    else if (arg == "--coarse-fit-stride") {
      a.options.coarse_fit_stride = static_cast<std::size_t>(wholeNumberOption(arg, value(), 1, 1000));
    }
    else if (arg == "--time-budget") a.time_budget_hours = numberOption(arg, value(), 0.0, 1e4, "h");
    else if (arg == "--one-fold") a.options.two_folds = false;
    else if (arg == "--every-fold") a.options.every_fold = true;
    else if (arg == "--no-measured-corrections") a.options.correct_measured_sensor_errors = false;
    else if (arg == "--no-targeted-test") a.options.targeted_delay_test = false;
    else if (arg == "--max-side-force") a.options.max_side_force = numberOption(arg, value(), 0.0, 10.0, "g");
    else if (arg == "--candidate-forms-only") a.options.leader_forms = false;
    else if (arg == "--no-closed-loop-placement") a.options.closed_loop_placement = false;
    else if (arg == "--no-plots") a.plots = false;
    else if (arg == "--quiet") a.quiet = true;
    else if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      std::exit(0);
    } else {
      badUsage("unknown argument '" + arg + "'");
    }
  }
  if (a.configs.empty() || a.logs.empty() || a.report_dir.empty()) badUsage("--config, --log and --report are required");
  return a;
}

/// Before any work: every log a different file (a held-out log that is a training log scored in-sample),
/// and the report directory neither an input nor holding one (it is replaced as a whole).
void checkArgumentFiles(const Arguments& a) {
  std::vector<PathArgument> runs;
  for (const auto& r : a.logs) runs.emplace_back("--log", r.log);
  for (const auto& r : a.heldout) runs.emplace_back("--holdout", r.log);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    for (std::size_t k = 0; k < i; ++k) {
      if (!sameFile(runs[i].second, runs[k].second)) continue;
      if (runs[i].first == "--holdout" && runs[k].first == "--log") {
        badUsage("--holdout " + runs[i].second + " is the file given as --log " + runs[k].second +
                 ": its held-out scores would be in-sample; give a log of another run, or no --holdout (blocks of "
                 "the logs are then held out)");
      }
      badUsage(runs[i].first + " " + runs[i].second + " is the file given as " + runs[k].first + " " +
               runs[k].second + " already: each run once");
    }
  }
  // A log must be a file (a directory read as an empty log, a device without end), and one a diagnosis
  // can hold: its size is checked before it is read, its rows and span after (lk_gap_budget.h).
  for (const auto& [option, path] : runs) {
    const std::string why = whyNotRegularFile(path);
    if (!why.empty() && why.find("pipe") == std::string::npos) throw InputError(option + " " + path + ": it " + why);
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(path, ec);
    if (!ec && static_cast<double>(bytes) > kMaxLogBytes) {
      throw InputError(option + " " + path + ": " + formatBytes(static_cast<double>(bytes)) + "; a log is at most " +
                       formatBytes(kMaxLogBytes) + " (an hour at 1 kHz is about 0.5 GB): diagnose a part of it");
    }
  }
  std::vector<PathArgument> inputs = runs;
  for (const auto& file : a.configs) inputs.emplace_back("--config", file);
  for (const auto* list : {&a.logs, &a.heldout}) {
    for (const auto& r : *list) {
      inputs.emplace_back("--scenario", r.scenario);
      inputs.emplace_back("--log-map", r.log_map);
    }
  }
  refuseOutputAmongInputs({"--report", a.report_dir}, inputs, true);
}

int run(int argc, char** argv) {
  Arguments a = parseArguments(argc, argv);
  checkArgumentFiles(a);
  // The report directory is checked, locked and staged before the diagnosis: an unwritable one used to
  // be found after it, and two runs into one directory both exited 0 with one report lost.
  ReportDirectory report_dir(a.report_dir);
  registerBagLogReader([](const std::string& path) { return readBagLog(path); });
  DiagnosisOptions& options = a.options;
  FlatParams nominal_params;
  LogMapping shared_mapping;  // a log: section of the nominal configuration applies to every log
  for (const auto& file : a.configs) {
    nominal_params.overlayFile(file);
    const LogMapping m = readLogMapping(file);
    if (!m.source.empty()) shared_mapping = m;
  }
  for (const auto& assignment : a.sets) nominal_params.overlayAssignment(assignment);
  nominal_params.erasePrefix("log.");
  const SimConfig nominal = simConfigFromFlat(nominal_params);
  for (const auto& effect : options.effects) {
    bool known = false;
    for (const auto& name : candidateEffectNames()) known = known || name == effect;
    if (!known) throw ConfigError("--effects: '" + effect + "' is not a candidate effect");
  }
  auto runsOf = [&](const std::vector<RunArgument>& arguments) {
    std::vector<GapRun> runs;
    for (const auto& r : arguments) {
      // The log's mapping: its own file, else its scenario's log: section, else the nominal's.
      LogMapping mapping = shared_mapping;
      if (!r.scenario.empty()) {
        const LogMapping m = readLogMapping(r.scenario);
        if (!m.source.empty()) mapping = m;
      }
      if (!r.log_map.empty()) {
        mapping = readLogMapping(r.log_map);
        if (mapping.source.empty()) throw ConfigError("--log-map " + r.log_map + ": the file has no log: section");
      }
      GapLog log = readLog(r.log, mapping);
      runs.push_back(r.scenario.empty() ? gapRun(std::move(log), nominal_params, FlatParams{}, "")
                                        : gapRun(std::move(log), nominal_params, r.scenario));
    }
    return runs;
  };
  const std::vector<GapRun> training = runsOf(a.logs), held = runsOf(a.heldout);
  // The budget: what the logs' rows and spans will cost, before the work (lk_gap_budget.h).
  const DiagnosisBudget budget = estimateDiagnosisBudget(training, held, options);
  checkDiagnosisBudget(budget, a.time_budget_hours, std::cerr);
  if (!a.quiet) options.progress = [](const std::string& m) { std::cerr << "[lk_gap] " << m << "\n"; };
  DiagnosisArtifacts artifacts;
  const GapReport report = diagnoseGap(nominal, training, held, options, &artifacts);
  const std::string& dir = report_dir.staging();
  writeGapReportJson(dir + "/report.json", report);
  writeDiagnosisArtifacts(dir, artifacts);
  if (a.plots) {
    // Started from its argument vector: no shell reads the directory's name (child_process.h).
    const std::string script = std::string(lane_keeping::build_paths::sourceDir()) + "/scripts/gap_report_plots.py";
    const ChildResult plot = runChild({"/usr/bin/python3", script, dir});
    if (!plot.ok()) {
      std::cerr << "lk_gap: plotting failed (/usr/bin/python3 scripts/gap_report_plots.py: " << plot.failure()
                << "); report.md has no figures\n";
    }
  }
  writeGapReportMarkdown(dir, report, a.report_dir);
  report_dir.publish();
  const GapVerdict& v = report.verdict;
  for (const auto& s : report.skipped_subsystems) std::cout << "skipped: the " << s.name << " replay (" << s.reason << ")\n";
  for (const auto& e : report.not_testable) std::cout << "not testable: " << e.effect << " (" << e.reason << ")\n";
  std::cout << "verdict: " << v.effect << (v.form.empty() ? "" : " (" + v.form + ")") << " (confidence "
            << v.confidence << ")\n"
            << "held-out gap: " << v.gap_before << " -> " << v.gap_after << " (shrink " << 100.0 * v.shrink << " %)\n"
            << "where: " << report.where.subsystem << "\n"
            << "reason: " << v.reason << "\n"
            << "report: " << a.report_dir << "/report.md\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "lk_gap: " << e.what() << "\n(lk_gap --help lists the options)\n";
    return 2;
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
