#pragma once
/// The noise-only null distribution of a diagnosis (diagnosis.h, step 2): B draws of each run's
/// nominal closed loop over the run's span, with white noise at the levels the log shows
/// (noise_reference.h), each replayed exactly like the log on the same training and held-out segments.
/// Under the hypothesis "the nominal model is right", the log is one more draw of the same kind, so its
/// statistics rank uniformly among the draws' — the Monte Carlo test (Barnard 1963; Davison and Hinkley,
/// Bootstrap Methods, §4.2.5): p = (1 + #{draws at least as extreme}) / (B + 1). With B = 19, p <= 0.05
/// exactly when the log is more extreme than every draw, a false-alarm rate of 5 % by construction, as
/// far as the draws are exchangeable with the log (the noise white at the estimated levels; the
/// nominal trajectory close to the logged one).
///
/// What is tested: the total excess T = sum over subsystems of excess^2 (gap_metrics.h) of the nominal
/// replays, on held-out and on training data separately. The largest draw's excess per subsystem is also
/// each subsystem's noise reference (SubsystemScore::reference), so that the gap is net of it.
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/evaluation/loop_ringing.h"
#include "lane_keeping/gap/evaluation/residual_structure.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace lane_keeping {
namespace diagnosis {

/// One draw's data: each run's noise-only reference (its nominal closed loop with noise drawn at the
/// log's levels) on the data sets' segments.
struct NoiseDraw {
  bool ok = false;
  std::vector<Dataset> train, held;
  std::string note;  ///< why not ok
};

struct NoiseNull {
  std::vector<std::map<std::string, SubsystemScore>> train, held;  ///< per draw that ran
  /// Draw k's data again, with the seed it had (0 <= k < the draws asked for): for a test that fits a
  /// candidate on the draws themselves (targeted_test.h). Empty without draws. It holds the nominal
  /// closed loops the draws were made from, so they are not simulated again.
  std::function<NoiseDraw(int)> redraw;
  std::vector<std::map<std::string, ResidualStructure>> held_structure;  ///< per draw, per subsystem
  /// Why draws are missing (the nominal loop cannot cover a log); a log's steering-loop ringing that its
  /// nominal reference lacks (loop_ringing.h).
  std::vector<std::string> notes;
  /// The ringings behind those notes, ordered by source and column (what modal_evidence.h scores).
  std::vector<LoopRinging> ringings;

  int draws() const { return static_cast<int>(held.size()); }
  /// Per subsystem: the largest held-out excess over the draws (0 without draws).
  std::map<std::string, double> largestHeldExcess() const;
  /// T of every draw, held-out or training.
  std::vector<double> heldTotals() const;
  std::vector<double> trainTotals() const;
};

/// `draws` realisations (seeded: the same data give the same null) of the replays of `subsystems`, on up
/// to `threads` threads.
NoiseNull noiseNull(const std::vector<Dataset>& train, const std::vector<Dataset>& held,
                    const std::set<std::string>& subsystems, const ReplayOptions& options, int draws, int threads);

/// T = sum over subsystems of excess^2.
double totalExcessSquared(const std::map<std::string, SubsystemScore>& scores);

/// The fewest draws with which the Monte Carlo test can reject at `false_alarm_rate`: its smallest
/// p-value is 1 / (B + 1), so B >= ceil(1 / alpha) - 1 (19 at 5 %). With fewer, every gap is "nothing to
/// explain": `--noise-reference-draws 5` turned a steering-friction log's verdict into `unexplained`.
int minimumNoiseDraws(double false_alarm_rate);

/// (1 + #{d in draws: d >= value}) / (draws.size() + 1); 1 without draws.
double monteCarloPValue(double value, const std::vector<double>& draws);

/// The calibrated tests on held-out and training data: detected when p <= options.false_alarm_rate and
/// the net gap (gapOf) reaches options.detection_gap. Without draws, the net gap alone decides. Also the
/// pooled test of both sides (T_train + T_held against each draw's sum; its net gap the RMS of the two).
GapDetection detectGap(const std::map<std::string, SubsystemScore>& train, const std::map<std::string, SubsystemScore>& held,
                       const NoiseNull& null, const DiagnosisOptions& options);

/// The noise-only spread of T: the 95 % quantile of the held-out draws minus their median (0 with fewer
/// than two draws).
double heldSpread(const NoiseNull& null);

}  // namespace diagnosis
}  // namespace lane_keeping
