#pragma once
// The inputs of a candidate's objective on one benchmark log, for tests of the fit machinery: the case
// shortened to `duration`, its truth log at `log_rate`, the nominal configuration, the whole log (after
// `margin`) as the data, and the nominal replays' sigma1 the objective reuses.
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/bounded_loop.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/candidate_objective.h"

namespace lane_keeping {
namespace diagnosis {

struct BenchmarkObjectiveFixture {
  std::vector<RunData> runs;
  std::vector<Dataset> data;
  Evaluation nominal;
  std::set<std::string> available;
  SimConfig config;

  BenchmarkObjectiveFixture(const std::string& case_id, double duration, double log_rate, double margin) {
    BenchmarkCase c = benchmarkCase(case_id);
    c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
    GapRun run;
    run.log = generateBenchmarkLog(c, SensorNoise{}, log_rate);
    run.config = benchmarkNominal(c.manoeuvre);
    run.config.simulation.duration = duration;
    config = run.config;
    runs = prepareRuns({run});
    data = wholeLogs(runs, margin);
    available = availableSubsystems(runs);
    nominal = evaluate(nullptr, data, available, ReplayOptions{});
  }

  /// `effect`'s objective on the whole log, as fitCandidate builds it (the nominal replays' sigma1).
  /// Returned as a prvalue: the objective holds a mutex and cannot move.
  CandidateObjective objective(const CandidateEffect& effect, const ReplayOptions& replay = ReplayOptions{}) const {
    return CandidateObjective(effect, config, data, replay, nominal.sigma1, available);
  }
};

/// The logged bounds as stabilityRequirements sets them (1.5 times the steering range + 0.02 rad, twice
/// the torque range + 5 N m) on the fixture's first run, over its first `horizon` seconds.
inline BoundedLoopRequirement loggedBoundsOverFirstSeconds(const BenchmarkObjectiveFixture& f, double horizon) {
  const LogSignals& log = *f.runs[0].log;
  double angle = 0.0, torque = 0.0;
  for (double v : log.samples(LogSignals::kDelta)) angle = std::max(angle, std::fabs(v));
  for (double v : log.samples(LogSignals::kTorque)) torque = std::max(torque, std::fabs(v));
  return {&log, f.runs[0].config.get(), horizon, 1.5 * angle + 0.02, 2.0 * torque + 5.0};
}

/// The candidate `name` in its form `form` (empty: its first form).
inline const CandidateEffect& candidateNamed(const std::string& name, const std::string& form = "") {
  for (const auto& e : candidateEffects()) {
    if (e.name == name && (form.empty() || e.form == form)) return e;
  }
  throw std::runtime_error("no candidate " + name + (form.empty() ? "" : " (" + form + ")"));
}

/// The column (steering_compliance) on the candidates' small lane change, 8 s at 100 Hz: the bounded
/// refit's case. With little damping the linear column's closed loop leaves the logged bounds, `required`,
/// over the log's first `horizon` seconds (the whole log if `horizon` is 0).
struct ColumnLaneChangeFixture : BenchmarkObjectiveFixture {
  const CandidateEffect& column = candidateNamed("steering_compliance");
  const BoundedLoopRequirement required;

  explicit ColumnLaneChangeFixture(double horizon)
      : BenchmarkObjectiveFixture("steering_compliance-small-lane_change", 8.0, 100.0, 0.6),
        required(loggedBoundsOverFirstSeconds(
            *this, horizon > 0.0 ? horizon : runs[0].log->end() - runs[0].log->start())) {}
};

}  // namespace diagnosis
}  // namespace lane_keeping
