// Benchmark of the gap diagnosis (issue #5): wall time to diagnose a 60 s log sampled at 100 Hz and at
// 1 kHz with all eleven candidates (held-out blocks, closed-loop replay included), on the threads given.
// The logs are generated like the withheld-effect benchmark (steering friction hidden, sensor noise).
//   lk_bench_gap [--threads N] [--duration S] [--rate HZ] [--effects a,b,...] [--case ID] [--coarse-stride K]
// (--coarse-stride: DiagnosisOptions::coarse_fit_stride, default 3, the smallest stride: a 60 s log's
// 18-20 training pieces take round(sqrt(n)) = 4 (coarseFitData); 1 to time the fits on all the data;
// --rate: one log rate instead of both; --effects: fit only these candidates, to time one of them;
// --case: another benchmark case than steering_friction-large-lane_change, e.g. a column log whose
// winning fit must be held to a bounded closed loop.)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/common/command_line.h"
#include "lane_keeping/gap/diagnosis.h"

using namespace lane_keeping;

int main(int argc, char** argv) {
  int threads = 2;
  double duration = 60.0;
  std::vector<double> rates{100.0, 1000.0};
  std::vector<std::string> effects;
  std::string case_id = "steering_friction-large-lane_change";
  std::size_t coarse_stride = DiagnosisOptions{}.coarse_fit_stride;
  // Options read strictly (common/command_line.h): a bad value exits 2 naming it, as the tools do.
  try {
    for (int i = 1; i < argc; i += 2) {
      const std::string arg = argv[i];
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      if (arg == "--threads") threads = static_cast<int>(wholeNumberOption(arg, argv[i + 1], 1, 256));
      else if (arg == "--duration") duration = numberOption(arg, argv[i + 1], 1.0, 3600.0, "s");
      else if (arg == "--rate") rates = {numberOption(arg, argv[i + 1], 1.0, 1e4, "Hz")};
      else if (arg == "--case") case_id = argv[i + 1];
      else if (arg == "--coarse-stride") coarse_stride = static_cast<std::size_t>(wholeNumberOption(arg, argv[i + 1], 1, 1000));
      else if (arg == "--effects") {
        std::stringstream list(argv[i + 1]);
        for (std::string name; std::getline(list, name, ',');) effects.push_back(name);
      } else {
        throw UsageError("unknown argument '" + arg + "'");
      }
    }
  } catch (const UsageError& e) {
    std::fprintf(stderr, "lk_bench_gap: %s\n", e.what());
    return 2;
  }
  std::printf("lane_keeping gap diagnosis benchmark: %g s log of %s, %s, %d thread(s), coarse fit stride at least %zu\n\n",
              duration, case_id.c_str(), effects.empty() ? "all 11 candidates" : "selected candidates", threads,
              coarse_stride);
  std::printf("%-10s %10s %14s %22s\n", "log rate", "rows", "wall time", "verdict");
  for (const double rate : rates) {
    BenchmarkCase c;
    try {
      c = benchmarkCase(case_id);
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "lk_bench_gap: %s\n", e.what());
      return 2;
    }
    c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
    const GapLog log = generateBenchmarkLog(c, SensorNoise{}, rate);
    SimConfig nominal = benchmarkNominal(c.manoeuvre);
    nominal.simulation.duration = duration;
    DiagnosisOptions options;
    options.threads = threads;
    options.effects = effects;
    options.coarse_fit_stride = coarse_stride;
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const GapReport report = diagnoseGap(nominal, {log}, {}, options);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%7.0f Hz %10zu %12.1f s %22s\n", rate, log.size(), wall, report.verdict.effect.c_str());
    std::printf("           stages:");
    for (const auto& [stage, seconds] : report.wall_seconds) std::printf(" %s %.1f s;", stage.c_str(), seconds);
    std::printf("\n");
    std::printf("           reason: %s\n", report.verdict.reason.c_str());
    std::printf("           effects named:");
    for (const auto& e : report.verdict.effects) {
      std::printf(" %s%s share %.1f %%;", e.effect.c_str(), e.form.empty() ? "" : (" (" + e.form + ")").c_str(), 100.0 * e.share);
    }
    std::printf("\n           CPU time of the process: %.1f s\n", static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    std::size_t checked = 0;  // closed loops run: the rest could not change the verdict (closed_loop_checks.h)
    for (const auto& r : report.ranking) checked += r.closed_loop_checked ? 1 : 0;
    std::printf("           closed loops checked: %zu of the %zu ranked effects\n", checked, report.ranking.size());
    for (const auto& note : report.notes) std::printf("           note: %s\n", note.c_str());
    std::fflush(stdout);
  }
  return 0;
}
