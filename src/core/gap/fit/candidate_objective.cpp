#include "lane_keeping/gap/fit/candidate_objective.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lane_keeping {
namespace diagnosis {

CandidateObjective::CandidateObjective(const CandidateEffect& effect, const SimConfig& nominal,
                                       const std::vector<Dataset>& data, const ReplayOptions& options,
                                       const Sigma1Cache& nominal_sigma1, const std::set<std::string>& available)
    : effect_(effect), nominal_(nominal), data_(data), options_(options), nominal_sigma1_(nominal_sigma1) {
  for (const std::string& s : effect.subsystems) {
    if (available.count(s)) subsystems_.insert(s);
  }
}

std::vector<double> CandidateObjective::toTheta(const double* x) const {
  std::vector<double> theta(effect_.params.size());
  for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = effect_.params[i].log_scale ? std::exp(x[i]) : x[i];
  return theta;
}

std::vector<double> CandidateObjective::toFitSpace(const std::vector<double>& theta) const {
  std::vector<double> x(theta.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = effect_.params[i].log_scale ? std::log(theta[i]) : theta[i];
  return x;
}

ConfigChange CandidateObjective::changeFor(const std::vector<double>& theta) const {
  const CandidateEffect* effect = &effect_;
  return [effect, theta](SimConfig& c) { effect->apply(theta, c); };
}

SimConfig CandidateObjective::configFor(const std::vector<double>& theta) const {
  SimConfig c = nominal_;
  effect_.apply(theta, c);
  return c;
}

bool CandidateObjective::admissible(const std::vector<double>& theta) const {
  return configFor(theta).problems().empty() && !(divergence(theta) > 0.0);
}

Evaluation CandidateObjective::evaluation(const std::vector<double>& theta) const {
  const bool reuse = subsystems_.count("chassis") == 0;
  ++evaluations_;
  return evaluate(changeFor(theta), data_, subsystems_, options_, reuse ? &nominal_sigma1_ : nullptr);
}

bool CandidateObjective::residuals(const std::vector<double>& theta, std::vector<double>* out) const {
  if (!admissible(theta) || !spend(replays_used_, budget_.replays)) return false;
  *out = fitResiduals(evaluation(theta));
  return true;
}

void CandidateObjective::limit(const EvaluationBudget& budget) const {
  budget_ = budget;
  replays_used_ = 0;
  closed_loops_used_ = 0;
  spent_ = false;
}

bool CandidateObjective::spend(std::atomic<std::size_t>& used, std::size_t allowed) const {
  if (allowed == EvaluationBudget::kUnlimited) return true;
  if (used.fetch_add(1) < allowed) return true;
  spent_ = true;
  return false;
}

bool CandidateObjective::residuals(const std::vector<double>& theta, const Evaluation& ev,
                                   std::vector<double>* out) const {
  if (!admissible(theta)) return false;
  *out = fitResiduals(ev);
  return true;
}

namespace {

/// A point the memos may hold: std::map orders its keys with <, under which a NaN is equivalent to
/// every number, so a point with one would find another point's value.
bool memoizable(const std::vector<double>& theta) {
  return std::none_of(theta.begin(), theta.end(), [](double v) { return std::isnan(v); });
}

/// memo[key], computed and stored on the first call; not stored once the evaluation budget is spent
/// (a value computed then may be the budget's stand-in, CandidateObjective::limit). The computation
/// runs outside the lock: Ceres evaluates points from several threads, and two threads computing one
/// point store the same value.
template <typename Memo, typename Compute>
typename Memo::mapped_type remembered(std::mutex& mutex, Memo& memo, typename Memo::key_type key,
                                      const std::atomic<bool>& spent, const Compute& compute) {
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = memo.find(key); it != memo.end()) return it->second;
  }
  const typename Memo::mapped_type value = compute();
  if (spent.load()) return value;
  std::lock_guard<std::mutex> lock(mutex);
  memo.emplace(std::move(key), value);
  return value;
}

}  // namespace

double CandidateObjective::replayLoss(const std::vector<double>& theta) const {
  auto compute = [&] {
    if (!configFor(theta).problems().empty() || !spend(replays_used_, budget_.replays)) {
      return std::numeric_limits<double>::infinity();
    }
    return sumOfSquares(fitResiduals(evaluation(theta)));
  };
  return memoizable(theta) ? remembered(memo_mutex_, replay_losses_, theta, spent_, compute) : compute();
}

double CandidateObjective::loss(const std::vector<double>& theta) const {
  auto compute = [&] {
    if (!configFor(theta).problems().empty()) return std::numeric_limits<double>::infinity();
    if (const double d = divergence(theta); d > 0.0) return kUnstableLoss * (1.0 + d);
    return replayLoss(theta);
  };
  return memoizable(theta) ? remembered(memo_mutex_, losses_, theta, spent_, compute) : compute();
}

bool CandidateObjective::remembersLoss(const std::vector<double>& theta) const {
  std::lock_guard<std::mutex> lock(memo_mutex_);
  if (losses_.count(theta) > 0) return true;
  if (!memoizable(theta)) return false;
  for (const BoundedLoopRequirement& r : stable_on_) {  // as divergence() checks them
    if (!memoizable({r.horizon, r.max_steering_angle, r.max_torque})) return false;
    const auto it = bounds_.find({theta, RequirementKey{r.log, r.config, r.horizon, r.max_steering_angle, r.max_torque}});
    if (it == bounds_.end()) return false;
    if (it->second.diverged) return true;
  }
  return replay_losses_.count(theta) > 0;
}

void CandidateObjective::requireStability(std::vector<BoundedLoopRequirement> requirements) {
  stable_on_ = std::move(requirements);
  std::lock_guard<std::mutex> lock(memo_mutex_);
  losses_.clear();  // the loss depends on the requirement; the bounds checks do not
}

LoopDivergence CandidateObjective::bounds(const std::vector<double>& theta, const BoundedLoopRequirement& r) const {
  auto compute = [&] {
    if (!spend(closed_loops_used_, budget_.closed_loops)) {
      LoopDivergence spent;
      spent.diverged = true;
      spent.time = 0.0;
      spent.message = "not run: the search's evaluation budget is spent";
      return spent;
    }
    return boundsCheck(changeFor(theta), r);
  };
  if (!memoizable(theta) || !memoizable({r.horizon, r.max_steering_angle, r.max_torque})) return compute();
  return remembered(memo_mutex_, bounds_,
                    {theta, RequirementKey{r.log, r.config, r.horizon, r.max_steering_angle, r.max_torque}}, spent_,
                    compute);
}

double CandidateObjective::divergence(const std::vector<double>& theta) const {
  for (const BoundedLoopRequirement& s : stable_on_) {
    const LoopDivergence d = bounds(theta, s);
    if (d.diverged) return std::clamp(1.0 - d.time / s.horizon, 1e-6, 1.0);
  }
  return 0.0;
}

}  // namespace diagnosis
}  // namespace lane_keeping
