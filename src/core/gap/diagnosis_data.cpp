#include "lane_keeping/gap/diagnosis_data.h"

#include <algorithm>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace diagnosis {

std::vector<RunData> prepareRuns(const std::vector<GapRun>& runs) {
  std::vector<RunData> out;
  for (const GapRun& run : runs) {
    auto log = std::make_shared<LogSignals>(run.log);
    SimConfig config = run.config;
    if (run.initial_from_log) {
      config = withInitialStateFromLog(config, run.log, log->at(LogSignals::kSigma1, log->start()));
    }
    out.push_back({std::move(log), std::make_shared<const SimConfig>(std::move(config))});
  }
  return out;
}

std::vector<Dataset> wholeLogs(const std::vector<RunData>& runs, double margin) {
  std::vector<Dataset> out;
  for (const auto& run : runs) out.push_back({run.log, run.config, {{run.log->start() + margin, run.log->end() + 1e-9}}});
  return out;
}

DataSplit splitData(const std::vector<RunData>& train_runs, const std::vector<RunData>& held_runs,
                    const DiagnosisOptions& options) {
  DataSplit split;
  if (!held_runs.empty()) {
    split.train = wholeLogs(train_runs, options.start_margin);
    split.held = wholeLogs(held_runs, options.start_margin);
    return split;
  }
  for (const auto& run : train_runs) {
    const auto& log = run.log;
    Dataset tr{log, run.config, {}}, ho{log, run.config, {}};
    int block = 0;
    for (double a = log->start() + options.start_margin; a < log->end(); a += options.block_length, ++block) {
      const TimeSegment s{a, std::min(a + options.block_length, log->end() + 1e-9)};
      (block % 2 == 0 ? tr : ho).segments.push_back(s);
    }
    split.train.push_back(tr);
    if (!ho.segments.empty()) split.held.push_back(ho);
    split.held_blocks.push_back(log->log().source + " (odd " + formatNumber(options.block_length) + " s blocks)");
  }
  if (split.held.empty()) {
    throw InputError("gap diagnosis: the log is too short to hold out a block of " + formatNumber(options.block_length) + " s");
  }
  return split;
}

}  // namespace diagnosis
}  // namespace lane_keeping
