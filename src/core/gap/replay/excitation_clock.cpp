#include "lane_keeping/gap/replay/excitation_clock.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>

#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"
#include "lane_keeping/gap/replay/tracker_replay.h"

namespace lane_keeping {
namespace {

constexpr double kSearchHalfWidth = 60.0;  ///< [s] around each origin
constexpr double kSnap = 1e-3;             ///< [s] an offset this close to an origin is that origin
constexpr double kFits = 0.9;              ///< coherence at which the log's clock is kept
constexpr double kFound = 0.7;             ///< coherence below which no offset is trusted

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof(text), pattern, a, b, c);
  return text;
}

}  // namespace

ExcitationClock estimateExcitationClock(const SimConfig& config, const LogSignals& log) {
  ExcitationClock out;
  if (!(config.tracker.excitation_amplitude > 0.0) || !replayUnavailable("tracker", log.log()).empty()) return out;
  const auto sines = PathTracker(config.tracker, createPath(config.path)).excitationComponents();
  if (sines.empty()) return out;
  // The tracker's law alone on the logged pose; what delta_des holds beyond it is the excitation.
  SimConfig plain = config;
  plain.tracker.excitation_amplitude = 0.0;
  const SubsystemReplay replay = replayTracker(plain, log, {{log.start(), log.end() + 1e-9}});
  if (replay.traces.empty()) return out;
  const ReplayTrace& trace = replay.traces.front();
  const std::size_t n = trace.t.size(), k_count = sines.size(), columns = 2 * k_count + 3;
  if (n < 4 * columns) return out;
  const double t_ref = trace.t.front(), span = std::max(trace.t.back() - t_ref, 1e-9);
  // Least squares of the residual on every sine (sin and cos at s = t - t_ref) and a quadratic drift (the
  // law's own slow mismatch), by normal equations accumulated row by row (no n x columns matrix).
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(columns, columns);
  Eigen::VectorXd right = Eigen::VectorXd::Zero(columns), row(columns);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = trace.t[i] - t_ref, u = s / span;
    for (std::size_t k = 0; k < k_count; ++k) {
      const double w = 2.0 * M_PI * sines[k].frequency;
      row[2 * k] = std::sin(w * s);
      row[2 * k + 1] = std::cos(w * s);
    }
    row[2 * k_count] = 1.0;
    row[2 * k_count + 1] = u;
    row[2 * k_count + 2] = u * u;
    normal.selfadjointView<Eigen::Lower>().rankUpdate(row);
    right += row * (trace.measured[i] - trace.predicted[i]);
  }
  normal.triangularView<Eigen::Upper>() = normal.transpose();
  const Eigen::VectorXd coef = normal.ldlt().solve(right);
  // Sine k of the residual: m_k sin(w_k s + theta_k). The multisine at the log's t + c has the phase
  // w_k (t_ref + c) + phi_k there.
  std::vector<double> magnitude(k_count), theta(k_count);
  double magnitudes = 0.0, amplitudes = 0.0;
  for (std::size_t k = 0; k < k_count; ++k) {
    magnitude[k] = std::hypot(coef[2 * k], coef[2 * k + 1]);
    theta[k] = std::atan2(coef[2 * k + 1], coef[2 * k]);
    magnitudes += magnitude[k];
    amplitudes += sines[k].amplitude;
  }
  if (!(magnitudes > 0.0) || !std::isfinite(magnitudes)) return out;
  auto coherence = [&](double c) {
    double sum = 0.0;
    const double clock = t_ref + c;  // exact when c is near -t_ref (a log of epoch seconds)
    for (std::size_t k = 0; k < k_count; ++k) {
      const double phase = std::fmod(2.0 * M_PI * sines[k].frequency * clock, 2.0 * M_PI);
      sum += magnitude[k] * std::cos(phase + sines[k].phase - theta[k]);
    }
    return sum / magnitudes;
  };
  out.coherence_at_log_clock = coherence(0.0);
  out.coherence = out.coherence_at_log_clock;
  if (out.coherence_at_log_clock >= kFits) return out;  // the usual case: no search
  // Grid fine enough for the fastest sine (16 points a period), around both origins, then golden section.
  double f_max = 0.0;
  for (const auto& sine : sines) f_max = std::max(f_max, sine.frequency);
  const double step = 1.0 / (16.0 * f_max);
  double best = 0.0, best_value = out.coherence_at_log_clock;
  for (const double origin : {0.0, -log.start()}) {
    for (double c = origin - kSearchHalfWidth; c <= origin + kSearchHalfWidth; c += step) {
      const double v = coherence(c);
      if (v > best_value) {
        best_value = v;
        best = c;
      }
    }
  }
  double a = best - step, b = best + step;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 60; ++it) {
    const double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
    if (coherence(x1) > coherence(x2)) b = x2;
    else a = x1;
  }
  best = 0.5 * (a + b);
  for (const double origin : {0.0, -log.start()}) {
    if (std::fabs(best - origin) < kSnap) best = origin;
  }
  out.best_offset = best;
  out.coherence = std::max(coherence(best), best_value);
  if (out.coherence_at_log_clock >= kFits || out.coherence - out.coherence_at_log_clock < 0.05) return out;
  const std::string found = format("coherence %.2f at the log's t %+.6g s, %.2f on the log's own clock", out.coherence,
                                   best, out.coherence_at_log_clock);
  if (out.coherence < kFound || magnitudes < 0.3 * amplitudes) {
    out.note = "the identification excitation was not found in delta_des as configured (" + found +
               "; its sines at " + format("%.2g", magnitudes / amplitudes) +
               " of their amplitude): the replays run it on the log's clock";
    return out;
  }
  // A channel logged late moves the tracker's law with the excitation; a clock of another origin moves
  // the excitation alone. Compare both readings where the law is known at the shifted times.
  const PathTracker excitation(config.tracker, createPath(config.path));
  double only_excitation = 0.0, whole_channel = 0.0;
  std::size_t j = 0, common = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double shifted = trace.t[i] + best;
    if (shifted < trace.t.front() || shifted > trace.t.back()) continue;
    while (j + 1 < n && trace.t[j + 1] <= shifted) ++j;
    const std::size_t j1 = std::min(j + 1, n - 1);
    const double w = trace.t[j1] > trace.t[j] ? (shifted - trace.t[j]) / (trace.t[j1] - trace.t[j]) : 0.0;
    const double law_shifted = trace.predicted[j] + w * (trace.predicted[j1] - trace.predicted[j]);
    const double e = excitation.excitation(trace.t[i] + best).delta_des;
    only_excitation += std::pow(trace.measured[i] - trace.predicted[i] - e, 2);
    whole_channel += std::pow(trace.measured[i] - law_shifted - e, 2);
    ++common;
  }
  if (common > n / 4 && whole_channel < 0.8 * only_excitation) {
    out.note = format("delta_des looks logged %.3g s ", std::fabs(best)) + (best < 0.0 ? "late" : "early") +
               ", the tracker's law and its identification excitation alike: a channel's latency, left to the "
               "diagnosis (" + found + ")";
    return out;
  }
  out.offset = best;
  out.note = format("the identification excitation in delta_des runs on the log's t %+.9g s (", best) + found +
             "): its clock's origin is not the log's; the replays and simulations of this run use that clock";
  return out;
}

}  // namespace lane_keeping
