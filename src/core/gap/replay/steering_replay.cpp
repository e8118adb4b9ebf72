#include "lane_keeping/gap/replay/steering_replay.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "lane_keeping/gap/replay/replay_shooting.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

namespace {

/// Twist of a column transmitting `torque` at rest: torque / k, or for a progressive column the root
/// of k twist (1 + (twist / angle)^2) = torque (monotone cubic; Newton from the linear twist, which
/// overshoots, so the iterates decrease onto the root).
double staticColumnTwist(const SteeringParams& sp, double torque) {
  double twist = torque / sp.column_stiffness;
  const double a = sp.column_stiffening_angle;
  if (a <= 0.0) return twist;
  for (int i = 0; i < 30; ++i) {
    const double r = twist / a;
    const double f = sp.column_stiffness * twist * (1.0 + r * r) - torque;
    const double df = sp.column_stiffness * (1.0 + 3.0 * r * r);
    const double next = twist - f / df;
    if (std::fabs(next - twist) <= 1e-12 * (std::fabs(twist) + 1e-12)) return next;
    twist = next;
  }
  return twist;
}

/// The LuGre kingpin friction state (Deur eq 9) at every log sample, driven by the logged steering
/// rate w from the log's start (z = 0). Over a sample interval, w is held at its midpoint value, and
/// z' = w - sigma0 |w| z / g(w) is then linear in z: z relaxes exactly (exponential integrator, stable
/// at any sigma0) towards its sliding value sign(w) g(w) / sigma0. The state depends on the rate
/// history only, so the log gives it; held at the sliding value, a replay starting in presliding
/// (w near 0) started from the wrong side of the bristle.
std::vector<double> kingpinFrictionStates(const SteeringParams& sp, const LogSignals& log) {
  const auto& times = log.times();
  const auto& rate = log.samples(LogSignals::kDeltaRate);
  std::vector<double> z(times.size(), 0.0);
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double w = 0.5 * (rate[i - 1] + rate[i]);
    const double h = times[i] - times[i - 1];
    const double k = sp.friction_stiffness * std::fabs(w) / sp.lugreLevel(w);
    if (k * h < 1e-12) {
      z[i] = z[i - 1] + w * h;
      continue;
    }
    const double sliding = w / k;  // sign(w) g / sigma0
    z[i] = sliding + (z[i - 1] - sliding) * std::exp(-k * h);
  }
  return z;
}

/// Cubic Hermite interpolant at s in [0, 1] of a value x0 -> x1 with rates v0, v1 over a span of h.
double hermite(double x0, double v0, double x1, double v1, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * v0 + (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * h * v1;
}

}  // namespace

SubsystemReplay replaySteering(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                               const ReplayOptions& options, const std::vector<std::pair<double, double>>* sigma1) {
  SubsystemReplay out;
  out.name = "steering";
  // Lateral velocity of G: the chassis replay's model-based estimate where given (precise), else the
  // differentiated positions (noisy: the aligning moment needs sigma1 to a few mm/s).
  std::vector<double> sigma1_times, sigma1_values;
  if (sigma1 != nullptr) {
    for (const auto& [t, v] : *sigma1) {
      if (sigma1_times.empty() || t > sigma1_times.back()) {
        sigma1_times.push_back(t);
        sigma1_values.push_back(v);
      }
    }
  }
  std::size_t s1_cursor = 0;
  auto lateralVelocity = [&](double t) {
    if (sigma1_times.size() < 2 || t < sigma1_times.front() || t > sigma1_times.back()) {
      return log.has(C::kSigma1) ? log.at(C::kSigma1, t) : 0.0;
    }
    std::size_t j = std::min(s1_cursor, sigma1_times.size() - 2);
    while (j > 0 && sigma1_times[j] > t) --j;
    while (j + 2 < sigma1_times.size() && sigma1_times[j + 1] <= t) ++j;
    s1_cursor = j;
    const std::size_t i = j + 1;
    if (sigma1_times[i] - sigma1_times[j] > 0.05) return log.has(C::kSigma1) ? log.at(C::kSigma1, t) : 0.0;  // a gap between intervals
    const double w = (t - sigma1_times[j]) / (sigma1_times[i] - sigma1_times[j]);
    return sigma1_values[j] + w * (sigma1_values[i] - sigma1_values[j]);
  };
  SingleTrackModel model = replayModel(config, log);
  const int n_full = model.stateSize();
  const int steer0 = model.steeringStateOffset();
  const int steer_n = model.steering().stateSize();
  const int front0 = model.frontTireOffset();
  const int front_n = model.frontTire().stateSize();
  // Integrated states: delta, sigma3, the steering system's, the front tire's.
  const int n = 2 + steer_n + front_n;
  const double JF = config.vehicle.steering_inertia;
  const double torque_delay = config.delays.torque_to_plant;
  const double limit = config.simulation.divergence.max_steering_angle;

  Eigen::VectorXd full = Eigen::VectorXd::Zero(n_full), full_dot = Eigen::VectorXd::Zero(n_full);
  std::size_t hint = 0, torque_hint = 0, speed_hint = 0;
  // The front tire's states follow the steering system's in the model's state (single_track_model.h), as
  // they do in q after delta and sigma3: each evaluation copies them in, and their rates out, as one block.
  if (front0 != steer0 + steer_n) throw std::logic_error("replaySteering: the front tire's states do not follow the steering system's");
  const int carried = steer_n + front_n;
  // Deur eq 9's bristle relaxes at a = sigma0 |delta_dot| / g: in sliding, at the benchmark's sigma0 = 2e4, 1.3e4 1/s
  // at 1 rad/s, and a fit's low Coulomb levels (0.02 N m) push it past 1e6 1/s, where a step bounded by
  // 2 / a was a microsecond (a forward selection's LuGre fit took 160 s of a 20 s log). The step is bounded so
  // only down to kShortestBristleStep; where a h > 2 (beyond RK4's stability on the real axis, 2.78) the bristle
  // is sliding, and its rate is taken as the exact mean slope over a step of h with the rate held,
  // (z_ss - z)(1 - exp(-a h)) / h (z_ss = delta_dot / a, its sliding deflection), which RK4 steps stably at any a
  // and which leaves z at z_ss within a step as the exact solution does; elsewhere the rate is Deur's own.
  // (With the slope from a h > 1 and no relaxation bound at all, the LuGre fits lost accuracy: the candidates'
  // small friction lane change 87 -> 78 % held out.) Only without bristle damping (sigma1 = 0, the LuGre form's),
  // whose torque sigma1 z' the slope would change; with it the relaxation bounds the step as before.
  const SteeringParams& friction_params = model.steering();
  const bool sliding_slope = friction_params.lugreFriction() && friction_params.friction_damping == 0.0;
  const int bristle = steer0 + (friction_params.compliant() ? 2 : 0);  // z in the model's state
  double slope_step = 0.0;  // the step h of the run in progress (simulateWithStep)
  auto slidingSlope = [&](double rate) {
    const double a = friction_params.friction_stiffness * std::fabs(rate) / friction_params.lugreLevel(rate);
    if (!(a * slope_step > 2.0)) return;
    full_dot[bristle] = (rate / a - full[bristle]) * -std::expm1(-a * slope_step) / slope_step;
  };
  // Returns the position of t in the log, for the other channels read at t.
  auto assemble = [&](double t, const Eigen::VectorXd& q) {
    imposeLoggedSpeed(model, log, t, &speed_hint);
    const LogSignals::Position here = log.positionAt(t, &hint);
    full[kDelta] = q[0];
    full[kSigma3] = q[1];
    full[kSigma1] = lateralVelocity(t);
    full[kSigma2] = log.at(C::kYawRate, here);
    copyStates(q.data() + 2, carried, full.data() + steer0);
    return here;
  };
  auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    const LogSignals::Position here = assemble(t, q);
    const SingleTrackModel::Trig<double> steer(q[0]);
    const auto contacts = model.contacts(full.data(), steer);
    const TireForces<double> tf =
        model.frontTire().evaluate(contacts.front, full.data() + front0, full_dot.data() + front0);
    const double torque = torque_delay == 0.0 ? log.at(C::kTorque, here) : log.at(C::kTorque, t - torque_delay, &torque_hint);
    const double transmitted = model.steeringSystem(full.data(), torque, full_dot.data());
    if (sliding_slope) slidingSlope(q[1]);
    q_dot[0] = q[1];
    // Row 3 of eq 3: J_F (sigma2' + sigma3') = M_F + (transmitted torque), sigma2' from the log.
    q_dot[1] = (tf.aligning_moment + transmitted) / JF - log.at(C::kYawAcceleration, here);
    copyStates(full_dot.data() + steer0, carried, q_dot.data() + 2);
  };

  ReplayTrace trace = makeTrace("delta", log.samples(C::kDelta));
  Rk4 rk4(n);
  const double tire_step =
      std::min(options.steering_step, tireStep(model.frontTire(), log.fastestSpeed(config.vehicle.fastestSpeed())));
  const auto& times = log.times();
  // Stiff steering systems need a shorter step: RK4 is stable up to ~2.8 / (fastest rate).
  double step = tire_step;
  // A linear column's spring-damper is the stiff part of the replay (k = 1e6 N m/rad, the fit's bound,
  // asked ~40 RK4 steps per 10 ms sample): it is stepped exactly by exponential time differencing
  // (sim/etdrk4.h), its torques taken out of the rest. L acts on (delta, delta', column, column'):
  //   J_F delta'' = k (column - delta) + c (column' - delta') + ...,  J_c column'' = -k (...) - c (...) + ...
  // and the step is then bounded by the tire and the friction alone. A progressive column's spring is
  // nonlinear (its tangent stiffness grows with the twist) and keeps RK4 at the column's step.
  const SteeringParams& sp = model.steering();
  const bool exponential = sp.compliant() && sp.column_stiffening_angle <= 0.0;
  const double k = sp.column_stiffness, c = sp.column_damping, jc = sp.column_inertia;
  Eigen::MatrixXd linear = Eigen::MatrixXd::Zero(n, n);
  if (exponential) {
    linear(0, 1) = 1.0;
    linear(1, 0) = -k / JF, linear(1, 1) = -c / JF, linear(1, 2) = k / JF, linear(1, 3) = c / JF;
    linear(2, 3) = 1.0;
    linear(3, 0) = k / jc, linear(3, 1) = c / jc, linear(3, 2) = -k / jc, linear(3, 3) = -c / jc;
  }
  Etdrk4 etd(linear);
  // N = f - L q: the column's torque taken out as f computed it (twist = column - delta), so the two cancel
  // to rounding of the torque, not of k delta / J_F.
  auto nonlinear = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    f(t, q, q_dot);
    const double column_torque = k * (q[2] - q[0]) + c * (q[3] - q[1]);
    q_dot[0] = 0.0;  // delta' = delta_dot, all in L
    q_dot[1] -= column_torque / JF;
    q_dot[2] = 0.0;
    q_dot[3] += column_torque / jc;
  };
  if (sp.compliant() && !exponential) {
    // Column and wheel as two inertias on a spring-damper: the fastest mode is bounded by the
    // undamped frequency plus the damping rate. A step sized by the frequency alone let a
    // well-damped column (c / J_c = 1300 1/s at c = 26, J_c = 0.02) sit at RK4's limit with the
    // 2 ms step. (A progressive column stiffens with twist; three times the base rate covers a
    // tangent stiffness of ten times k.)
    const double inv_j = 1.0 / sp.column_inertia + 1.0 / JF;
    const double stiffening = sp.column_stiffening_angle > 0.0 ? 3.0 : 1.0;
    // 2 / rate: inside RK4's stability limits (2.78 on the real axis, 2.83 on the imaginary one).
    step = std::min(step, 2.0 / (stiffening * std::sqrt(sp.column_stiffness * inv_j) + sp.column_damping * inv_j));
  }
  if (sp.lugreFriction()) {
    // Deur eq 9's bristle: it oscillates at sqrt(sigma0 / J_F) and relaxes at sigma0 |delta_dot| / g
    // (g >= the smaller of T_c and T_s); at the benchmark's sigma0 = 2e4 N m/rad the relaxation is the
    // faster one (1.3e4 1/s at 1 rad/s). The step is bounded by both, the relaxation at the log's fastest rate
    // and, where the sliding slope (above) is taken, not below kShortestBristleStep.
    double fastest_rate = 0.0;
    for (double w : log.samples(C::kDeltaRate)) fastest_rate = std::max(fastest_rate, std::fabs(w));
    const double g_min = std::min(sp.coulomb_friction, sp.breakaway_friction) > 0.0
                             ? std::min(sp.coulomb_friction, sp.breakaway_friction)
                             : std::max(sp.coulomb_friction, sp.breakaway_friction);
    const double relaxation = sp.friction_stiffness * fastest_rate / g_min + sp.friction_damping / JF;
    constexpr double kShortestBristleStep = 2.5e-4;  // [s] an eighth of the tire's 2 ms
    step = std::min({step, 1.0 / std::sqrt(sp.friction_stiffness / JF),
                     sliding_slope ? std::max(2.0 / relaxation, kShortestBristleStep) : 2.0 / relaxation});
  }
  const std::vector<double> friction_states = sp.lugreFriction() ? kingpinFrictionStates(sp, log) : std::vector<double>{};
  Eigen::VectorXd sigmas(1);
  sigmas << noiseFor(log, C::kDelta, trace.scale);
  const std::vector<double> priors{noiseFor(log, C::kDelta, trace.scale), std::max(log.noise(C::kDeltaRate), 1e-6)};
  for (const TimeSegment& interval : shootingIntervals(segments, options.steering_horizon)) {
    if (interval.t0 - torque_delay < log.start()) continue;
    const std::size_t first = log.indexAtOrBefore(interval.t0) + 1;
    std::size_t last = first;
    while (last < times.size() && times[last] < interval.t1) ++last;
    if (last <= first) continue;
    const double t0 = interval.t0;
    // Initial state from the log at the start of the interval.
    Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
    q0[0] = log.at(C::kDelta, t0);
    q0[1] = log.at(C::kDeltaRate, t0);
    assemble(t0, q0);
    if (sp.compliant()) {
      // Column twisted by the torque it transmits, moving with the wheel.
      q0[2] = q0[0] + staticColumnTwist(sp, log.at(C::kTorque, t0 - torque_delay));
      q0[3] = q0[1];
    }
    if (sp.lugreFriction()) {
      // The bristle state the logged rate history leaves at t0 (interpolated between samples).
      const std::size_t j = log.indexAtOrBefore(t0);
      const double w = j + 1 < times.size() ? (t0 - times[j]) / (times[j + 1] - times[j]) : 0.0;
      q0[2 + (sp.compliant() ? 2 : 0)] =
          j + 1 < times.size() ? friction_states[j] + w * (friction_states[j + 1] - friction_states[j]) : friction_states[j];
    }
    if (front_n > 0) {
      // The front tire's state at t0, driven by the logged steering angle and rate before it.
      Eigen::VectorXd motion = Eigen::VectorXd::Zero(n);
      const auto logged = [&](double t) {
        const LogSignals::Position here = log.positionAt(t);
        motion[0] = log.at(C::kDelta, here);
        motion[1] = log.at(C::kDeltaRate, here);
        assemble(t, motion);
      };
      const Eigen::VectorXd z = tireStatesAfterLeadIn(model, false, log.start(), t0, tire_step, logged, full, full_dot);
      for (int i = 0; i < front_n; ++i) q0[2 + steer_n + i] = z[i];
    }
    Eigen::MatrixXd measured(last - first, 1);
    for (std::size_t i = first; i < last; ++i) measured(i - first, 0) = log.samples(C::kDelta)[i];
    // Samples closer together than the step (a 1 kHz log against the 2 ms step) need not each end a
    // step: on a rigid column a step spans as many as fit in h, and the angle at those inside it is the
    // cubic Hermite interpolant of the angle and its rate (state q[1]) at the step's ends. Its error,
    // h^4 / 384 times the angle's fourth derivative, is far below any encoder's resolution where the
    // wheel's fastest motion is the tire's and the friction's, which bound the step (on the benchmark's
    // 1 kHz lane change it stays within the 1 ms replay's own difference from the 2 ms one, ~1e-6 rad).
    // A compliant column's mode is faster than the step (a stiff one is stepped exactly, sim/etdrk4.h):
    // at k = 1e5 N m/rad it rings at 360 Hz, and the interpolant missed it by 3e-5 rad. A linear one
    // takes two samples a step where both fit in h and the first sits at the step's midpoint (to 1 % of
    // the step): the first's angle is the scheme's own dense output at h/2 (Etdrk4::stepWithMidpoint: the
    // column exact, the rest from the step's four stages), carried to the sample by the midpoint's rate
    // (on a 1 kHz column log 1.4-1.8e-6 rad from a 0.25 ms replay, the sample-by-sample replay
    // 0.5-0.9e-6: Replay.ALinearColumnTakesTwoSamplesAStep...). Elsewhere (a progressive column, uneven
    // stamps) every sample of a compliant column ends a step. At 1 kHz this halves the steps; where
    // samples are h or more apart (100 Hz) every sample ends a step, as before.
    const bool interpolate = !sp.compliant();
    Eigen::VectorXd midpoint(n);
    // The sample from which the run left the model's domain; std::nullopt where it stayed inside.
    auto simulateWithStep = [&](const Eigen::VectorXd& start, Eigen::MatrixXd& outputs,
                                double h) -> std::optional<std::size_t> {
      Eigen::VectorXd q = start;
      double t = t0;
      slope_step = h;
      // Left the model's domain from sample i on: the rest held at the (clamped) angle reached.
      auto diverged = [&](const Eigen::VectorXd& q_end, std::size_t i) -> std::optional<std::size_t> {
        for (std::size_t k = i; k < last; ++k) {
          outputs(k - first, 0) = std::isfinite(q_end[0]) ? std::clamp(q_end[0], -limit, limit) : limit;
        }
        return i;
      };
      for (std::size_t i = first; i < last;) {
        if (exponential && options.steering_midpoint_output && i + 1 < last && times[i + 1] - t <= h * (1.0 + 1e-9)) {
          const double span = times[i + 1] - t, offset = times[i] - t - 0.5 * span;
          if (span > 0.0 && std::fabs(offset) <= 0.01 * span) {
            etd.stepWithMidpoint(
                [&](int stage, const Eigen::VectorXd& s, Eigen::VectorXd& d) {
                  nonlinear(t + (stage == 0 ? 0.0 : (stage == 3 ? span : 0.5 * span)), s, d);
                },
                span, q, midpoint);
            const double at_sample = midpoint[0] + offset * midpoint[1];
            if (!q.allFinite() || std::fabs(q[0]) > limit || !std::isfinite(at_sample) || std::fabs(at_sample) > limit) {
              return diverged(q, i);
            }
            outputs(i - first, 0) = at_sample;
            outputs(i + 1 - first, 0) = q[0];
            t = times[i + 1];
            i += 2;
            continue;
          }
        }
        std::size_t end = i;  // the step's last sample: the furthest within h of t, at least the next
        while (interpolate && end + 1 < last && times[end + 1] - t <= h * (1.0 + 1e-9)) ++end;
        const double angle0 = q[0], rate0 = q[1];
        if (exponential) {
          integrate(nonlinear, t, times[end], h, q, etd);
        } else {
          integrate(f, t, times[end], h, q, rk4);
        }
        if (!q.allFinite() || std::fabs(q[0]) > limit) {
          return diverged(q, i);
        }
        const double span = times[end] - t;
        for (std::size_t k = i; k < end; ++k) {
          outputs(k - first, 0) = hermite(angle0, rate0, q[0], q[1], span, (times[k] - t) / span);
        }
        outputs(end - first, 0) = q[0];
        t = times[end];
        i = end + 1;
      }
      return std::nullopt;
    };
    // The step bounds above hold for the logged motion; the model's own motion can be faster (a LuGre
    // bristle relaxes at sigma0 |delta_dot| / g with the predicted rate, which overshoots at a stick-slip
    // transition). An interval that leaves the model's domain is tried again with a quarter, then a
    // sixteenth of the step before it counts as diverged, unless it leaves at the same sample again
    // (withShorterStepsWhereTheyHelp, replay_shooting.h): on the benchmark's LuGre-friction truth, two of
    // the 0.15 s intervals starting near a rate reversal (t = 22.0 s and 22.08 s of the small sinusoid)
    // blew up at the bounded step and replay to 0.002-0.003 at a quarter of it.
    auto simulate = [&](const Eigen::VectorXd& start, Eigen::MatrixXd& outputs) {
      return withShorterStepsWhereTheyHelp(step, [&](double h) { return simulateWithStep(start, outputs, h); });
    };
    Eigen::MatrixXd predicted;
    if (!shootWithNuisance(simulate, q0, {0, 1}, priors, measured, sigmas, options.estimate_initial_conditions,
                           &predicted)) {
      ++out.diverged_intervals;
    }
    trace.breaks.push_back(trace.t.size());
    for (std::size_t i = first; i < last; ++i) {
      trace.t.push_back(times[i]);
      trace.measured.push_back(measured(i - first, 0));
      trace.predicted.push_back(predicted(i - first, 0));
    }
  }
  out.traces.push_back(std::move(trace));
  return out;
}

}  // namespace lane_keeping
