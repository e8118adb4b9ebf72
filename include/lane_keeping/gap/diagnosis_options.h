#pragma once
/// The settings of a gap diagnosis (diagnosis.h): data split, detection and acceptance thresholds,
/// the replays' options, parallelism and progress reporting.
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "lane_keeping/gap/replay/replay_trace.h"

namespace lane_keeping {

struct SimConfig;

struct DiagnosisOptions {
  ReplayOptions replay;
  /// [s] mean length of the alternating train / held-out blocks of a log when no run is held out; the
  /// blocks are shorter where the log is more excited (diagnosis_data.h), never below min_block_length
  double block_length = 3.0;
  double min_block_length = 0.5;    ///< [s]
  double start_margin = 0.6;        ///< [s] skipped at the start of each log (delayed inputs need history)
  double detection_gap = 1e-3;      ///< nominal held-out gap below which there is nothing to explain
  /// Draws of the noise-only null (noise_null.h): its largest draw is each subsystem's noise reference,
  /// and all of them place the tail of the detection test. 19 draws make a Monte Carlo test at 5 %
  /// (0: no reference, no test).
  int noise_reference_draws = 19;
  double false_alarm_rate = 0.05;   ///< alpha of the Monte Carlo tests (detection, residual structure)
  double min_shrink = 0.3;          ///< fraction of the held-out gap a candidate must remove
  /// A winner is only a partial explanation when subsystems it does not change keep at least this share
  /// of the held-out gap (squared), or when it removes less than `half_explanation` of the gap and its
  /// residual keeps structure beyond the noise-only null.
  double untouched_share = 0.25;
  double half_explanation = 0.5;
  /// The best this many candidates that leave excess in subsystems they do not change get noise-only
  /// draws of their own closed loop, to tell the effect's knock-on there from a second gap (knock_on.h).
  int knock_on_candidates = 2;
  double min_evidence_per_parameter = 50.0;  ///< held-out evidence a candidate needs per fitted parameter
  /// Several effects at once (forward_selection.h): at most this many named, each further one removing
  /// at least min_further_shrink of what the effects before it leave and min_effect_share of the
  /// original gap, by more than the noise-only draws' spread.
  int max_effects = 3;
  double min_further_shrink = 0.1;
  double min_effect_share = 0.02;
  double upstream_share = 0.2;      ///< chassis excess (relative to steering) that makes the chassis the "where"
  /// Above 1: a fit's coordinate search and first polish run on every coarse_fit_stride-th piece of the
  /// training data, one Levenberg-Marquardt step on all of it (candidate_fit.h). At 3 (the default since
  /// 2026-11-26) both benchmark families keep every verdict, the held-out shrinks within 0.8 points,
  /// and the benchmark's 60 s log is diagnosed in 8.7-8.8 s instead of 14.0-14.9 s (docs/gap.md,
  /// "Coarse to fine"); 1 fits on all the data throughout. The smallest stride: a log of more than 12
  /// pieces takes the square root of its pieces (coarseFitData, diagnosis_data.h).
  std::size_t coarse_fit_stride = 3;
  int threads = 2;                  ///< candidates fitted in parallel
  bool closed_loop = true;          ///< run the closed-loop replays of "how far"
  /// A single run whose gap sets in mid-run (GapWhere::onset) and that no candidate explains over the
  /// whole log is diagnosed again on the part from the onset on (gap_onset.h).
  bool from_onset = true;
  /// [s] in the logs' own time: where the diagnosed effect sets in (the diagnosis from a gap's onset sets it,
  /// gap_onset.h). How far's corrected closed loop switches the effect on there, as the car met it, not from
  /// the log's first sample; NaN: on from the start.
  double effect_onset = std::numeric_limits<double>::quiet_NaN();
  /// Where the held-out test alone does not detect a gap and both sides together do, the diagnosis is run
  /// again with training and held-out data swapped, and an effect is named only if both folds name it
  /// (fold_pooling.h; issue 47, kind 1).
  bool two_folds = true;
  /// Hold every run (or side) out in turn even where the held-out test alone detects the gap: the folds
  /// decide as they do on the pooled test, and the report lists each (lk_gap --every-fold).
  bool every_fold = false;
  /// Where the replays' test sees no gap on held-out data and names nothing, a steering-loop delay is
  /// tested on its own fit against the same fit on the noise-only draws (decision/targeted_test.h; issue
  /// 47, kind 3): a delay of a few milliseconds near the loop's margin moves the replays' total excess less
  /// than noise does, yet its fit places it sharply and removes held-out excess no draw's fit removes.
  bool targeted_delay_test = true;
  /// Correct the sensor errors the input checks measure before any model (log/heading_agreement.h: the gyro's
  /// scale where the course and ay / V outvote it, its drift from psi where ay / V does not contradict it) before
  /// the fits, and name them as the verdict's effects (decision/measured_sensor_errors.h). An engineer fixes a
  /// calibration the data prove before modelling. Off (lk_gap --no-measured-corrections): they are reported, with
  /// a note where the verdict does not hold them, and the log read as it is.
  bool correct_measured_sensor_errors = true;
  /// Set by the diagnosis where it corrected measured sensor errors (decision/measured_sensor_errors.h): undoes
  /// them on each run's configuration for how far's "before" closed loop, so that the gap before is the nominal's
  /// as configured and the correction's own shrink is counted (empty: the runs' configurations as they are).
  std::function<void(SimConfig&)> how_far_before;
  /// [g] the largest steady side force a candidate may fit and still be the cause, as a fraction of the car's
  /// weight (fit/plausible_magnitude.h): 0.1 g is a road's steepest superelevation (8-12 %) or a storm's
  /// crosswind on an SUV's side; a banked oval needs more (lk_gap --max-side-force).
  double max_side_force = 0.1;
  /// Fit the leader's other forms (LuGre kingpin friction, a soft saturation) and let the one that fits
  /// better stand for it (leader_forms.h; issue 47, kind 7).
  bool leader_forms = true;
  /// Place a single named effect by the training runs' closed loop where its own closed loop closes clearly
  /// less of the gap than its replays, among the values the replays cannot tell from its fit
  /// (closed_loop_placement.h; issue 47, kind 7).
  bool closed_loop_placement = true;
  /// Which fold this diagnosis is: 0 the split as splitData makes it, 1 another fold (its two sides
  /// swapped, or one run held out of three or more; set by the diagnosis for the folds it runs).
  int fold = 0;
  /// A fold of every run held out in turn fits exactly these candidates (labels), whatever its own tests
  /// say: the split as made decided that there is a gap and which candidates can change it, and the folds'
  /// held-out evidence is pooled candidate by candidate (fold_pooling.h). Empty: the diagnosis decides.
  std::set<std::string> fold_candidates;
  std::vector<std::string> effects; ///< restrict the candidates (empty: all)
  std::function<void(const std::string&)> progress;  ///< progress messages (may be empty)
};

}  // namespace lane_keeping
