#include "lane_keeping/gap/evaluation.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/gap/noise_reference.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// The noise-only reference of each data set (same segments, noise drawn from `seed`), or empty with
/// a note if the nominal closed loop cannot cover a log.
std::vector<Dataset> noiseReferenceData(const std::vector<Dataset>& data, unsigned seed, std::vector<std::string>* notes) {
  std::vector<Dataset> out;
  for (const Dataset& set : data) {
    try {
      out.push_back({std::make_shared<LogSignals>(noiseReferenceLog(*set.config, *set.log, seed++)), set.config,
                     set.segments});
    } catch (const LaneKeepingError& e) {
      notes->push_back(std::string(e.what()) + "; the gap is not corrected for noise propagation");
      return {};
    }
  }
  return out;
}

}  // namespace

Evaluation evaluate(const ConfigChange& change, const std::vector<Dataset>& data, const std::set<std::string>& subsystems,
                    const ReplayOptions& options, const Sigma1Cache* sigma1) {
  Evaluation ev;
  const bool chassis = subsystems.count("chassis") > 0;
  const bool steering = subsystems.count("steering") > 0;
  for (std::size_t d = 0; d < data.size(); ++d) {
    const Dataset& set = data[d];
    const SimConfig config = changed(*set.config, change);
    std::vector<std::pair<double, double>> s1;
    if (chassis || (steering && sigma1 == nullptr)) {
      SubsystemReplay r = replayChassis(config, *set.log, set.segments, options);
      s1 = r.sigma1_estimate;
      if (chassis) {
        auto it = ev.replays.find("chassis");
        ev.starts["chassis"].push_back(it == ev.replays.end() || it->second.traces.empty() ? 0 : it->second.traces[0].t.size());
        if (it == ev.replays.end()) {
          ev.replays["chassis"] = std::move(r);
        } else {
          for (std::size_t k = 0; k < it->second.traces.size(); ++k) it->second.traces[k].append(r.traces[k]);
          it->second.diverged_intervals += r.diverged_intervals;
        }
      }
    } else if (sigma1 != nullptr) {
      s1 = (*sigma1)[d];
    }
    ev.sigma1.push_back(s1);
    for (const std::string name : {"steering", "tracker", "actuator"}) {
      if (!subsystems.count(name)) continue;
      SubsystemReplay r = name == std::string("steering") ? replaySteering(config, *set.log, set.segments, options, &s1)
                                                          : replaySubsystem(name, config, *set.log, set.segments, options);
      auto it = ev.replays.find(name);
      ev.starts[name].push_back(it == ev.replays.end() || it->second.traces.empty() ? 0 : it->second.traces[0].t.size());
      if (it == ev.replays.end()) {
        ev.replays[name] = std::move(r);
      } else {
        for (std::size_t k = 0; k < it->second.traces.size(); ++k) it->second.traces[k].append(r.traces[k]);
        it->second.diverged_intervals += r.diverged_intervals;
      }
    }
  }
  for (const auto& [name, replay] : ev.replays) ev.scores[name] = scoreReplay(replay);
  return ev;
}

std::set<std::string> allSubsystems() {
  const auto& names = subsystemNames();
  return std::set<std::string>(names.begin(), names.end());
}

double gapOf(const std::map<std::string, SubsystemScore>& nominal, const std::map<std::string, SubsystemScore>& changed) {
  std::vector<SubsystemScore> scores;
  for (const auto& [name, score] : nominal) {
    const auto it = changed.find(name);
    scores.push_back(it != changed.end() ? it->second : score);
    scores.back().reference = score.reference;
  }
  return combinedGap(scores);
}

std::map<std::string, double> noiseReferenceExcess(const std::vector<Dataset>& data,
                                                   const ReplayOptions& options, int realisations, int threads,
                                                   std::vector<std::string>* notes) {
  std::vector<std::map<std::string, SubsystemScore>> scores(realisations);
  std::vector<bool> ok(realisations, false);
  std::vector<std::vector<std::string>> draw_notes(realisations);
  parallelFor(static_cast<std::size_t>(realisations), threads, [&](std::size_t k) {
    const std::vector<Dataset> reference = noiseReferenceData(data, 9001u + 1000u * static_cast<unsigned>(k), &draw_notes[k]);
    if (reference.empty()) return;
    scores[k] = evaluate(nullptr, reference, allSubsystems(), options).scores;
    ok[k] = true;
  });
  std::map<std::string, double> largest;
  int used = 0;
  for (int k = 0; k < realisations; ++k) {
    if (!ok[k]) continue;
    ++used;
    for (const auto& [name, score] : scores[k]) largest[name] = std::max(largest[name], score.excess);
  }
  if (used == 0) {
    if (!draw_notes.empty() && !draw_notes[0].empty()) notes->push_back(draw_notes[0].front());
    return {};
  }
  return largest;
}

void setReference(std::map<std::string, SubsystemScore>& scores, const std::map<std::string, double>& reference) {
  for (auto& [name, score] : scores) {
    const auto it = reference.find(name);
    score.reference = it == reference.end() ? 0.0 : it->second;
  }
}

std::vector<double> fitResiduals(const Evaluation& ev) {
  std::vector<double> out;
  for (const auto& [name, replay] : ev.replays) {
    for (const auto& trace : replay.traces) {
      const std::vector<double> r = trace.residual();
      const double w = r.empty() ? 0.0 : 1.0 / std::sqrt(static_cast<double>(r.size()));
      for (double v : r) out.push_back(std::isfinite(v) ? v * w : 1e3 * w);
    }
  }
  return out;
}

double sumOfSquares(const std::vector<double>& r) {
  double s = 0.0;
  for (double v : r) s += v * v;
  return s;
}

double evidenceOf(const std::map<std::string, SubsystemScore>& before, const std::map<std::string, SubsystemScore>& after) {
  double evidence = 0.0;
  for (const auto& [name, cand] : after) {
    const auto it = before.find(name);
    if (it == before.end()) continue;
    for (std::size_t k = 0; k < cand.traces.size() && k < it->second.traces.size(); ++k) {
      const TraceScore& b = it->second.traces[k];
      const TraceScore& a = cand.traces[k];
      const double f2 = std::max(b.floor * b.floor, 1e-12);
      evidence += static_cast<double>(b.samples) * (b.nrmse * b.nrmse - a.nrmse * a.nrmse) / f2;
    }
  }
  return evidence;
}

}  // namespace diagnosis
}  // namespace lane_keeping
