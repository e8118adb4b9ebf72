#pragma once
/// The settings of a gap diagnosis (diagnosis.h): data split, detection and acceptance thresholds,
/// the replays' options, parallelism and progress reporting.
#include <functional>
#include <string>
#include <vector>

#include "lane_keeping/gap/replay_trace.h"

namespace lane_keeping {

struct DiagnosisOptions {
  ReplayOptions replay;
  double block_length = 3.0;        ///< [s] train/held-out blocks when a single log is given
  double start_margin = 0.6;        ///< [s] skipped at the start of each log (delayed inputs need history)
  double detection_gap = 1e-3;      ///< nominal held-out gap below which there is nothing to explain
  int noise_reference_draws = 3;    ///< noise draws of the noise-only reference (0: no reference)
  double min_shrink = 0.3;          ///< fraction of the held-out gap a candidate must remove
  double min_evidence_per_parameter = 50.0;  ///< held-out evidence a candidate needs per fitted parameter
  double upstream_share = 0.2;      ///< chassis excess (relative to steering) that makes the chassis the "where"
  int threads = 2;                  ///< candidates fitted in parallel
  bool closed_loop = true;          ///< run the closed-loop replays of "how far"
  std::vector<std::string> effects; ///< restrict the candidates (empty: all)
  std::function<void(const std::string&)> progress;  ///< progress messages (may be empty)
};

}  // namespace lane_keeping
