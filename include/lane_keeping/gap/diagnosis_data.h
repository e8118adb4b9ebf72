#pragma once
/// The data a diagnosis works on (diagnosis.h, step 1): each run's log as a continuous-time view with
/// its own configuration (gap_run.h) and the time segments used from it, and the split into training
/// and held-out data.
#include <memory>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/gap_run.h"
#include "lane_keeping/gap/log_signals.h"
#include "lane_keeping/gap/replay_trace.h"

namespace lane_keeping {
namespace diagnosis {

/// A run ready for the replays: its log as a continuous-time view, and its configuration (with the
/// initial state estimated from the log where the configuration does not state it).
struct RunData {
  std::shared_ptr<const LogSignals> log;
  std::shared_ptr<const SimConfig> config;
};

std::vector<RunData> prepareRuns(const std::vector<GapRun>& runs);

/// A run and the time segments of it that a data set uses.
struct Dataset {
  std::shared_ptr<const LogSignals> log;
  std::shared_ptr<const SimConfig> config;
  std::vector<TimeSegment> segments;
};

/// Each run whole, from `margin` seconds after its start.
std::vector<Dataset> wholeLogs(const std::vector<RunData>& runs, double margin);

/// Training and held-out data: whole runs when held-out runs are given; otherwise alternating blocks
/// of each log (even blocks train, odd ones are held out), named in `held_blocks`.
struct DataSplit {
  std::vector<Dataset> train, held;
  std::vector<std::string> held_blocks;
};

DataSplit splitData(const std::vector<RunData>& train_runs, const std::vector<RunData>& held_runs,
                    const DiagnosisOptions& options);

}  // namespace diagnosis
}  // namespace lane_keeping
