#pragma once
/// The live gap monitor (shadow mode): while the car drives, every `period` seconds it replays each
/// subsystem whose signals it has over the last `window` seconds (monitor_window.h) with the nominal
/// model — the same replays, scores and noise-only reference as the offline diagnosis (subsystem_replay.h,
/// gap_metrics.h, noise_null.h) — and grades each subsystem by its excess beyond that reference:
///   net = sqrt(max(0, excess^2 - reference^2))          (gap_metrics.h netExcess)
///   OK    net < warn_excess
///   WARN  warn_excess <= net < error_excess
///   ERROR net >= error_excess
/// A subsystem whose outputs barely move in the window (a car driving straight) is not judged: its
/// normalised residual is then mostly noise (floor ~ 1), and the excess of a noise-dominated residual
/// scatters by tenths (measured: 0.1-1.3 on a no-effect lane-change log once the car drove straight).
/// It is kStale ("no verdict now") until the floor drops below `max_floor` again.
/// An effect that sets in mid-window shows in the window's excess diluted by the share of the window
/// it covers (an excess E after a third of a window reads ~E / sqrt(3)): a shorter window sees it
/// sooner and scatters more. (Scoring the window's last seconds on their own was tried: with the
/// threshold the tail's larger scatter needs, it saw nothing sooner than the whole window.)
/// The noise-only reference costs a closed-loop simulation and a replay per draw; the noise levels and
/// the manoeuvre change slowly, so it is refreshed every `reference_every` seconds (always on the first
/// evaluation and after a restart of the window), not every period.
/// Where in the window and in which frequency band the leading subsystem's excess lies comes from the
/// diagnosis's "where" step (where_analysis.h).
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "lane_keeping/config/param_visitor.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/monitor/monitor_window.h"

namespace lane_keeping {

struct GapMonitorOptions {
  double window = 10.0;          ///< [s] sliding window replayed
  double period = 1.0;           ///< [s] time between evaluations (stamps, i.e. simulated or log time)
  double sample_period = 0.002;  ///< [s] the replays' sampling: input is thinned to it
  double min_span = 3.0;         ///< [s] data needed before the first evaluation
  double warn_excess = 0.03;     ///< net excess (normalised RMS) from which a subsystem is WARN
  double error_excess = 0.1;    ///< ... ERROR
  int reference_draws = 3;       ///< noise-only draws per reference refresh; 0 = no reference (net = excess)
  double reference_every = 0.0; ///< [s] refresh period of the noise-only reference
  double start_margin = 1.0;     ///< [s] the window's first part, not scored (delayed inputs need history)
  double max_floor = 0.3;        ///< judge a subsystem only while its white-noise floor is below this share of
                                 ///< its outputs' RMS (a car driving straight leaves mostly noise: no verdict)

  void visit(ParamVisitor& v, const std::string& prefix);
  /// Throws ConfigError naming every key out of range, and `<prefix>error_excess` when not above warn_excess.
  void validate(const std::string& prefix = "") const;
};

enum class MonitorLevel { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };  ///< diagnostic_msgs' levels
const char* monitorLevelName(MonitorLevel level);

struct MonitorSubsystem {
  std::string name;           ///< tracker | actuator | steering | chassis
  MonitorLevel level = MonitorLevel::kStale;
  std::string message;        ///< one line for the diagnostics: why this level
  bool available = false;     ///< the window feeds its replay
  std::vector<std::string> outputs;
  double nrmse = 0.0, floor = 0.0, excess = 0.0, reference = 0.0;
  double net = 0.0;           ///< netExcess over the window
  int diverged_intervals = 0;
  bool judged = false;        ///< excited enough for a verdict (floor <= max_floor)
};

struct MonitorStatus {
  double stamp = 0.0;                        ///< [s] the newest sample evaluated
  double window_start = 0.0, window_end = 0.0;
  std::size_t samples = 0;                   ///< rows replayed
  MonitorLevel level = MonitorLevel::kStale; ///< the worst subsystem's
  std::string leading;                       ///< the subsystem carrying most net excess ("" if none)
  double leading_t0 = 0.0, leading_t1 = 0.0, leading_share = 0.0;  ///< its largest time window [s]
  double band_f0 = 0.0, band_f1 = 0.0, band_share = 0.0;           ///< its largest frequency band [Hz]
  std::vector<MonitorSubsystem> subsystems;  ///< in subsystemNames() order
  bool reference_refreshed = false;
  double evaluation_seconds = 0.0;           ///< wall time of this evaluation
  double evaluation_cpu_seconds = 0.0;       ///< CPU time of this evaluation (its thread)
  std::vector<std::string> notes;
};

/// The window's rows at one instant, for an evaluation that runs while the window keeps filling.
struct MonitorSnapshot {
  GapLog log;
  double stamp = 0.0;          ///< the newest state stamp
  std::size_t restarts = 0;    ///< the window's clock-jump count at that instant
};

/// Threads: the window (adding samples, due(), snapshot()) belongs to one thread, or to callers that
/// serialise it; evaluate(snapshot) may run in another thread, and setOptions() in a third.
class GapMonitor {
 public:
  /// Throws ConfigError (options) or what nominal.validate() throws.
  GapMonitor(SimConfig nominal, GapMonitorOptions options);

  MonitorWindow& window() { return window_; }
  const MonitorWindow& window() const { return window_; }
  GapMonitorOptions options() const;
  const SimConfig& nominal() const { return nominal_; }

  /// Thresholds, reference and period may change at run time; window and sample_period only by a new
  /// monitor (they size the buffer). Throws ConfigError (nothing changed) naming the key otherwise.
  void setOptions(const GapMonitorOptions& options);

  /// Whether an evaluation is due. Evaluations fall on the stamps k * period (k integer) once min_span
  /// of data is in, each as soon as every stream covers its stamp — or, if a stream stops, once the
  /// state is `kStreamTimeout` past it. So the same data give the same snapshots, live or from a bag,
  /// however the messages interleave.
  bool due() const;
  /// The window ending at the next due stamp; moves the next stamp on by one period (call while due()).
  MonitorSnapshot snapshot();
  static constexpr double kStreamTimeout = 0.5;  ///< [s]
  /// Replays the snapshot and grades each subsystem. Never throws for data: a window the replays cannot
  /// use gives every subsystem kStale with the reason.
  MonitorStatus evaluate(const MonitorSnapshot& snapshot);
  MonitorStatus evaluate() { return evaluate(snapshot()); }
  /// The window as a log, for the full diagnosis (lk_gap's code) on demand.
  GapLog windowLog() const;

 private:
  SimConfig nominal_;
  mutable std::mutex options_mutex_;
  GapMonitorOptions options_;
  MonitorWindow window_;
  double next_stamp_ = std::nan("");  ///< the next evaluation's stamp (NaN: not yet known)
  double reference_stamp_ = -1e300;
  std::size_t restarts_seen_ = 0;     ///< restarts the reference knows of
  std::size_t snapshot_restarts_ = 0; ///< restarts next_stamp_ knows of
  std::map<std::string, double> reference_;
};

}  // namespace lane_keeping
