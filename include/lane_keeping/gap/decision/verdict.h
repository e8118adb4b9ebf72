#pragma once
/// Which effect (diagnosis.h, step 3; DESIGN §5 question 2): the ranking of the fitted candidates and
/// the verdict — the winner (winner_selection.h), its confidence, look-alikes that score close to it,
/// and the one-sentence reason; `unexplained` when the gap is below detection or no candidate earns
/// its parameters.
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/common/brief_number.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/decision/modal_evidence.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_fit.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// The fits as ranked effects, best first (bounded fits before unbounded ones, then by held-out gap),
/// with parameters, uncertainties and the config overlay each adds to `nominal`. Notes on failed fits,
/// parameters pinned at a bound and closed loops that leave the logged bounds go to `notes`, in fit order.
std::vector<RankedEffect> rankFits(const std::vector<CandidateFit>& fits, const SimConfig& nominal, double gap_before,
                                   std::vector<std::string>* notes);

/// The candidates whose fit has a parameter pinned at a bound of its range.
std::set<std::string> pinnedEffects(const std::vector<CandidateFit>& fits);

/// The pinned candidates whose held-out improvement (gap_before^2 - gap_after^2) is within the
/// noise-only spread of the total excess (heldSpread): a fit stretched to a bound of its range that
/// improves the gap by what noise alone moves it is no evidence of anything.
std::set<std::string> pinnedWithinNoise(const std::vector<RankedEffect>& ranking, const std::set<std::string>& pinned,
                                        const NoiseNull& null, double gap_before);

/// What the verdict is decided on besides the ranking.
struct VerdictContext {
  std::set<std::string> pinned;          ///< candidates with a parameter at a bound (pinnedEffects)
  /// Pinned candidates whose held-out improvement (gap^2 before - after) lies inside the noise-only
  /// spread of the total excess (its 95 % quantile minus its median): they never win.
  std::set<std::string> pinned_within_noise;
  /// Candidates with every parameter pinned (CandidateFit::at_bound_everywhere), with their fitted parameters
  /// for the reason: the data place none of them, and they never win either (a fit pinned on some of its
  /// parameters may, where nothing unpinned qualifies: the data may fix only a combination of them).
  std::map<std::string, std::string> pinned_everywhere;
  const GapWhere* where = nullptr;       ///< the where-analysis (subsystem, nrmse and floor for the reason)
  double gap_before = 0.0;               ///< held-out gap of the nominal, net of the noise reference
  GapDetection detection;                ///< the calibrated tests on held-out and training data
  /// The partial-explanation analysis of a would-be winner (what it leaves; see partialExplanation).
  std::function<PartialExplanation(const RankedEffect&)> partial_of;
  /// Candidates (labels) that do not change the where-subsystem but whose own closed loop's noise-only
  /// draws leave as much excess there: its excess is their knock-on (knock_on.h).
  std::set<std::string> where_by_knock_on;
  /// Candidates whose loop has a mode where a log rings that the nominal's does not (modal_evidence.h):
  /// where no candidate earns its parameters by the replays and one alone has this evidence, it is named.
  std::vector<ModalSupport> modal;
};

/// The candidate a verdict may name on the loop's modes alone: the one with modal evidence, if only one has it.
const ModalSupport* modalWinner(const std::vector<ModalSupport>& modal);

/// The verdict: `unexplained` when the held-out test does not detect a gap (saying so, and saying when
/// the training data carry one the held-out data do not confirm), when no candidate earns its
/// parameters, or when the best one is only a partial explanation; else the winner.
GapVerdict decideVerdict(const std::vector<RankedEffect>& ranking, const VerdictContext& context,
                         const DiagnosisOptions& options);

/// A verdict naming no effect, where the diagnosis's own evidence overrules the one it had (folds that do
/// not agree, fold_pooling.h; a closed loop that drives farther from the logs, how_far.h): the held-out gap
/// left as it was (`gap_before`), confidence 0.5, `reason` saying why.
GapVerdict unexplainedVerdict(double gap_before, const std::string& reason);

}  // namespace diagnosis
}  // namespace lane_keeping
