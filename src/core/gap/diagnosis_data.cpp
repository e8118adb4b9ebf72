#include "lane_keeping/gap/diagnosis_data.h"

#include <algorithm>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace diagnosis {

std::vector<Dataset> wholeLogs(const std::vector<std::shared_ptr<const LogSignals>>& logs, double margin) {
  std::vector<Dataset> out;
  for (const auto& log : logs) out.push_back({log, {{log->start() + margin, log->end() + 1e-9}}});
  return out;
}

DataSplit splitData(const std::vector<std::shared_ptr<const LogSignals>>& train_logs,
                    const std::vector<std::shared_ptr<const LogSignals>>& held_logs, const DiagnosisOptions& options) {
  DataSplit split;
  if (!held_logs.empty()) {
    split.train = wholeLogs(train_logs, options.start_margin);
    split.held = wholeLogs(held_logs, options.start_margin);
    return split;
  }
  for (const auto& log : train_logs) {
    Dataset tr{log, {}}, ho{log, {}};
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

std::vector<std::shared_ptr<const LogSignals>> signalsOf(const std::vector<GapLog>& logs) {
  std::vector<std::shared_ptr<const LogSignals>> out;
  for (const auto& log : logs) out.push_back(std::make_shared<LogSignals>(log));
  return out;
}

}  // namespace diagnosis
}  // namespace lane_keeping
