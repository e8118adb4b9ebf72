#pragma once
// lk_gap's budget check: what diagnosing the given logs will cost in time and memory, estimated from their
// rows and spans before the work starts (docs/reliability.md). A log with time in milliseconds read as
// seconds (a 30 s run spanning 30,000 s) spent hours in the noise-only null, whose draws simulate the
// whole span at the plant's step; a 1 GB log (4.6 M rows) grew past 5 GB there. Both started without a
// word.
#include <iosfwd>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/log/gap_run.h"

namespace lane_keeping {

/// Largest log file read [bytes]: refused before reading.
constexpr double kMaxLogBytes = 4e9;

struct DiagnosisBudget {
  double rows = 0.0;             ///< samples of every run
  double span = 0.0;             ///< [s] the runs' spans, summed
  double simulated_steps = 0.0;  ///< plant steps of the noise-only null and the closed-loop replays
  double seconds = 0.0;          ///< estimated wall time
  double bytes = 0.0;            ///< estimated peak memory
  std::string largest;           ///< the log that costs most, for messages
  double largest_rows = 0.0, largest_span = 0.0, largest_interval = 0.0;
  std::string folds;             ///< the folds the estimate counts ("" for one), for messages
};

DiagnosisBudget estimateDiagnosisBudget(const std::vector<GapRun>& training, const std::vector<GapRun>& heldout,
                                        const DiagnosisOptions& options);

/// Throws InputError naming the costliest log, its rows, span and sample interval, and the estimate, if
/// the diagnosis would need more memory than the machine has or more than `budget_hours`; writes the
/// estimate to `warnings` if it exceeds 10 minutes.
void checkDiagnosisBudget(const DiagnosisBudget& budget, double budget_hours, std::ostream& warnings);

}  // namespace lane_keeping
