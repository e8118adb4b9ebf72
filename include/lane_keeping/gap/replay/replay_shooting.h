#pragma once
/// The machinery the four subsystem replays share (subsystem_replay.h): trace normalisation and
/// segment bookkeeping, shooting intervals, the fixed-step RK4 driver, the tires' lead-in over the
/// logged motion before each interval, and the estimation of each interval's nuisance initial
/// conditions. Internal to the replays (namespace replay), not part of the diagnosis's interface.
#include <Eigen/Core>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_trace.h"
#include "lane_keeping/sim/etdrk4.h"
#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/tire/tire.h"
#include "lane_keeping/vehicle/single_track_model.h"

namespace lane_keeping {
namespace replay {

/// [s] of logged motion the steering and chassis replays run the tires' own equations over before
/// each shooting interval (several of their relaxation times at the benchmark's 15 m/s).
constexpr double kTireLeadIn = 0.1;

/// Copies `n` states from `from` to `to`: the steering and chassis replays integrate blocks of the model's
/// state that lie together there and in their own vectors (the steering system's and the front tire's;
/// both tires'), and copy them in, and their rates out, at every evaluation. Two loops through the
/// vectors' accessors, for 2-5 values each, were 8 % of the instructions of a motor-side column fit; this
/// loop, which the compiler turns into a call to memcpy, 5 % fewer in all (callgrind, 2026-11-28).
inline void copyStates(const double* __restrict from, int n, double* __restrict to) {
  for (int i = 0; i < n; ++i) to[i] = from[i];
}

/// Largest RK4 step that resolves a tire's fastest dynamics at `speed`: its relaxation lag
/// (relaxation length / V), the lumped LuGre transport (~ a / V) or, for the distributed tread, the
/// transport across one bristle spacing (L / (N - 1) / V: 0.34 ms at 40 bristles and 15 m/s; the
/// replays' 2-4 ms steps made a distributed tire blow up).
double tireStep(const Tire& tire, double speed);

/// Normalisation of an output: RMS about its mean over the whole log (never below a tiny floor).
double scaleOf(const std::vector<double>& v);

bool inSegments(double t, const std::vector<TimeSegment>& segments);

ReplayTrace makeTrace(const std::string& name, const std::vector<double>& measured_all);

/// The vehicle model a replay integrates: the configuration's, except that a log whose speed varies
/// (LogSignals::speedVaries) drives the speed itself (imposeLoggedSpeed), so the configured profiles (along
/// the road, in time) are off.
SingleTrackModel replayModel(const SimConfig& config, const LogSignals& log);
/// Sets V and dV/dt at `t` from the log into `model` when the log's speed varies; else from the
/// configuration's vehicle.speed_profile at t - log.start() if it has one (the run's t = 0 is the log's
/// start, as in the closed-loop replay), else nothing.
void imposeLoggedSpeed(SingleTrackModel& model, const LogSignals& log, double t, std::size_t* hint);

/// Shooting intervals [a, b) covering the segments.
std::vector<TimeSegment> shootingIntervals(const std::vector<TimeSegment>& segments, double horizon);

/// Noise level used for weighting: the estimate, but never below a small fraction of the scale (a
/// noise-free simulated log must not divide by zero).
double noiseFor(const LogSignals& log, LogSignals::Channel c, double scale);

/// Integrates from t0 to t1 in equal steps of at most h with a stepper of the form
/// step(stage_fn, dt, q) (Rk4, Etdrk4). For Rk4, f(t, q, d) writes the derivative; for Etdrk4 it
/// writes N, the derivative minus L q.
template <class F, class Stepper>
void integrate(F&& f, double t0, double t1, double h, Eigen::VectorXd& q, Stepper& stepper) {
  const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) / h - 1e-9)));
  const double dt = (t1 - t0) / steps;
  for (int k = 0; k < steps; ++k) {
    const double ta = t0 + k * dt;
    stepper.step([&](int stage, const Eigen::VectorXd& s, Eigen::VectorXd& d) {
      f(ta + (stage == 0 ? 0.0 : (stage == 3 ? dt : 0.5 * dt)), s, d);
    }, dt, q);
  }
}

/// Runs `attempt(h)` at the step h and, while the run leaves the model's domain, again at a quarter and
/// a sixteenth of it; `attempt` returns the sample at which its run left (std::nullopt: it stayed
/// inside). True once a run stays inside.
/// A shorter step helps where the step made the run unstable: that departure moves (or goes) with the
/// step. A run that leaves at the same sample at two steps in a row follows the model's own motion out of
/// the domain (a fitted column that lets the wheel swing past its stop), and no shorter step is tried.
/// (On the candidates' torque-limit lane change, diagnosed with the column candidates alone, 7,765 of
/// 35,818 runs of a steering interval left the domain at every step, 7,733 of them at the same sample at
/// h and h/4; their tries at h/16 were 1.1-1.3 s of 2.4-2.7 s of steering replays, one thread.)
template <class Attempt>
bool withShorterStepsWhereTheyHelp(double h, Attempt&& attempt) {
  std::optional<std::size_t> left_before;
  for (int tries = 0; tries < 3; ++tries, h *= 0.25) {
    const std::optional<std::size_t> left = attempt(h);
    if (!left) return true;
    if (left_before && *left == *left_before) return false;
    left_before = left;
  }
  return false;
}

/// The tires' states at t0 from the logged motion before it: settled at ta = max(log start,
/// t0 - kTireLeadIn), then their own equations driven by the logged motion up to t0 (Deur's lumped
/// LuGre relaxes over ~L / V = 13 ms at 15 m/s). Settling them at t0 instead left an aligning-moment
/// error at every interval start of the slip rate times that lag, which short intervals could not
/// forget. `set_motion(t)` writes the logged motion at t into `full` (the model's state vector; the
/// tire states in it are overwritten); the front tire's states come first, then, if `with_rear`, the
/// rear's. `full_dot` is scratch.
template <typename SetMotion>
Eigen::VectorXd tireStatesAfterLeadIn(const SingleTrackModel& model, bool with_rear, double log_start, double t0,
                                      double step, const SetMotion& set_motion, Eigen::VectorXd& full,
                                      Eigen::VectorXd& full_dot) {
  const int front0 = model.frontTireOffset(), front_n = model.frontTire().stateSize();
  const int rear0 = model.rearTireOffset(), rear_n = with_rear ? model.rearTire().stateSize() : 0;
  const double ta = std::max(log_start, t0 - kTireLeadIn);
  set_motion(ta);
  const auto c = model.contacts(full.data(), SingleTrackModel::Trig<double>(full[kDelta]));
  std::vector<double> settled(std::max(front_n, rear_n));
  Eigen::VectorXd z(front_n + rear_n);
  model.frontTire().steadyStateVector(c.front, settled.data());
  for (int i = 0; i < front_n; ++i) z[i] = settled[i];
  if (rear_n > 0) model.rearTire().steadyStateVector(c.rear, settled.data());
  for (int i = 0; i < rear_n; ++i) z[front_n + i] = settled[i];
  if (t0 > ta) {
    auto tires = [&](double t, const Eigen::VectorXd& state, Eigen::VectorXd& state_dot) {
      set_motion(t);
      for (int i = 0; i < front_n; ++i) full[front0 + i] = state[i];
      for (int i = 0; i < rear_n; ++i) full[rear0 + i] = state[front_n + i];
      const auto contacts = model.contacts(full.data(), SingleTrackModel::Trig<double>(full[kDelta]));
      model.frontTire().evaluate(contacts.front, full.data() + front0, full_dot.data() + front0);
      if (rear_n > 0) model.rearTire().evaluate(contacts.rear, full.data() + rear0, full_dot.data() + rear0);
      for (int i = 0; i < front_n; ++i) state_dot[i] = full_dot[front0 + i];
      for (int i = 0; i < rear_n; ++i) state_dot[front_n + i] = full_dot[rear0 + i];
    };
    Rk4 rk4(front_n + rear_n);
    integrate(tires, ta, t0, step, z, rk4);
  }
  return z;
}

/// One shooting interval with nuisance initial conditions, estimated by maximum a posteriori:
/// each nuisance starts at its logged value with a Gaussian prior of the measurement's noise
/// (`prior_sigma`), and the outputs are weighted by their measurement noise (`output_sigma`):
///   min  sum_c sum_k ((y_ck - f_ck(d)) / sigma_c)^2 + sum_j (d_j / prior_j)^2,
/// solved by one Gauss-Newton step on finite-difference sensitivities (the model is near linear in
/// its initial conditions over an interval). Without the priors, two free initial conditions would
/// fit any smooth short trace and hide the very effects sought.
/// `predicted` has the columns of `measured` plus `extra` columns projected with the same correction.
template <class Simulate>
bool shootWithNuisance(Simulate&& simulate, const Eigen::VectorXd& q0, const std::vector<int>& nuisance,
                       const std::vector<double>& prior_sigma, const Eigen::MatrixXd& measured,
                       const Eigen::VectorXd& output_sigma, bool estimate, Eigen::MatrixXd* predicted, int extra = 0) {
  const Eigen::Index rows = measured.rows(), fitted = measured.cols(), cols = fitted + extra;
  const Eigen::Index p = static_cast<Eigen::Index>(nuisance.size());
  Eigen::MatrixXd base(rows, cols);
  if (!simulate(q0, base)) {
    *predicted = base;
    return false;
  }
  *predicted = base;
  if (!estimate || nuisance.empty()) return true;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows * fitted + p, p);
  std::vector<Eigen::MatrixXd> sensitivities;
  Eigen::MatrixXd perturbed(rows, cols);
  for (Eigen::Index j = 0; j < p; ++j) {
    const double step = std::max(prior_sigma[j], 1e-9);
    Eigen::VectorXd q = q0;
    q[nuisance[j]] += step;
    if (!simulate(q, perturbed)) return true;  // keep the unprojected prediction
    sensitivities.push_back((perturbed - base) / step);
    for (Eigen::Index c = 0; c < fitted; ++c) J.block(c * rows, j, rows, 1) = sensitivities.back().col(c) / output_sigma[c];
    J(rows * fitted + j, j) = 1.0 / step;  // the prior
  }
  Eigen::VectorXd r = Eigen::VectorXd::Zero(rows * fitted + p);
  for (Eigen::Index c = 0; c < fitted; ++c) r.segment(c * rows, rows) = (measured.col(c) - base.col(c)) / output_sigma[c];
  const Eigen::VectorXd delta = J.colPivHouseholderQr().solve(r);
  if (!delta.allFinite()) return true;
  for (Eigen::Index j = 0; j < p; ++j) *predicted += delta[j] * sensitivities[j];
  return true;
}

}  // namespace replay
}  // namespace lane_keeping
