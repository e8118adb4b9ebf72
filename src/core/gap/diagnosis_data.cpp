#include "lane_keeping/gap/diagnosis_data.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/log/logged_speed.h"
#include "lane_keeping/gap/replay/excitation_clock.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace diagnosis {

std::vector<RunData> prepareRuns(const std::vector<GapRun>& runs) {
  std::vector<RunData> out;
  for (const GapRun& run : runs) {
    std::vector<InputCheck> checks = inputChecks(run.log, run.config);
    refuseImplausibleLog(checks);
    std::shared_ptr<const LogSignals> log = std::make_shared<LogSignals>(run.log);
    // The replays need V of eq 1; a speed of G (lk_simulate's, a bus's) is converted with the run's geometry.
    if (holdsCentreOfGravitySpeed(run.log)) {
      log = std::make_shared<LogSignals>(withFrontAxleSpeed(*log, run.config.vehicle));
    }
    SimConfig config = run.config;
    if (run.initial_from_log) {
      // (sigma1 from the logged positions; a log without them starts at 0, the chassis replay estimating it)
      const double sigma1 = log->has(LogSignals::kSigma1) ? log->at(LogSignals::kSigma1, log->start()) : 0.0;
      config = withInitialStateFromLog(config, run.log, sigma1);
    }
    // The identification excitation on the clock the log's delta_des shows, not on the log's t by
    // assumption: a log whose t was shifted replayed it out of phase (excitation_clock.h).
    const ExcitationClock clock = estimateExcitationClock(config, *log);
    config.tracker.excitation_clock_offset += clock.offset;
    out.push_back({std::move(log), std::make_shared<const SimConfig>(std::move(config)),
                   clock.note.empty() ? "" : run.log.source + ": " + clock.note, std::move(checks)});
  }
  return out;
}

namespace {

/// Why an input check rules out the replay of `subsystem` on `run` ("" if none does): a rate check that
/// skips it, or a stuck channel it reads (the replay would be unavailable without that channel).
std::string ruledOutByChecks(const std::string& subsystem, const RunData& run) {
  for (const InputCheck& check : run.input_checks) {
    if (std::find(check.skip.begin(), check.skip.end(), subsystem) != check.skip.end()) return check.detail;
    if (!check.unusable) continue;
    GapLog without = run.log->log();
    if (std::vector<double>* column = without.column(check.channel)) column->clear();
    if (!replayUnavailable(subsystem, without).empty()) return check.detail;
  }
  return "";
}

}  // namespace

std::map<std::string, std::string> unavailableSubsystems(const std::vector<RunData>& runs) {
  std::map<std::string, std::string> out;
  for (const std::string& name : subsystemNames()) {
    for (const RunData& run : runs) {
      std::string why = replayUnavailable(name, run.log->log());
      if (why.empty()) why = ruledOutByChecks(name, run);
      if (why.empty()) continue;
      out[name] = run.log->log().source + ": " + why;
      break;
    }
  }
  return out;
}

std::set<std::string> availableSubsystems(const std::vector<RunData>& runs) {
  const auto unavailable = unavailableSubsystems(runs);
  std::set<std::string> out;
  for (const std::string& name : subsystemNames()) {
    if (!unavailable.count(name)) out.insert(name);
  }
  return out;
}

std::vector<Dataset> wholeLogs(const std::vector<RunData>& runs, double margin) {
  std::vector<Dataset> out;
  for (const auto& run : runs) {
    // (A margin of 0 stays 0: "how far" reads the lateral velocity at the log's first sample, where its
    // closed loops start.)
    const double skip = startsWithTransient(*run.log, *run.config) ? std::min(margin, kStartTransientLead) : margin;
    const double from = run.log->start() + skip;
    out.push_back({run.log, run.config, {{from, run.log->end() + 1e-9}}});
  }
  cutAtHoles(&out, margin);
  return out;
}

void cutAtHoles(std::vector<Dataset>* data, double margin) {
  std::vector<Dataset> kept;
  for (Dataset& set : *data) {
    const std::vector<TimeHole> holes = timeHoles(set.log->log());
    if (holes.empty()) {
      kept.push_back(std::move(set));
      continue;
    }
    std::vector<TimeSegment> pieces;
    for (const TimeSegment& segment : set.segments) {
      // A segment no hole touches stays whole, however short (a start transient's slivers).
      if (std::none_of(holes.begin(), holes.end(), [&](const TimeHole& hole) {
            return hole.t0 < segment.t1 && hole.t1 + margin > segment.t0;
          })) {
        pieces.push_back(segment);
        continue;
      }
      double from = segment.t0;
      for (const TimeHole& hole : holes) {
        if (hole.t0 >= segment.t1 || hole.t1 + margin <= from) continue;  // outside what is left of it
        if (hole.t0 - from >= kMinPieceBetweenHoles) pieces.push_back({from, hole.t0});
        from = std::max(from, hole.t1 + margin);
      }
      if (segment.t1 - from >= kMinPieceBetweenHoles) pieces.push_back({from, segment.t1});
    }
    set.segments = std::move(pieces);
    if (!set.segments.empty()) kept.push_back(std::move(set));
  }
  *data = std::move(kept);
}

std::vector<Dataset> decimatedData(const std::vector<Dataset>& data, double piece, std::size_t stride) {
  if (!(piece > 0.0) || stride == 0) throw std::invalid_argument("decimatedData: piece and stride must be positive");
  std::vector<Dataset> out;
  for (const Dataset& set : data) {
    Dataset coarse{set.log, set.config, {}};
    std::size_t index = 0;
    for (const TimeSegment& s : set.segments) {
      for (double a = s.t0; a < s.t1 - 1e-9; a += piece, ++index) {
        if (index % stride == 0) coarse.segments.push_back({a, std::min(a + piece, s.t1)});
      }
    }
    out.push_back(std::move(coarse));
  }
  return out;
}

std::size_t pieceCount(const std::vector<Dataset>& data, double piece) {
  std::size_t pieces = 0;
  for (const Dataset& set : decimatedData(data, piece, 1)) pieces += set.segments.size();  // its cut, not a copy of it
  return pieces;
}

std::vector<Dataset> coarseFitData(const std::vector<Dataset>& data, double piece, std::size_t min_stride) {
  if (!(piece > 0.0) || min_stride == 0) throw std::invalid_argument("coarseFitData: piece and stride must be positive");
  std::vector<Dataset> out;
  for (const Dataset& set : data) {
    const double pieces = static_cast<double>(pieceCount({set}, piece));
    const auto root = static_cast<std::size_t>(std::llround(std::sqrt(pieces)));
    out.push_back(decimatedData({set}, piece, std::max(min_stride, root)).front());
  }
  return out;
}

std::map<std::string, std::vector<double>> excitations(const LogSignals& log, const SimConfig& config) {
  // Each kind where the log has what it is made of (a partial log has fewer).
  std::map<std::string, std::vector<double>> out;
  const std::size_t n = log.times().size();
  auto magnitude = [&](const std::string& kind, const std::vector<double>& v, double centre) {
    auto& values = out[kind];
    values.reserve(n);
    for (double x : v) values.push_back(std::fabs(x - centre));
  };
  if (log.has(LogSignals::kDeltaRate)) magnitude("steering_rate", log.samples(LogSignals::kDeltaRate), 0.0);
  if (log.has(LogSignals::kTorque)) {
    std::vector<double> sorted = log.samples(LogSignals::kTorque);
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    magnitude("steering_torque", log.samples(LogSignals::kTorque), sorted[sorted.size() / 2]);
  }
  if (log.has(LogSignals::kLateralAcceleration)) {
    magnitude("lateral_acceleration", log.samples(LogSignals::kLateralAcceleration), 0.0);
  } else if (log.has(LogSignals::kYawRate)) {
    auto& values = out["lateral_acceleration"];
    for (double r : log.samples(LogSignals::kYawRate)) values.push_back(std::fabs(config.vehicle.speed * r));
  }
  if (log.has(LogSignals::kDeltaDes) && log.has(LogSignals::kDelta)) {
    auto& values = out["steering_error"];
    const auto& des = log.samples(LogSignals::kDeltaDes);
    const auto& delta = log.samples(LogSignals::kDelta);
    for (std::size_t i = 0; i < n; ++i) values.push_back(std::fabs(des[i] - delta[i]));
  }
  return out;
}

namespace {

/// Cumulative integral (trapezoid) of `values` over `times` from index `first`, normalised to end at 1
/// (a flat 0 when the integral is 0).
std::vector<double> normalisedCumulative(const std::vector<double>& times, const std::vector<double>& values,
                                         std::size_t first) {
  std::vector<double> c(times.size(), 0.0);
  for (std::size_t i = first + 1; i < times.size(); ++i) {
    c[i] = c[i - 1] + 0.5 * (values[i] + values[i - 1]) * (times[i] - times[i - 1]);
  }
  const double total = c.back();
  for (double& v : c) v = total > 0.0 ? v / total : 0.0;
  return c;
}

}  // namespace

bool startsWithTransient(const LogSignals& log, const SimConfig& config) {
  const auto& times = log.times();
  const double span = log.end() - log.start();
  if (times.size() < 3 || !(span > kStartTransientWindow)) return false;
  const auto kinds = excitations(log, config);
  if (kinds.empty()) return false;
  double share = 0.0;
  for (const auto& [name, values] : kinds) {
    const std::vector<double> c = normalisedCumulative(times, values, 0);
    const auto end = std::lower_bound(times.begin(), times.end(), log.start() + kStartTransientWindow);
    share += c[static_cast<std::size_t>(std::min<std::ptrdiff_t>(end - times.begin(), times.size() - 1))];
  }
  share /= static_cast<double>(kinds.size());
  return share >= kStartTransientShare && share >= kStartTransientRatio * kStartTransientWindow / span;
}

namespace {

/// Excitation-balanced block boundaries of one log from `t0` on (see DataSplit).
std::vector<double> balancedBoundaries(const LogSignals& log, const SimConfig& config, double t0,
                                       const DiagnosisOptions& options) {
  const auto& times = log.times();
  const double t_end = log.end() + 1e-9;
  std::size_t first = 0;
  while (first + 1 < times.size() && times[first] < t0) ++first;
  const double span = t_end - t0;
  const int blocks = std::max(2, static_cast<int>(std::lround(span / options.block_length)));
  const auto kinds = excitations(log, config);
  std::vector<double> activity(times.size(), 0.0);
  for (std::size_t i = first; i < times.size(); ++i) activity[i] = 0.5 * (times[i] - times[first]) / span;
  for (const auto& [name, values] : kinds) {
    // Smoothed over +-0.25 s: block boundaries must follow the manoeuvre, not the log's noise. Placed
    // by the noisy magnitudes, they correlated with the noise the held-out replays then see, and the
    // noise-only null (whose draws share the boundaries but not the noise) was too narrow: 3 of 16
    // no-effect lane changes at 500 Hz fell beyond every draw, against 1 with equal-time blocks.
    const std::vector<double> c = normalisedCumulative(times, smoothedDerivative(times, values, 0.25, 0), first);
    for (std::size_t i = first; i < times.size(); ++i) activity[i] += 0.5 * c[i] / static_cast<double>(kinds.size());
  }
  if (kinds.empty()) {  // nothing measured that excites: equal times
    for (std::size_t i = first; i < times.size(); ++i) activity[i] *= 2.0;
  }
  const double total = activity.back() > 0.0 ? activity.back() : 1.0;
  std::vector<double> bounds{t0};
  std::size_t i = first;
  for (int b = 1; b < blocks; ++b) {
    const double target = total * b / blocks;
    while (i + 1 < times.size() && activity[i] < target) ++i;
    // On a 0.1 s grid from the start, for the same reason.
    const double t = t0 + 0.1 * std::round((times[i] - t0) / 0.1);
    if (t - bounds.back() >= options.min_block_length && t_end - t >= options.min_block_length) bounds.push_back(t);
  }
  bounds.push_back(t_end);
  return bounds;
}

/// Held-out share of each excitation kind, over the data sets' segments.
std::map<std::string, double> heldCoverage(const std::vector<Dataset>& train, const std::vector<Dataset>& held) {
  std::map<std::string, double> train_sum, held_sum;
  auto add = [](const std::vector<Dataset>& sets, std::map<std::string, double>* sum) {
    for (const Dataset& set : sets) {
      const auto kinds = excitations(*set.log, *set.config);
      const auto& times = set.log->times();
      for (const auto& [name, values] : kinds) {
        double& s = (*sum)[name];
        for (std::size_t i = 1; i < times.size(); ++i) {
          for (const TimeSegment& seg : set.segments) {
            if (times[i] >= seg.t0 && times[i] < seg.t1) {
              s += 0.5 * (values[i] + values[i - 1]) * (times[i] - times[i - 1]);
              break;
            }
          }
        }
      }
    }
  };
  add(train, &train_sum);
  add(held, &held_sum);
  std::map<std::string, double> out;
  for (const auto& [name, h] : held_sum) {
    const double total = h + train_sum[name];
    out[name] = total > 0.0 ? h / total : 0.0;
  }
  return out;
}

}  // namespace

DataSplit splitData(const std::vector<RunData>& train_runs, const std::vector<RunData>& held_runs,
                    const DiagnosisOptions& options) {
  DataSplit split;
  if (!held_runs.empty()) {
    split.method = "held-out runs";
    split.train = wholeLogs(train_runs, options.start_margin);
    split.held = wholeLogs(held_runs, options.start_margin);
  } else if (train_runs.size() >= 2) {
    split.method = "whole runs";
    std::vector<std::size_t> order(train_runs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    auto length = [&](std::size_t i) { return train_runs[i].log->end() - train_runs[i].log->start(); };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return length(a) > length(b); });
    std::vector<RunData> train, held;
    for (std::size_t k = 0; k < order.size(); ++k) (k % 2 == 0 ? train : held).push_back(train_runs[order[k]]);
    split.train = wholeLogs(train, options.start_margin);
    split.held = wholeLogs(held, options.start_margin);
    for (const RunData& run : held) split.held_blocks.push_back(run.log->log().source + " (whole run)");
    for (const RunData& run : train) split.train_blocks.push_back(run.log->log().source + " (whole run)");
  } else {
    split.method = "excitation-balanced blocks";
    for (const auto& run : train_runs) {
      const auto& log = run.log;
      Dataset tr{log, run.config, {}}, ho{log, run.config, {}};
      // A start transient in alternating slivers, then the blocks from its end (startsWithTransient).
      const bool transient = startsWithTransient(*log, *run.config);
      std::vector<double> slivers;
      if (transient) {
        slivers.push_back(log->start() + kStartTransientLead);
        const int n = static_cast<int>(std::lround(kStartTransientWindow / kStartSliver));
        for (int k = 1; k < n; ++k) {
          if (k * kStartSliver > kStartTransientLead) slivers.push_back(log->start() + k * kStartSliver);
        }
      }
      const double blocks_from = log->start() + (transient ? kStartTransientWindow : options.start_margin);
      std::vector<double> bounds = slivers;
      for (double b : balancedBoundaries(*log, *run.config, blocks_from, options)) bounds.push_back(b);
      for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
        (b % 2 == 0 ? tr : ho).segments.push_back({bounds[b], bounds[b + 1]});
      }
      split.train.push_back(tr);
      if (!ho.segments.empty()) split.held.push_back(ho);
      double shortest = bounds.back() - bounds.front(), longest = 0.0;
      for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
        shortest = std::min(shortest, bounds[b + 1] - bounds[b]);
        longest = std::max(longest, bounds[b + 1] - bounds[b]);
      }
      auto tenths = [](double s) { return formatNumber(std::round(10.0 * s) / 10.0); };
      const std::string blocks = " of " + std::to_string(bounds.size() - 1) + " blocks balanced in excitation, " +
                                 tenths(shortest) + "-" + tenths(longest) + " s" +
                                 (transient ? "; " + formatNumber(kStartTransientLead) + "-" + tenths(kStartTransientWindow) +
                                                  " s, a start transient, in slivers of " + formatNumber(kStartSliver) + " s"
                                            : std::string()) +
                                 ")";
      split.held_blocks.push_back(log->log().source + " (the odd ones" + blocks);
      split.train_blocks.push_back(log->log().source + " (the even ones" + blocks);
    }
    cutAtHoles(&split.train, options.start_margin);
    cutAtHoles(&split.held, options.start_margin);
    if (split.held.empty() || split.train.empty()) {
      throw InputError("gap diagnosis: the log is too short to hold out a block of " +
                       formatNumber(options.min_block_length) + " s");
    }
  }
  if (options.fold == 1 && held_runs.empty()) {
    // The second fold (fold_pooling.h): every side held out once. Given held-out runs, the caller swaps them.
    std::swap(split.train, split.held);
    split.method += ", second fold (training and held-out sides swapped)";
    std::swap(split.train_blocks, split.held_blocks);
  }
  split.coverage = heldCoverage(split.train, split.held);
  return split;
}

}  // namespace diagnosis
}  // namespace lane_keeping
