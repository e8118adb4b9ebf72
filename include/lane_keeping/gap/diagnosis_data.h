#pragma once
/// The data a diagnosis works on (diagnosis.h, step 1): each log as a continuous-time view with the
/// time segments used from it, and the split into training and held-out data.
#include <memory>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/gap_log.h"
#include "lane_keeping/gap/log_signals.h"
#include "lane_keeping/gap/replay_trace.h"

namespace lane_keeping {
namespace diagnosis {

/// A log and the time segments of it that a data set uses.
struct Dataset {
  std::shared_ptr<const LogSignals> log;
  std::vector<TimeSegment> segments;
};

/// Each log whole, from `margin` seconds after its start.
std::vector<Dataset> wholeLogs(const std::vector<std::shared_ptr<const LogSignals>>& logs, double margin);

/// Training and held-out data: whole runs when held-out runs are given; otherwise alternating blocks
/// of each log (even blocks train, odd ones are held out), named in `held_blocks`.
struct DataSplit {
  std::vector<Dataset> train, held;
  std::vector<std::string> held_blocks;
};

DataSplit splitData(const std::vector<std::shared_ptr<const LogSignals>>& train_logs,
                    const std::vector<std::shared_ptr<const LogSignals>>& held_logs, const DiagnosisOptions& options);

std::vector<std::shared_ptr<const LogSignals>> signalsOf(const std::vector<GapLog>& logs);

}  // namespace diagnosis
}  // namespace lane_keeping
