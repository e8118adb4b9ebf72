#pragma once
/// A steering-loop delay tested on its own fit (issue 47, kind 3): where the replays' test sees no gap.
///
/// The detection test (noise_null.h) is an omnibus test: the total excess of every subsystem's replay,
/// against its 19 noise-only draws. Its power is spread over every way a model can miss. An actuation
/// delay of 1-2 ms near the steering loop's stability margin changes the loop's ringing clearly, but
/// moves that total by less than the noise moves it from draw to draw (the independent family with fresh
/// noise: held-out p = 0.1-0.4 on 7 of its 13 margin delays), while a least-squares fit of the delay
/// places it to a tenth of a millisecond and removes most of the steering replay's excess, on held-out
/// data too. A targeted test has the power the omnibus one lacks (Neyman-Pearson: a test aimed at one
/// alternative is the most powerful against it).
///
/// The test. Fit the delay on the training data and measure the held-out excess it removes,
///   D = T_held(nominal) - T_held(fit),   T = sum over the delay's subsystems of excess^2 (gross:
///   no noise reference taken off, as the draws' own excess is not),
/// and do the same on each noise-only draw: its nominal closed loop with the log's noise, fitted on its
/// own training segments and scored on its held-out ones exactly as the log is. Under "the nominal is
/// right" the log is one more draw, so its D ranks uniformly among theirs: p = (1 + #{D_k >= D}) / (B + 1)
/// (the Monte Carlo test, as the detection's). The delay is named where p <= the false-alarm rate on both
/// sides, its fit removes at least kTargetedMinShrink of the held-out gap, and is not pinned at a bound. A draw's fit
/// mostly stays at nil delay (D_k = 0), or removes training noise that the held-out half does not share
/// (D_k < 0): the log's D must beat them all.
///
/// Only the actuation delay: the one candidate whose signature (a time shift between the logged torque and
/// the wheel's response) a fit pins sharply while the omnibus test misses it. Testing every candidate so
/// would cost 19 fits each and divide the false-alarm rate among them. Cost: up to 19 fits of one profile
/// parameter on the steering replay, only on logs where nothing else is named; none where the log's own fit
/// removes nothing or is pinned, and none after the first draw that removes as much as the log's.
#include <string>
#include <vector>

#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

namespace lane_keeping {
namespace diagnosis {

/// The candidate the test aims at.
inline const char* const kTargetedCandidate = "actuation_delay";
/// The least share of the delay's subsystems' held-out gross gap its fit must remove. Where the draws' fits
/// all stay at nil their drops tie at 0, and any positive drop of the log's lies beyond them: a no-effect log of
/// the candidates' family with fresh noise, fitted at the search grid's first step off nil (0.27 ms), removed
/// 3 % and a no-effect SUV log 1.6 %; the margin delays named remove 15-100 %. A tenth, as the replays ask a
/// third (DiagnosisOptions::min_shrink) of a gap their test sees.
constexpr double kTargetedMinShrink = 0.1;

struct TargetedTest {
  bool ran = false;
  bool detected = false;
  CandidateFit fit;  ///< on the log's training data (its held-out scores on the log's held-out data)
  /// Total excess^2 the fit removes from the nominal's (gross), on training and held-out data.
  double train_drop = 0.0, held_drop = 0.0;
  /// The same, per noise-only draw fitted (none where the log's fit cannot be named).
  std::vector<double> draws_train_drop, draws_held_drop;
  bool stopped_early = false;  ///< a draw's fit removed as much as the log's: the rest were not fitted
  double p_train = 1.0, p_held = 1.0;  ///< among all the draws asked for (a lower bound after an early stop)
  /// Held-out gap of the delay's subsystems, sqrt(T), before and after the fit (gross of the noise reference).
  double gross_before = 0.0, gross_after = 0.0;
  std::string summary;  ///< what it found, for the report's notes and the verdict's reason
};

/// Runs the test for `effect` on the data of `context`, against `null`'s draws (null.redraw), on up to
/// options.threads threads. Not run (ran false) without draws, or where the logs do not feed a subsystem the
/// effect changes.
TargetedTest targetedTest(const CandidateEffect& effect, const FitContext& context, const NoiseNull& null,
                          const DiagnosisOptions& options);

/// The verdict the test names: the effect at its fit, basis "targeted", confidence 0.5, the held-out
/// gap gross of the noise reference (before, after) with `net_before` (the detection's) in the reason.
GapVerdict targetedVerdict(const TargetedTest& test, const SimConfig& nominal, double net_before);

}  // namespace diagnosis
}  // namespace lane_keeping
