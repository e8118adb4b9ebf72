#pragma once
/// A fit placed by the closed loop where the replays leave it loose (issue 47, kind 7: how far).
///
/// The replays fit an effect on the log's own inputs; some effects barely show there but shape the loop
/// they close. A localisation latency on a bend: the pose changes slowly, so the replays' training loss
/// moves by 2 % between 70 and 110 ms and the fit lands at 83 ms for a truth of 100, while the closed loop's
/// net gap is 0.104 at 83 ms and 0.032 at 100. A localisation bias: the tracker replay sees mostly
/// y + L psi, and the fit slid along that ridge to y = -1.2 m, psi = 85 mrad for a truth of 0.08 m, 4 mrad
/// (its closed loop 61 % of the way, the truth's constant part 82 %).
///
/// So, once a single effect is named by the replays and its corrected closed loop closes clearly less of the
/// gap than its replays do (net shrink below kPlacementTrigger of the held-out replays' shrink, leaving at least
/// kClosedLoopVisible of the noise floor), the fit is
/// moved along the directions its replays determine least — the eigenvectors of J^T J of its training
/// residuals, in fit space, flattest first — to where the *training* runs' closed loop is nearest the logs
/// (net of their noise), among the points whose replays' training loss stays within
/// kPlacementReplayTolerance of the fit's: values the replays cannot tell from their own fit. It is kept
/// where it takes the training runs' closed loop nearer the logs by at least kPlacementMinGain of their
/// nominal net gap. With held-out runs how far is then measured on runs the placement never saw; on a single
/// log (no run held out) the closed loop that placed it is the one how far is measured on, and the note says
/// so (in-sample, one to three parameters against thousands of samples; the placed parameters against the
/// truth are the out-of-sample check, docs/gap.md).
#include <limits>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/report/diagnosis_artifacts.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// The closed loop closes less than this share of the replays' held-out shrink (net of noise): placed.
constexpr double kPlacementTrigger = 0.9;
/// The replays' training loss may rise by this share of the fit's: the values they cannot tell apart
/// (their residuals are correlated over a few hundred samples: 2 % of the loss is a standard error or two).
constexpr double kPlacementReplayTolerance = 0.02;
/// The placement must take the training runs' closed loop nearer the logs by this share of their nominal
/// net gap (less is within what the floor's estimate and one run's noise move).
constexpr double kPlacementMinGain = 0.05;

struct ClosedLoopPlacement {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool placed = false;
  std::vector<double> theta;  ///< the placed parameters (SI); the fit's own where not placed
  /// The training runs' closed-loop gap net of noise (RMS over runs): the nominal's and at the fit (the note
  /// gives it where placed).
  double nominal_net = kNaN, fit_net = kNaN;
  double fit_loss = kNaN;  ///< the replays' training loss at the fit
  std::size_t closed_loops = 0;  ///< closed-loop runs it took
  std::string note;              ///< what was tried and found (empty where it did not run)
};

/// Places `fit` by the closed loop of `runs` (the training runs, whole) as above; `context` is the fit's
/// (its objective's data, nominal and replay options). Returns placed = false with a note where the
/// placement does not move the fit, and an empty note where it cannot run (no parameter, no closed loop).
ClosedLoopPlacement placeByClosedLoop(const CandidateFit& fit, const FitContext& context, const std::vector<RunData>& runs,
                                      const DiagnosisOptions& options);

/// Whether `fit` is the one effect the report's verdict names (its effect and form): only that fit is placed.
/// (Where the verdict names the leader alone, its further effects dropped because their combined closed loop
/// was contradicted, the combination's fit is not it.)
bool verdictNames(const GapReport& report, const CandidateFit& fit);

/// Whether the report's verdict is placed (with options.closed_loop_placement): one effect named by the
/// replays, whose how far sees the gap (its nominal net gap at least kClosedLoopVisible of the floor), leaves at
/// least kClosedLoopVisible of the floor of it (less is within the floor's own error) and closes less than
/// kPlacementTrigger of the verdict's held-out replay shrink.
bool placementApplies(const GapReport& report, const DiagnosisOptions& options);

/// Places the verdict's fit `winner` (placeByClosedLoop on `training_runs`) and, where placed, puts the placed
/// parameters in the verdict's effect (its `replay_params` the replays' fit; its gap, share and the verdict's
/// shrink stay the replays' fit's, the evidence that named it) and measures how far again on `how_far_runs`
/// (with `how_far_options`). `in_sample`: how_far_runs are the training runs (the note says so). Where the placed
/// fit's closed loop is contradicted by the logs (closedLoopContradicts) the report is left as it was. The
/// placement's note, with the held-out replays' gap at the placed values, goes to the report either way.
void placeVerdict(const CandidateFit& winner, const FitContext& context, const std::vector<RunData>& training_runs,
                  const std::vector<RunData>& how_far_runs, bool in_sample, const DiagnosisOptions& options,
                  const DiagnosisOptions& how_far_options, GapReport* report, DiagnosisArtifacts* artifacts);

}  // namespace diagnosis
}  // namespace lane_keeping
