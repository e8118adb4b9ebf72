#pragma once
/// Every side held out once (issue 47, kind 1). One split into training and held-out data lets one side
/// veto the other: an effect fitted nearly exactly on the training side (a cornering stiffness at
/// 0.856/0.906 for 0.85/0.90) was "a gap the held-out data do not confirm" because the held-out side's own
/// test, on half the data, did not reach 5 %. With two folds — the split as made, then its two sides
/// swapped — each side is held out once, and the detection test pools them: the training and held-out
/// totals summed, against each noise-only draw's two totals summed (noise_null.h, GapDetection::pooled; one
/// Monte Carlo test, exact as each side's is).
///
/// The rule: where the held-out test alone detects a gap, nothing changes (one fold). Where it does not
/// and the pooled test does, the diagnosis goes on in both folds on the pooled test, and names an effect
/// only if both folds name it (the same effect and form: each fold's fit, made on one side, must earn its
/// parameters on the other). A gap whose folds disagree is `unexplained`, saying what each named. Two folds
/// rather than one pooled fit: the candidates' evidence stays held-out evidence, and asking both folds to
/// agree is what keeps the second look at the data from adding false alarms.
///
/// Three runs or more (training and held-out runs together): every run is held out in turn, fitted on all
/// the others (leave one run out), and the verdict is decided again on the held-out evidence pooled over
/// those folds — each candidate's evidence summed, its held-out gaps before and after summed in squares —
/// rather than on every fold agreeing. With K folds, asking all of them to agree lets one run's noise veto
/// the rest: a yaw-rate bias fitted at 0.0026 rad/s for 0.0025, removing 100 % of every run's held-out gap,
/// had evidence -2864 on one of three runs of the same manoeuvre (a second of a steering reversal where
/// the chassis replay's lateral-velocity estimate, 0.015 m/s further off, doubles the steering replay's
/// residual) and +16,490 on another. Summed over the runs, the evidence is what cross-validation measures.
#include <map>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// Whether a diagnosis decides on the pooled test: two_folds on, noise-only draws ran, the held-out test
/// alone does not detect a gap and the pooled test does.
bool decidesOnPooledTest(const GapDetection& detection, const DiagnosisOptions& options);

/// The tests the diagnosis goes on: `detection` with the pooled test in place of the held-out one where
/// decidesOnPooledTest, else `detection` as it is.
GapDetection decisiveDetection(const GapDetection& detection, const DiagnosisOptions& options);

/// A fold as the report lists it: the data it fitted on and scored on, and what its verdict named.
GapFold foldOf(const GapReport& report, const std::vector<std::string>& training);

/// Joins the second fold into the first's verdict (both diagnosed on the pooled test): the effect stands
/// if both folds name it, with the two folds' figures in its reason; otherwise the verdict becomes
/// `unexplained` (confidence 0.5), naming what each fold named. `folds` is report.folds (first, second).
void poolFolds(GapVerdict* verdict, const GapDetection& detection, const std::vector<GapFold>& folds);

/// The ranking pooled over folds that each hold out other data (every run once): each candidate of `first`
/// (the split as made: its parameters, training scores and closed-loop flags) with its held-out gaps
/// before and after the root of the folds' sums of squares, its evidence the folds' sum, bounded only if
/// bounded in every fold; sorted as rankFits sorts. A candidate some fold did not rank is left out (saying
/// so in `notes`).
std::vector<RankedEffect> pooledRanking(const std::vector<RankedEffect>& first,
                                        const std::vector<std::vector<RankedEffect>>& folds,
                                        std::vector<std::string>* notes);

/// What a candidate changing `changes` leaves, pooled over every run held out once: the nominal's net excess^2
/// in the other subsystems summed over the folds' held-out data (`excess`, one map per fold: subsystem -> net
/// excess), as a share of the pooled gap^2 `gap_before` (partial_explanation.h's untouched share).
double pooledUntouchedShare(const std::vector<std::string>& changes,
                            const std::vector<std::map<std::string, double>>& excess, double gap_before);

/// The reason of a verdict decided on the pooled ranking of every run held out once: what each fold
/// named, before the verdict's own reason.
void describeRunFolds(GapVerdict* verdict, const GapDetection& detection, const std::vector<GapFold>& folds);

}  // namespace diagnosis
}  // namespace lane_keeping
