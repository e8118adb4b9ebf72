#pragma once
/// The sim-to-real gap diagnosis (DESIGN §5): where the simulation departs from the logs, which
/// candidate effect causes it, and how far the gap shrinks once that effect is added.
///
/// 1. Data: the training logs, and held-out logs — or, with a single log, alternating blocks of it
///    (even blocks train, odd blocks are held out; the replays are local, so blocks are independent).
/// 2. Where: every subsystem is replayed open loop with its logged inputs (subsystem_replay.h) under
///    the nominal configuration; its excess over the noise floor (gap_metrics.h) is the gap it carries.
/// 3. Which: each candidate (candidate_effects.h) is fitted on the training data, minimising the summed
///    mean-square residuals of the subsystems it changes — Levenberg-Marquardt (Ceres, central numeric
///    derivatives) for smooth parameters, a grid and golden section for delays and saturations — with
///    the nominal parameters held at their configured values. It is then scored on held-out data. A
///    candidate earns its parameters only if (a) it changes the subsystem where the gap lies, (b) it
///    removes at least `min_shrink` of the held-out gap, and (c) the held-out evidence (the drop of the
///    noise-normalised squared residual, a chi-square-like count) is at least
///    `min_evidence_per_parameter` per fitted parameter. Noise fitted on training data does not carry
///    over to held-out data, so (b) and (c) reject candidates that merely fit noise; otherwise the
///    verdict is `unexplained`. A fit pinned at a bound of its range wins only when no unpinned
///    candidate qualifies (winner_selection.h).
/// 4. How far: the gap before and after adding the winner, per subsystem on held-out data and in a
///    closed-loop replay of the held-out runs.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/gap_log.h"
#include "lane_keeping/gap/gap_report.h"
#include "lane_keeping/gap/subsystem_replay.h"

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

/// Series for the plots (scripts/gap_report_plots.py formats).
struct DiagnosisArtifacts {
  std::vector<double> residual_t;
  std::map<std::string, std::vector<double>> residual;  ///< per subsystem, NaN where not replayed
  std::vector<double> spectrum_f;
  std::map<std::string, std::vector<double>> spectrum;
  std::vector<double> overlay_t;
  std::map<std::string, std::vector<double>> overlay;  ///< y_real, y_nominal, y_corrected, yaw_rate_*, delta_*
};

GapReport diagnoseGap(const SimConfig& nominal, const std::vector<GapLog>& training, const std::vector<GapLog>& heldout,
                      const DiagnosisOptions& options = {}, DiagnosisArtifacts* artifacts = nullptr);

/// The held-out gap of `nominal`, then of each of `alternatives`, scored as diagnoseGap scores its
/// candidates (the same held-out runs or blocks, the same noise reference). The gap benchmark's ceiling:
/// the gap its truth model leaves, which no candidate fit can be expected to beat.
std::vector<double> heldoutGaps(const SimConfig& nominal, const std::vector<SimConfig>& alternatives,
                                const std::vector<GapLog>& training, const std::vector<GapLog>& heldout,
                                const DiagnosisOptions& options = {});

/// residuals.csv, spectrum.csv, overlay.csv in `dir`.
void writeDiagnosisArtifacts(const std::string& dir, const DiagnosisArtifacts& artifacts);

}  // namespace lane_keeping
