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
///
/// Each stage has its own file: data and split (diagnosis_data.h), evaluation and metrics
/// (evaluation.h), candidate fitting (candidate_objective.h, candidate_fit.h, bounded_loop.h,
/// bounded_refit.h), where (where_analysis.h), verdict (verdict.h), how far (how_far.h); diagnoseGap
/// runs them in that order.
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {

/// Diagnoses the gap between the runs and their configurations: each run carries the nominal
/// configuration with its own scenario (gap_run.h). `heldout` runs are used only for scoring; without
/// them, blocks of the training runs are held out.
GapReport diagnoseGap(const SimConfig& nominal, const std::vector<GapRun>& training, const std::vector<GapRun>& heldout,
                      const DiagnosisOptions& options = {}, DiagnosisArtifacts* artifacts = nullptr);
/// The same with every log under the shared configuration `nominal` (one road and initial state).
GapReport diagnoseGap(const SimConfig& nominal, const std::vector<GapLog>& training, const std::vector<GapLog>& heldout,
                      const DiagnosisOptions& options = {}, DiagnosisArtifacts* artifacts = nullptr);

/// The held-out gap of the runs' own configurations, then with each of `alternatives` applied,
/// scored as diagnoseGap scores its candidates (the same held-out runs or blocks, the same noise
/// reference). The gap benchmark's ceiling: the gap its truth model leaves, which no candidate fit can
/// be expected to beat.
std::vector<double> heldoutGaps(const std::vector<GapRun>& training, const std::vector<GapRun>& heldout,
                                const std::vector<ConfigChange>& alternatives, const DiagnosisOptions& options = {});

/// How far `change` takes the closed loop, measured as diagnoseGap measures its verdict's (how_far.h): the
/// closed-loop replays of the held-out runs (of the training runs where none is held out) with each run's
/// configuration (before) and with `change` (after), gross and net of the logs' noise. The gap benchmark's
/// ceiling in closed loop: where the truth model itself closes little, what noise leaves in the replay beyond
/// the floor of its white levels (a replay started from the log's noisy first samples; a run whose motion is
/// small beside its noise) is what the net does not hold, not a verdict's miss.
ClosedLoopGap closedLoopHowFar(const std::vector<GapRun>& training, const std::vector<GapRun>& heldout,
                               const ConfigChange& change, const DiagnosisOptions& options = {});

/// Every log under the shared configuration `nominal`.
std::vector<GapRun> sharedConfigurationRuns(const SimConfig& nominal, const std::vector<GapLog>& logs);

}  // namespace lane_keeping
