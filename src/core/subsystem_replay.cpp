#include "lane_keeping/gap/subsystem_replay.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/sim/model_factory.h"
#include "lane_keeping/sim/rk4.h"
#include "lane_keeping/tire/tire.h"

namespace lane_keeping {
namespace {

using C = LogSignals::Channel;

/// [s] of logged motion the steering and chassis replays run the tires' own equations over before
/// each shooting interval (several of their relaxation times at the benchmark's 15 m/s).
constexpr double kTireLeadIn = 0.1;

/// Largest RK4 step that resolves a tire's fastest dynamics at `speed`: its relaxation lag
/// (relaxation length / V), the lumped LuGre transport (~ a / V) or, for the distributed tread, the
/// transport across one bristle spacing (L / (N - 1) / V: 0.34 ms at 40 bristles and 15 m/s; the
/// replays' 2-4 ms steps made a distributed tire blow up).
double tireStep(const Tire& tire, double speed) {
  double step = std::numeric_limits<double>::infinity();
  if (tire.relaxationLength() > 0.0) step = std::min(step, 0.5 * tire.relaxationLength() / speed);
  if (const auto* distributed = std::get_if<LugreDistributedTire>(&tire.model())) {
    step = std::min(step, distributed->coefficients().contact_length / (distributed->bristles() - 1) / speed);
  } else if (tire.stateSize() > 0 && tire.name() != "brush" && tire.name() != "magic_formula") {
    step = std::min(step, 0.5 * tire.contactHalfLength() / speed);
  }
  return step;
}

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
  const double tc = sp.coulomb_friction, ts = std::max(sp.breakaway_friction, sp.coulomb_friction);
  std::vector<double> z(times.size(), 0.0);
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double w = 0.5 * (rate[i - 1] + rate[i]);
    const double h = times[i] - times[i - 1];
    const double ratio = w / sp.friction_velocity;
    const double g = tc + (ts - tc) * std::exp(-ratio * ratio);
    const double k = sp.friction_stiffness * std::fabs(w) / g;
    if (k * h < 1e-12) {
      z[i] = z[i - 1] + w * h;
      continue;
    }
    const double sliding = w / k;  // sign(w) g / sigma0
    z[i] = sliding + (z[i - 1] - sliding) * std::exp(-k * h);
  }
  return z;
}

/// Normalisation of an output: RMS about its mean over the whole log (never below a tiny floor).
double scaleOf(const std::vector<double>& v) {
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= std::max<std::size_t>(1, v.size());
  double sum = 0.0;
  for (double x : v) sum += (x - mean) * (x - mean);
  const double s = v.empty() ? 0.0 : std::sqrt(sum / v.size());
  return std::max(s, 1e-9);
}

bool inSegments(double t, const std::vector<TimeSegment>& segments) {
  for (const auto& s : segments) {
    if (t >= s.t0 && t < s.t1) return true;
  }
  return false;
}

ReplayTrace makeTrace(const std::string& name, const std::vector<double>& measured_all) {
  ReplayTrace trace;
  trace.name = name;
  trace.scale = scaleOf(measured_all);
  return trace;
}

/// Shooting intervals [a, b) covering the segments.
std::vector<TimeSegment> shootingIntervals(const std::vector<TimeSegment>& segments, double horizon) {
  std::vector<TimeSegment> out;
  for (const auto& s : segments) {
    for (double a = s.t0; a < s.t1 - 1e-9; a += horizon) out.push_back({a, std::min(a + horizon, s.t1)});
  }
  return out;
}

/// Integrates q' = f(t, q) with RK4 from t0 to t1 in steps of at most h.
template <class F>
void integrate(F&& f, double t0, double t1, double h, Eigen::VectorXd& q, Rk4& rk4) {
  const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) / h - 1e-9)));
  const double dt = (t1 - t0) / steps;
  for (int k = 0; k < steps; ++k) {
    const double ta = t0 + k * dt;
    rk4.step([&](int stage, const Eigen::VectorXd& s, Eigen::VectorXd& d) {
      f(ta + (stage == 0 ? 0.0 : (stage == 3 ? dt : 0.5 * dt)), s, d);
    }, dt, q);
  }
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

/// Noise level used for weighting: the estimate, but never below a small fraction of the scale (a
/// noise-free simulated log must not divide by zero).
double noiseFor(const LogSignals& log, LogSignals::Channel c, double scale) {
  return std::max(log.noise(c), 1e-6 * scale);
}

}  // namespace

std::vector<double> ReplayTrace::residual() const {
  std::vector<double> r(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) r[i] = (measured[i] - predicted[i]) / scale;
  return r;
}

void ReplayTrace::append(const ReplayTrace& other) {
  const std::size_t offset = t.size();
  breaks.push_back(offset);
  for (std::size_t b : other.breaks) breaks.push_back(offset + b);
  t.insert(t.end(), other.t.begin(), other.t.end());
  // Keep residuals comparable: re-express the other's values in this trace's scale is unnecessary,
  // both store raw values; the normalisation of the first trace is kept.
  measured.insert(measured.end(), other.measured.begin(), other.measured.end());
  predicted.insert(predicted.end(), other.predicted.begin(), other.predicted.end());
}

const std::vector<std::string>& subsystemNames() {
  static const std::vector<std::string> names{"steering", "chassis", "tracker", "actuator"};
  return names;
}

SubsystemReplay replaySubsystem(const std::string& name, const SimConfig& config, const LogSignals& log,
                                const std::vector<TimeSegment>& segments, const ReplayOptions& options) {
  if (name == "tracker") return replayTracker(config, log, segments);
  if (name == "actuator") return replayActuator(config, log, segments);
  if (name == "steering") return replaySteering(config, log, segments, options, nullptr);
  if (name == "chassis") return replayChassis(config, log, segments, options);
  throw LaneKeepingError("unknown subsystem '" + name + "'");
}

// ------------------------------------------------------------------------------------------------
SubsystemReplay replayTracker(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments) {
  SubsystemReplay out;
  out.name = "tracker";
  const PathTracker tracker(config.tracker, createPath(config.path));
  const double tau = config.delays.pose_to_tracker;
  ReplayTrace trace = makeTrace("delta_des", log.samples(C::kDeltaDes));
  const auto& times = log.times();
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    if (!inSegments(t, segments) || t - tau < log.start()) continue;
    const double q = t - tau;  // Beregi eq 11: the pose tau1 earlier
    // Nearest samples carried along the smoothed pose (LogSignals::nearestAlongSmoothed): interpolating
    // the noisy samples made the noise depend on where between samples t - tau falls, and a fitted
    // delay chased half-sample offsets.
    const PoseSample pose{log.nearestAlongSmoothed(C::kX, q), log.nearestAlongSmoothed(C::kY, q),
                          log.nearestAlongSmoothed(C::kPsi, q), log.at(C::kXDot, q), log.at(C::kYDot, q),
                          log.at(C::kYawRate, q)};
    trace.t.push_back(t);
    trace.measured.push_back(log.samples(C::kDeltaDes)[i]);
    trace.predicted.push_back(tracker.command(pose, t).delta_des);  // the excitation runs on log time
  }
  out.traces.push_back(std::move(trace));
  return out;
}

// ------------------------------------------------------------------------------------------------
SubsystemReplay replayActuator(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments) {
  SubsystemReplay out;
  out.name = "actuator";
  const ActuatorParams& p = config.actuator;
  const double tau_des = config.delays.desired_steering_to_actuator;
  const double tau_meas = config.delays.steering_angle_to_actuator;
  const double lag = std::max(tau_des, tau_meas);
  ReplayTrace trace = makeTrace("torque", log.samples(C::kTorque));
  const auto& times = log.times();
  // z(t - tau2): trapezoid over the logged error from the first usable sample (eq 13).
  double z = 0.0, previous_t = 0.0, previous_e = 0.0;
  bool started = false;
  std::vector<double> base;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double t = times[i];
    if (t - lag < log.start()) continue;
    // The measured angle and rate: nearest samples carried along their smoothed curves (interpolated
    // 0.1 ms back, their noise was coloured and read as excess; LogSignals::nearestAlongSmoothed).
    const double e = log.at(C::kDeltaDes, t - tau_des) - log.nearestAlongSmoothed(C::kDelta, t - tau_meas);
    const double e_rate =
        log.at(C::kDeltaDesRate, t - tau_des) - log.nearestAlongSmoothed(C::kDeltaRate, t - tau_meas);
    if (started) z += 0.5 * (t - previous_t) * (previous_e + e);
    started = true;
    previous_t = t;
    previous_e = e;
    if (!inSegments(t, segments)) continue;
    trace.t.push_back(t);
    trace.measured.push_back(log.samples(C::kTorque)[i]);
    base.push_back(p.kp() * e + p.kd() * e_rate + p.ki() * z);  // eq 12 with z(start) = 0
  }
  // The integral's value at the start of the log is unknown: a constant torque offset k_i z0, fitted.
  double offset = 0.0;
  for (std::size_t k = 0; k < base.size(); ++k) offset += trace.measured[k] - base[k];
  if (!base.empty() && p.ki() != 0.0) offset /= base.size();
  else offset = 0.0;
  for (double b : base) trace.predicted.push_back(b + offset);
  out.traces.push_back(std::move(trace));
  return out;
}

// ------------------------------------------------------------------------------------------------
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
    if (sigma1_times.size() < 2 || t < sigma1_times.front() || t > sigma1_times.back()) return log.at(C::kSigma1, t);
    std::size_t j = std::min(s1_cursor, sigma1_times.size() - 2);
    while (j > 0 && sigma1_times[j] > t) --j;
    while (j + 2 < sigma1_times.size() && sigma1_times[j + 1] <= t) ++j;
    s1_cursor = j;
    const std::size_t i = j + 1;
    if (sigma1_times[i] - sigma1_times[j] > 0.05) return log.at(C::kSigma1, t);  // a gap between intervals
    const double w = (t - sigma1_times[j]) / (sigma1_times[i] - sigma1_times[j]);
    return sigma1_values[j] + w * (sigma1_values[i] - sigma1_values[j]);
  };
  const SingleTrackModel model = createVehicleModel(config);
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
  std::size_t hint = 0, torque_hint = 0;
  auto assemble = [&](double t, const Eigen::VectorXd& q) {
    full[kDelta] = q[0];
    full[kSigma3] = q[1];
    full[kSigma1] = lateralVelocity(t);
    full[kSigma2] = log.at(C::kYawRate, t, &hint);
    for (int i = 0; i < steer_n; ++i) full[steer0 + i] = q[2 + i];
    for (int i = 0; i < front_n; ++i) full[front0 + i] = q[2 + steer_n + i];
  };
  auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    assemble(t, q);
    const SingleTrackModel::Trig<double> steer(q[0]);
    const auto contacts = model.contacts(full.data(), steer);
    const TireForces<double> tf =
        model.frontTire().evaluate(contacts.front, full.data() + front0, full_dot.data() + front0);
    const double torque = torque_delay == 0.0 ? log.at(C::kTorque, t, &hint) : log.at(C::kTorque, t - torque_delay, &torque_hint);
    const double transmitted = model.steeringSystem(full.data(), torque, full_dot.data());
    q_dot[0] = q[1];
    // Row 3 of eq 3: J_F (sigma2' + sigma3') = M_F + (transmitted torque), sigma2' from the log.
    q_dot[1] = (tf.aligning_moment + transmitted) / JF - log.at(C::kYawAcceleration, t, &hint);
    for (int i = 0; i < steer_n; ++i) q_dot[2 + i] = full_dot[steer0 + i];
    for (int i = 0; i < front_n; ++i) q_dot[2 + steer_n + i] = full_dot[front0 + i];
  };

  ReplayTrace trace = makeTrace("delta", log.samples(C::kDelta));
  Rk4 rk4(n);
  const double tire_step = std::min(options.steering_step, tireStep(model.frontTire(), config.vehicle.speed));
  const auto& times = log.times();
  // Stiff steering systems need a shorter step: RK4 is stable up to ~2.8 / (fastest rate).
  double step = tire_step;
  const SteeringParams& sp = model.steering();
  if (sp.compliant()) {
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
    // faster one (1.3e4 1/s at 1 rad/s), so the step is bounded by both, at the log's fastest rate.
    double fastest_rate = 0.0;
    for (double w : log.samples(C::kDeltaRate)) fastest_rate = std::max(fastest_rate, std::fabs(w));
    const double g_min = std::min(sp.coulomb_friction, sp.breakaway_friction) > 0.0
                             ? std::min(sp.coulomb_friction, sp.breakaway_friction)
                             : std::max(sp.coulomb_friction, sp.breakaway_friction);
    const double relaxation = sp.friction_stiffness * fastest_rate / g_min + sp.friction_damping / JF;
    step = std::min({step, 1.0 / std::sqrt(sp.friction_stiffness / JF), 2.0 / relaxation});
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
        motion[0] = log.at(C::kDelta, t);
        motion[1] = log.at(C::kDeltaRate, t);
        assemble(t, motion);
      };
      const Eigen::VectorXd z = tireStatesAfterLeadIn(model, false, log.start(), t0, tire_step, logged, full, full_dot);
      for (int i = 0; i < front_n; ++i) q0[2 + steer_n + i] = z[i];
    }
    Eigen::MatrixXd measured(last - first, 1);
    for (std::size_t i = first; i < last; ++i) measured(i - first, 0) = log.samples(C::kDelta)[i];
    auto simulate = [&](const Eigen::VectorXd& start, Eigen::MatrixXd& outputs) {
      Eigen::VectorXd q = start;
      double t = t0;
      for (std::size_t i = first; i < last; ++i) {
        integrate(f, t, times[i], step, q, rk4);
        t = times[i];
        if (!q.allFinite() || std::fabs(q[0]) > limit) {
          for (std::size_t k = i; k < last; ++k) outputs(k - first, 0) = std::isfinite(q[0]) ? std::clamp(q[0], -limit, limit) : limit;
          return false;
        }
        outputs(i - first, 0) = q[0];
      }
      return true;
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

// ------------------------------------------------------------------------------------------------
SubsystemReplay replayChassis(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                              const ReplayOptions& options) {
  SubsystemReplay out;
  out.name = "chassis";
  const SingleTrackModel model = createVehicleModel(config);
  const int n_full = model.stateSize();
  const int front0 = model.frontTireOffset(), front_n = model.frontTire().stateSize();
  const int rear0 = model.rearTireOffset(), rear_n = model.rearTire().stateSize();
  // Integrated states: x, y, psi, sigma1, sigma2, the tires'.
  const int n = 5 + front_n + rear_n;
  Eigen::VectorXd full = Eigen::VectorXd::Zero(n_full), full_dot = Eigen::VectorXd::Zero(n_full);
  std::size_t hint = 0;
  auto assemble = [&](double t, const Eigen::VectorXd& q) {
    full[kX] = q[0];
    full[kY] = q[1];
    full[kPsi] = q[2];
    full[kSigma1] = q[3];
    full[kSigma2] = q[4];
    full[kDelta] = log.at(C::kDelta, t, &hint);
    full[kSigma3] = log.at(C::kDeltaRate, t, &hint);
    for (int i = 0; i < front_n; ++i) full[front0 + i] = q[5 + i];
    for (int i = 0; i < rear_n; ++i) full[rear0 + i] = q[5 + front_n + i];
  };
  double last_u = config.vehicle.speed;
  auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    assemble(t, q);
    const SingleTrackModel::Trig<double> steer(full[kDelta]);
    model.kinematics(full.data(), steer, full_dot.data());
    const auto c = model.contacts(full.data(), steer);
    const TireForces<double> tf = model.frontTire().evaluate(c.front, full.data() + front0, full_dot.data() + front0);
    const TireForces<double> tr = model.rearTire().evaluate(c.rear, full.data() + rear0, full_dot.data() + rear0);
    double f1, f2, sigma_dot[2];
    model.bodyForces(full.data(), steer, tf, tr, &f1, &f2);
    model.solveChassisAccelerations(steer, f1, f2, log.at(C::kDeltaAcceleration, t, &hint), sigma_dot);
    q_dot[0] = full_dot[kX];
    q_dot[1] = full_dot[kY];
    q_dot[2] = full_dot[kPsi];
    q_dot[3] = sigma_dot[0];
    q_dot[4] = sigma_dot[1];
    for (int i = 0; i < front_n; ++i) q_dot[5 + i] = full_dot[front0 + i];
    for (int i = 0; i < rear_n; ++i) q_dot[5 + front_n + i] = full_dot[rear0 + i];
    last_u = c.u;
  };

  const bool with_ay = log.has(C::kLateralAcceleration);
  std::vector<ReplayTrace> traces{makeTrace("yaw_rate", log.samples(C::kYawRate)), makeTrace("psi", log.samples(C::kPsi)),
                                  makeTrace("y", log.samples(C::kY))};
  if (with_ay) traces.push_back(makeTrace("ay", log.samples(C::kLateralAcceleration)));
  const std::vector<C> channels{C::kYawRate, C::kPsi, C::kY, C::kLateralAcceleration};
  const int outputs_n = static_cast<int>(traces.size());
  Eigen::VectorXd sigmas(outputs_n);
  for (int c = 0; c < outputs_n; ++c) sigmas[c] = noiseFor(log, channels[c], traces[c].scale);
  const std::vector<double> priors{std::max(log.noise(C::kSigma1), 1e-6), noiseFor(log, C::kPsi, traces[1].scale),
                                   noiseFor(log, C::kY, traces[2].scale)};
  Rk4 rk4(n);
  Eigen::VectorXd q_dot(n);
  const auto& times = log.times();
  // Fast tire dynamics (relaxation, LuGre transport ~ kappa V / L) need a shorter step.
  const double step = std::min({options.chassis_step, tireStep(model.frontTire(), config.vehicle.speed),
                                 tireStep(model.rearTire(), config.vehicle.speed)});
  for (const TimeSegment& interval : shootingIntervals(segments, options.chassis_horizon)) {
    // The chassis is slow (a few Hz): compare at most every chassis_compare_period seconds.
    std::vector<std::size_t> samples;
    for (std::size_t i = log.indexAtOrBefore(interval.t0) + 1; i < times.size() && times[i] < interval.t1; ++i) {
      if (samples.empty() || times[i] - times[samples.back()] >= options.chassis_compare_period - 1e-9) samples.push_back(i);
    }
    if (samples.empty()) continue;
    const double t0 = interval.t0;
    Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
    q0[0] = log.at(C::kX, t0);
    q0[1] = log.at(C::kY, t0);
    q0[2] = log.at(C::kPsi, t0);
    q0[3] = log.at(C::kSigma1, t0);
    q0[4] = log.at(C::kYawRate, t0);
    if (front_n + rear_n > 0) {
      // Both tires' states at t0, driven by the logged steering, yaw rate and sigma1 before it.
      Eigen::VectorXd motion = Eigen::VectorXd::Zero(n);
      const auto logged = [&](double t) {
        motion[3] = log.at(C::kSigma1, t);
        motion[4] = log.at(C::kYawRate, t);
        assemble(t, motion);
      };
      const Eigen::VectorXd z = tireStatesAfterLeadIn(model, true, log.start(), t0, step, logged, full, full_dot);
      for (int i = 0; i < front_n + rear_n; ++i) q0[5 + i] = z[i];
    }
    assemble(t0, q0);
    const Eigen::Index rows = static_cast<Eigen::Index>(samples.size());
    Eigen::MatrixXd measured(rows, outputs_n);
    for (Eigen::Index k = 0; k < rows; ++k) {
      for (int c = 0; c < outputs_n; ++c) measured(k, c) = log.samples(channels[c])[samples[k]];
    }
    auto simulate = [&](const Eigen::VectorXd& start, Eigen::MatrixXd& outputs) {
      Eigen::VectorXd q = start;
      double t = t0;
      for (Eigen::Index k = 0; k < rows; ++k) {
        const double tk = times[samples[k]];
        integrate(f, t, tk, step, q, rk4);
        t = tk;
        if (!q.allFinite() || std::fabs(q[3]) > 50.0 || std::fabs(q[4]) > 10.0) {
          outputs.bottomRows(rows - k).setZero();
          return false;
        }
        outputs(k, outputs_n) = q[3];  // sigma1: projected, not compared
        outputs(k, 0) = q[4];
        outputs(k, 1) = q[2];
        outputs(k, 2) = q[1];
        if (with_ay) {
          f(t, q, q_dot);  // a_y = sigma1' + sigma2 u at this state
          outputs(k, 3) = q_dot[3] + q[4] * last_u;
        }
      }
      return true;
    };
    Eigen::MatrixXd predicted;
    if (!shootWithNuisance(simulate, q0, {3, 2, 1}, priors, measured, sigmas, options.estimate_initial_conditions,
                           &predicted, 1)) {
      ++out.diverged_intervals;
    }
    for (auto& trace : traces) trace.breaks.push_back(trace.t.size());
    for (Eigen::Index k = 0; k < rows; ++k) {
      const double tk = times[samples[k]];
      out.sigma1_estimate.emplace_back(tk, predicted(k, outputs_n));
      for (int c = 0; c < outputs_n; ++c) {
        traces[c].t.push_back(tk);
        traces[c].measured.push_back(measured(k, c));
        traces[c].predicted.push_back(predicted(k, c));
      }
    }
  }
  for (auto& trace : traces) out.traces.push_back(std::move(trace));
  return out;
}

}  // namespace lane_keeping
