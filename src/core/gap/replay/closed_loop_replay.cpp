#include "lane_keeping/gap/replay/closed_loop_replay.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>

#include "lane_keeping/gap/log/logged_speed.h"
#include "lane_keeping/gap/log/sensor_correction.h"
#include "lane_keeping/gap/replay/replay_shooting.h"
#include "lane_keeping/sim/closed_loop.h"

namespace lane_keeping {
namespace {

/// RMS about the mean, at least 1e-9 (what a channel's residual is measured against).
double spreadOf(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m += x;
  m /= static_cast<double>(std::max<std::size_t>(1, v.size()));
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::max(1e-9, std::sqrt(s / static_cast<double>(std::max<std::size_t>(1, v.size()))));
}

}  // namespace

SimConfig closedLoopConfigOnLog(SimConfig config, const LogSignals& log, double sigma1_0, double duration,
                                double log_rate) {
  const double t0 = log.start();
  InitialState& init = config.simulation.initial;
  // The simulation starts from the true state; the log holds what the sensors report (config.sensors),
  // which log/sensor_correction.h undoes.
  std::optional<LogSignals> undone;
  if (sensorsChangeTheLog(config.sensors)) undone.emplace(log.withSensorsUndone(config.sensors));
  const LogSignals& truth = undone ? *undone : log;
  init.x = truth.at(LogSignals::kX, t0);
  init.y = truth.at(LogSignals::kY, t0);
  init.psi = truth.at(LogSignals::kPsi, t0);
  init.delta = truth.at(LogSignals::kDelta, t0);
  init.sigma2 = truth.at(LogSignals::kYawRate, t0);
  init.sigma3 = truth.at(LogSignals::kDeltaRate, t0);
  init.sigma1 = std::isfinite(sigma1_0) ? sigma1_0 : (truth.has(LogSignals::kSigma1) ? truth.at(LogSignals::kSigma1, t0) : 0.0);
  config.simulation.duration = std::min(duration, log.end() - t0);
  // The simulation's t = 0 is the log's t0; the excitation runs on the log's t plus the run's own clock
  // offset (excitation_clock.h).
  config.tracker.excitation_clock_offset += t0;
  config.simulation.log_rate = std::min(log_rate, 1.0 / config.simulation.step);  // a row per plant step at most
  return withLoggedSpeed(std::move(config), log);  // a speed that varies is followed in time, as the car drove
}

ClosedLoopReplay closedLoopReplay(const SimConfig& config, const LogSignals& log, double sigma1_0,
                                  const std::vector<TimedChange>& changes) {
  ClosedLoopReplay out;
  const double t0 = log.start();
  const double rate = std::min(1000.0, 1.0 / std::max(1e-4, log.log().medianStep()));
  RunResult run;
  try {
    run = ClosedLoop(closedLoopConfigOnLog(config, log, sigma1_0, log.end() - t0, rate), changes).run();
  } catch (const std::exception& e) {
    out.note = std::string("closed-loop replay failed: ") + e.what();
    return out;
  }
  if (run.diverged()) out.note = "closed-loop replay " + run.message;
  std::vector<double> res_y, res_r, res_d;
  std::size_t k = 0;
  for (std::size_t i = 0; i < log.times().size(); ++i) {
    const double ts = log.times()[i] - t0;
    while (k + 1 < run.rows.size() && run.rows[k + 1].t <= ts) ++k;
    if (run.rows.empty() || ts > run.end_time) break;
    const LogRow& a = run.rows[k];
    const LogRow& b = run.rows[std::min(k + 1, run.rows.size() - 1)];
    const double w = b.t > a.t ? std::clamp((ts - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
    const double y = a.state.y + w * (b.state.y - a.state.y);
    const double r = a.state.sigma2 + w * (b.state.sigma2 - a.state.sigma2);
    const double d = a.state.delta + w * (b.state.delta - a.state.delta);
    out.t.push_back(log.times()[i]);
    out.y.push_back(y);
    out.yaw_rate.push_back(r);
    out.delta.push_back(d);
    res_y.push_back(log.samples(LogSignals::kY)[i] - y);
    res_r.push_back(log.samples(LogSignals::kYawRate)[i] - r);
    res_d.push_back(log.samples(LogSignals::kDelta)[i] - d);
  }
  auto rms = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x * x;
    return v.empty() ? 0.0 : std::sqrt(s / v.size());
  };
  if (res_y.empty()) return out;
  const double gy = rms(res_y) / spreadOf(log.samples(LogSignals::kY));
  const double gr = rms(res_r) / spreadOf(log.samples(LogSignals::kYawRate));
  const double gd = rms(res_d) / spreadOf(log.samples(LogSignals::kDelta));
  out.channel_gaps = {gy, gr, gd};
  out.gap = std::sqrt((gy * gy + gr * gr + gd * gd) / 3.0);
  return out;
}

std::array<double, 3> closedLoopNoiseFloor(const LogSignals& log, const std::array<double, 3>& sigma) {
  const LogSignals::Channel channels[3] = {LogSignals::kY, LogSignals::kYawRate, LogSignals::kDelta};
  std::array<double, 3> floor{};
  for (std::size_t c = 0; c < 3; ++c) {
    floor[c] = std::isfinite(sigma[c]) && sigma[c] > 0.0 ? sigma[c] / spreadOf(log.samples(channels[c])) : 0.0;
  }
  return floor;
}

double netClosedLoopGap(const ClosedLoopReplay& replay, const std::array<double, 3>& floor) {
  if (!std::isfinite(replay.gap)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    const double g = replay.channel_gaps[c];
    if (!std::isfinite(g)) return std::numeric_limits<double>::quiet_NaN();
    sum += std::max(0.0, g * g - floor[c] * floor[c]);
  }
  return std::sqrt(sum / 3.0);
}

LoopDivergence closedLoopDivergence(const SimConfig& config, const LogSignals& log, double sigma1_0, double horizon,
                                    double max_torque) {
  LoopDivergence out;
  RunResult run;
  const bool torque_bound = std::isfinite(max_torque);
  try {
    // Logged sparsely: the divergence monitor's verdict, and the torque if it is bounded.
    run = ClosedLoop(closedLoopConfigOnLog(config, log, sigma1_0, horizon, torque_bound ? 200.0 : 10.0)).run();
  } catch (const std::exception& e) {
    out.diverged = true;
    out.time = 0.0;
    out.message = e.what();
    return out;
  }
  if (run.diverged()) {
    out.diverged = true;
    out.time = run.end_time;
    out.message = run.message;
    return out;
  }
  for (const LogRow& row : run.rows) {
    if (torque_bound && !(std::fabs(row.torque_command) <= max_torque)) {
      out.diverged = true;
      out.time = row.t;
      out.message = "steering torque " + std::to_string(row.torque_command) + " N m at t = " + std::to_string(row.t) +
                    " s beyond +-" + std::to_string(max_torque) + " N m";
      break;
    }
  }
  return out;
}

}  // namespace lane_keeping
