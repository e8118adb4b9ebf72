#pragma once
/// The withheld-effect benchmark of the gap diagnosis (DESIGN §5, issue 5 item 3).
///
/// A truth generator makes "real" logs: the closed loop of a truth configuration — the nominal one
/// plus one hidden effect in a *higher-fidelity form than the candidate model* (distributed LuGre
/// tires with carcass relaxation for tire lag, LuGre friction with a Stribeck peak for steering
/// friction, a soft saturation for the torque limit, a different contact length for cornering
/// stiffness, partial sliding friction for road friction, gusts along the road for the lateral
/// disturbance, a bias varying along the road for the pose bias, a heavier steering column for
/// compliance, mass with yaw inertia for inertia, delays that are not multiples of the step) — at two
/// magnitudes and on two manoeuvres, plus logs with no effect and logs with effects outside the
/// candidate list (steering dead band, a delay on the steering-angle sensor only, a varying speed).
/// Every log gets sensor noise. The diagnosis sees only the log and the nominal configuration.
#include <map>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"
#include "lane_keeping/gap/log/gap_log.h"

namespace lane_keeping {


/// A further training run of a case (BenchmarkCase::more_runs): its road and the scenario keys on top of the
/// case's set-up.
struct MoreRun {
  std::string manoeuvre;
  std::vector<std::string> setup{};
};

/// One hidden effect of a case with several (BenchmarkCase::truths): a candidate name and the form
/// (channel or placement) the verdict must name ("" = any).
struct TruthEffect {
  std::string effect;
  std::string form{};
};

struct BenchmarkCase {
  std::string id;                  ///< e.g. "steering_friction-large-sinusoid"
  std::string category;            ///< in_list | none | out_of_list
  std::string truth;               ///< candidate name, "none", or the out-of-list effect's name
  std::string magnitude;           ///< small | large, or the magnitude in words (empty for none)
  std::string manoeuvre;           ///< lane_change | sinusoid | straight | bend
  std::vector<std::string> truth_overlay;  ///< key=value on top of the nominal configuration
  unsigned seed = 1;               ///< noise seed
  /// The independent family: the case's own set-up (key=value on the manoeuvre's nominal, known to the
  /// diagnosis: gains, actuator strength, initial state, duration), its log rate (0: the command
  /// line's) and a factor on every sensor noise level.
  // (Empty default initialisers: a case braced with only its first fields then leaves these at their
  // defaults without GCC's -Wmissing-field-initializers.)
  std::vector<std::string> setup{};
  double log_rate = 0.0;
  double noise_scale = 1.0;
  /// A held-out run on another road (empty: none; blocks of the one log are held out): the diagnosis
  /// gets it as `--holdout` with a scenario of its own (its path, initial state and duration), as a
  /// user brings runs of different roads.
  std::string heldout_manoeuvre{};
  std::vector<std::string> heldout_setup{};  ///< scenario keys on top of the held-out manoeuvre
  /// Further training runs (empty: none), each on its road with its own noise seed: the diagnosis gets them
  /// as further `--log` runs with their scenarios; with three runs or more it holds each out in turn.
  std::vector<MoreRun> more_runs{};

  // What the groups (independent_groups.h) need; every default leaves a case as it was (its log the
  // same to the last bit).
  /// The table the scorer counts the case in ("" = the family's first table, where the cases written
  /// before these groups stay).
  std::string group{};
  /// The form the verdict must name with `truth` (a sensor error's channel, an effect's placement; ""
  /// = any form): "heading" for a heading mount, "pose" for a localisation latency.
  std::string truth_form{};
  /// Several hidden effects at once (two-at-once cases; empty: the one of truth / truth_form): the
  /// verdict is right if its effect is one of them, "both named" if each is among verdict.effects.
  std::vector<TruthEffect> truths{};
  /// Per logged column ("yaw_rate", "delta", "torque", "ay", ...): the sensor's character where it is
  /// more than white noise (a vehicle bus's quantised, held, coloured channels; sensor_character.h).
  std::map<std::string, ChannelCharacter> sensor_character{};

  /// The hidden effects the verdict is scored against: `truths`, or {truth, truth_form} for one.
  std::vector<TruthEffect> truthEffects() const;
};

/// The held-out run of a case: its manoeuvre, the case's set-up plus heldout_setup, its own noise seed.
BenchmarkCase heldoutRunOf(const BenchmarkCase& c);
/// The k-th further training run of a case (k from 0): its road, the case's set-up plus the run's keys, its
/// own noise seed; its id the case's with ".run<k + 2>".
BenchmarkCase moreRunOf(const BenchmarkCase& c, std::size_t k);
/// The scenario of a case's run as lk_gap reads it (only the per-run keys: path, initial state,
/// duration; gap_run.h), as YAML text.
std::string benchmarkScenarioYaml(const BenchmarkCase& c);

/// The nominal configuration of a manoeuvre (lumped LuGre tires, the paper's vehicle, k_psi = 0.8,
/// k_y = 0.05 1/m, tau1 = 0.2 s, tau2 = 0.1 ms, p = 1000, an identification multisine on delta_des;
/// 30 s logged at 500 Hz).
SimConfig benchmarkNominal(const std::string& manoeuvre);
/// All cases: 11 effects x 2 magnitudes x 2 manoeuvres, `none_per_manoeuvre` no-effect logs per
/// manoeuvre, and 3 out-of-list effects x 2 magnitudes x 2 manoeuvres.
std::vector<BenchmarkCase> benchmarkCases(int none_per_manoeuvre = 6);
/// The case of benchmarkCases() with this id; std::invalid_argument naming the id if there is none.
BenchmarkCase benchmarkCase(const std::string& id);
/// The independent family, made with choices the candidates did not make (docs/gap.md): effects where
/// real cars have them (a localisation bias the log records too, a column sensed on the motor side, a
/// road bank the accelerometer does not sense), other path shapes (a bend, a straight road with initial
/// offsets up to 3 m), actuator strengths p 500-2000, other tracker gains, 100 Hz and 1 kHz logs, noise
/// levels +-50 %; 40 no-effect logs over those set-ups; sensor errors (out of the list until issue 46:
/// a localisation latency, a yaw-rate bias); a crosswind that sets in mid-run; and pairs of runs on
/// different roads (a training and a held-out run). Then the groups (independent_groups.h: sensor
/// errors alone and with a physical effect), each scored in its own table.
std::vector<BenchmarkCase> independentCases();
/// The independent family's case `id` (std::invalid_argument if there is none).
BenchmarkCase independentCase(const std::string& id);
/// The cases of a family: "candidates" (benchmarkCases()) or "independent".
std::vector<BenchmarkCase> familyCases(const std::string& family);
/// The nominal configuration the diagnosis of a case is given: its manoeuvre's with the case's set-up.
SimConfig benchmarkCaseNominal(const BenchmarkCase& c);
/// The truth configuration of a case: its nominal with the case's overlay applied.
SimConfig benchmarkTruth(const BenchmarkCase& c);
/// Simulates the truth of a case and returns its noisy log, each column through its sensor character
/// where the case gives one (throws if the truth run diverges), sampled at the case's own log rate where it
/// has one (BenchmarkCase::log_rate), else at `log_rate`.
GapLog generateBenchmarkLog(const BenchmarkCase& c, const SensorNoise& noise = {}, double log_rate = 500.0);

}  // namespace lane_keeping
