#include "lane_keeping/gap/decision/closed_loop_placement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "lane_keeping/common/brief_number.h"
#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/gap/decision/forward_selection.h"
#include "lane_keeping/gap/decision/how_far.h"
#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/fit/candidate_objective.h"
#include "lane_keeping/gap/replay/closed_loop_replay.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Points of the first scan along a direction, and of the second around its best point.
constexpr int kScanPoints = 9;
constexpr int kRefinePoints = 4;

/// The training runs' closed loop with a change, net of each log's noise: RMS over the runs (+inf where a
/// run's loop gives no gap — diverged or unschedulable).
class TrainingClosedLoop {
 public:
  TrainingClosedLoop(const std::vector<RunData>& runs, const DiagnosisOptions& options)
      : runs_(runs), starts_(closedLoopStarts(runs, options)) {
    for (const RunData& run : runs) floors_.push_back(closedLoopFloor(*run.log));
  }
  double net(const ConfigChange* change) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      const SimConfig config = change != nullptr ? changed(*runs_[i].config, *change) : *runs_[i].config;
      const double g = netClosedLoopGap(closedLoopReplay(config, *runs_[i].log, starts_[i]), floors_[i]);
      if (!std::isfinite(g)) return kInf;
      sum += g * g;
    }
    return std::sqrt(sum / static_cast<double>(runs_.size()));
  }
  std::size_t runs() const { return runs_.size(); }

 private:
  const std::vector<RunData>& runs_;
  std::vector<double> starts_;
  std::vector<std::array<double, 3>> floors_;
};

struct ScanPoint {
  std::vector<double> x;  // fit space
  double loss = kInf, net = kInf;
};

}  // namespace

ClosedLoopPlacement placeByClosedLoop(const CandidateFit& fit, const FitContext& context, const std::vector<RunData>& runs,
                                      const DiagnosisOptions& options) {
  ClosedLoopPlacement out;
  out.theta = fit.theta;
  if (!fit.ok || fit.effect == nullptr || fit.theta.empty() || runs.empty() || !options.closed_loop ||
      !context.closed_loop_checks) {
    return out;
  }
  const CandidateEffect& effect = *fit.effect;
  const std::size_t p = fit.theta.size();
  const CandidateObjective objective(effect, *context.nominal, *context.train, options.replay,
                                     context.nominal_train->sigma1, context.available);
  const TrainingClosedLoop loop(runs, options);
  std::mutex count_mutex;
  auto closedLoopAt = [&](const std::vector<double>& theta) {
    const ConfigChange change = objective.changeFor(theta);
    const double net = loop.net(&change);
    std::lock_guard<std::mutex> lock(count_mutex);
    out.closed_loops += loop.runs();
    return net;
  };

  // The fit, the nominal, and the replays' Jacobian in fit space (p + 1 replays, side by side).
  const std::vector<double> x0 = objective.toFitSpace(fit.theta);
  std::vector<double> lower(p), upper(p);
  for (std::size_t j = 0; j < p; ++j) {
    lower[j] = effect.params[j].lower;
    upper[j] = effect.params[j].upper;
  }
  const std::vector<double> xlo = objective.toFitSpace(lower), xhi = objective.toFitSpace(upper);
  std::vector<std::vector<double>> residuals(p + 1);
  std::vector<char> residuals_ok(p + 1, 0);
  std::vector<double> steps(p);
  for (std::size_t j = 0; j < p; ++j) steps[j] = 1e-3 * (xhi[j] - xlo[j]);
  parallelFor(p + 3, options.threads, [&](std::size_t k) {
    if (k == p + 1) {
      out.nominal_net = loop.net(nullptr);
    } else if (k == p + 2) {
      out.fit_net = closedLoopAt(fit.theta);
    } else {
      std::vector<double> x = x0;
      if (k > 0) x[k - 1] += (x[k - 1] + steps[k - 1] <= xhi[k - 1] ? 1.0 : -1.0) * steps[k - 1];
      residuals_ok[k] = objective.residuals(objective.toTheta(x.data()), &residuals[k]);
    }
  });
  if (!residuals_ok[0] || !std::isfinite(out.fit_net) || !std::isfinite(out.nominal_net)) return out;
  out.fit_loss = sumOfSquares(residuals[0]);
  const std::size_t n = residuals[0].size();
  Eigen::MatrixXd J(n, p);
  for (std::size_t j = 0; j < p; ++j) {
    if (!residuals_ok[j + 1] || residuals[j + 1].size() != n) return out;
    const double h = (x0[j] + steps[j] <= xhi[j] ? 1.0 : -1.0) * steps[j];
    for (std::size_t i = 0; i < n; ++i) J(i, j) = (residuals[j + 1][i] - residuals[0][i]) / h;
  }
  // Directions the replays determine least first: the loss rises as |J s|^2 = lambda s^2 along an
  // eigenvector of J^T J, so the tolerance allows |s| <= sqrt(tolerance * loss / lambda) along it.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(J.transpose() * J);
  const double allowed = out.fit_loss * (1.0 + kPlacementReplayTolerance);

  ScanPoint best{x0, out.fit_loss, out.fit_net};
  auto scan = [&](const std::vector<double>& from, const Eigen::VectorXd& v, double s_lo, double s_hi, int points) {
    std::vector<ScanPoint> grid;
    for (int k = 0; k < points; ++k) {
      const double s = points == 1 ? 0.5 * (s_lo + s_hi) : s_lo + (s_hi - s_lo) * k / (points - 1);
      ScanPoint q;
      q.x = from;
      for (std::size_t j = 0; j < p; ++j) q.x[j] = std::clamp(from[j] + s * v(static_cast<Eigen::Index>(j)), xlo[j], xhi[j]);
      grid.push_back(q);
    }
    parallelFor(grid.size(), options.threads, [&](std::size_t k) {
      const std::vector<double> theta = objective.toTheta(grid[k].x.data());
      grid[k].loss = objective.replayLoss(theta);
      // The replays first: a point they can tell from the fit costs no closed loop.
      if (grid[k].loss <= allowed) grid[k].net = closedLoopAt(theta);
    });
    for (const ScanPoint& q : grid) {
      if (q.loss <= allowed && q.net < best.net) best = q;
    }
  };
  for (Eigen::Index d = 0; d < static_cast<Eigen::Index>(p); ++d) {
    const double lambda = eigen.eigenvalues()(d);
    const Eigen::VectorXd v = eigen.eigenvectors().col(d);
    // The reach the tolerance allows on the quadratic model, within the parameters' ranges.
    double reach = lambda > 0.0 ? std::sqrt(kPlacementReplayTolerance * out.fit_loss / lambda) : kInf;
    double span = 0.0;
    for (std::size_t j = 0; j < p; ++j) span = std::max(span, std::fabs(v(static_cast<Eigen::Index>(j))) > 0.0 ?
                                                                  (xhi[j] - xlo[j]) / std::fabs(v(static_cast<Eigen::Index>(j))) : 0.0);
    reach = std::min(reach, 0.5 * span);
    if (!(reach > 0.0) || !std::isfinite(reach)) continue;
    const std::vector<double> from = best.x;
    scan(from, v, -reach, reach, kScanPoints);
    // Then around the best point of that scan, at a quarter of its spacing.
    const double spacing = 2.0 * reach / (kScanPoints - 1);
    const std::vector<double> around = best.x;
    scan(around, v, -0.75 * spacing, 0.75 * spacing, kRefinePoints);
  }
  const std::vector<double> theta = objective.toTheta(best.x.data());
  std::string values;
  for (std::size_t j = 0; j < p; ++j) {
    values += (j ? ", " : "") + effect.params[j].name + " " + briefNumber(fit.theta[j]) + " -> " + briefNumber(theta[j]);
  }
  const std::string figures =
      "the training runs' closed loop net of noise " + briefNumber(out.fit_net) + " -> " + briefNumber(best.net) +
      " (nominal " + briefNumber(out.nominal_net) + "), the replays' training loss " + briefNumber(out.fit_loss) +
      " -> " + briefNumber(best.loss) + " (" + std::to_string(out.closed_loops) + " closed-loop runs)";
  if (out.fit_net - best.net >= kPlacementMinGain * out.nominal_net) {
    out.placed = true;
    out.theta = theta;
    out.note = "placed by the closed loop: " + values + ": " + figures;
  } else {
    out.note = "not placed by the closed loop (no value the replays cannot tell from the fit takes the training "
               "runs' closed loop nearer the logs by " + briefNumber(100.0 * kPlacementMinGain) +
               " % of the nominal's gap): best " + values + ": " + figures;
  }
  return out;
}

bool verdictNames(const GapReport& report, const CandidateFit& fit) {
  if (fit.effect == nullptr || report.verdict.effects.size() != 1) return false;
  const VerdictEffect& named = report.verdict.effects.front();
  // Its form, or its form first among forms the data cannot tell apart ("pose or ...").
  return named.effect == fit.effect->name &&
         (named.form == fit.effect->form || named.form.rfind(fit.effect->form + " or ", 0) == 0);
}

bool placementApplies(const GapReport& report, const DiagnosisOptions& options) {
  const GapVerdict& v = report.verdict;
  const ClosedLoopGap& h = report.how_far;
  if (!options.closed_loop_placement || v.effect.empty() || v.effect == "unexplained" || v.basis != "replays" ||
      v.effects.size() != 1 || v.effects.front().measured) {
    return false;
  }
  // The closed loop must see the gap, and the fit's must leave something of it: a net gap below
  // kClosedLoopVisible of the floor is within what the floor's estimate can tell (nothing to place on: the
  // candidates' family's friction, tire lags and limit that closed less than their replays were left at
  // 0.16-0.33 of their floors and no value moved them by kPlacementMinGain; the placed ones at 0.88-2.7).
  if (!std::isfinite(h.net_before) || !std::isfinite(h.net_after) || !std::isfinite(h.noise_floor) ||
      !(h.net_before >= kClosedLoopVisible * h.noise_floor) || !(h.net_after >= kClosedLoopVisible * h.noise_floor) ||
      !(v.shrink > 0.0)) {
    return false;
  }
  return 1.0 - h.net_after / h.net_before < kPlacementTrigger * v.shrink;
}

void placeVerdict(const CandidateFit& winner, const FitContext& context, const std::vector<RunData>& training_runs,
                  const std::vector<RunData>& how_far_runs, bool in_sample, const DiagnosisOptions& options,
                  const DiagnosisOptions& how_far_options, GapReport* report, DiagnosisArtifacts* artifacts) {
  if (!verdictNames(*report, winner)) return;  // only the fit the verdict names is placed
  const ClosedLoopPlacement placement = placeByClosedLoop(winner, context, training_runs, options);
  if (placement.note.empty()) return;
  if (!placement.placed) {
    report->notes.push_back(winner.effect->label() + ": " + placement.note);
    return;
  }
  // The placed fit scored as the replays' was: its held-out replays go to the note, and how far reads its change
  // and its subsystems' held-out excess. The verdict's gap and shrink stay the replays' fit's: the evidence
  // that named the effect.
  CandidateFit placed = winner;
  const CandidateObjective objective(*winner.effect, *context.nominal, *context.train, options.replay,
                                     context.nominal_train->sigma1, context.available);
  scoreFit(objective, placement.theta, context, options, &placed, options.threads);
  GapReport with = *report;
  GapVerdict& v = with.verdict;
  VerdictEffect& e = v.effects.front();
  const VerdictEffect at_placed = verdictEffect(placed, *context.nominal);
  e.replay_params = e.params;
  e.params = at_placed.params;
  e.param_sigma = at_placed.param_sigma;
  e.config = at_placed.config;
  // How far again: its own notes replace the replays' fit's (a "still misses" note was of that fit).
  with.how_far = ClosedLoopGap{};
  with.notes.clear();
  DiagnosisArtifacts overlay;
  howFar(&placed, *context.nominal_held, how_far_runs, how_far_options, &with, artifacts != nullptr ? &overlay : nullptr);
  const std::string contradicted = closedLoopContradicts(with);
  std::string note = winner.effect->label() + ": " + placement.note;
  if (!contradicted.empty()) {
    report->notes.push_back(note + "; not kept: " + contradicted);
    return;
  }
  note += "; the held-out replays' gap " + briefNumber(winner.heldout_after) + " at the replays' fit, " +
          briefNumber(placed.heldout_after) + " placed (of " + briefNumber(v.gap_before) + "); how far " +
          briefNumber(report->how_far.net_before) + " -> " + briefNumber(report->how_far.net_after) + " at the replays' fit, " + briefNumber(with.how_far.net_after) + " placed, net of noise" +
          (in_sample ? " (in-sample: no run is held out, so the closed loop that placed it is the one how far is "
                       "measured on)" : " (on the held-out runs, which the placement did not see)");
  std::vector<std::string> notes;
  for (const std::string& n : report->notes) {
    if (n.rfind("how far: the corrected closed loop still misses", 0) != 0) notes.push_back(n);
  }
  for (const std::string& n : with.notes) {
    if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(n);
  }
  notes.push_back(note);
  v.reason += "; placed by the closed loop of the training runs among the values its replays cannot tell apart (" +
              placement.note.substr(placement.note.find(": ") + 2) + ")";
  with.notes = std::move(notes);
  *report = std::move(with);
  if (artifacts != nullptr) {
    artifacts->overlay_t = std::move(overlay.overlay_t);
    artifacts->overlay = std::move(overlay.overlay);
  }
}

}  // namespace diagnosis
}  // namespace lane_keeping
