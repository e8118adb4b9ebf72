#include "lk_gap_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/resources.h"

namespace lane_keeping {
namespace {

// Calibrated on this project's 2-core VM (docs/reliability.md). lk_bench_gap, on a quiet machine, diagnoses a
// 60 s log (19 noise draws, all candidates, 2 threads) in about 8-10 s at 100 Hz and 10-12 s at 1 kHz: about
// 0.17 s of wall time per second of log, of which the noise-only draws' plant steps (21 simulations of the
// span at 0.1 ms, about 0.5 us a step) are a third, plus 4e-5 s per logged row. lk_gap on the same logs
// beside builds (load 15) took 37 s and 81 s, peaking at 40 MB and 118 MB: 1.5 kB per row.
constexpr double kSecondsPerPlantStep = 0.5e-6;   // one thread
constexpr double kFitSecondsPerLogSecond = 0.11;  // two threads, every candidate
constexpr double kSecondsPerRow = 4e-5;           // two threads
constexpr double kBytesPerRow = 1500.0;           // two threads
constexpr double kBaseBytes = 40e6;

}  // namespace

DiagnosisBudget estimateDiagnosisBudget(const std::vector<GapRun>& training, const std::vector<GapRun>& heldout,
                                        const DiagnosisOptions& options) {
  DiagnosisBudget b;
  double costliest = -1.0;
  for (const auto* runs : {&training, &heldout}) {
    for (const GapRun& run : *runs) {
      const GapLog& log = run.log;
      if (log.t.size() < 2) continue;
      const double rows = static_cast<double>(log.t.size());
      const double span = log.t.back() - log.t.front();
      const double steps = span / run.config.simulation.step;
      b.rows += rows;
      b.span += span;
      // Each noise-only draw and the closed-loop replays (nominal and corrected) simulate the span.
      b.simulated_steps += (options.noise_reference_draws + 2.0) * steps;
      const double cost = steps * (options.noise_reference_draws + 2.0) * kSecondsPerPlantStep + span + rows;
      if (cost > costliest) {
        costliest = cost;
        b.largest = log.source;
        b.largest_rows = rows;
        b.largest_span = span;
        b.largest_interval = span / (rows - 1.0);
      }
    }
  }
  const double threads = std::max(1, options.threads), parallel = std::min(threads, 2.0);  // 2 cores measured
  const double candidates = options.effects.empty() ? 1.0 : std::min(1.0, options.effects.size() / 11.0);
  b.seconds = b.simulated_steps * kSecondsPerPlantStep / parallel +
              (b.span * kFitSecondsPerLogSecond * candidates + b.rows * kSecondsPerRow) * 2.0 / parallel;
  // Three runs or more: each held out in turn, a diagnosis of (nearly) all the data per run (fold_pooling.h);
  // every fold asked for with fewer: the sides swapped, a second one.
  const std::size_t runs = training.size() + heldout.size();
  if (options.two_folds && runs >= 3) {
    b.seconds *= static_cast<double>(runs);
    b.folds = "each of the " + std::to_string(runs) + " runs held out in turn";
  } else if (options.two_folds && options.every_fold) {
    b.seconds *= 2.0;
    b.folds = "each side held out in turn";
  }
  b.bytes = kBaseBytes + kBytesPerRow * b.rows * std::max(1.0, threads / 2.0);
  return b;
}

void checkDiagnosisBudget(const DiagnosisBudget& b, double budget_hours, std::ostream& warnings) {
  auto g = [](double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.4g", v);
    return std::string(text);
  };
  const std::string what = b.largest + ": " + g(b.largest_rows) + " rows over " + g(b.largest_span) +
                           " s (a sample every " + g(b.largest_interval) + " s)";
  const std::string estimate = "the diagnosis would take about " + formatDuration(b.seconds) +
                               (b.folds.empty() ? "" : " (" + b.folds + ")") + " and " + formatBytes(b.bytes) +
                               " of memory";
  // A car's log samples at 10 Hz or faster: slower suggests a time column in other units than seconds.
  const std::string units = b.largest_interval > 0.1 ? "; a sample every " + g(b.largest_interval) +
                                                           " s is slower than a car's log (10 Hz to 1 kHz): is the time "
                                                           "column in seconds? (a log mapping says `time: {column: t, "
                                                           "unit: ms}`)"
                                                     : "";
  const double memory = physicalMemoryBytes();
  if (memory > 0.0 && b.bytes > 0.8 * memory) {
    throw InputError(what + ": " + estimate + ", more than this machine's " + formatBytes(memory) +
                     "; diagnose a part of the log (a car's log of a few minutes at 100 Hz to 1 kHz has 10^4 to 10^6 "
                     "rows)" + units);
  }
  if (b.seconds > budget_hours * 3600.0) {
    throw InputError(what + ": " + estimate + ", more than --time-budget " + g(budget_hours) + " h" + units +
                     "; diagnose a part of the log, or raise --time-budget");
  }
  if (b.seconds > 600.0) warnings << "lk_gap: note: " << what << ": " << estimate << units << "\n";
}

}  // namespace lane_keeping
