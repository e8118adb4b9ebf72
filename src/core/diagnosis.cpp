#include "lane_keeping/gap/diagnosis.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>

#include <ceres/ceres.h>
#include <unsupported/Eigen/FFT>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/candidate_effects.h"
#include "lane_keeping/gap/closed_loop_replay.h"
#include "lane_keeping/gap/gap_metrics.h"
#include "lane_keeping/gap/log_signals.h"
#include "lane_keeping/gap/noise_reference.h"
#include "lane_keeping/gap/winner_selection.h"

namespace lane_keeping {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ================================================================================================
// Data sets and evaluation
// ================================================================================================

struct Dataset {
  std::shared_ptr<const LogSignals> log;
  std::vector<TimeSegment> segments;
};

/// Replays of a configuration over data sets, traces concatenated across them.
struct Evaluation {
  std::map<std::string, SubsystemReplay> replays;
  std::map<std::string, SubsystemScore> scores;
  std::vector<std::vector<std::pair<double, double>>> sigma1;  ///< chassis estimate per data set
};

using Sigma1Cache = std::vector<std::vector<std::pair<double, double>>>;

/// Replays `subsystems` of `config` over the data sets. The steering replay takes sigma1 from this
/// configuration's chassis replay, or from `sigma1` when the chassis is not re-run.
Evaluation evaluate(const SimConfig& config, const std::vector<Dataset>& data, const std::set<std::string>& subsystems,
                    const ReplayOptions& options, const Sigma1Cache* sigma1 = nullptr) {
  Evaluation ev;
  const bool chassis = subsystems.count("chassis") > 0;
  const bool steering = subsystems.count("steering") > 0;
  for (std::size_t d = 0; d < data.size(); ++d) {
    const Dataset& set = data[d];
    std::vector<std::pair<double, double>> s1;
    if (chassis || (steering && sigma1 == nullptr)) {
      SubsystemReplay r = replayChassis(config, *set.log, set.segments, options);
      s1 = r.sigma1_estimate;
      if (chassis) {
        auto it = ev.replays.find("chassis");
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

/// Combined gap with `changed` scores replacing the nominal ones where present (each keeps the
/// nominal score's noise reference: it belongs to the data, not to the model).
double gapOf(const std::map<std::string, SubsystemScore>& nominal, const std::map<std::string, SubsystemScore>& changed) {
  std::vector<SubsystemScore> scores;
  for (const auto& [name, score] : nominal) {
    const auto it = changed.find(name);
    scores.push_back(it != changed.end() ? it->second : score);
    scores.back().reference = score.reference;
  }
  return combinedGap(scores);
}

/// Runs body(0) .. body(count - 1) on up to `threads` threads (each index once, in any order);
/// `announce(i)`, if given, runs under a lock just before body(i) (progress messages).
void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body,
                 const std::function<void(std::size_t)>& announce = nullptr) {
  std::mutex mutex;
  std::size_t next = 0;
  auto worker = [&]() {
    while (true) {
      std::size_t index;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (next >= count) return;
        index = next++;
        if (announce) announce(index);
      }
      body(index);
    }
  };
  std::vector<std::thread> pool;
  const std::size_t n = std::max<std::size_t>(1, std::min<std::size_t>(static_cast<std::size_t>(std::max(1, threads)), count));
  for (std::size_t i = 0; i < n; ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
}

/// The noise-only reference of each data set (same segments, noise drawn from `seed`), or empty with
/// a note if the nominal closed loop cannot cover a log.
std::vector<Dataset> noiseReferenceData(const SimConfig& nominal, const std::vector<Dataset>& data, unsigned seed,
                                        std::vector<std::string>* notes) {
  std::vector<Dataset> out;
  for (const Dataset& set : data) {
    try {
      out.push_back({std::make_shared<LogSignals>(noiseReferenceLog(nominal, *set.log, seed++)), set.segments});
    } catch (const LaneKeepingError& e) {
      notes->push_back(std::string(e.what()) + "; the gap is not corrected for noise propagation");
      return {};
    }
  }
  return out;
}

/// Reference excess per subsystem: the largest excess of `realisations` noise draws. Near the noise
/// floor a trace's excess is clipped at zero or not depending on the draw, so the noise-only excess is
/// 0 or a few thousandths (the benchmark's sinusoid references draw chassis 0, 0, 0.0032; its 12
/// no-effect logs show chassis 0-0.003, steering 0.0011-0.0022). Subtracting the draws' RMS (as
/// before) left the excess of every draw above it as "gap" that no model can remove: the truth model
/// itself - the best any candidate could be - then removed only 56-89 % of the held-out gap on 7 of the
/// benchmark's 44 in-list logs where noise, not a replay limit, held it back (lk_gap_benchmark's
/// ceiling); with the largest draw two remain (61 and 83 %), the truth's median is 99.8 %, and the 12
/// no-effect logs' gap falls from 0-0.0029 to 0-0.0022.
std::map<std::string, double> noiseReferenceExcess(const SimConfig& nominal, const std::vector<Dataset>& data,
                                                   const ReplayOptions& options, int realisations, int threads,
                                                   std::vector<std::string>* notes) {
  std::vector<std::map<std::string, SubsystemScore>> scores(realisations);
  std::vector<bool> ok(realisations, false);
  std::vector<std::vector<std::string>> draw_notes(realisations);
  parallelFor(static_cast<std::size_t>(realisations), threads, [&](std::size_t k) {
    const std::vector<Dataset> reference =
        noiseReferenceData(nominal, data, 9001u + 1000u * static_cast<unsigned>(k), &draw_notes[k]);
    if (reference.empty()) return;
    scores[k] = evaluate(nominal, reference, allSubsystems(), options).scores;
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

/// Stores the reference excess of each subsystem in `scores`.
void setReference(std::map<std::string, SubsystemScore>& scores, const std::map<std::string, double>& reference) {
  for (auto& [name, score] : scores) {
    const auto it = reference.find(name);
    score.reference = it == reference.end() ? 0.0 : it->second;
  }
}

/// Residual vector for the fit: each trace's residuals / sqrt(its sample count), so that the
/// objective is the sum over traces of mean squares (the sum of nrmse^2).
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

// ================================================================================================
// Candidate fitting
// ================================================================================================

/// The closed loop of a fit must stay bounded on `log` over `horizon` seconds from its start, its
/// steering angle within `max_steering_angle` and its torque command within `max_torque`.
struct BoundedLoopRequirement {
  const LogSignals* log;
  double horizon;
  double max_steering_angle;
  double max_torque;
};

struct CandidateFit {
  const CandidateEffect* effect = nullptr;
  bool ok = false;
  std::string note;
  std::vector<double> theta, sigma;
  bool at_bound = false;  ///< a fitted parameter is pinned at a bound of its range
  std::string stability_note;  ///< set when the least-squares fit's closed loop leaves the logged bounds
  /// Logs on which the fit's closed loop leaves the bounds (empty: it stays bounded, also after a
  /// bounded refit that succeeded).
  std::vector<BoundedLoopRequirement> unbounded_on;
  SimConfig corrected;
  double train_before = 0.0, train_after = 0.0;
  double heldout_before = 0.0, heldout_after = 0.0;
  double evidence = 0.0;  ///< held-out reduction of the noise-normalised squared residual (see evidenceOf)
  std::map<std::string, SubsystemScore> heldout_scores;
};

/// Held-out evidence for a candidate: the reduction of sum_traces N (nrmse^2) / floor^2 that it brings,
/// with the nominal floors — a chi-square-like count of how many noise variances of mismatch it
/// removes. Noise fitted on training data does not carry over to held-out data, so this stays near
/// (or below) zero for a candidate that explains nothing.
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

/// Whether the closed loop of `config` leaves requirement `r`'s bounds on its log: the divergence
/// monitor with its steering-angle limit lowered to r.max_steering_angle, and the torque command.
LoopDivergence boundsCheck(SimConfig config, const BoundedLoopRequirement& r) {
  double& limit = config.simulation.divergence.max_steering_angle;
  limit = std::min(limit, r.max_steering_angle);
  return closedLoopDivergence(config, *r.log, kNaN, r.horizon, r.max_torque);
}

/// The loss of one candidate as a function of its (transformed) parameters.
class CandidateObjective {
 public:
  CandidateObjective(const CandidateEffect& effect, const SimConfig& nominal, const std::vector<Dataset>& data,
                     const ReplayOptions& options, const Sigma1Cache& nominal_sigma1)
      : effect_(effect), nominal_(nominal), data_(data), options_(options), nominal_sigma1_(nominal_sigma1) {
    subsystems_ = std::set<std::string>(effect.subsystems.begin(), effect.subsystems.end());
  }

  /// Parameters from fit space (log for log-scale ones) to SI.
  std::vector<double> toTheta(const double* x) const {
    std::vector<double> theta(effect_.params.size());
    for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = effect_.params[i].log_scale ? std::exp(x[i]) : x[i];
    return theta;
  }
  std::vector<double> toFitSpace(const std::vector<double>& theta) const {
    std::vector<double> x(theta.size());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = effect_.params[i].log_scale ? std::log(theta[i]) : theta[i];
    return x;
  }

  SimConfig configFor(const std::vector<double>& theta) const {
    SimConfig c = nominal_;
    effect_.apply(theta, c);
    return c;
  }

  /// Residual vector for parameters theta (SI); false if the configuration is invalid, or if it makes
  /// the closed loop diverge on a log where stability is required.
  bool residuals(const std::vector<double>& theta, std::vector<double>* out) const {
    const SimConfig c = configFor(theta);
    if (!c.problems().empty() || divergence(c) > 0.0) return false;
    replayResiduals(c, out);
    return true;
  }

  /// Sum of squared residuals. Under a stability requirement a point whose closed loop diverges ranks
  /// after every bounded one, and the later it diverges the better — so that a coordinate search
  /// started in the unstable region finds its way out.
  double loss(const std::vector<double>& theta) const {
    const SimConfig c = configFor(theta);
    if (!c.problems().empty()) return std::numeric_limits<double>::infinity();
    if (const double d = divergence(c); d > 0.0) return kUnstableLoss * (1.0 + d);
    std::vector<double> r;
    replayResiduals(c, &r);
    return sumOfSquares(r);
  }

  const std::set<std::string>& subsystems() const { return subsystems_; }
  const CandidateEffect& effect() const { return effect_; }

  /// The closed loop must stay bounded on these logs over these horizons, its steering angle within
  /// `max_steering_angle` and its torque command within `max_torque`.
  void requireStability(std::vector<BoundedLoopRequirement> requirements) { stable_on_ = std::move(requirements); }

 private:
  static constexpr double kUnstableLoss = 1e100;

  void replayResiduals(const SimConfig& c, std::vector<double>* out) const {
    const bool reuse = subsystems_.count("chassis") == 0;
    *out = fitResiduals(evaluate(c, data_, subsystems_, options_, reuse ? &nominal_sigma1_ : nullptr));
  }

  /// 0 if the closed loop of `c` stays bounded on every required log, else 1 - (time it took to
  /// diverge) / horizon, in (0, 1].
  double divergence(const SimConfig& c) const {
    for (const BoundedLoopRequirement& s : stable_on_) {
      const LoopDivergence d = boundsCheck(c, s);
      if (d.diverged) return std::clamp(1.0 - d.time / s.horizon, 1e-6, 1.0);
    }
    return 0.0;
  }

  std::vector<BoundedLoopRequirement> stable_on_;
  const CandidateEffect& effect_;
  const SimConfig& nominal_;
  const std::vector<Dataset>& data_;
  ReplayOptions options_;
  const Sigma1Cache& nominal_sigma1_;
  std::set<std::string> subsystems_;
};

/// Ceres functor over the transformed parameters.
struct CeresResiduals {
  const CandidateObjective* objective;
  std::size_t count;
  bool operator()(double const* const* parameters, double* residuals) const {
    std::vector<double> r;
    if (!objective->residuals(objective->toTheta(parameters[0]), &r) || r.size() != count) return false;
    std::copy(r.begin(), r.end(), residuals);
    return true;
  }
};

/// Minimises the loss over parameter j with the others fixed: a grid over [lo, hi] (log-spaced for
/// log-scale parameters), then golden section in the bracket around the best grid point.
double lineSearch(const CandidateObjective& objective, std::vector<double>& theta, std::size_t j, double lo, double hi,
                  int points, double current_loss) {
  const EffectParameter& p = objective.effect().params[j];
  auto lossAt = [&](double value) {
    std::vector<double> t = theta;
    t[j] = value;
    return objective.loss(t);
  };
  auto toAxis = [&](double v) { return p.log_scale ? std::log(v) : v; };
  auto fromAxis = [&](double u) { return p.log_scale ? std::exp(u) : u; };
  const double ua = toAxis(lo), ub = toAxis(hi);
  std::vector<double> grid, losses;
  for (int i = 0; i < points; ++i) {
    grid.push_back(ua + (ub - ua) * i / (points - 1));
    losses.push_back(lossAt(fromAxis(grid.back())));
  }
  const std::size_t best = static_cast<std::size_t>(std::min_element(losses.begin(), losses.end()) - losses.begin());
  double a = grid[best > 0 ? best - 1 : 0], b = grid[std::min(best + 1, grid.size() - 1)];
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = lossAt(fromAxis(c)), fd = lossAt(fromAxis(d));
  for (int it = 0; it < 10 && (b - a) > 1e-3 * (1.0 + std::fabs(b)); ++it) {
    if (fc < fd) {
      b = d; d = c; fd = fc; c = b - phi * (b - a); fc = lossAt(fromAxis(c));
    } else {
      a = c; c = d; fc = fd; d = a + phi * (b - a); fd = lossAt(fromAxis(d));
    }
  }
  double u = fc < fd ? c : d, loss = std::min(fc, fd);
  if (losses[best] < loss) {
    u = grid[best];
    loss = losses[best];
  }
  if (loss < current_loss) {
    theta[j] = fromAxis(u);
    return loss;
  }
  return current_loss;
}

/// Robust low-dimensional fit: coordinate-wise grid + golden section over the whole bounds, then a
/// second round in a narrowed range. (Gauss-Newton alone crawls here: stick-slip friction and
/// saturations make the residuals far from linear in the parameters.)
std::vector<double> coordinateFit(const CandidateObjective& objective, std::vector<double> theta = {}) {
  const auto& params = objective.effect().params;
  if (theta.empty()) {
    for (const auto& p : params) theta.push_back(p.initial);
  }
  double loss = objective.loss(theta);
  for (int round = 0; round < (params.size() > 1 ? 2 : 1); ++round) {
    for (std::size_t j = 0; j < params.size(); ++j) {
      const auto& p = params[j];
      double lo = p.lower, hi = p.upper;
      if (round > 0) {  // narrow the range around the current value
        if (p.log_scale) {
          lo = std::max(p.lower, theta[j] / 3.0);
          hi = std::min(p.upper, theta[j] * 3.0);
        } else {
          const double span = 0.15 * (p.upper - p.lower);
          lo = std::max(p.lower, theta[j] - span);
          hi = std::min(p.upper, theta[j] + span);
        }
      }
      loss = lineSearch(objective, theta, j, lo, hi, round == 0 ? 13 : 7, loss);
    }
  }
  return theta;
}

/// The logged runs stayed bounded, so a fitted effect under which the closed loop of the log diverges
/// contradicts the log, however well it fits the open-loop replays (a column fitted with too little
/// damping does: the steering replay hardly sees the damping, the actuator's PD loop does). Bounded
/// means within the simulator's divergence limits, with the steering angle within 1.5 times the logged
/// range (+ 0.02 rad) and the torque command within twice the logged range (+ 5 N m): a column fitted at
/// the edge of stability kept a 69 Hz oscillation that grew at 0.2 1/s to 0.93 rad and 40 kN m within
/// the log's 30 s, under the monitor's 1.2 rad; one at 0.05 1/s reached 480 N m (logged: 35 N m).
/// Returns the training logs on which the closed loop of theta leaves those bounds where the nominal's
/// does not (empty: theta is consistent with the logs), and says so in `note`.
std::vector<BoundedLoopRequirement> stabilityRequirements(const CandidateObjective& objective, const std::vector<double>& theta,
                                                          const std::vector<Dataset>& train, const SimConfig& nominal,
                                                          std::string* note) {
  std::vector<const LogSignals*> logs;
  for (const Dataset& d : train) {
    if (std::find(logs.begin(), logs.end(), d.log.get()) == logs.end()) logs.push_back(d.log.get());
  }
  std::vector<BoundedLoopRequirement> requirements;
  for (const LogSignals* log : logs) {
    const double span = log->end() - log->start();
    double logged_angle = 0.0, logged_torque = 0.0;
    for (double delta : log->samples(LogSignals::kDelta)) logged_angle = std::max(logged_angle, std::fabs(delta));
    for (double torque : log->samples(LogSignals::kTorque)) logged_torque = std::max(logged_torque, std::fabs(torque));
    const BoundedLoopRequirement required{log, span, 1.5 * logged_angle + 0.02, 2.0 * logged_torque + 5.0};
    const LoopDivergence d = boundsCheck(objective.configFor(theta), required);
    if (!d.diverged || boundsCheck(nominal, required).diverged) continue;
    requirements.push_back(required);
    if (!note->empty()) continue;
    std::ostringstream os;
    os << "the least-squares fit (";
    for (std::size_t j = 0; j < theta.size(); ++j) {
      os << (j ? ", " : "") << objective.effect().params[j].name << " " << formatNumber(theta[j]);
    }
    os << ") makes the closed loop diverge on " << log->log().source << " (" << d.message << ")";
    *note = os.str();
  }
  return requirements;
}

/// Fits again from theta with the closed loop required to stay bounded on `requirements` (see
/// stabilityRequirements); *bounded_fit says whether the result does.
std::vector<double> holdStable(CandidateObjective& objective, std::vector<double> theta,
                               const std::vector<BoundedLoopRequirement>& requirements,
                               std::string* note, bool* bounded_fit) {
  *bounded_fit = true;
  if (requirements.empty()) return theta;
  // The search checks the first kSearchHorizon seconds of each log (a 60 s log's closed loop costs
  // 0.2-0.3 s per point, and a refit visits ~200 points); the result is checked over the whole log,
  // and searched again over it only if it fails there.
  constexpr double kSearchHorizon = 10.0;
  auto shortened = requirements;
  for (auto& r : shortened) r.horizon = std::min(r.horizon, kSearchHorizon);
  auto search = [&](const std::vector<BoundedLoopRequirement>& required, std::vector<double> start) {
    objective.requireStability(required);
    // First move: the one parameter whose change alone best restores a bounded loop. (Sweeping the
    // parameters in order would move the first however badly while the loop still diverges: a column's
    // stiffness, searched at the fitted low damping, lands at its bound.)
    const double start_loss = objective.loss(start);
    std::vector<double> best = start;
    double best_loss = start_loss;
    for (std::size_t j = 0; j < start.size(); ++j) {
      std::vector<double> moved = start;
      const auto& p = objective.effect().params[j];
      const double loss = lineSearch(objective, moved, j, p.lower, p.upper, 13, start_loss);
      if (loss < best_loss) {
        best_loss = loss;
        best = moved;
      }
    }
    return coordinateFit(objective, best);
  };
  auto bounded = [&](const std::vector<double>& t) {
    for (const auto& r : requirements) {
      if (boundsCheck(objective.configFor(t), r).diverged) return false;
    }
    return true;
  };
  theta = search(shortened, theta);
  bool ok = bounded(theta);
  if (!ok) {
    theta = search(requirements, theta);
    ok = bounded(theta);
  }
  *bounded_fit = ok;
  *note += ok ? "; fitted again with the closed loop required to stay bounded"
              : "; fitted again with the closed loop required to stay bounded, but no bounded fit was found: "
                "it still diverges on the training logs";
  objective.requireStability({});
  return theta;
}

/// Unconstrained least-squares fit: coordinate search, polished with Levenberg-Marquardt.
std::vector<double> leastSquaresFit(const CandidateObjective& objective) {
  const CandidateEffect& effect = objective.effect();
  std::vector<double> theta = coordinateFit(objective);
  if (effect.profile) return theta;
  // Polish with Levenberg-Marquardt (Ceres, central differences) from the coordinate optimum.
  std::vector<double> x = objective.toFitSpace(theta);
  std::vector<double> r0;
  if (!objective.residuals(theta, &r0)) return theta;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<CeresResiduals, ceres::CENTRAL>(
      new CeresResiduals{&objective, r0.size()});
  cost->AddParameterBlock(static_cast<int>(x.size()));
  cost->SetNumResiduals(static_cast<int>(r0.size()));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto& p = effect.params[i];
    problem.SetParameterLowerBound(x.data(), static_cast<int>(i), p.log_scale ? std::log(p.lower) : p.lower);
    problem.SetParameterUpperBound(x.data(), static_cast<int>(i), p.log_scale ? std::log(p.upper) : p.upper);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 4;
  solver.function_tolerance = 1e-6;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  const std::vector<double> polished = objective.toTheta(x.data());
  if (std::getenv("LK_GAP_DEBUG")) std::fprintf(stderr, "%s: %s\n", effect.name.c_str(), summary.BriefReport().c_str());
  if (objective.loss(polished) < objective.loss(theta)) theta = polished;
  return theta;
}

/// Parameters, bound flag, uncertainty and training / held-out scores of a fit at theta.
void scoreFit(const CandidateObjective& objective, const std::vector<double>& theta, const std::vector<Dataset>& train,
              const std::vector<Dataset>& heldout, const Evaluation& nominal_train, const Evaluation& nominal_heldout,
              const DiagnosisOptions& options, CandidateFit* out) {
  CandidateFit& fit = *out;
  const CandidateEffect& effect = objective.effect();
  fit.theta = theta;
  fit.corrected = objective.configFor(theta);
  fit.at_bound = false;
  for (std::size_t i = 0; i < theta.size(); ++i) {
    const auto& p = effect.params[i];
    const double span = p.log_scale ? std::log(p.upper / p.lower) : (p.upper - p.lower);
    const double from_lower = p.log_scale ? std::log(theta[i] / p.lower) : theta[i] - p.lower;
    const double from_upper = p.log_scale ? std::log(p.upper / theta[i]) : p.upper - theta[i];
    if (std::min(from_lower, from_upper) < 0.01 * span) fit.at_bound = true;
  }

  // 1-sigma uncertainty from the Gauss-Newton covariance s^2 (J^T J)^-1 at the optimum (central
  // differences in SI units). Residuals of neighbouring samples are correlated, so this is a lower bound.
  // (The local curvature of the least-squares loss, also at a fit held to a stable closed loop.)
  std::vector<double> r_opt;
  if (objective.residuals(theta, &r_opt)) {
    const std::size_t n = r_opt.size(), p = theta.size();
    Eigen::MatrixXd J(n, p);
    bool ok = true;
    for (std::size_t j = 0; j < p && ok; ++j) {
      const double h = 1e-4 * std::max(std::fabs(theta[j]), effect.params[j].log_scale ? 1e-3 : 1e-3 * (effect.params[j].upper - effect.params[j].lower));
      std::vector<double> tp = theta, tm = theta, rp, rm;
      tp[j] += h;
      tm[j] -= h;
      ok = objective.residuals(tp, &rp) && objective.residuals(tm, &rm) && rp.size() == n && rm.size() == n;
      for (std::size_t i = 0; ok && i < n; ++i) J(i, j) = (rp[i] - rm[i]) / (2.0 * h);
    }
    fit.sigma.assign(p, kNaN);
    if (ok && n > p) {
      // Residuals are weighted by 1/sqrt(N_trace); s^2 is estimated per weighted residual.
      const double s2 = sumOfSquares(r_opt) / static_cast<double>(n - p);
      const Eigen::MatrixXd info = J.transpose() * J;
      const Eigen::MatrixXd cov = s2 * info.completeOrthogonalDecomposition().pseudoInverse();
      for (std::size_t j = 0; j < p; ++j) fit.sigma[j] = std::sqrt(std::max(0.0, cov(j, j)));
    }
  }

  // Scores: training and held-out, all subsystems (unchanged ones keep their nominal scores).
  const std::set<std::string>& changed = objective.subsystems();
  const bool reuse = changed.count("chassis") == 0;
  const Evaluation train_ev = evaluate(fit.corrected, train, changed, options.replay, reuse ? &nominal_train.sigma1 : nullptr);
  const Evaluation held_ev =
      evaluate(fit.corrected, heldout, changed, options.replay, reuse ? &nominal_heldout.sigma1 : nullptr);
  fit.train_before = combinedGap([&] {
    std::vector<SubsystemScore> v;
    for (const auto& [n, s] : nominal_train.scores) v.push_back(s);
    return v;
  }());
  fit.train_after = gapOf(nominal_train.scores, train_ev.scores);
  fit.heldout_before = gapOf(nominal_heldout.scores, {});
  fit.heldout_after = gapOf(nominal_heldout.scores, held_ev.scores);
  fit.heldout_scores = nominal_heldout.scores;
  for (const auto& [n, s] : held_ev.scores) {
    fit.heldout_scores[n] = s;
    fit.heldout_scores[n].reference = nominal_heldout.scores.at(n).reference;
  }
  fit.evidence = evidenceOf(nominal_heldout.scores, held_ev.scores);
  fit.ok = true;
}

/// The least-squares fit of one candidate, scored; `unbounded_on` lists the training logs whose
/// closed loop it makes leave the logged bounds (refitBounded fits it again under them).
CandidateFit fitCandidate(const CandidateEffect& effect, const SimConfig& nominal, const std::vector<Dataset>& train,
                          const std::vector<Dataset>& heldout, const Evaluation& nominal_train,
                          const Evaluation& nominal_heldout, const DiagnosisOptions& options) {
  CandidateFit fit;
  fit.effect = &effect;
  CandidateObjective objective(effect, nominal, train, options.replay, nominal_train.sigma1);
  std::vector<double> theta;
  try {
    theta = leastSquaresFit(objective);
    fit.unbounded_on = stabilityRequirements(objective, theta, train, nominal, &fit.stability_note);
  } catch (const std::exception& e) {
    fit.note = std::string("fit failed: ") + e.what();
    return fit;
  }
  scoreFit(objective, theta, train, heldout, nominal_train, nominal_heldout, options, &fit);
  return fit;
}

/// Fits `fit` again from its least-squares parameters with its closed loop required to stay bounded
/// on the logs in fit->unbounded_on, and scores it again.
void refitBounded(const SimConfig& nominal, const std::vector<Dataset>& train, const std::vector<Dataset>& heldout,
                  const Evaluation& nominal_train, const Evaluation& nominal_heldout, const DiagnosisOptions& options,
                  CandidateFit* fit) {
  CandidateObjective objective(*fit->effect, nominal, train, options.replay, nominal_train.sigma1);
  std::vector<double> theta;
  bool bounded = false;
  try {
    theta = holdStable(objective, fit->theta, fit->unbounded_on, &fit->stability_note, &bounded);
  } catch (const std::exception& e) {
    fit->ok = false;
    fit->note = std::string("bounded refit failed: ") + e.what();
    return;
  }
  if (bounded) fit->unbounded_on.clear();
  scoreFit(objective, theta, train, heldout, nominal_train, nominal_heldout, options, fit);
}

// ================================================================================================
// Where: windows, bands, regimes
// ================================================================================================

/// Residual energy above the noise floor of each sample of a subsystem: sum over its traces of
/// max(0, r^2 - floor^2), with the sample times.
void excessEnergy(const SubsystemReplay& replay, const SubsystemScore& score, std::vector<double>* t, std::vector<double>* e) {
  for (std::size_t k = 0; k < replay.traces.size(); ++k) {
    const auto r = replay.traces[k].residual();
    const double f2 = score.traces[k].floor * score.traces[k].floor;
    for (std::size_t i = 0; i < r.size(); ++i) {
      t->push_back(replay.traces[k].t[i]);
      e->push_back(std::max(0.0, r[i] * r[i] - f2) / std::max<std::size_t>(1, r.size()));
    }
  }
}

/// Welch power spectral density of a uniformly resampled series (Hann windows, 50 % overlap).
void welch(const std::vector<double>& x, double dt, std::vector<double>* f, std::vector<double>* psd) {
  const std::size_t n = x.size();
  std::size_t len = 256;
  while (len > 16 && len > n) len /= 2;
  f->clear();
  psd->clear();
  if (n < 16) return;
  std::vector<double> w(len);
  double wss = 0.0;
  for (std::size_t i = 0; i < len; ++i) {
    w[i] = 0.5 - 0.5 * std::cos(2.0 * M_PI * i / (len - 1));
    wss += w[i] * w[i];
  }
  Eigen::FFT<double> fft;
  std::vector<double> acc(len / 2 + 1, 0.0), chunk(len);
  std::vector<std::complex<double>> spectrum;
  int count = 0;
  for (std::size_t start = 0; start + len <= n; start += len / 2) {
    double mean = 0.0;
    for (std::size_t i = 0; i < len; ++i) mean += x[start + i];
    mean /= len;
    for (std::size_t i = 0; i < len; ++i) chunk[i] = (x[start + i] - mean) * w[i];
    fft.fwd(spectrum, chunk);
    for (std::size_t k = 0; k <= len / 2; ++k) acc[k] += std::norm(spectrum[k]);
    ++count;
  }
  for (std::size_t k = 0; k <= len / 2; ++k) {
    f->push_back(k / (len * dt));
    const double one_sided = (k == 0 || k == len / 2) ? 1.0 : 2.0;
    psd->push_back(one_sided * acc[k] * dt / (wss * std::max(1, count)));
  }
}

/// The residual of a subsystem as one series at the log rate (RMS over its traces), time-sorted.
std::vector<std::pair<double, double>> subsystemSeries(const SubsystemReplay& replay) {
  std::map<double, std::pair<double, int>> acc;
  for (const auto& trace : replay.traces) {
    const auto r = trace.residual();
    for (std::size_t i = 0; i < r.size(); ++i) {
      auto& a = acc[trace.t[i]];
      a.first += r[i] * r[i];
      a.second += 1;
    }
  }
  std::vector<std::pair<double, double>> out;
  for (const auto& [t, a] : acc) out.emplace_back(t, std::sqrt(a.first / a.second));
  return out;
}

/// Signed residual series of the first trace (for spectra: RMS would rectify).
std::vector<double> signedSeries(const SubsystemReplay& replay, double* dt) {
  std::vector<double> values;
  if (replay.traces.empty() || replay.traces[0].t.size() < 2) return values;
  const auto& trace = replay.traces[0];
  const auto r = trace.residual();
  std::vector<double> steps;
  for (std::size_t i = 1; i < trace.t.size(); ++i) {
    if (trace.t[i] > trace.t[i - 1]) steps.push_back(trace.t[i] - trace.t[i - 1]);
  }
  std::sort(steps.begin(), steps.end());
  *dt = steps.empty() ? 0.01 : steps[steps.size() / 2];
  return r;
}

/// The chassis residual must be this many times its noise floor to count as an upstream cause.
constexpr double kUpstreamSignalToNoise = 2.0;

GapWhere whereAnalysis(const Evaluation& ev, const std::vector<Dataset>& data, const SimConfig& nominal,
                       double upstream_share, DiagnosisArtifacts* artifacts) {
  GapWhere where;
  double best = -1.0;
  for (const std::string& name : subsystemNames()) {
    const auto it = ev.scores.find(name);
    if (it == ev.scores.end()) continue;
    SubsystemGap g;
    g.name = name;
    g.nrmse = it->second.nrmse;
    g.noise_floor = it->second.floor;
    for (const auto& t : it->second.traces) g.outputs.push_back(t.name);
    where.subsystems.push_back(g);
    // Ranked by the excess beyond the noise-only reference: what noise alone leaves in a replay is not
    // a gap (ranked by raw excess, a 60 s, 1 kHz column log whose actuator noise excess matched its
    // reference was placed in the actuator, which no candidate changes, and judged unexplained).
    if (netExcess(it->second) > best) {
      best = netExcess(it->second);
      where.subsystem = name;
    }
  }
  // The steering replay takes the chassis replay's lateral velocity, and its tiny inertia J_F amplifies
  // any aligning-moment mismatch: a chassis cause shows in both, often more in the steering. A pure
  // steering effect leaves the chassis at its noise floor. So the chassis is reported when it carries
  // a real share of the steering's excess and stands clearly above its own noise floor. (A steering
  // effect that shakes the wheel fast — e.g. a torque limit that lets the steering loop chatter — can
  // leave the chassis replay of the sampled angle noisy in one trace: excess, but not above the floor.)
  if (where.subsystem == "steering" && ev.scores.count("chassis")) {
    const SubsystemScore& chassis = ev.scores.at("chassis");
    if (netExcess(chassis) >= upstream_share * netExcess(ev.scores.at("steering")) && netExcess(chassis) > 0.005 &&
        chassis.nrmse >= kUpstreamSignalToNoise * chassis.floor) {
      where.subsystem = "chassis";
    }
  }
  if (where.subsystem.empty()) return where;
  const SubsystemReplay& replay = ev.replays.at(where.subsystem);
  const SubsystemScore& score = ev.scores.at(where.subsystem);

  // Windows: excess energy per time window of the dominant subsystem.
  std::vector<double> t, e;
  excessEnergy(replay, score, &t, &e);
  double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min, total = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    t_min = std::min(t_min, t[i]);
    t_max = std::max(t_max, t[i]);
    total += e[i];
  }
  if (total > 0.0 && t_max > t_min) {
    const double width = std::max(0.5, (t_max - t_min) / 24.0);
    const int bins = static_cast<int>(std::ceil((t_max - t_min) / width + 1e-9));
    std::vector<double> energy(std::max(1, bins), 0.0);
    for (std::size_t i = 0; i < t.size(); ++i) {
      energy[std::min(bins - 1, static_cast<int>((t[i] - t_min) / width))] += e[i];
    }
    std::vector<WindowShare> windows;
    for (int b = 0; b < bins; ++b) windows.push_back({t_min + b * width, t_min + (b + 1) * width, energy[b] / total});
    std::sort(windows.begin(), windows.end(), [](const auto& a, const auto& b) { return a.share > b.share; });
    windows.resize(std::min<std::size_t>(5, windows.size()));
    where.windows = windows;
  }

  // Bands: spectrum of the dominant subsystem's residual minus its white-noise level.
  double dt = 0.01;
  const std::vector<double> series = signedSeries(replay, &dt);
  std::vector<double> f, psd;
  welch(series, dt, &f, &psd);
  if (!f.empty()) {
    const double noise_psd = 2.0 * dt * score.traces[0].floor * score.traces[0].floor;
    const double nyquist = 0.5 / dt;
    std::vector<double> edges{0.0, 0.5, 2.0, 8.0, 32.0};
    edges.erase(std::remove_if(edges.begin(), edges.end(), [&](double x) { return x >= nyquist; }), edges.end());
    edges.push_back(nyquist);
    std::vector<double> energy(edges.size() - 1, 0.0);
    double sum = 0.0;
    const double df = f.size() > 1 ? f[1] - f[0] : 1.0;
    for (std::size_t k = 1; k < f.size(); ++k) {
      const double excess = std::max(0.0, psd[k] - noise_psd) * df;
      for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
        if (f[k] >= edges[b] && (f[k] < edges[b + 1] || b + 2 == edges.size())) {
          energy[b] += excess;
          break;
        }
      }
      sum += excess;
    }
    for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
      where.bands.push_back({edges[b], edges[b + 1], sum > 0.0 ? energy[b] / sum : 0.0});
    }
  }

  // Regimes: share of the excess energy vs share of samples in bins of |front slip angle|, |a_y|,
  // |steering rate| (from the log; the slip angle with the chassis replay's lateral velocity).
  struct Binning {
    std::string name;
    std::vector<double> edges;
  };
  const std::vector<Binning> binnings{{"slip_angle", {0.0, 0.0087, 0.0175, 0.035, 0.07, 1e9}},
                                      {"lateral_acceleration", {0.0, 0.5, 1.0, 2.0, 4.0, 1e9}},
                                      {"steering_rate", {0.0, 0.02, 0.05, 0.1, 0.3, 1e9}}};
  const double b_front = nominal.vehicle.cgToFrontAxle(), V = nominal.vehicle.speed;
  for (const auto& binning : binnings) {
    std::vector<double> energy(binning.edges.size() - 1, 0.0), count(binning.edges.size() - 1, 0.0);
    double e_sum = 0.0, n_sum = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      // Find the data set holding t[i] (segments do not overlap across data sets in time order).
      const LogSignals* log = nullptr;
      for (const auto& d : data) {
        if (t[i] >= d.log->start() && t[i] <= d.log->end()) {
          log = d.log.get();
          break;
        }
      }
      if (log == nullptr) continue;
      double value = 0.0;
      if (binning.name == "slip_angle") {
        value = std::fabs(log->at(LogSignals::kDelta, t[i]) -
                          (log->at(LogSignals::kSigma1, t[i]) + b_front * log->at(LogSignals::kYawRate, t[i])) / V);
      } else if (binning.name == "lateral_acceleration") {
        value = log->has(LogSignals::kLateralAcceleration) ? std::fabs(log->at(LogSignals::kLateralAcceleration, t[i]))
                                                           : std::fabs(V * log->at(LogSignals::kYawRate, t[i]));
      } else {
        value = std::fabs(log->at(LogSignals::kDeltaRate, t[i]));
      }
      for (std::size_t b = 0; b + 1 < binning.edges.size(); ++b) {
        if (value >= binning.edges[b] && value < binning.edges[b + 1]) {
          energy[b] += e[i];
          count[b] += 1.0;
          break;
        }
      }
      e_sum += e[i];
      n_sum += 1.0;
    }
    for (std::size_t b = 0; b + 1 < binning.edges.size(); ++b) {
      if (count[b] == 0.0) continue;
      RegimeShare r;
      r.variable = binning.name;
      r.lo = binning.edges[b];
      r.hi = binning.edges[b + 1] > 1e8 ? std::numeric_limits<double>::infinity() : binning.edges[b + 1];
      r.share = e_sum > 0.0 ? energy[b] / e_sum : 0.0;
      r.time_share = n_sum > 0.0 ? count[b] / n_sum : 0.0;
      where.regimes.push_back(r);
    }
  }

  if (artifacts != nullptr) {
    // residuals.csv: per subsystem RMS-over-outputs residual on a common time base.
    std::map<std::string, std::vector<std::pair<double, double>>> series_by_name;
    std::set<double> times;
    for (const auto& [name, r] : ev.replays) {
      series_by_name[name] = subsystemSeries(r);
      for (const auto& p : series_by_name[name]) times.insert(p.first);
    }
    artifacts->residual_t.assign(times.begin(), times.end());
    for (const auto& [name, s] : series_by_name) {
      std::map<double, double> lookup(s.begin(), s.end());
      auto& column = artifacts->residual[name];
      for (double time : artifacts->residual_t) {
        const auto it = lookup.find(time);
        column.push_back(it == lookup.end() ? kNaN : it->second);
      }
    }
    // spectrum.csv on the dominant subsystem's frequency grid.
    artifacts->spectrum_f = f;
    for (const auto& [name, r] : ev.replays) {
      double step = 0.01;
      std::vector<double> fs, ps;
      welch(signedSeries(r, &step), step, &fs, &ps);
      std::vector<double> column;
      for (double fk : f) {
        double value = kNaN;
        for (std::size_t k = 0; k + 1 < fs.size(); ++k) {
          if (fk >= fs[k] && fk <= fs[k + 1]) {
            const double w = (fk - fs[k]) / std::max(1e-12, fs[k + 1] - fs[k]);
            value = ps[k] + w * (ps[k + 1] - ps[k]);
            break;
          }
        }
        column.push_back(value);
      }
      artifacts->spectrum[name] = column;
    }
  }
  return where;
}

std::vector<Dataset> wholeLogs(const std::vector<std::shared_ptr<const LogSignals>>& logs, double margin) {
  std::vector<Dataset> out;
  for (const auto& log : logs) out.push_back({log, {{log->start() + margin, log->end() + 1e-9}}});
  return out;
}

/// Training and held-out data: whole runs when held-out runs are given; otherwise alternating blocks
/// of each log (even blocks train, odd ones are held out), named in `held_blocks`.
struct DataSplit {
  std::vector<Dataset> train, held;
  std::vector<std::string> held_blocks;
};

DataSplit splitData(const std::vector<std::shared_ptr<const LogSignals>>& train_logs,
                    const std::vector<std::shared_ptr<const LogSignals>>& held_logs, const DiagnosisOptions& options) {
  DataSplit split;
  if (!held_logs.empty()) {
    split.train = wholeLogs(train_logs, options.start_margin);
    split.held = wholeLogs(held_logs, options.start_margin);
    return split;
  }
  for (const auto& log : train_logs) {
    Dataset tr{log, {}}, ho{log, {}};
    int block = 0;
    for (double a = log->start() + options.start_margin; a < log->end(); a += options.block_length, ++block) {
      const TimeSegment s{a, std::min(a + options.block_length, log->end() + 1e-9)};
      (block % 2 == 0 ? tr : ho).segments.push_back(s);
    }
    split.train.push_back(tr);
    if (!ho.segments.empty()) split.held.push_back(ho);
    split.held_blocks.push_back(log->log().source + " (odd " + formatNumber(options.block_length) + " s blocks)");
  }
  if (split.held.empty()) {
    throw InputError("gap diagnosis: the log is too short to hold out a block of " + formatNumber(options.block_length) + " s");
  }
  return split;
}

std::vector<std::shared_ptr<const LogSignals>> signalsOf(const std::vector<GapLog>& logs) {
  std::vector<std::shared_ptr<const LogSignals>> out;
  for (const auto& log : logs) out.push_back(std::make_shared<LogSignals>(log));
  return out;
}

}  // namespace

// ================================================================================================
std::vector<double> heldoutGaps(const SimConfig& nominal, const std::vector<SimConfig>& alternatives,
                                const std::vector<GapLog>& training, const std::vector<GapLog>& heldout,
                                const DiagnosisOptions& options) {
  if (training.empty()) throw InputError("gap diagnosis: no training log given");
  nominal.validate();
  const DataSplit split = splitData(signalsOf(training), signalsOf(heldout), options);
  const std::set<std::string> all = allSubsystems();
  Evaluation nominal_held = evaluate(nominal, split.held, all, options.replay);
  if (options.noise_reference_draws > 0) {
    std::vector<std::string> notes;
    setReference(nominal_held.scores, noiseReferenceExcess(nominal, split.held, options.replay,
                                                           options.noise_reference_draws, options.threads, &notes));
  }
  std::vector<double> gaps{gapOf(nominal_held.scores, {})};
  for (const SimConfig& config : alternatives) {
    config.validate();
    gaps.push_back(gapOf(nominal_held.scores, evaluate(config, split.held, all, options.replay).scores));
  }
  return gaps;
}

GapReport diagnoseGap(const SimConfig& nominal, const std::vector<GapLog>& training, const std::vector<GapLog>& heldout,
                      const DiagnosisOptions& options, DiagnosisArtifacts* artifacts) {
  if (training.empty()) throw InputError("gap diagnosis: no training log given");
  nominal.validate();
  auto say = [&](const std::string& message) {
    if (options.progress) options.progress(message);
  };
  GapReport report;
  using Clock = std::chrono::steady_clock;
  auto secondsSince = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };

  // ---- Data sets ------------------------------------------------------------------------------
  std::vector<std::shared_ptr<const LogSignals>> train_logs, held_logs;
  for (const auto& log : training) {
    train_logs.push_back(std::make_shared<LogSignals>(log));
    report.logs.push_back(log.source);
    report.rows_used += log.size();
    report.rows_skipped += log.rows_skipped;
    for (const auto& note : log.notes) report.notes.push_back(log.source + ": " + note);
  }
  for (const auto& log : heldout) {
    held_logs.push_back(std::make_shared<LogSignals>(log));
    report.heldout.push_back(log.source);
    report.rows_used += log.size();
    report.rows_skipped += log.rows_skipped;
    for (const auto& note : log.notes) report.notes.push_back(log.source + ": " + note);
  }
  const DataSplit split = splitData(train_logs, held_logs, options);
  const std::vector<Dataset>& train = split.train;
  const std::vector<Dataset>& held = split.held;
  if (held_logs.empty()) report.heldout = split.held_blocks;

  // ---- Where ----------------------------------------------------------------------------------
  say("replaying subsystems with the nominal model");
  const Clock::time_point where_start = Clock::now();
  const std::set<std::string> all = allSubsystems();
  Evaluation nominal_train = evaluate(nominal, train, all, options.replay);
  Evaluation nominal_held = evaluate(nominal, held, all, options.replay);
  std::map<std::string, double> reference;
  if (options.noise_reference_draws > 0) {
    // On held-out data, where shrink is measured; the training blocks (or runs) have the same noise
    // levels and sampling, so their gaps use the same reference (and so does the "where" report).
    say("replaying the noise-only reference (nominal closed loop with the logs' noise levels)");
    reference =
        noiseReferenceExcess(nominal, held, options.replay, options.noise_reference_draws, options.threads, &report.notes);
    setReference(nominal_train.scores, reference);
    setReference(nominal_held.scores, reference);
  }
  std::vector<Dataset> everything = train;
  everything.insert(everything.end(), held.begin(), held.end());
  // (For the "where" report, the union of training and held-out data.)
  Evaluation nominal_all = evaluate(nominal, everything, all, options.replay);
  setReference(nominal_all.scores, reference);
  report.where = whereAnalysis(nominal_all, everything, nominal, options.upstream_share, artifacts);
  const double gap_before = gapOf(nominal_held.scores, {});
  report.wall_seconds.emplace_back("where", secondsSince(where_start));

  // ---- Which ----------------------------------------------------------------------------------
  std::vector<const CandidateEffect*> candidates;
  for (const auto& c : candidateEffects()) {
    if (options.effects.empty() || std::find(options.effects.begin(), options.effects.end(), c.name) != options.effects.end()) {
      candidates.push_back(&c);
    }
  }
  std::vector<CandidateFit> fits(candidates.size());
  std::vector<double> fit_seconds(candidates.size(), 0.0);
  const Clock::time_point which_start = Clock::now();
  parallelFor(
      candidates.size(), options.threads,
      [&](std::size_t i) {
        const Clock::time_point start = Clock::now();
        fits[i] = fitCandidate(*candidates[i], nominal, train, held, nominal_train, nominal_held, options);
        fit_seconds[i] = secondsSince(start);
      },
      [&](std::size_t i) { say("fitting " + candidates[i]->name); });
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    report.wall_seconds.emplace_back("fit " + candidates[i]->name, fit_seconds[i]);
  }

  // A candidate can be the cause only if it changes the subsystem where the gap lies (a pure steering
  // effect leaves no chassis residual; no candidate touches the actuator subsystem).
  const std::string& where_subsystem = report.where.subsystem;
  auto changesWhere = [&](const std::string& effect) {
    const CandidateEffect& e = candidateEffect(effect);
    return std::find(e.subsystems.begin(), e.subsystems.end(), where_subsystem) != e.subsystems.end();
  };

  // Bounded refits. A least-squares fit whose closed loop leaves the logged bounds is contradicted by
  // the logs; fitting it again under those bounds costs a closed-loop run per point visited (40-60 s on
  // a 60 s log). It is worth that only if the refit could become the verdict: the refit fits the
  // training data no better than the unconstrained fit, so a candidate whose unconstrained held-out
  // gap already loses to the best qualifying bounded candidate (or misses the min_shrink needed), or
  // that does not change the subsystem carrying the gap, or a gap below the detection threshold, keeps
  // its unconstrained fit marked unbounded, and cannot be the verdict.
  double bar = gap_before * (1.0 - options.min_shrink);
  for (const auto& fit : fits) {
    if (fit.ok && fit.unbounded_on.empty() && !fit.at_bound && changesWhere(fit.effect->name) &&
        fit.evidence >= options.min_evidence_per_parameter * static_cast<double>(fit.theta.size())) {
      bar = std::min(bar, fit.heldout_after);
    }
  }
  std::vector<std::size_t> refit;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    const CandidateFit& fit = fits[i];
    if (!fit.ok || fit.unbounded_on.empty()) continue;
    if (gap_before >= options.detection_gap && changesWhere(fit.effect->name) && fit.heldout_after < bar) {
      refit.push_back(i);
    } else {
      char numbers[96];
      std::snprintf(numbers, sizeof numbers, "held-out gap %.4g against %.4g to beat", fit.heldout_after, bar);
      fits[i].stability_note +=
          std::string("; not fitted again under the logged bounds: it could not become the verdict (") + numbers + ")";
    }
  }
  std::vector<double> refit_seconds(refit.size(), 0.0);
  parallelFor(
      refit.size(), options.threads,
      [&](std::size_t k) {
        const Clock::time_point start = Clock::now();
        refitBounded(nominal, train, held, nominal_train, nominal_held, options, &fits[refit[k]]);
        refit_seconds[k] = secondsSince(start);
      },
      [&](std::size_t k) { say("fitting " + candidates[refit[k]]->name + " again with its closed loop bounded"); });
  for (std::size_t k = 0; k < refit.size(); ++k) {
    report.wall_seconds.emplace_back("bounded refit " + candidates[refit[k]]->name, refit_seconds[k]);
  }
  report.wall_seconds.emplace_back("which", secondsSince(which_start));

  std::set<std::string> pinned;
  for (const auto& fit : fits) {
    if (fit.ok && fit.at_bound) pinned.insert(fit.effect->name);
  }
  for (const auto& fit : fits) {
    RankedEffect r;
    r.effect = fit.effect->name;
    r.heldout_gap_before = gap_before;
    if (!fit.ok) {
      r.heldout_gap_after = gap_before;
      r.shrink = 0.0;
      report.notes.push_back(fit.effect->name + ": " + fit.note);
    } else {
      for (std::size_t i = 0; i < fit.theta.size(); ++i) {
        r.params[fit.effect->params[i].name] = fit.theta[i];
        r.param_sigma[fit.effect->params[i].name] = i < fit.sigma.size() ? fit.sigma[i] : kNaN;
      }
      r.config = configDifference(nominal, fit.corrected);
      r.train_gap_before = fit.train_before;
      r.train_gap_after = fit.train_after;
      r.heldout_gap_after = fit.heldout_after;
      r.shrink = gap_before > 0.0 ? 1.0 - fit.heldout_after / gap_before : 0.0;
    }
    r.score = fit.ok ? fit.evidence : 0.0;
    r.closed_loop_bounded = !fit.ok || fit.unbounded_on.empty();
    if (fit.ok && fit.at_bound) report.notes.push_back(fit.effect->name + ": a fitted parameter is pinned at a bound of its range");
    if (fit.ok && !fit.stability_note.empty()) report.notes.push_back(fit.effect->name + ": " + fit.stability_note);
    report.ranking.push_back(r);
  }
  std::sort(report.ranking.begin(), report.ranking.end(), [](const RankedEffect& a, const RankedEffect& b) {
    if (a.closed_loop_bounded != b.closed_loop_bounded) return a.closed_loop_bounded;
    return a.heldout_gap_after < b.heldout_gap_after;
  });

  // ---- Verdict --------------------------------------------------------------------------------
  GapVerdict& v = report.verdict;
  v.gap_before = gap_before;
  const WinnerSelection selection =
      selectWinner(report.ranking, changesWhere, pinned, options.min_shrink, options.min_evidence_per_parameter);
  const RankedEffect* top = selection.top;
  const RankedEffect* best = selection.winner;
  const RankedEffect* second = selection.runner_up;
  const bool pinned_winner = selection.winner_pinned;
  std::ostringstream reason;
  if (gap_before < options.detection_gap) {
    v.effect = "unexplained";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    v.confidence = std::clamp(1.0 - gap_before / options.detection_gap, 0.0, 1.0) * 0.5 + 0.5;
    reason << "the nominal model matches the held-out data to within noise (gap " << formatNumber(gap_before)
           << " < detection threshold " << formatNumber(options.detection_gap) << "): nothing to explain";
  } else if (best == nullptr) {
    v.effect = "unexplained";
    v.gap_after = gap_before;
    v.shrink = 0.0;
    const double s = top ? std::max(0.0, top->shrink) : 0.0;
    v.confidence = std::clamp(1.0 - s / options.min_shrink, 0.0, 1.0) * 0.5 + 0.5;
    reason << "a gap of " << formatNumber(gap_before) << " (mostly in the " << where_subsystem
           << " subsystem) that no candidate explains: ";
    if (top == nullptr) {
      reason << "no candidate changes the " << where_subsystem << " subsystem";
    } else {
      reason << "the best candidate that changes it, " << top->effect << ", removes " << formatNumber(100.0 * s)
             << " % of it on held-out data with evidence " << formatNumber(top->score) << " (needs "
             << formatNumber(100.0 * options.min_shrink) << " % and " << formatNumber(options.min_evidence_per_parameter)
             << " per parameter)";
    }
  } else {
    v.effect = best->effect;
    v.gap_after = best->heldout_gap_after;
    v.shrink = best->shrink;
    // Confidence: how much of the gap it explains, times how clearly it beats the runner-up.
    const double margin = second ? (best->shrink - second->shrink) / std::max(1e-9, best->shrink) : 1.0;
    v.confidence = std::clamp(best->shrink, 0.0, 1.0) * (0.5 + 0.5 * std::clamp(margin / 0.3, 0.0, 1.0));
    if (pinned_winner) v.confidence *= 0.5;
    for (const auto& r : report.ranking) {
      if (&r != best && changesWhere(r.effect) && r.closed_loop_bounded && r.shrink >= options.min_shrink &&
          best->shrink - r.shrink < 0.1) {
        v.confusable_with.push_back(r.effect);
      }
    }
    reason << best->effect << " removes " << formatNumber(100.0 * best->shrink) << " % of the held-out gap ("
           << formatNumber(gap_before) << " -> " << formatNumber(best->heldout_gap_after) << ")";
    if (second) reason << "; next best " << second->effect << " removes " << formatNumber(100.0 * second->shrink) << " %";
    if (pinned_winner) {
      reason << "; a fitted parameter sits at a bound of its range (the effect's form differs from the candidate's, "
                "or the data fix only a combination of its parameters): confidence halved";
    }
    const auto& known = knownLookAlikes(best->effect);
    for (const auto& c : v.confusable_with) {
      if (std::find(known.begin(), known.end(), c) != known.end()) reason << "; " << c << " is a known look-alike";
    }
  }
  v.reason = reason.str();

  // ---- How far --------------------------------------------------------------------------------
  const CandidateFit* winner = nullptr;
  for (const auto& fit : fits) {
    if (fit.ok && fit.effect->name == v.effect) winner = &fit;
  }
  for (const auto& [name, score] : nominal_held.scores) {
    report.how_far.subsystems_before[name] = score.excess;
    report.how_far.subsystems_noise_reference[name] = score.reference;
  }
  for (const auto& [name, score] : (winner ? winner->heldout_scores : nominal_held.scores)) {
    report.how_far.subsystems_after[name] = score.excess;
  }
  if (options.closed_loop) {
    say("closed-loop replays");
    const Clock::time_point how_far_start = Clock::now();
    const auto& cl_logs = held_logs.empty() ? train_logs : held_logs;
    double before = 0.0, after = 0.0;
    int counted = 0;
    for (std::size_t i = 0; i < cl_logs.size(); ++i) {
      const Evaluation chassis = evaluate(nominal, wholeLogs({cl_logs[i]}, 0.0), {"chassis"}, options.replay);
      const double s1 = chassis.sigma1.empty() || chassis.sigma1[0].empty() ? kNaN : chassis.sigma1[0].front().second;
      const ClosedLoopReplay b = closedLoopReplay(nominal, *cl_logs[i], s1);
      const ClosedLoopReplay a = winner ? closedLoopReplay(winner->corrected, *cl_logs[i], s1) : b;
      if (!b.note.empty()) report.notes.push_back("nominal " + b.note);
      if (winner && !a.note.empty()) report.notes.push_back("corrected " + a.note);
      if (std::isfinite(b.gap) && std::isfinite(a.gap)) {
        before += b.gap * b.gap;
        after += a.gap * a.gap;
        ++counted;
      }
      if (artifacts != nullptr && i == 0) {
        artifacts->overlay_t = b.t;
        artifacts->overlay["y_real"] = {};
        for (double t : b.t) {
          artifacts->overlay["y_real"].push_back(cl_logs[i]->at(LogSignals::kY, t));
          artifacts->overlay["yaw_rate_real"].push_back(cl_logs[i]->at(LogSignals::kYawRate, t));
          artifacts->overlay["delta_real"].push_back(cl_logs[i]->at(LogSignals::kDelta, t));
        }
        artifacts->overlay["y_nominal"] = b.y;
        artifacts->overlay["yaw_rate_nominal"] = b.yaw_rate;
        artifacts->overlay["delta_nominal"] = b.delta;
        if (winner) {
          auto pad = [&](std::vector<double> v) {
            v.resize(b.t.size(), kNaN);
            return v;
          };
          artifacts->overlay["y_corrected"] = pad(a.y);
          artifacts->overlay["yaw_rate_corrected"] = pad(a.yaw_rate);
          artifacts->overlay["delta_corrected"] = pad(a.delta);
        }
      }
    }
    report.how_far.before = counted ? std::sqrt(before / counted) : kNaN;
    report.how_far.after = counted ? std::sqrt(after / counted) : kNaN;
    report.wall_seconds.emplace_back("how_far", secondsSince(how_far_start));
  }
  say("done");
  return report;
}

void writeDiagnosisArtifacts(const std::string& dir, const DiagnosisArtifacts& artifacts) {
  auto write = [&](const std::string& name, const std::string& first, const std::vector<double>& x,
                   const std::vector<std::string>& columns, const std::map<std::string, std::vector<double>>& data) {
    std::ofstream out(dir + "/" + name);
    if (!out) throw InputError(dir + "/" + name + ": cannot write");
    out << first;
    for (const auto& c : columns) out << "," << c;
    out << "\n";
    char buffer[40];
    for (std::size_t i = 0; i < x.size(); ++i) {
      std::snprintf(buffer, sizeof(buffer), "%.10g", x[i]);
      out << buffer;
      for (const auto& c : columns) {
        const auto it = data.find(c);
        const double value = (it != data.end() && i < it->second.size()) ? it->second[i] : kNaN;
        if (std::isfinite(value)) {
          std::snprintf(buffer, sizeof(buffer), "%.10g", value);
          out << "," << buffer;
        } else {
          out << ",nan";
        }
      }
      out << "\n";
    }
  };
  write("residuals.csv", "t", artifacts.residual_t, {"tracker", "actuator", "steering", "chassis"}, artifacts.residual);
  write("spectrum.csv", "f", artifacts.spectrum_f, {"tracker", "actuator", "steering", "chassis"}, artifacts.spectrum);
  write("overlay.csv", "t", artifacts.overlay_t,
        {"y_real", "y_nominal", "y_corrected", "yaw_rate_real", "yaw_rate_nominal", "yaw_rate_corrected", "delta_real",
         "delta_nominal", "delta_corrected"},
        artifacts.overlay);
}

}  // namespace lane_keeping
