// The live gap monitor: the offline diagnosis's nominal replays, noise-only reference and "where"
// step, run over a sliding window and graded per subsystem.
#include "lane_keeping/gap/monitor/gap_monitor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <set>
#include <utility>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/decision/where_analysis.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/diagnosis_options.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/log/gap_run.h"

namespace lane_keeping {

using namespace diagnosis;

namespace {
std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}
}  // namespace

void GapMonitorOptions::visit(ParamVisitor& v, const std::string& prefix) {
  v.number(prefix + "window", window, "s", Range::closed(1.0, 600.0), "sliding window replayed");
  v.number(prefix + "period", period, "s", Range::closed(0.05, 600.0), "time between evaluations (stamp time)");
  v.number(prefix + "sample_period", sample_period, "s", Range::closed(1e-4, 0.1),
           "the replays' sampling: the input is thinned to it");
  v.number(prefix + "min_span", min_span, "s", Range::closed(0.5, 600.0), "data needed before the first evaluation");
  v.number(prefix + "warn_excess", warn_excess, "", Range::positive(),
           "net excess (normalised RMS beyond the noise-only reference) from which a subsystem is WARN");
  v.number(prefix + "error_excess", error_excess, "", Range::positive(), "net excess from which a subsystem is ERROR");
  v.integer(prefix + "reference_draws", reference_draws, Range::closed(0, 19),
            "noise-only draws per reference refresh; 0 = none (net excess = excess)");
  v.number(prefix + "reference_every", reference_every, "s", Range::closed(0.0, 3600.0),
           "refresh period of the noise-only reference; 0 = every evaluation");
  v.number(prefix + "start_margin", start_margin, "s", Range::closed(0.0, 10.0),
           "the window's first part, not scored (replay lead-in)");
  v.number(prefix + "max_floor", max_floor, "", Range::open(0.0, 1.0),
           "judge a subsystem only while its noise floor is below this share of its outputs' RMS");
}

void GapMonitorOptions::validate(const std::string& prefix) const {
  GapMonitorOptions copy = *this;
  RangeChecker checker;
  copy.visit(checker, prefix);
  std::vector<ConfigProblem> problems = checker.problems();
  if (error_excess <= warn_excess) {
    problems.push_back({prefix + "error_excess", "",
                        "= " + text(error_excess) + ", must be above " + prefix + "warn_excess (" +
                            text(warn_excess) + ")"});
  }
  if (window <= sample_period * 20.0) {
    problems.push_back({prefix + "window", "", "= " + text(window) + " s holds fewer than 20 samples of " +
                                                   prefix + "sample_period"});
  }
  if (min_span > window) {
    problems.push_back({prefix + "min_span", "", "= " + text(min_span) + " s, longer than " + prefix +
                                                     "window (" + text(window) + " s)"});
  }
  if (start_margin >= min_span) {
    problems.push_back({prefix + "start_margin", "", "= " + text(start_margin) + " s, must be below " +
                                                         prefix + "min_span (" + text(min_span) + " s)"});
  }
  if (!problems.empty()) throw ConfigError(problems);
}

const char* monitorLevelName(MonitorLevel level) {
  switch (level) {
    case MonitorLevel::kOk: return "OK";
    case MonitorLevel::kWarn: return "WARN";
    case MonitorLevel::kError: return "ERROR";
    case MonitorLevel::kStale: return "STALE";
  }
  return "?";
}

namespace {

GapMonitorOptions validated(GapMonitorOptions options) {
  options.validate();
  return options;
}

/// CPU time of the calling thread [s] (an evaluation's own cost, whatever else the machine runs).
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

MonitorLevel grade(double net, const GapMonitorOptions& o) {
  if (!(net < o.error_excess)) return MonitorLevel::kError;  // NaN grades as ERROR, never as OK
  return net >= o.warn_excess ? MonitorLevel::kWarn : MonitorLevel::kOk;
}

std::string fixed(double value, int digits = 4) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

}  // namespace

GapMonitor::GapMonitor(SimConfig nominal, GapMonitorOptions options)
    : nominal_(std::move(nominal)),
      options_(validated(options)),
      window_(options.window, options.sample_period, std::max(1.0, 2.0 * options.sample_period)) {
  nominal_.validate();
}

GapMonitorOptions GapMonitor::options() const {
  std::lock_guard<std::mutex> lock(options_mutex_);
  return options_;
}

void GapMonitor::setOptions(const GapMonitorOptions& options) {
  options.validate();
  std::lock_guard<std::mutex> lock(options_mutex_);
  std::vector<ConfigProblem> problems;
  if (options.window != options_.window) {
    problems.push_back({"window", "", "cannot change while running (it sizes the buffer): restart the monitor"});
  }
  if (options.sample_period != options_.sample_period) {
    problems.push_back({"sample_period", "", "cannot change while running (it thins the buffer): restart the monitor"});
  }
  if (!problems.empty()) throw ConfigError(problems);
  options_ = options;
}

bool GapMonitor::due() const {
  if (window_.empty()) return false;
  const GapMonitorOptions o = options();
  double next = next_stamp_;
  if (std::isnan(next) || window_.counts().restarts != snapshot_restarts_) {
    // The first stamp k * period with min_span of data before it.
    const double oldest = window_.latest() - window_.span();
    next = std::ceil((oldest + o.min_span) / o.period - 1e-9) * o.period;
  }
  const double covered = window_.coveredUntil();
  return covered >= next || window_.latest() >= next + kStreamTimeout;
}

GapLog GapMonitor::windowLog() const { return window_.log("gap_monitor window"); }

MonitorSnapshot GapMonitor::snapshot() {
  const GapMonitorOptions o = options();
  if (std::isnan(next_stamp_) || window_.counts().restarts != snapshot_restarts_) {
    const double oldest = window_.latest() - window_.span();
    next_stamp_ = std::ceil((oldest + o.min_span) / o.period - 1e-9) * o.period;
    snapshot_restarts_ = window_.counts().restarts;
  }
  MonitorSnapshot snap;
  snap.stamp = next_stamp_;
  snap.log = window_.log("gap_monitor window", snap.stamp);
  snap.restarts = window_.counts().restarts;
  // The next stamp: one period on (k * period, computed from k so that rounding does not drift).
  next_stamp_ = (std::round(next_stamp_ / o.period) + 1.0) * o.period;
  return snap;
}

MonitorStatus GapMonitor::evaluate(const MonitorSnapshot& snapshot) {
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuSeconds();
  const GapMonitorOptions o = options();  // one set of thresholds for the whole evaluation
  MonitorStatus status;
  status.stamp = snapshot.stamp;
  for (const std::string& name : subsystemNames()) {
    MonitorSubsystem s;
    s.name = name;
    status.subsystems.push_back(s);
  }
  auto finish = [&]() {
    status.level = MonitorLevel::kOk;
    bool any_available = false;
    for (const MonitorSubsystem& s : status.subsystems) {
      if (!s.judged) continue;
      any_available = true;
      status.level = std::max(status.level, s.level);
    }
    if (!any_available) status.level = MonitorLevel::kStale;
    status.evaluation_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    status.evaluation_cpu_seconds = threadCpuSeconds() - cpu_start;
    return status;
  };
  auto stale = [&](const std::string& why) {
    for (MonitorSubsystem& s : status.subsystems) {
      s.level = MonitorLevel::kStale;
      if (s.message.empty()) s.message = why;
    }
    return finish();
  };
  if (snapshot.restarts != restarts_seen_) {
    restarts_seen_ = snapshot.restarts;
    reference_stamp_ = -1e300;  // a new run: its noise and manoeuvre are not the last one's
    reference_.clear();
  }
  GapLog log = snapshot.log;
  status.notes = log.notes;
  if (log.size() < 20) return stale("only " + std::to_string(log.size()) + " complete samples in the window");
  status.window_start = log.t.front();
  status.window_end = log.t.back();
  status.samples = log.size();
  try {
    GapRun run;
    run.log = std::move(log);
    run.config = nominal_;
    run.initial_from_log = true;  // the window starts mid-run: the state at its start, not the configured one
    const std::vector<RunData> runs = prepareRuns({run});
    for (const auto& [name, why] : unavailableSubsystems(runs)) {
      for (MonitorSubsystem& s : status.subsystems) {
        if (s.name == name) s.message = "not replayed: " + why;
      }
    }
    const std::set<std::string> available = availableSubsystems(runs);
    if (available.empty()) return stale("the window feeds no subsystem's replay");
    const std::vector<Dataset> data = wholeLogs(runs, o.start_margin);
    const ReplayOptions replay_options;
    Evaluation ev = diagnosis::evaluate(nullptr, data, available, replay_options);

    if (o.reference_draws == 0) reference_.clear();
    if (o.reference_draws > 0 &&
        (reference_.empty() || status.stamp - reference_stamp_ >= o.reference_every * (1.0 - 1e-9))) {
      const NoiseNull null = noiseNull({}, data, available, replay_options, o.reference_draws, 1);
      if (null.draws() > 0) {
        reference_ = null.largestHeldExcess();
        reference_stamp_ = status.stamp;
        status.reference_refreshed = true;
      } else {
        status.notes.insert(status.notes.end(), null.notes.begin(), null.notes.end());
      }
    }
    setReference(ev.scores, reference_);

    for (MonitorSubsystem& s : status.subsystems) {
      const auto it = ev.scores.find(s.name);
      if (it == ev.scores.end()) {
        s.level = MonitorLevel::kStale;
        continue;
      }
      const SubsystemScore& score = it->second;
      s.available = true;
      for (const auto& trace : score.traces) s.outputs.push_back(trace.name);
      s.nrmse = score.nrmse;
      s.floor = score.floor;
      s.excess = score.excess;
      s.reference = score.reference;
      s.net = netExcess(score);
      s.diverged_intervals = score.diverged_intervals;
      s.judged = score.floor <= o.max_floor;
      if (!s.judged) {
        s.level = MonitorLevel::kStale;
        s.message = "no verdict: " + join(s.outputs) + " barely move in the window (noise floor " + fixed(score.floor, 2) +
                    " of their RMS, above " + fixed(o.max_floor, 2) + ")";
        continue;
      }
      s.level = grade(s.net, options_);
      s.message = std::string(monitorLevelName(s.level)) + ": net excess " + fixed(s.net) + " over " +
                  fixed(status.window_end - status.window_start, 1) + " s (warn " + fixed(o.warn_excess) +
                  ", error " + fixed(o.error_excess) + ")";
      if (s.diverged_intervals > 0) {
        s.message += "; " + std::to_string(s.diverged_intervals) + " shooting intervals left the model's domain";
      }
    }

    const GapWhere where = whereAnalysis(ev, data, DiagnosisOptions{}.upstream_share, nullptr);
    status.leading = where.subsystem;
    if (!where.windows.empty()) {
      status.leading_t0 = where.windows.front().t0;
      status.leading_t1 = where.windows.front().t1;
      status.leading_share = where.windows.front().share;
    }
    for (const BandShare& band : where.bands) {
      if (band.share > status.band_share) {
        status.band_f0 = band.f0;
        status.band_f1 = band.f1;
        status.band_share = band.share;
      }
    }
  } catch (const LaneKeepingError& e) {
    return stale(std::string("replay failed: ") + e.what());
  }
  return finish();
}

}  // namespace lane_keeping
