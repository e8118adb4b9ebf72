#pragma once
/// The diagnosis result: where the gap lies, which effect causes it, how far it shrinks.
/// report.json carries the fields of DESIGN §5 (an interface outside checks rely on) and more.
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace lane_keeping {

/// The candidate effects, with the names report.json uses (DESIGN §5).
const std::vector<std::string>& candidateEffectNames();

struct SubsystemGap {
  std::string name;      ///< steering | chassis | tracker | actuator
  double nrmse = 0.0;    ///< RMS of the replay residual / RMS of the measured output (per output, averaged)
  double noise_floor = 0.0;  ///< estimated measurement-noise contribution to nrmse
  std::vector<std::string> outputs;  ///< the compared outputs, e.g. {"yaw_rate", "psi", "y", "ay"}
};

struct WindowShare {
  std::string log;            ///< the run (log source) the window lies in
  double t0 = 0.0, t1 = 0.0;  ///< [s], the log's own time
  double share = 0.0;         ///< fraction of the residual energy in [t0, t1)
  /// [s] the log's first sample, in its own time: report.md and the plots show t0 - log_t0 (an epoch
  /// stamp, t ~ 1.7e9 s, read as 1.692e+09 there)
  double log_t0 = 0.0;
};

struct BandShare {
  double f0 = 0.0, f1 = 0.0;  ///< [Hz]
  double share = 0.0;         ///< fraction of the residual energy in [f0, f1)
};

struct RegimeShare {
  std::string variable;       ///< slip_angle | lateral_acceleration | steering_rate
  double lo = 0.0, hi = 0.0;  ///< bin of |variable|, SI units
  double share = 0.0;         ///< fraction of the residual energy
  double time_share = 0.0;    ///< fraction of the samples (to compare with `share`)
};

/// Where one run's gap sets in mid-run (where_analysis.h): before it, the nominal matches the log.
struct RunOnset {
  std::string log;      ///< the run (log source)
  double t = 0.0;       ///< [s] the onset, in the log's own time
  double log_t0 = 0.0;  ///< [s] the log's first sample, in its own time: t - log_t0 is the time since its start
};

struct GapWhere {
  std::string subsystem;  ///< the subsystem that carries the gap
  std::vector<SubsystemGap> subsystems;
  std::vector<WindowShare> windows;  ///< the time windows carrying most of the gap, largest first
  /// [s] where the gap of a diagnosis of one run sets in mid-run (the single-log mode; its one entry of
  /// `onsets`); NaN when the gap is there from the start, none is detected or the data hold several runs.
  double onset = std::numeric_limits<double>::quiet_NaN();
  /// Per run (training and held-out runs alike, in the order of the logs), where its gap sets in mid-run;
  /// runs whose gap is there from the start (or that have none) are absent. Empty when no gap is detected.
  std::vector<RunOnset> onsets;
  std::vector<BandShare> bands;      ///< all bands, low to high frequency
  std::vector<RegimeShare> regimes;
};

struct RankedEffect {
  std::string effect;                     ///< one of candidateEffectNames()
  std::string form;                       ///< where the effect sits, for effects with several placements ("" otherwise)
  std::map<std::string, double> params;   ///< fitted parameters, SI units (names: candidate_effects.h)
  std::map<std::string, double> param_sigma;  ///< 1-sigma uncertainty of each fitted parameter
  std::map<std::string, std::string> config;  ///< the config overlay that adds the effect ("key" -> "value")
  double train_gap_before = 0.0, train_gap_after = 0.0;
  double heldout_gap_before = 0.0;
  double heldout_gap_after = 0.0;
  double shrink = 0.0;                    ///< 1 - heldout_gap_after / heldout_gap_before
  double score = 0.0;                     ///< evidence used for the verdict (docs/gap.md, "Which")
  /// False when the fitted effect makes the closed loop of a training log leave the logged bounds
  /// (the log contradicts it): such a candidate cannot be the verdict and ranks last.
  bool closed_loop_bounded = true;
  /// False when the fitted closed loop was not checked: its boundedness could not change the verdict
  /// (closed_loop_checks.h), or the logs cannot drive a closed loop. closed_loop_bounded is then true
  /// (nothing contradicts the fit).
  bool closed_loop_checked = true;
  /// Why the fitted magnitude is beyond what the world makes ("" where it is not): a side force beyond
  /// DiagnosisOptions::max_side_force (fit/plausible_magnitude.h). Such a candidate, like one whose closed
  /// loop leaves the logged bounds, cannot be the verdict and ranks last.
  std::string implausible;
  /// Whether it may be the cause: its closed loop bounded and its magnitude plausible.
  bool mayBeTheCause() const { return closed_loop_bounded && implausible.empty(); }

  /// "sensor_offset (yaw_rate)", or the bare name for an effect with one form.
  std::string label() const { return form.empty() ? effect : effect + " (" + form + ")"; }
};

/// A candidate that explains part of the gap and leaves structure beyond the noise (the verdict is then
/// `unexplained`, naming it).
struct PartialExplanation {
  std::string effect;            ///< "" when the winner explains the gap
  std::string form;
  double share = 0.0;            ///< the gap it removes: the larger of its held-out and training shrink
  double untouched_share = 0.0;  ///< share of the held-out gap^2 in subsystems it does not change
  double whiteness_p = 1.0;      ///< Monte Carlo p-value of its residual's whiteness statistic (residual_structure.h)
  double input_correlation_p = 1.0;  ///< ... of its residual's correlation with the subsystem's input
};

/// One of the effects a verdict names: a real car has several at once (a sensor's offset and a road's
/// bank; forward_selection.h). The first is the verdict's `effect`; each further one was fitted on top of
/// those before it and earned its parameters by its own held-out evidence.
struct VerdictEffect {
  std::string effect;                          ///< one of candidateEffectNames()
  std::string form;                            ///< its channel (sensor errors) or placement ("" for one form)
  std::map<std::string, double> params;        ///< fitted parameters, SI units
  std::map<std::string, double> param_sigma;   ///< their 1-sigma uncertainty
  /// The replays' own fit where the closed loop placed the effect (decision/closed_loop_placement.h: `params`,
  /// `param_sigma` and `config` are then the placed values; `share` and `gap_after` stay the replays' fit's);
  /// empty otherwise.
  std::map<std::string, double> replay_params;
  std::map<std::string, std::string> config;   ///< the config overlay that adds it ("key" -> "value")
  double share = 0.0;       ///< its share of the held-out gap: (gap before it - gap with it) / gap_before
  double gap_after = 0.0;   ///< held-out gap with it and every effect before it
  double evidence = 0.0;    ///< its held-out evidence over the effects before it
  bool sensor = false;      ///< a sensor or data error, not physics
  /// Measured before any model by the input checks (log/heading_agreement.h) and corrected before the fits
  /// (decision/measured_sensor_errors.h): no held-out evidence (NaN), its share the gap its correction removes.
  bool measured = false;
  /// Candidates that, fitted in its place (on top of the same effects before it), remove nearly as much
  /// (within 10 points of shrink): the logs cannot tell them apart from it.
  std::vector<std::string> confusable_with;
};

struct GapVerdict {
  std::string effect;       ///< winning effect, or "unexplained"
  std::string form;         ///< where the winning effect sits, for effects with several placements
  double confidence = 0.0;  ///< in [0, 1]
  double gap_before = 0.0;  ///< held-out gap without the effect
  double gap_after = 0.0;   ///< held-out gap with the fitted effect
  double shrink = 0.0;      ///< 1 - gap_after / gap_before
  std::string reason;       ///< one sentence: why this verdict
  /// What named the effect: "replays" (its held-out shrink and evidence), "modal" where the replays
  /// cannot weigh it and the loop's characteristic roots do (modal_evidence.h: gap_after = gap_before),
  /// "targeted" where the replays' test sees no gap and a delay's fit beats its fit on every noise-only draw
  /// (targeted_test.h: the gaps gross of the noise reference), or "measured" (measured_sensor_errors.h).
  std::string basis = "replays";
  std::vector<std::string> confusable_with;  ///< effects the data cannot tell apart from the winner
  PartialExplanation partial;  ///< set when the best candidate explains only part of the gap
  /// Every effect named, the leading one (`effect`) first; empty when `unexplained`.
  std::vector<VerdictEffect> effects;
  double combined_gap_after = 0.0;  ///< held-out gap with all of `effects` (= gap_after with one)
  double combined_shrink = 0.0;     ///< 1 - combined_gap_after / gap_before
};

/// The calibrated decision "the nominal model misses something" (noise_null.h): the total excess of the
/// nominal replays against the same statistic of the noise-only null draws.
struct DetectionTest {
  /// Whether noise-only draws ran: without them there is no calibrated test (report.json: no p-value,
  /// no "detected"; the diagnosis goes on only where the net gap reaches detection_gap).
  bool tested = true;
  double value = 0.0;        ///< sum over subsystems of excess^2
  double p_value = 1.0;      ///< Monte Carlo p-value among the draws
  double null_median = 0.0, null_max = 0.0;  ///< of the draws
  bool detected = false;     ///< p_value <= false_alarm_rate, and the net gap above detection_gap
};

struct GapDetection {
  int draws = 0;                   ///< noise-only null draws
  double false_alarm_rate = 0.05;  ///< alpha
  DetectionTest heldout, training;
  /// Both sides together (value = training + held-out, against each draw's two totals summed): the test
  /// of the two folds, in which each side is held out once (fold_pooling.h). Decides in place of the
  /// held-out test where that alone does not detect a gap.
  DetectionTest pooled;
};

/// One fold of a diagnosis (fold_pooling.h): what was fitted on which data and what it named. The first
/// fold is the split of `split.method`; the second swaps its training and held-out sides.
struct GapFold {
  std::vector<std::string> training;  ///< logs or blocks fitted on
  std::vector<std::string> heldout;   ///< logs or blocks scored on
  std::string effect;                 ///< its verdict ("unexplained" when it names nothing)
  std::string form;
  std::string basis = "replays";
  double heldout_p = 1.0;             ///< its held-out test alone
  double gap_before = 0.0;            ///< its held-out gap, nominal
  double gap_after = 0.0;             ///< with its verdict's effect
  std::map<std::string, double> params;
};

/// How training and held-out data were chosen (diagnosis_data.h).
struct GapSplit {
  std::string method;                      ///< held-out runs | whole runs | excitation-balanced blocks
  std::map<std::string, double> coverage;  ///< excitation kind -> share of it in held-out data
};

struct ClosedLoopGap {
  double before = 0.0;  ///< closed-loop replay gap (held-out) with the nominal model
  double after = 0.0;   ///< with the winning effect added
  /// What a perfect model's closed loop would leave: the logs' white noise on y, yaw rate and delta over each
  /// channel's spread (closedLoopNoiseFloor), RMS over the channels and runs; NaN where not run.
  double noise_floor = std::numeric_limits<double>::quiet_NaN();
  /// before and after net of that floor, channel by channel in quadrature (netClosedLoopGap): what the
  /// corrected model can still close. 1 - net_after / net_before is the closed-loop shrink net of noise.
  double net_before = std::numeric_limits<double>::quiet_NaN();
  double net_after = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double> subsystems_before;  ///< per-subsystem held-out excess (gap_metrics.h)
  std::map<std::string, double> subsystems_after;
  /// Per-subsystem excess of the noise-only reference (noise_reference.h): the part of each excess a
  /// perfect model would leave; the gap subtracts it in quadrature.
  std::map<std::string, double> subsystems_noise_reference;
  /// Why the closed-loop replay did not run or gave no gap ("" when it did): before and after are NaN then.
  std::string not_run;
};

/// A subsystem the logs cannot feed (a partial log), and why.
struct SkippedSubsystem {
  std::string name;
  std::string reason;
};

/// A candidate that acts only on skipped subsystems: not testable on these logs (not rejected).
struct UntestableEffect {
  std::string effect;
  std::string reason;
};

/// Something odd about a log, found before the diagnosis (log/input_checks.h; kinds: hole, stuck, rate,
/// units, speed, span), with what the diagnosis did about it.
struct InputCheckEntry {
  std::string log;
  std::string channel;  ///< schema column ("t" for the time axis)
  std::string kind;
  std::string detail;
  /// [s] a hole's last sample before and first after it, in the log's own time (NaN for other kinds)
  double t0 = std::numeric_limits<double>::quiet_NaN();
  double t1 = std::numeric_limits<double>::quiet_NaN();
};

struct GapReport {
  std::vector<std::string> logs;     ///< training logs
  std::vector<std::string> heldout;  ///< held-out logs or segments
  std::size_t rows_used = 0;
  std::size_t rows_skipped = 0;
  std::vector<std::string> notes;
  std::vector<SkippedSubsystem> skipped_subsystems;  ///< replays the logs cannot feed
  std::vector<UntestableEffect> not_testable;        ///< candidates acting only on skipped subsystems
  /// Candidates not fitted because they change only subsystems whose replays match the logs to within the
  /// noise-only draws (or because there is no gap at all): they cannot explain what is there.
  std::vector<UntestableEffect> not_fitted;
  GapSplit split;
  GapDetection detection;
  /// Where the held-out test alone misses and the pooled one detects (or every fold is asked for): both
  /// folds, the first as reported; with three runs or more, each run held out in turn (empty otherwise;
  /// fold_pooling.h).
  std::vector<GapFold> folds;
  /// The nominal's net excess per subsystem on the held-out data. Not written to report.json: what the
  /// folds of every run held out in turn pool their partial explanation from (fold_pooling.h).
  std::map<std::string, double> heldout_net_excess;
  GapWhere where;
  std::vector<RankedEffect> ranking;  ///< best first
  GapVerdict verdict;
  ClosedLoopGap how_far;
  /// Wall time per stage in seconds, in the order run: "where" (nominal replays, noise reference),
  /// "fit <effect>" per candidate (on its worker thread), "which" (all fits), "how_far" (closed-loop
  /// replays). Says where a slow diagnosis spends its time.
  std::vector<std::pair<std::string, double>> wall_seconds;
  std::vector<InputCheckEntry> input_checks;  ///< what is odd about the logs, found before the diagnosis
  /// [s] each log's first sample in its own time (by source): report.md and the plots give times since it
  std::map<std::string, double> logs_t0;
};

/// DIR/report.json (DESIGN §5 fields and the rest). Throws InputError if DIR cannot be written.
/// `path` is the file to write; if it names an existing directory, DIR/report.json is written.
/// Non-finite numbers (NaN, +-Inf) are written as JSON null (read back as NaN). Layout: gap_report.cpp.
void writeGapReportJson(const std::string& path, const GapReport& report);
/// The text writeGapReportJson writes (report.json), e.g. for a service response.
std::string gapReportJson(const GapReport& report);
/// report.json's `how_far` object alone, as JSON text (the benchmark's ceiling, Python's how_far).
std::string closedLoopGapJson(const ClosedLoopGap& how_far);
/// Reads it back (tests, the benchmark scorer). Accepts the file or its directory. Throws InputError
/// naming the file and the JSON path (e.g. "$.verdict.effect: missing") if a DESIGN §5 key is absent
/// or has the wrong type; fields beyond DESIGN §5 default when absent.
GapReport readGapReportJson(const std::string& path);

}  // namespace lane_keeping
