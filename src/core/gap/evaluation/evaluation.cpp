#include "lane_keeping/gap/evaluation/evaluation.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/sensor_correction.h"

namespace lane_keeping {
namespace diagnosis {

Evaluation evaluate(const ConfigChange& change, const std::vector<Dataset>& data, const std::set<std::string>& subsystems,
                    const ReplayOptions& options, const Sigma1Cache* sigma1) {
  Evaluation ev;
  const bool chassis = subsystems.count("chassis") > 0;
  const bool steering = subsystems.count("steering") > 0;
  for (std::size_t d = 0; d < data.size(); ++d) {
    const Dataset& set = data[d];
    const SimConfig config = changed(*set.config, change);
    // The physics replays compare with the true motion, the controllers' with what their sensors told
    // them: the log as it is (log/sensor_correction.h).
    const std::shared_ptr<const LogSignals> truth =
        chassis || steering ? correctedForSensors(set.log, config.sensors) : set.log;
    std::vector<std::pair<double, double>> s1;
    if (chassis || (steering && sigma1 == nullptr)) {
      SubsystemReplay r = replayChassis(config, *truth, set.segments, options);
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
      SubsystemReplay r = name == std::string("steering") ? replaySteering(config, *truth, set.segments, options, &s1)
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

Evaluation concatenated(Evaluation first, const Evaluation& second) {
  // As evaluate() appends each data set's replay to the traces so far (ReplayTrace::append keeps the
  // breaks; each trace keeps its first data set's scale, and the chassis its first sigma1 estimate).
  for (const auto& [name, replay] : second.replays) {
    const auto it = first.replays.find(name);
    if (it == first.replays.end()) {
      first.replays[name] = replay;
      first.starts[name] = second.starts.at(name);
      continue;
    }
    const std::size_t offset = it->second.traces.empty() ? 0 : it->second.traces[0].t.size();
    for (std::size_t start : second.starts.at(name)) first.starts[name].push_back(offset + start);
    for (std::size_t k = 0; k < it->second.traces.size() && k < replay.traces.size(); ++k) {
      it->second.traces[k].append(replay.traces[k]);
    }
    it->second.diverged_intervals += replay.diverged_intervals;
  }
  first.sigma1.insert(first.sigma1.end(), second.sigma1.begin(), second.sigma1.end());
  first.scores.clear();
  for (const auto& [name, replay] : first.replays) first.scores[name] = scoreReplay(replay);
  return first;
}

Evaluation overlaid(Evaluation base, const Evaluation& changed) {
  for (const auto& [name, replay] : changed.replays) {
    base.replays[name] = replay;
    const auto starts = changed.starts.find(name);
    if (starts != changed.starts.end()) base.starts[name] = starts->second;
    const auto score = changed.scores.find(name);
    if (score != changed.scores.end()) base.scores[name] = score->second;
  }
  if (changed.replays.count("chassis")) base.sigma1 = changed.sigma1;
  return base;
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

std::map<std::string, ResidualStructure> residualStructures(const Evaluation& ev, const std::vector<Dataset>& data) {
  std::map<std::string, ResidualStructure> out;
  for (const auto& [name, replay] : ev.replays) {
    if (replay.traces.empty()) continue;
    const auto starts_it = ev.starts.find(name);
    const std::vector<std::size_t>& starts = starts_it->second;
    const std::vector<double>& times = replay.traces[0].t;
    std::vector<double> input(times.size());
    std::size_t d = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
      while (d + 1 < starts.size() && i >= starts[d + 1]) ++d;
      const LogSignals& log = *data[d].log;
      const double t = times[i];
      if (name == "steering") input[i] = log.at(LogSignals::kTorque, t);
      else if (name == "chassis") input[i] = log.at(LogSignals::kDelta, t);
      else if (name == "tracker") input[i] = log.at(LogSignals::kY, t - data[d].config->delays.pose_to_tracker);
      else input[i] = log.at(LogSignals::kDeltaDes, t) - log.at(LogSignals::kDelta, t);
    }
    out[name] = residualStructure(replay, input);
  }
  return out;
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
