#include "lane_keeping/gap/decision/noise_null.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <tuple>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/evaluation/input_driven_reference.h"
#include "lane_keeping/gap/evaluation/loop_ringing.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

/// Each run's noise-free nominal closed loop (nominalReferenceLog), or why it cannot be simulated. The
/// draws differ in their noise only: the loop was simulated again for each of them, 19 closed loops of
/// the log's span at the plant's 0.1 ms step where one does (~75 % of a 60 s log's `where` stage).
struct NominalReference {
  GapLog log;
  SensorNoise noise;  ///< the log's noise (estimatedNoise), its nominal motion taken out by this reference
  std::string error;  ///< set when the nominal closed loop diverges before the log's end
  std::vector<LoopRinging> ringing;  ///< the log's steering-loop ringing the reference lacks (loop_ringing.h)
};
using NominalReferences = std::map<const LogSignals*, NominalReference>;

/// The nominal references of every distinct log of the data sets, on up to `threads` threads: the
/// nominal closed loop, or where the logs feed the chassis replay alone (a real car's log without the
/// controllers' signals, a vehicle bus's), the nominal chassis driven by each log's own steering
/// (input_driven_reference.h).
NominalReferences nominalReferences(const std::vector<Dataset>& train, const std::vector<Dataset>& held, int threads,
                                    bool input_driven) {
  std::vector<const Dataset*> distinct;
  NominalReferences out;
  for (const auto* sets : {&held, &train}) {
    for (const Dataset& set : *sets) {
      if (out.emplace(set.log.get(), NominalReference{}).second) distinct.push_back(&set);
    }
  }
  parallelFor(distinct.size(), threads, [&](std::size_t k) {
    NominalReference& r = out.at(distinct[k]->log.get());  // the map's nodes are not moved: one per thread
    try {
      const LogSignals& log = *distinct[k]->log;
      r.log = input_driven ? inputDrivenReferenceLog(*distinct[k]->config, log)
                           : nominalReferenceLog(*distinct[k]->config, log);
      // The input-driven reference's steering, torque and speed are the log's own (smoothed or copied):
      // only what its chassis simulates tells the log's motion from its noise.
      GapLog simulated;
      simulated.t = r.log.t;
      for (const char* column : {"x", "y", "psi", "yaw_rate", "ay"}) *simulated.column(column) = *r.log.column(column);
      r.noise = estimatedNoise(log, input_driven ? &simulated : &r.log);
      // (The input-driven reference's steering and torque are the log's own: nothing to compare.)
      if (!input_driven) {
        for (auto [channel, column] : {std::pair<LogSignals::Channel, const char*>{LogSignals::kTorque, "torque"},
                                       {LogSignals::kDelta, "delta"}}) {
          if (const auto ringing = loopRinging(log, r.log, channel, column)) {
            r.ringing.push_back(*ringing);
          }
        }
      }
    } catch (const LaneKeepingError& e) {
      r.error = e.what();
    }
  });
  return out;
}

/// One draw: each run's noise-only reference (its nominal reference with noise drawn from `seed` and the
/// run's rank), on the data sets' segments.
using Draw = NoiseDraw;

/// The seed of draw k.
unsigned drawSeed(std::size_t k) { return 9001u + 1000u * static_cast<unsigned>(k); }

Draw referenceDraw(const std::vector<Dataset>& train, const std::vector<Dataset>& held,
                   const NominalReferences& nominal, unsigned seed) {
  Draw draw;
  std::map<const LogSignals*, std::shared_ptr<const LogSignals>> reference;
  auto referenceOf = [&](const Dataset& set) {
    auto it = reference.find(set.log.get());
    if (it != reference.end()) return it->second;
    const unsigned run_seed = seed + static_cast<unsigned>(reference.size());
    const NominalReference& loop = nominal.at(set.log.get());
    if (!loop.error.empty()) throw LaneKeepingError(loop.error);
    GapLog noisy = loop.log;
    addSensorNoise(noisy, loop.noise, run_seed);
    auto log = std::make_shared<const LogSignals>(std::move(noisy));
    reference[set.log.get()] = log;
    return std::shared_ptr<const LogSignals>(log);
  };
  try {
    for (const Dataset& set : held) draw.held.push_back({referenceOf(set), set.config, set.segments});
    for (const Dataset& set : train) draw.train.push_back({referenceOf(set), set.config, set.segments});
  } catch (const LaneKeepingError& e) {
    draw.note = std::string(e.what()) + "; the gap is not corrected for noise propagation";
    return draw;
  }
  draw.ok = true;
  return draw;
}

}  // namespace

std::map<std::string, double> NoiseNull::largestHeldExcess() const {
  std::map<std::string, double> largest;
  for (const auto& draw : held) {
    for (const auto& [name, score] : draw) largest[name] = std::max(largest[name], score.excess);
  }
  return largest;
}

std::vector<double> NoiseNull::heldTotals() const {
  std::vector<double> out;
  for (const auto& draw : held) out.push_back(totalExcessSquared(draw));
  return out;
}

std::vector<double> NoiseNull::trainTotals() const {
  std::vector<double> out;
  for (const auto& draw : train) out.push_back(totalExcessSquared(draw));
  return out;
}

NoiseNull noiseNull(const std::vector<Dataset>& train, const std::vector<Dataset>& held,
                    const std::set<std::string>& subsystems, const ReplayOptions& options, int draws, int threads) {
  struct Result {
    bool ok = false;
    std::map<std::string, SubsystemScore> train, held;
    std::map<std::string, ResidualStructure> structure;
    std::string note;
  };
  std::vector<Result> results(static_cast<std::size_t>(std::max(0, draws)));
  const bool input_driven = subsystems.size() == 1 && subsystems.count("chassis") == 1;
  const auto references = std::make_shared<const NominalReferences>(
      results.empty() ? NominalReferences{} : nominalReferences(train, held, threads, input_driven));
  const NominalReferences& nominal = *references;
  parallelFor(results.size(), threads, [&](std::size_t k) {
    const Draw draw = referenceDraw(train, held, nominal, drawSeed(k));
    Result& r = results[k];
    if (!draw.ok) {
      r.note = draw.note;
      return;
    }
    const Evaluation held_ev = evaluate(nullptr, draw.held, subsystems, options);
    r.held = held_ev.scores;
    r.structure = residualStructures(held_ev, draw.held);
    if (!draw.train.empty()) r.train = evaluate(nullptr, draw.train, subsystems, options).scores;
    r.ok = true;
  });
  NoiseNull null;
  if (!results.empty()) {
    null.redraw = [references, train, held](int k) {
      return referenceDraw(train, held, *references, drawSeed(static_cast<std::size_t>(k)));
    };
  }
  for (const Result& r : results) {
    if (!r.ok) {
      if (null.notes.empty()) null.notes.push_back(r.note);
      continue;
    }
    null.held.push_back(r.held);
    null.train.push_back(r.train);
    null.held_structure.push_back(r.structure);
  }
  // In the order of their sources and columns, whatever the order of the logs in memory.
  for (const auto& [log, reference] : nominal) {
    null.ringings.insert(null.ringings.end(), reference.ringing.begin(), reference.ringing.end());
  }
  std::sort(null.ringings.begin(), null.ringings.end(), [](const LoopRinging& a, const LoopRinging& b) {
    return std::tie(a.source, a.column) < std::tie(b.source, b.column);
  });
  for (const LoopRinging& r : null.ringings) null.notes.push_back(ringingNote(r.source, r));
  return null;
}

double totalExcessSquared(const std::map<std::string, SubsystemScore>& scores) {
  double sum = 0.0;
  for (const auto& [name, score] : scores) sum += score.excess * score.excess;
  return sum;
}

double monteCarloPValue(double value, const std::vector<double>& draws) {
  std::size_t at_least = 0;
  for (double d : draws) {
    if (d >= value) ++at_least;
  }
  return static_cast<double>(1 + at_least) / static_cast<double>(draws.size() + 1);
}

namespace {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double w = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] + w * (v[i + 1] - v[i]) : v[i];
}

/// T = `value` among `draws`; detected when significant and the net gap reaches detection_gap.
DetectionTest test(double value, double net_gap, const std::vector<double>& draws, const DiagnosisOptions& options) {
  DetectionTest out;
  out.value = value;
  out.p_value = monteCarloPValue(out.value, draws);
  out.null_median = quantile(draws, 0.5);
  out.null_max = draws.empty() ? 0.0 : *std::max_element(draws.begin(), draws.end());
  out.tested = !draws.empty();
  if (!out.tested) out.p_value = std::numeric_limits<double>::quiet_NaN();
  const bool significant = draws.empty() || out.p_value <= options.false_alarm_rate;
  out.detected = significant && net_gap >= options.detection_gap;
  return out;
}

DetectionTest test(const std::map<std::string, SubsystemScore>& scores, const std::vector<double>& draws,
                   const DiagnosisOptions& options) {
  return test(totalExcessSquared(scores), gapOf(scores, {}), draws, options);
}

}  // namespace

int minimumNoiseDraws(double false_alarm_rate) {
  if (!(false_alarm_rate > 0.0 && false_alarm_rate < 1.0)) {
    throw ConfigError("false_alarm_rate = " + std::to_string(false_alarm_rate) + " must be in (0, 1)");
  }
  // The small tolerance keeps 1 / 0.05 = 20.000000000000004 from asking for 20.
  return static_cast<int>(std::ceil(1.0 / false_alarm_rate - 1e-9)) - 1;
}

GapDetection detectGap(const std::map<std::string, SubsystemScore>& train, const std::map<std::string, SubsystemScore>& held,
                       const NoiseNull& null, const DiagnosisOptions& options) {
  GapDetection d;
  d.draws = null.draws();
  d.false_alarm_rate = options.false_alarm_rate;
  const std::vector<double> held_totals = null.heldTotals(), train_totals = null.trainTotals();
  d.heldout = test(held, held_totals, options);
  d.training = test(train, train_totals, options);
  // Both sides together: each draw's training and held-out totals summed, as the log's (the draws replay
  // both sides of one realisation, so the sums are exchangeable with the log's as each side's are).
  std::vector<double> pooled(std::min(held_totals.size(), train_totals.size()));
  for (std::size_t i = 0; i < pooled.size(); ++i) pooled[i] = train_totals[i] + held_totals[i];
  const double g_train = gapOf(train, {}), g_held = gapOf(held, {});
  d.pooled = test(d.training.value + d.heldout.value, std::sqrt(0.5 * (g_train * g_train + g_held * g_held)), pooled,
                  options);
  return d;
}

double heldSpread(const NoiseNull& null) {
  const std::vector<double> totals = null.heldTotals();
  if (totals.size() < 2) return 0.0;
  return quantile(totals, 0.95) - quantile(totals, 0.5);
}

}  // namespace diagnosis
}  // namespace lane_keeping
