#include "lane_keeping/gap/fit/plausible_magnitude.h"
#include "lane_keeping/gap/fit/candidate_fit.h"

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <boost/math/tools/minima.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <string>

#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/fit/closed_loop_checks.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using search::kBoundaryBisections;
using search::kLineSearchBits;

/// Brent's stopping width near u on a line's axis (Boost.Math: 2^(1 - bits) (|u| + 1/4)).
double axisTolerance(double u) { return std::ldexp(1.0, 1 - kLineSearchBits) * (std::fabs(u) + 0.25); }

/// The residuals of the points a polish evaluated last: Levenberg-Marquardt evaluates a step's point,
/// and, if it takes it, the point again for its Jacobian (forward differences start from it); the
/// search's result and the polish's own result are among them too. Each repeat was one more replay
/// of all the data: per polish one for its start, one per step taken and one for its result.
class RecentResiduals {
 public:
  explicit RecentResiduals(std::size_t capacity) : capacity_(capacity) {}
  bool find(const std::vector<double>& point, std::vector<double>* out) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [p, r] : entries_) {
      if (p == point) {
        *out = r;
        return true;
      }
    }
    return false;
  }
  void add(const std::vector<double>& point, const std::vector<double>& r) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.emplace_back(point, r);
    if (entries_.size() > capacity_) entries_.pop_front();
  }

 private:
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<std::pair<std::vector<double>, std::vector<double>>> entries_;
};

/// Ceres functor over the free ones of the transformed parameters (the others held at `x`).
struct CeresResiduals {
  const CandidateObjective* objective;
  std::vector<double> x;
  std::vector<std::size_t> free;
  std::size_t count;
  RecentResiduals* recent;
  bool operator()(double const* const* parameters, double* residuals) const {
    std::vector<double> at = x;
    for (std::size_t k = 0; k < free.size(); ++k) at[free[k]] = parameters[0][k];
    const std::vector<double> theta = objective->toTheta(at.data());
    std::vector<double> r;
    if (!recent->find(theta, &r)) {
      if (!objective->residuals(theta, &r)) return false;
      recent->add(theta, r);
    }
    if (r.size() != count) return false;
    std::copy(r.begin(), r.end(), residuals);
    return true;
  }
};

}  // namespace

/// Levenberg-Marquardt (Ceres) from theta, at most `iterations` steps; theta itself when no step lowers
/// the loss. A parameter at a bound of its range is held there: the coordinate search put it there as
/// the best point of its line, so the loss falls outward, and LM's steps projected back onto the box
/// were rejected one after the other (a fit on a log without the effect spent five iterations, ~45 % of
/// its time, without moving; held there in every polish, the motor-side column fit's polish on the
/// benchmark's 60 s log took 33 replays instead of 93).
/// The Jacobian is by forward differences: p + 1 replays per iteration instead of central differences'
/// 2p + 1. The polish follows a search that already stands near the optimum, and LM's steps need the
/// Jacobian's direction, not its last digits (on the benchmark's 60 s log the polishes took 223 replays
/// instead of 455; their final losses within 0.14 % of central differences', some lower, the verdict's
/// shrink 82.915 -> 82.911 %; both benchmark families' 145 verdicts unchanged).
std::vector<double> polish(const CandidateObjective& objective, std::vector<double> theta, int iterations) {
  const CandidateEffect& effect = objective.effect();
  const std::vector<double> x = objective.toFitSpace(theta);
  std::vector<std::size_t> free;
  std::vector<double> lower, upper;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto& p = effect.params[i];
    const double lo = p.log_scale ? std::log(p.lower) : p.lower, hi = p.log_scale ? std::log(p.upper) : p.upper;
    if (std::min(x[i] - lo, hi - x[i]) <= 1e-9 * (hi - lo)) continue;
    free.push_back(i);
    lower.push_back(lo);
    upper.push_back(hi);
  }
  std::vector<double> r0;
  if (free.empty() || !objective.residuals(theta, &r0)) return theta;
  // (Ceres's functor evaluates theta from fit space, where a log-scale parameter's exp(log(v)) may
  // differ from v in its last bit: r0 is its residual only if the round trip is exact.)
  RecentResiduals recent(2 * free.size() + 4);
  if (objective.toTheta(x.data()) == theta) recent.add(theta, r0);
  std::vector<double> y;
  for (std::size_t i : free) y.push_back(x[i]);
  auto* cost = new ceres::DynamicNumericDiffCostFunction<CeresResiduals, ceres::FORWARD>(
      new CeresResiduals{&objective, x, free, r0.size(), &recent});
  cost->AddParameterBlock(static_cast<int>(y.size()));
  cost->SetNumResiduals(static_cast<int>(r0.size()));
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, y.data());
  for (std::size_t k = 0; k < y.size(); ++k) {
    problem.SetParameterLowerBound(y.data(), static_cast<int>(k), lower[k]);
    problem.SetParameterUpperBound(y.data(), static_cast<int>(k), upper[k]);
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = iterations;
  // Under bounds, Ceres searches along each projected step (Armijo). With its default cubic
  // interpolation every trial point costs the forward-difference Jacobian too (p + 1 replays of all the
  // data); a quadratic one needs the cost alone, and six trials bound it. (The motor-side column's
  // polish on all of the independent family's none-31 log, 1 kHz: its step rejected, 12 trials shrank
  // towards the start, 49 replays and 0.8 s of its 1.7 s fit; now 10 replays. Without the search the
  // friction fits stopped short: held-out shrinks 72.9 -> 71.5 % and 68.6 -> 67.9 %.)
  solver.line_search_interpolation_type = ceres::QUADRATIC;
  solver.max_num_line_search_step_size_iterations = search::kPolishLineSearchTrials;
  solver.function_tolerance = 1e-6;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  std::vector<double> moved = x;
  for (std::size_t k = 0; k < free.size(); ++k) moved[free[k]] = y[k];
  const std::vector<double> polished = objective.toTheta(moved.data());
  if (std::getenv("LK_GAP_DEBUG")) std::fprintf(stderr, "%s: %s\n", effect.name.c_str(), summary.BriefReport().c_str());
  std::vector<double> r;
  const double polished_loss = recent.find(polished, &r) ? sumOfSquares(r) : objective.loss(polished);
  return polished_loss < sumOfSquares(r0) ? polished : theta;
}

namespace {

/// A line search's axis: the logarithm of a log-scale parameter, else the parameter itself.
double toAxis(const EffectParameter& p, double v) { return p.log_scale ? std::log(v) : v; }
double fromAxis(const EffectParameter& p, double u) { return p.log_scale ? std::exp(u) : u; }

/// The grid of a line search over [lo, hi], on the axis.
std::vector<double> axisGrid(const EffectParameter& p, double lo, double hi, int points) {
  const double ua = toAxis(p, lo), ub = toAxis(p, hi);
  std::vector<double> grid(points);
  for (int i = 0; i < points; ++i) grid[i] = ua + (ub - ua) * i / (points - 1);
  return grid;
}

/// The order in which a constrained line search checks its grid's closed loops: by replay loss, ties to
/// the lower index (the replays evaluated on `threads` threads, each loss in its place).
std::vector<std::size_t> scanOrder(const CandidateObjective& objective, const std::function<std::vector<double>(std::size_t)>& pointAt,
                                   std::vector<double>* replayed, int threads) {
  parallelFor(replayed->size(), threads, [&](std::size_t i) { (*replayed)[i] = objective.replayLoss(pointAt(i)); });
  std::vector<std::size_t> order(replayed->size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return (*replayed)[a] < (*replayed)[b]; });
  return order;
}

}  // namespace

std::vector<std::vector<double>> constrainedScanOrder(const CandidateObjective& objective, const std::vector<double>& theta,
                                                      std::size_t j, double lo, double hi, int points, int threads) {
  const EffectParameter& p = objective.effect().params[j];
  const std::vector<double> grid = axisGrid(p, lo, hi, points);
  auto pointAt = [&](std::size_t i) {
    std::vector<double> t = theta;
    t[j] = fromAxis(p, grid[i]);
    return t;
  };
  std::vector<double> replayed(grid.size());
  std::vector<std::vector<double>> out;
  for (std::size_t i : scanOrder(objective, pointAt, &replayed, threads)) out.push_back(pointAt(i));
  return out;
}

double lineSearch(const CandidateObjective& objective, std::vector<double>& theta, std::size_t j, double lo, double hi,
                  int points, double current_loss, int threads) {
  const EffectParameter& p = objective.effect().params[j];
  auto withValue = [&](double value) {
    std::vector<double> t = theta;
    t[j] = value;
    return t;
  };
  auto lossAt = [&](double value) { return objective.loss(withValue(value)); };
  auto fromAxis = [&](double u) { return lane_keeping::diagnosis::fromAxis(p, u); };
  const std::vector<double> grid = axisGrid(p, lo, hi, points);
  std::vector<double> losses(points, std::numeric_limits<double>::infinity());
  auto pointAt = [&](std::size_t i) {
    std::vector<double> t = theta;
    t[j] = fromAxis(grid[i]);
    return t;
  };
  // The grid's points are independent (the objective is safe to call from several threads): side by
  // side, each loss in its place, so the search is the same whatever the threads.
  auto each = [&](std::size_t count, const std::function<void(std::size_t)>& body) { parallelFor(count, threads, body); };
  std::vector<double> replayed(points);  // under a stability requirement
  std::size_t best = 0;
  bool found_bounded = false;  // constrained, and a grid point's closed loop stays bounded
  if (!objective.constrained()) {
    each(static_cast<std::size_t>(points), [&](std::size_t i) { losses[i] = objective.loss(pointAt(i)); });
    best = static_cast<std::size_t>(std::min_element(losses.begin(), losses.end()) - losses.begin());
  } else {
    // Under a stability requirement a point's loss needs a closed-loop run, and only the grid's best point
    // matters here. A bounded point's loss is its replay loss, a diverging one's ranks after every bounded
    // one: so the replays first, then the closed loops in order of replay loss until the first bounded
    // point, which is the best (as min_element over every point's loss would find it, ties to the lower
    // index). The bounded refit of a column (issue 18) spent most of its time checking points of the grid
    // that could not be its best.
    const std::vector<std::size_t> order = scanOrder(objective, pointAt, &replayed, threads);
    bool& found = found_bounded;
    const std::size_t batch = static_cast<std::size_t>(std::max(1, threads));
    for (std::size_t k = 0, n = 1; k < order.size() && !found; k += n) {
      // A point whose loss is remembered (the bounded refit runs the first ones ahead, beside its
      // whole-log check: bounded_refit.cpp) costs nothing and is taken alone: if it is bounded, the scan
      // ends without running a batch beside it.
      n = objective.remembersLoss(pointAt(order[k])) ? 1 : std::min(batch, order.size() - k);
      each(n, [&](std::size_t m) { losses[order[k + m]] = objective.loss(pointAt(order[k + m])); });
      for (std::size_t m = 0; m < n && !found; ++m) {
        const std::size_t i = order[k + m];
        if (std::isfinite(losses[i]) && losses[i] == replayed[i]) {
          best = i;
          found = true;
        }
      }
    }
    if (!found) best = static_cast<std::size_t>(std::min_element(losses.begin(), losses.end()) - losses.begin());
  }
  // Brent's minimisation in the bracket around the best grid point (Boost.Math): parabolic steps
  // where the loss is smooth, golden-section ones where it is not, to ~1e-3 (|u| + 1/4) on the axis.
  // (It starts at the bracket's end, a grid point the objective's memo returns.) Golden section alone
  // took 861 replays for the searches of the benchmark's 60 s log (lk_bench_gap), Brent 690.
  const double a = grid[best > 0 ? best - 1 : 0], b = grid[std::min(best + 1, grid.size() - 1)];
  boost::uintmax_t iterations = search::kBrentIterations;
  double u = grid[best], loss = losses[best];
  if (found_bounded) {
    // Under a stability requirement, with a bounded grid point: Brent on the replay loss alone (no
    // closed loop), then one closed-loop run at its minimum. If that point leaves the bounds, the
    // constrained minimum along the line lies on the boundary between it and the bounded grid point:
    // bisection on boundedness finds it, each step one closed loop. (Brent on the constrained loss ran a
    // closed loop at each of its ~10 points, on a cliff where its parabolas do not help: 80 % of the
    // closed loops of a column's bounded refit, issue 18.)
    const auto [u_replay, loss_replay] = boost::math::tools::brent_find_minima(
        [&](double v) { return objective.replayLoss(withValue(fromAxis(v))); }, a, b, kLineSearchBits, iterations);
    auto bounded = [&](double v, double constrained_loss) {
      return std::isfinite(constrained_loss) && constrained_loss == objective.replayLoss(withValue(fromAxis(v)));
    };
    // With threads to spare, the closed loops the search may ask for next run beside the one it asks
    // for now: the objective remembers each point's loss, so the search takes the same path to the same
    // result whatever the threads, and a guess it does not ask for costs a spare thread's time. (On the
    // benchmark's small column lane change the refit's narrowed line ran its four 30 s closed loops,
    // 0.14 s each, one after the other.) `upcoming`: the point needed now, then the guesses, in order;
    // the first `threads` of them not yet remembered are run side by side.
    auto alongside = [&](const std::vector<double>& upcoming) {
      if (threads <= 1) return;
      std::vector<double> run;
      for (double v : upcoming) {
        if (static_cast<int>(run.size()) == threads) break;
        if (!objective.remembersLoss(withValue(fromAxis(v)))) run.push_back(v);
      }
      if (run.size() > 1) each(run.size(), [&](std::size_t k) { lossAt(fromAxis(run[k])); });
    };
    // From a bounded `inside` towards a diverging `outside` on the axis: each step one closed loop.
    // The guesses beside a step are the next steps' points if it stays bounded: inside a boundary the
    // loop crosses once, a wrong guess lies beyond a diverging midpoint and diverges too, most often as
    // soon (a bounded run lasts the whole log, a diverging one stops where it leaves the bounds).
    auto boundedPath = [&](double inside, double outside, int step) {
      std::vector<double> path;
      for (; step < kBoundaryBisections && std::fabs(outside - inside) > axisTolerance(inside); ++step) {
        inside = 0.5 * (inside + outside);
        path.push_back(inside);
      }
      return path;
    };
    auto bisect = [&](double inside, double outside) {
      for (int step = 0; step < kBoundaryBisections && std::fabs(outside - inside) > axisTolerance(inside); ++step) {
        const double mid = 0.5 * (inside + outside);
        alongside(boundedPath(inside, outside, step));
        const double mid_loss = lossAt(fromAxis(mid));
        if (bounded(mid, mid_loss)) {
          inside = mid;
          if (mid_loss < loss) {
            u = mid;
            loss = mid_loss;
          }
        } else {
          outside = mid;
        }
      }
    };
    constexpr double kUnchecked = std::numeric_limits<double>::infinity();
    // The first grid point the loop over the line's other boundaries below may check: the first
    // unchecked neighbour of a diverging grid point whose replay loss is below the best found (as
    // that loop finds them; the best found only falls before it runs, so it may check fewer).
    auto firstNeighbourToCheck = [&]() -> std::optional<double> {
      for (std::size_t i = 0; i < grid.size(); ++i) {
        if (losses[i] == kUnchecked || bounded(grid[i], losses[i]) || !(replayed[i] < loss)) continue;
        for (std::size_t n : {i - 1, i + 1}) {
          if (n < grid.size() && n != best && losses[n] == kUnchecked) return grid[n];
        }
      }
      return std::nullopt;
    };
    if (loss_replay < loss) {
      if (const std::optional<double> next = firstNeighbourToCheck()) alongside({u_replay, *next});
      const double at_minimum = lossAt(fromAxis(u_replay));
      if (bounded(u_replay, at_minimum)) {
        u = u_replay;
        loss = at_minimum;
      } else {
        bisect(grid[best], u_replay);
      }
    }
    // Elsewhere on the line the bounded region may end next to a diverging grid point whose replay loss
    // is below the best found: the constrained minimum may be on that boundary, between two grid points
    // (a column's damping line: the replay loss falls towards low damping, the loop diverges below ~6
    // N m s/rad, and the grid's best bounded point was the far end, 100). Each such diverging point's
    // neighbours are checked, and the boundary towards a bounded one bisected. (The best point's own
    // bracket was searched above.)
    for (std::size_t i = 0; i < grid.size(); ++i) {
      if (losses[i] == kUnchecked || bounded(grid[i], losses[i]) || !(replayed[i] < loss)) continue;
      for (std::size_t n : {i - 1, i + 1}) {  // (i - 1 wraps past the grid's end for i = 0)
        if (n >= grid.size() || n == best) continue;
        if (losses[n] == kUnchecked) {
          std::vector<double> upcoming = boundedPath(grid[n], grid[i], 0);
          upcoming.insert(upcoming.begin(), grid[n]);
          alongside(upcoming);
          losses[n] = objective.loss(pointAt(n));
        }
        if (bounded(grid[n], losses[n])) bisect(grid[n], grid[i]);
      }
    }
  } else {
    const auto [u_brent, loss_brent] = boost::math::tools::brent_find_minima(
        [&](double v) { return lossAt(fromAxis(v)); }, a, b, kLineSearchBits, iterations);
    if (loss_brent <= loss) {
      u = u_brent;
      loss = loss_brent;
    }
  }
  if (loss < current_loss) {
    theta[j] = fromAxis(u);
    return loss;
  }
  return current_loss;
}

std::pair<double, double> narrowedRange(const EffectParameter& p, double value) {
  if (p.log_scale) return {std::max(p.lower, value / 3.0), std::min(p.upper, value * 3.0)};
  const double span = 0.15 * (p.upper - p.lower);
  return {std::max(p.lower, value - span), std::min(p.upper, value + span)};
}

std::vector<double> coordinateFit(const CandidateObjective& objective, std::vector<double> theta, int threads) {
  const auto& params = objective.effect().params;
  if (theta.empty()) {
    for (const auto& p : params) theta.push_back(p.initial);
  }
  double loss = objective.loss(theta);
  for (int round = 0; round < (params.size() > 1 ? 2 : 1); ++round) {
    for (std::size_t j = 0; j < params.size(); ++j) {
      const auto& p = params[j];
      const auto [lo, hi] = round > 0 ? narrowedRange(p, theta[j]) : std::make_pair(p.lower, p.upper);
      loss = lineSearch(objective, theta, j, lo, hi, round == 0 ? search::kFirstRoundGrid : search::kSecondRoundGrid, loss,
                        threads);
    }
  }
  return theta;
}

/// Under LK_GAP_DEBUG, each phase of a fit: its seconds and the objective's replays so far.
class FitPhases {
 public:
  explicit FitPhases(const CandidateEffect& effect)
      : effect_(effect), on_(std::getenv("LK_GAP_DEBUG") != nullptr), last_(std::chrono::steady_clock::now()) {}
  void done(const std::string& phase, std::size_t replays) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "%s %s: %.3f s, %zu replays of its data so far\n", effect_.label().c_str(), phase.c_str(),
                 std::chrono::duration<double>(now - last_).count(), replays);
    last_ = now;
  }
  void restart() { last_ = std::chrono::steady_clock::now(); }

 private:
  const CandidateEffect& effect_;
  bool on_;
  std::chrono::steady_clock::time_point last_;
};

std::vector<double> leastSquaresFit(const CandidateObjective& objective, std::size_t coarse_stride, std::string* note) {
  const std::size_t p = objective.effect().params.size();
  const bool profile = objective.effect().profile;
  // Each search held to its budget (evaluation_budget.h): the most its constants let it evaluate.
  auto budgeted = [&](const CandidateObjective& on, const EvaluationBudget& budget, auto&& run) {
    struct Lifted {  // also when the search throws
      const CandidateObjective& on;
      ~Lifted() { on.limit({}); }
    } lifted{on};
    on.limit(budget);
    std::vector<double> theta = run();
    if (on.budgetSpent() && note != nullptr) *note += (note->empty() ? "" : "; ") + budgetSpentNote("its search", budget);
    return theta;
  };
  if (profile || coarse_stride <= 1) {
    return budgeted(objective, fitSearchBudget(p, profile), [&] {
      return profile ? coordinateFit(objective) : polish(objective, coordinateFit(objective), search::kSearchPolishSteps);
    });
  }
  // Coarse to fine: the search (~20 evaluations per parameter and round) and a first polish run on a
  // coarse_stride-th of the data and find the optimum's neighbourhood; one Levenberg-Marquardt step on
  // all of it moves to the optimum of all the data (a Gauss-Newton step from near the optimum of a third
  // of the same manoeuvres; a second step moved the benchmark's 60 s log's shrink by 0.03 points). The
  // search keeps its second round: with one, the column's fit on the small lane change stopped in
  // another, bounded optimum of its flat stiffness-damping valley (held-out shrink 87.8 % instead of
  // the 100 % its bounded refit reaches).
  // (At least every coarse_stride-th piece; a long log's square root of its pieces, coarseFitData.)
  const double piece = objective.replayOptions().chassis_horizon;
  const std::vector<Dataset> coarse = coarseFitData(objective.data(), piece, coarse_stride);
  const CandidateObjective coarse_objective = objective.on(coarse);
  FitPhases phases(objective.effect());
  const std::vector<double> coarse_polished = budgeted(coarse_objective, fitSearchBudget(p, false), [&] {
    const std::vector<double> searched = coordinateFit(coarse_objective);
    phases.done("coarse search on " + std::to_string(pieceCount(coarse, piece)) + " of " +
                    std::to_string(pieceCount(objective.data(), piece)) + " pieces",
                coarse_objective.evaluations());
    const std::vector<double> polished = polish(coarse_objective, searched, search::kSearchPolishSteps);
    phases.done("coarse polish", coarse_objective.evaluations());
    return polished;
  });
  const std::vector<double> polished = budgeted(objective, fitFinalStepBudget(p), [&] {
    return polish(objective, coarse_polished, search::kFinalPolishSteps);
  });
  phases.done("polish on all", objective.evaluations());
  return polished;
}

std::vector<double> warmStartFit(const CandidateObjective& objective, std::vector<double> theta, std::size_t coarse_stride,
                                 int final_steps) {
  const auto& params = objective.effect().params;
  if (objective.effect().profile) {
    double loss = objective.loss(theta);
    for (std::size_t j = 0; j < params.size(); ++j) {
      const auto [lo, hi] = narrowedRange(params[j], theta[j]);
      loss = lineSearch(objective, theta, j, lo, hi, search::kSecondRoundGrid, loss);
    }
    return theta;
  }
  if (coarse_stride > 1) {
    const std::vector<Dataset> coarse = coarseFitData(objective.data(), objective.replayOptions().chassis_horizon, coarse_stride);
    theta = polish(objective.on(coarse), theta, search::kSearchPolishSteps);
  }
  return polish(objective, theta, final_steps);
}

bool pinnedAtBound(const CandidateEffect& effect, const std::vector<double>& theta, const std::vector<double>& sigma) {
  return pinnedParameterCount(effect, theta, sigma) > 0;
}

std::size_t pinnedParameterCount(const CandidateEffect& effect, const std::vector<double>& theta,
                                 const std::vector<double>& sigma, const SimConfig* nominal) {
  std::size_t pinned = 0;
  std::size_t as_nominal = 0;  // at the bound the nominal's value lies at or beyond
  for (std::size_t i = 0; i < theta.size() && i < effect.params.size(); ++i) {
    const auto& p = effect.params[i];
    const double span = p.log_scale ? std::log(p.upper / p.lower) : (p.upper - p.lower);
    const double from_lower = p.log_scale ? std::log(theta[i] / p.lower) : theta[i] - p.lower;
    const double from_upper = p.log_scale ? std::log(p.upper / theta[i]) : p.upper - theta[i];
    const double distance = std::min(from_lower, from_upper);
    if (!(distance < 0.01 * span)) continue;
    // The standard error on the axis the distance is measured on (d log theta = d theta / theta).
    const double s = i < sigma.size() ? (p.log_scale ? sigma[i] / std::fabs(theta[i]) : sigma[i]) : kNaN;
    const bool placed_off = std::isfinite(s) && distance >= 3.0 * s && distance >= 0.001 * span;
    if (placed_off) continue;
    if (nominal != nullptr && p.nominal) {
      const double held = p.nominal(*nominal);
      if (from_lower <= from_upper ? held <= p.lower : held >= p.upper) {
        ++as_nominal;
        continue;
      }
    }
    ++pinned;
  }
  const std::size_t off_bounds = std::min(theta.size(), effect.params.size()) - pinned - as_nominal;
  return off_bounds > 0 ? pinned : pinned + as_nominal;
}

void scoreFit(const CandidateObjective& objective, const std::vector<double>& theta, const FitContext& context,
              const DiagnosisOptions& options, CandidateFit* out, int threads) {
  CandidateFit& fit = *out;
  const std::vector<Dataset>& heldout = *context.held;
  const Evaluation& nominal_train = *context.nominal_train;
  const Evaluation& nominal_heldout = *context.nominal_held;
  const CandidateEffect& effect = objective.effect();
  fit.theta = theta;
  fit.corrected = objective.configFor(theta);
  fit.change = objective.changeFor(theta);

  // The replays the scores need are independent of one another: the training data at theta (the
  // training scores, and the residuals the uncertainty needs), the held-out data at theta, and the
  // training data at each parameter's forward step. Side by side on `threads` (each in its place, so the
  // scores are the same whatever the threads), for a bounded refit, which runs alone after the other
  // fits. (Its p + 2 replays are a small part of it: 0.06-0.07 s of the small column lane change's ~2 s
  // refit one after the other, 0.04-0.05 s side by side; more on a longer log.)
  const std::set<std::string>& changed = objective.subsystems();
  const bool reuse = changed.count("chassis") == 0;
  const std::size_t p = theta.size();
  std::vector<double> steps(p);
  for (std::size_t j = 0; j < p; ++j) {
    // A relative step of 1e-4 leaves an error of that order in sigma, which the report prints to two digits.
    steps[j] = 1e-4 * std::max(std::fabs(theta[j]), effect.params[j].log_scale ? 1e-3 : 1e-3 * (effect.params[j].upper - effect.params[j].lower));
  }
  Evaluation train_ev, held_ev;
  std::vector<std::vector<double>> stepped(p);
  std::vector<char> stepped_ok(p, 0);
  parallelFor(p + 2, threads, [&](std::size_t k) {
    if (k == 0) {
      train_ev = objective.evaluation(theta);
    } else if (k == 1) {
      held_ev = evaluate(fit.change, heldout, changed, options.replay, reuse ? &nominal_heldout.sigma1 : nullptr);
    } else {
      std::vector<double> tp = theta;
      tp[k - 2] += steps[k - 2];
      stepped_ok[k - 2] = objective.residuals(tp, &stepped[k - 2]);
    }
  });

  // 1-sigma uncertainty from the Gauss-Newton covariance s^2 (J^T J)^-1 at the optimum (forward
  // differences in SI units, from the training replays above: p replays, not central differences' 2p).
  // Residuals of neighbouring samples are correlated, so this is a lower bound.
  // (The local curvature of the least-squares loss, also at a fit held to a stable closed loop.)
  std::vector<double> r_opt;
  if (objective.residuals(theta, train_ev, &r_opt)) {
    const std::size_t n = r_opt.size();
    Eigen::MatrixXd J(n, p);
    bool ok = true;
    for (std::size_t j = 0; j < p && ok; ++j) {
      const std::vector<double>& rp = stepped[j];
      ok = stepped_ok[j] && rp.size() == n;
      for (std::size_t i = 0; ok && i < n; ++i) J(i, j) = (rp[i] - r_opt[i]) / steps[j];
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

  const std::size_t pinned = pinnedParameterCount(effect, theta, fit.sigma, context.nominal);
  fit.at_bound = pinned > 0;
  fit.at_bound_everywhere = pinned > 0 && pinned == theta.size();
  fit.implausible = implausibleMagnitude(effect, theta, fit.corrected, options.max_side_force);

  // Scores: training and held-out, all subsystems (unchanged ones keep their nominal scores).
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
  fit.train_evaluation = std::make_shared<const Evaluation>(std::move(train_ev));
  fit.heldout_evaluation = std::make_shared<const Evaluation>(std::move(held_ev));
  fit.ok = true;
}

CandidateFit fitCandidate(const CandidateEffect& effect, const FitContext& context, const DiagnosisOptions& options) {
  CandidateFit fit;
  fit.effect = &effect;
  CandidateObjective objective(effect, *context.nominal, *context.train, options.replay, context.nominal_train->sigma1,
                               context.available);
  std::vector<double> theta;
  FitPhases phases(effect);
  try {
    const std::vector<double>* start = nullptr;
    if (context.warm_start != nullptr) {
      const auto it = context.warm_start->find(effect.label());
      if (it != context.warm_start->end() && it->second.size() == effect.params.size()) start = &it->second;
    }
    if (start != nullptr) {
      theta = warmStartFit(objective, *start, options.coarse_fit_stride, context.warm_final_steps);
    } else {
      theta = leastSquaresFit(objective, options.coarse_fit_stride, &fit.note);
    }
  } catch (const std::exception& e) {
    fit.note = std::string("fit failed: ") + e.what();
    return fit;
  }
  phases.restart();
  scoreFit(objective, theta, context, options, &fit);
  phases.done("scores", objective.evaluations());
  // Scored first: whether the verdict reads this fit's closed loop depends on its held-out gap.
  if (context.closed_loop_checks && checkedAsFitted(fit, context.where_subsystem, options.min_shrink)) {
    try {
      checkClosedLoop(objective, context, &fit);
    } catch (const std::exception& e) {
      fit.ok = false;
      fit.note = std::string("fit failed: ") + e.what();
      return fit;
    }
    phases.done("closed-loop checks", objective.evaluations());
  }
  return fit;
}

}  // namespace diagnosis
}  // namespace lane_keeping
