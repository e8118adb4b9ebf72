#include "lane_keeping/gap/replay/chassis_replay.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lane_keeping/gap/replay/replay_shooting.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

SubsystemReplay replayChassis(const SimConfig& config, const LogSignals& log, const std::vector<TimeSegment>& segments,
                              const ReplayOptions& options) {
  SubsystemReplay out;
  out.name = "chassis";
  SingleTrackModel model = replayModel(config, log);
  const double mass = config.vehicle.mass;
  const int n_full = model.stateSize();
  const int front0 = model.frontTireOffset(), front_n = model.frontTire().stateSize();
  const int rear0 = model.rearTireOffset(), rear_n = model.rearTire().stateSize();
  // Integrated states: x, y, psi, sigma1, sigma2, the tires'.
  const int n = 5 + front_n + rear_n;
  Eigen::VectorXd full = Eigen::VectorXd::Zero(n_full), full_dot = Eigen::VectorXd::Zero(n_full);
  std::size_t hint = 0, speed_hint = 0;
  // The rear tire's states follow the front's in the model's state (single_track_model.h), as they do in q
  // after the five chassis states: each evaluation copies them in, and their rates out, as one block.
  if (rear0 != front0 + front_n) throw std::logic_error("replayChassis: the rear tire's states do not follow the front tire's");
  const int tire_n = front_n + rear_n;
  // Returns the position of t in the log, for the other channels read at t.
  // A vehicle bus gives no pose (speed, steering angle, yaw rate, perhaps a_y): the chassis is then
  // replayed on its lateral dynamics alone. x, y, psi are integrated from zero and not compared (the
  // lateral dynamics do not depend on them on a flat road), the lateral velocity is a nuisance state of
  // each interval with no measurement behind its prior, and yaw rate (and a_y) are compared.
  const bool pose = log.has(C::kX) && log.has(C::kY) && log.has(C::kPsi);
  // A heading that is the course over ground (log mapping `course: true`) is compared with the model's
  // heading plus its body slip, and gives no lateral velocity: that is estimated, as without a pose.
  const bool course = pose && log.log().psi_is_course;
  auto assemble = [&](double t, const Eigen::VectorXd& q) {
    imposeLoggedSpeed(model, log, t, &speed_hint);
    const LogSignals::Position here = log.positionAt(t, &hint);
    full[kX] = q[0];
    full[kY] = q[1];
    full[kPsi] = q[2];
    full[kSigma1] = q[3];
    full[kSigma2] = q[4];
    full[kDelta] = log.at(C::kDelta, here);
    full[kSigma3] = log.at(C::kDeltaRate, here);
    copyStates(q.data() + 5, tire_n, full.data() + front0);
    return here;
  };
  double last_u = config.vehicle.speed;
  auto f = [&](double t, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    const LogSignals::Position here = assemble(t, q);
    const SingleTrackModel::Trig<double> steer(full[kDelta]);
    model.kinematics(full.data(), steer, full_dot.data());
    const auto c = model.contacts(full.data(), steer);
    const TireForces<double> tf = model.frontTire().evaluate(c.front, full.data() + front0, full_dot.data() + front0);
    const TireForces<double> tr = model.rearTire().evaluate(c.rear, full.data() + rear0, full_dot.data() + rear0);
    double f1, f2, sigma_dot[2];
    model.bodyForces(full.data(), steer, tf, tr, &f1, &f2);
    model.solveChassisAccelerations(steer, f1, f2, log.at(C::kDeltaAcceleration, here), sigma_dot);
    q_dot[0] = full_dot[kX];
    q_dot[1] = full_dot[kY];
    q_dot[2] = full_dot[kPsi];
    q_dot[3] = sigma_dot[0];
    q_dot[4] = sigma_dot[1];
    copyStates(full_dot.data() + front0, tire_n, q_dot.data() + 5);
    last_u = c.u;
  };

  const bool with_ay = log.has(C::kLateralAcceleration);
  std::vector<ReplayTrace> traces{makeTrace("yaw_rate", log.samples(C::kYawRate))};
  std::vector<C> channels{C::kYawRate};
  // Where each output lands in a simulated row (the row holds yaw rate, psi, y, a_y, then sigma1).
  std::vector<int> slot{0};
  if (pose) {
    traces.push_back(makeTrace("psi", log.samples(C::kPsi)));
    traces.push_back(makeTrace("y", log.samples(C::kY)));
    channels.insert(channels.end(), {C::kPsi, C::kY});
    slot.insert(slot.end(), {1, 2});
  }
  if (with_ay) {
    traces.push_back(makeTrace("ay", log.samples(C::kLateralAcceleration)));
    channels.push_back(C::kLateralAcceleration);
    slot.push_back(3);
  }
  const int outputs_n = static_cast<int>(traces.size());
  Eigen::VectorXd sigmas(outputs_n);
  for (int c = 0; c < outputs_n; ++c) sigmas[c] = noiseFor(log, channels[c], traces[c].scale);
  // Nuisance initial conditions and their priors: with a pose, (sigma1, psi, y) at their logged values;
  // without, (sigma1, yaw rate), the yaw rate's its noise. Where the log does not measure sigma1 (no pose,
  // or a course for a heading) its prior is a tenth of the speed wide: a body slip angle of 6 degrees.
  const std::vector<int> nuisance = pose ? std::vector<int>{3, 2, 1} : std::vector<int>{3, 4};
  const double fastest_speed = log.fastestSpeed(config.vehicle.fastestSpeed());
  const double unmeasured_sigma1 = 0.1 * std::max(1.0, fastest_speed);
  const std::vector<double> priors =
      pose ? std::vector<double>{course ? unmeasured_sigma1 : std::max(log.noise(C::kSigma1), 1e-6),
                                 noiseFor(log, C::kPsi, traces[1].scale), noiseFor(log, C::kY, traces[2].scale)}
           : std::vector<double>{unmeasured_sigma1, noiseFor(log, C::kYawRate, traces[0].scale)};
  Rk4 rk4(n);
  Eigen::VectorXd q_dot(n);
  const auto& times = log.times();
  // Fast tire dynamics (relaxation, LuGre transport ~ kappa V / L) need a shorter step.
  const double step = std::min({options.chassis_step, tireStep(model.frontTire(), fastest_speed),
                                 tireStep(model.rearTire(), fastest_speed)});
  for (const TimeSegment& interval : shootingIntervals(segments, options.chassis_horizon)) {
    // The chassis is slow (a few Hz): compare at most every chassis_compare_period seconds.
    std::vector<std::size_t> samples;
    for (std::size_t i = log.indexAtOrBefore(interval.t0) + 1; i < times.size() && times[i] < interval.t1; ++i) {
      if (samples.empty() || times[i] - times[samples.back()] >= options.chassis_compare_period - 1e-9) samples.push_back(i);
    }
    if (samples.empty()) continue;
    const double t0 = interval.t0;
    Eigen::VectorXd q0 = Eigen::VectorXd::Zero(n);
    // The log holds the true motion here: the sensors' errors are undone before the replay
    // (evaluation.cpp, log/sensor_correction.h).
    if (pose) {
      q0[0] = log.at(C::kX, t0);
      q0[1] = log.at(C::kY, t0);
      q0[2] = log.at(C::kPsi, t0);
      if (!course) q0[3] = log.at(C::kSigma1, t0);
    }
    q0[4] = log.at(C::kYawRate, t0);
    if (front_n + rear_n > 0) {
      // Both tires' states at t0, driven by the logged steering, yaw rate and sigma1 before it.
      Eigen::VectorXd motion = Eigen::VectorXd::Zero(n);
      const auto logged = [&](double t) {
        const LogSignals::Position here = log.positionAt(t);
        motion[3] = log.has(C::kSigma1) ? log.at(C::kSigma1, here) : 0.0;
        motion[4] = log.at(C::kYawRate, here);
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
    // The model's outputs at a state, in the compared order, then sigma1.
    double row[5];
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
        if (with_ay || course) f(t, q, q_dot);  // (last_u: the forward velocity of G at this state)
        row[0] = q[4];
        row[1] = course ? q[2] + std::atan2(q[3], last_u) : q[2];
        row[2] = q[1];
        // a_y = sigma1' + sigma2 u at this state, less what the accelerometer does not sense.
        if (with_ay) row[3] = q_dot[3] + q[4] * last_u - model.unsensedLateralForce(full.data()) / mass;
        for (int c = 0; c < outputs_n; ++c) outputs(k, c) = row[slot[c]];
        outputs(k, outputs_n) = q[3];  // sigma1: projected, not compared
      }
      return true;
    };
    Eigen::MatrixXd predicted;
    if (!shootWithNuisance(simulate, q0, nuisance, priors, measured, sigmas, options.estimate_initial_conditions,
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
