#pragma once
/// The loss a candidate's fit minimises (diagnosis.h, step 3): the replays of the subsystems the
/// candidate changes, run with its parameters, over the training data; optionally with the closed
/// loop of each fitted configuration required to stay within the logged bounds (bounded_loop.h).
#include <atomic>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/evaluation/evaluation.h"
#include "lane_keeping/gap/fit/bounded_loop.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/evaluation_budget.h"

namespace lane_keeping {
namespace diagnosis {

/// The loss of one candidate as a function of its (transformed) parameters.
class CandidateObjective {
 public:
  /// @param nominal the shared nominal configuration (for validity and the report's overlay); each data
  ///        set is replayed under its own run's configuration with the effect applied.
  /// @param available the subsystems the logs can feed: the effect is fitted on those it changes.
  CandidateObjective(const CandidateEffect& effect, const SimConfig& nominal, const std::vector<Dataset>& data,
                     const ReplayOptions& options, const Sigma1Cache& nominal_sigma1,
                     const std::set<std::string>& available);

  /// Parameters from fit space (log for log-scale ones) to SI.
  std::vector<double> toTheta(const double* x) const;
  std::vector<double> toFitSpace(const std::vector<double>& theta) const;

  /// The effect at parameters theta (SI), as a change of any run's configuration.
  ConfigChange changeFor(const std::vector<double>& theta) const;
  /// The shared nominal configuration with the effect at parameters theta.
  SimConfig configFor(const std::vector<double>& theta) const;

  /// Residual vector for parameters theta (SI); false if the configuration is invalid, or if it makes
  /// the closed loop diverge on a log where stability is required.
  bool residuals(const std::vector<double>& theta, std::vector<double>* out) const;
  /// The replays behind residuals(theta): those of the subsystems the effect changes, over this
  /// objective's data (scoreFit keeps them as the fit's training scores).
  Evaluation evaluation(const std::vector<double>& theta) const;
  /// residuals(theta) from its replays `ev` = evaluation(theta), without replaying again.
  bool residuals(const std::vector<double>& theta, const Evaluation& ev, std::vector<double>* out) const;

  /// Sum of squared residuals. Under a stability requirement a point whose closed loop diverges ranks
  /// after every bounded one, and the later it diverges the better — so that a coordinate search
  /// started in the unstable region finds its way out. Remembered per theta until the requirement
  /// changes: a coordinate search revisits points (the start of each line, a line's grid again after a
  /// first move along it), and under a requirement each visit costs a closed-loop run.
  double loss(const std::vector<double>& theta) const;

  /// Whether loss(theta) costs no replay and no closed-loop run: it is remembered, or what it is made of
  /// is (the bounds checks under the requirement in force, up to the first that diverges, and the replay
  /// loss if none does).
  bool remembersLoss(const std::vector<double>& theta) const;

  /// The sum of squared residuals at theta whatever the stability requirement (+inf for an invalid
  /// configuration): loss(theta) where the closed loop stays bounded. Remembered per theta.
  double replayLoss(const std::vector<double>& theta) const;
  /// Whether a stability requirement is in force (requireStability).
  bool constrained() const { return !stable_on_.empty(); }

  /// Whether the closed loop at theta leaves requirement r's bounds (boundsCheck), remembered per theta
  /// and requirement.
  LoopDivergence bounds(const std::vector<double>& theta, const BoundedLoopRequirement& r) const;

  /// How many closed-loop runs (bounds checks) and replays (replayLoss points) this objective has
  /// made: a refit's evaluation count.
  std::size_t closedLoopRuns() const {
    std::lock_guard<std::mutex> lock(memo_mutex_);
    return bounds_.size();
  }
  std::size_t replays() const {
    std::lock_guard<std::mutex> lock(memo_mutex_);
    return replay_losses_.size();
  }
  /// Holds the searches on this objective to `budget` (evaluation_budget.h), counted from now;
  /// EvaluationBudget{} lifts it. Past it, a point not remembered costs nothing: replayLoss and loss
  /// return +inf, residuals false, bounds a loop that leaves the bounds at t = 0; nothing computed
  /// after that is remembered. (evaluation(), which the scores call, is never held.) Like the memos,
  /// bookkeeping of the searches run on the objective, hence const.
  void limit(const EvaluationBudget& budget) const;
  /// Whether a search reached the budget since the last limit().
  bool budgetSpent() const { return spent_.load(); }
  /// How many times this objective has replayed its data (evaluation(), from any caller).
  std::size_t evaluations() const { return evaluations_.load(); }

  /// The same loss over other data (such as decimatedData's coarse subset of this one's), with no
  /// stability requirement and nothing remembered. `data` must outlive the result.
  CandidateObjective on(const std::vector<Dataset>& data) const {
    return CandidateObjective(effect_, nominal_, data, options_, nominal_sigma1_, subsystems_);
  }
  const std::vector<Dataset>& data() const { return data_; }
  const ReplayOptions& replayOptions() const { return options_; }

  const std::set<std::string>& subsystems() const { return subsystems_; }
  const CandidateEffect& effect() const { return effect_; }

  /// The closed loop must stay bounded on these logs over these horizons, its steering angle within
  /// `max_steering_angle` and its torque command within `max_torque`.
  void requireStability(std::vector<BoundedLoopRequirement> requirements);

 private:
  static constexpr double kUnstableLoss = 1e100;

  /// Neither an invalid configuration nor, under a stability requirement, a diverging closed loop.
  bool admissible(const std::vector<double>& theta) const;

  /// 0 if the closed loop at theta stays bounded on every required log, else 1 - (time it took to
  /// diverge) / horizon, in (0, 1].
  double divergence(const std::vector<double>& theta) const;

  /// A requirement as a memo key: the log and its bounds.
  using RequirementKey = std::tuple<const LogSignals*, const SimConfig*, double, double, double>;

  std::vector<BoundedLoopRequirement> stable_on_;
  const CandidateEffect& effect_;
  const SimConfig& nominal_;
  const std::vector<Dataset>& data_;
  ReplayOptions options_;
  const Sigma1Cache& nominal_sigma1_;
  std::set<std::string> subsystems_;
  // Memos (the evaluations are deterministic, so a remembered value is the value). Fits call loss()
  // from one thread; Ceres may evaluate residuals() from several, hence the lock.
  mutable std::mutex memo_mutex_;
  mutable std::map<std::vector<double>, double> losses_;
  mutable std::map<std::vector<double>, double> replay_losses_;
  mutable std::map<std::pair<std::vector<double>, RequirementKey>, LoopDivergence> bounds_;
  mutable std::atomic<std::size_t> evaluations_{0};
  /// Takes one replay (or closed-loop run) from the budget; false, and the budget spent, past it.
  bool spend(std::atomic<std::size_t>& used, std::size_t allowed) const;
  mutable EvaluationBudget budget_;
  mutable std::atomic<std::size_t> replays_used_{0}, closed_loops_used_{0};
  mutable std::atomic<bool> spent_{false};
};

}  // namespace diagnosis
}  // namespace lane_keeping
