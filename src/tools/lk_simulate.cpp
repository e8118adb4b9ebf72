// lk_simulate: in-process closed-loop simulation of the lane-keeping loop.
//   lk_simulate --config FILE [--config FILE ...] [--set key=value ...] [--change T:key=value ...]
//               [--tire MODEL] [--out run.csv]
// Prints the run summary. Exit status: 0 completed, 3 diverged, 2 bad arguments or configuration (a lockstep
// schedule the delays cannot advance included), 1 other error.
#include <chrono>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/file_identity.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/run_summary.h"

namespace {

void usage(std::ostream& out) {
  out << "usage: lk_simulate --config FILE [--config FILE ...] [--set key=value ...] [--change T:key=value ...]\n"
         "                   [--tire MODEL] [--out run.csv] [--print-config] [--quiet]\n"
         "  --config FILE     YAML overlay on the paper defaults (config/default.yaml lists every key)\n"
         "  --set key=value   override one key, e.g. --set tracker.k_y=0.15 --set delays.steering_angle_to_actuator=1.9e-3\n"
         "  --change T:key=value  from simulated time T [s] on, key has value (runtime tuning; repeatable), e.g.\n"
         "                    --change 10:steering.coulomb_friction=3; it takes effect at its component's first\n"
         "                    sample at or after T; the summary lists each change (docs/ros.md, Runtime tuning)\n"
         "  --tire MODEL      shorthand for --set tire.front.model=MODEL --set tire.rear.model=MODEL\n"
         "  --out run.csv     write the log (DESIGN §5 columns + extras) and run.csv.config.yaml\n"
         "  --print-config    print the effective configuration and exit\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lane_keeping;
  std::vector<std::string> files, sets, change_texts;
  std::string out_path;
  bool print_config = false, quiet = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* name) -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "lk_simulate: " << name << " needs a value\n";
        usage(std::cerr);
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--config") {
      files.push_back(value("--config"));
    } else if (arg == "--set") {
      sets.push_back(value("--set"));
    } else if (arg == "--change") {
      change_texts.push_back(value("--change"));
    } else if (arg == "--tire") {
      const std::string model = value("--tire");
      sets.push_back("tire.front.model=" + model);
      sets.push_back("tire.rear.model=" + model);
    } else if (arg == "--out") {
      out_path = value("--out");
    } else if (arg == "--print-config") {
      print_config = true;
    } else if (arg == "--quiet") {
      quiet = true;
    } else if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return 0;
    } else {
      std::cerr << "lk_simulate: unknown argument '" << arg << "'\n";
      usage(std::cerr);
      return 2;
    }
  }
  try {
    if (!out_path.empty()) {
      // --out my.yaml beside --config my.yaml replaced the configuration with the log.
      std::vector<PathArgument> inputs;
      for (const auto& file : files) inputs.emplace_back("--config", file);
      refuseOutputAmongInputs({"--out", out_path}, inputs);
      refuseOutputAmongInputs({"--out", out_path + ".config.yaml"}, inputs);
    }
    const SimConfig config = loadSimConfig(files, sets);
    if (print_config) {
      config.print(std::cout, true);
      return 0;
    }
    std::vector<TimedChange> changes;
    for (const auto& text : change_texts) changes.push_back(parseTimedChange(text));
    const ClosedLoop loop(config, changes);
    const auto wall_start = std::chrono::steady_clock::now();
    const RunResult result = loop.run();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    if (!out_path.empty()) {
      writeLogCsv(out_path, result.rows);
      std::ofstream config_out(out_path + ".config.yaml");
      config_out << "# effective configuration of " << out_path << "\n";
      std::vector<ScheduledChange> changes = result.changes;
      sortForSummary(changes);
      for (const auto& change : changes) {
        config_out << "# changed during the run (--change " << change.argument() << "): " << change.describe() << "\n";
      }
      config.print(config_out);
    }
    if (!quiet) {
      std::cout << formatSummary(summarizeRun(config, result));
      std::cout << "wall time:              " << wall << " s (" << result.end_time / wall << "x real time, "
                << result.plant_steps << " plant steps)\n";
      if (!out_path.empty()) std::cout << "log:                    " << out_path << " (" << result.rows.size() << " rows)\n";
    }
    return result.diverged() ? 3 : 0;
  } catch (const UsageError& e) {
    std::cerr << "lk_simulate: " << e.what() << "\n";
    return 2;
  } catch (const ConfigError& e) {
    std::cerr << "lk_simulate: " << e.what() << "\n";
    return 2;
  } catch (const ScheduleError& e) {  // the configured step, rates and delays give the loop no lookahead
    std::cerr << "lk_simulate: invalid configuration: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "lk_simulate: " << e.what() << "\n";
    return 1;
  }
}
