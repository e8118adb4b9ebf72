#pragma once
/// Which effect (diagnosis.h, step 3; DESIGN §5 question 2): the ranking of the fitted candidates and
/// the verdict — the winner (winner_selection.h), its confidence, look-alikes that score close to it,
/// and the one-sentence reason; `unexplained` when the gap is below detection or no candidate earns
/// its parameters.
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/candidate_fit.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// The fits as ranked effects, best first (bounded fits before unbounded ones, then by held-out gap),
/// with parameters, uncertainties and the config overlay each adds to `nominal`. Notes on failed fits,
/// parameters pinned at a bound and closed loops that leave the logged bounds go to `notes`, in fit order.
std::vector<RankedEffect> rankFits(const std::vector<CandidateFit>& fits, const SimConfig& nominal, double gap_before,
                                   std::vector<std::string>* notes);

/// The candidates whose fit has a parameter pinned at a bound of its range.
std::set<std::string> pinnedEffects(const std::vector<CandidateFit>& fits);

/// The verdict on a ranking (best first) for a held-out gap `gap_before` located in `where_subsystem`.
GapVerdict decideVerdict(const std::vector<RankedEffect>& ranking, const std::set<std::string>& pinned,
                         const std::string& where_subsystem, double gap_before, const DiagnosisOptions& options);

}  // namespace diagnosis
}  // namespace lane_keeping
