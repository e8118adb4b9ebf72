#include "lane_keeping/gap/evaluation/input_driven_reference.h"

#include <algorithm>
#include <cmath>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/replay/replay_shooting.h"

namespace lane_keeping {

using C = LogSignals::Channel;
using namespace replay;

GapLog inputDrivenReferenceLog(const SimConfig& nominal, const LogSignals& log) {
  const GapLog& real = log.log();
  const std::vector<double>& t = log.times();
  // The steering the car had, without its sensor's noise: a local quadratic over +-50 ms (the steering
  // of a car moves well below 10 Hz), its rate and acceleration from the same fit.
  constexpr double kWindow = 0.05;
  const std::vector<double> delta = smoothedDerivative(t, real.delta, kWindow, 0);
  const std::vector<double> rate = smoothedDerivative(t, real.delta, kWindow, 1);
  const std::vector<double> acceleration = smoothedDerivative(t, real.delta, kWindow, 2);
  auto interpolate = [&](const std::vector<double>& v, const LogSignals::Position& p) {
    if (p.edge != 0) return p.edge < 0 ? v.front() : v.back();
    return v[p.i] + p.w * (v[p.i + 1] - v[p.i]);
  };

  SingleTrackModel model = replayModel(nominal, log);
  const int n_full = model.stateSize();
  const int front0 = model.frontTireOffset(), front_n = model.frontTire().stateSize();
  const int rear_n = model.rearTire().stateSize();
  const int n = 5 + front_n + rear_n;
  Eigen::VectorXd full = Eigen::VectorXd::Zero(n_full), full_dot = Eigen::VectorXd::Zero(n_full);
  std::size_t hint = 0, speed_hint = 0;
  double last_u = nominal.vehicle.speed;
  auto f = [&](double time, const Eigen::VectorXd& q, Eigen::VectorXd& q_dot) {
    imposeLoggedSpeed(model, log, time, &speed_hint);
    const LogSignals::Position here = log.positionAt(time, &hint);
    full[kX] = q[0];
    full[kY] = q[1];
    full[kPsi] = q[2];
    full[kSigma1] = q[3];
    full[kSigma2] = q[4];
    full[kDelta] = interpolate(delta, here);
    full[kSigma3] = interpolate(rate, here);
    copyStates(q.data() + 5, front_n + rear_n, full.data() + front0);
    const SingleTrackModel::Trig<double> steer(full[kDelta]);
    model.kinematics(full.data(), steer, full_dot.data());
    const auto c = model.contacts(full.data(), steer);
    const TireForces<double> tf = model.frontTire().evaluate(c.front, full.data() + front0, full_dot.data() + front0);
    const TireForces<double> tr =
        model.rearTire().evaluate(c.rear, full.data() + model.rearTireOffset(), full_dot.data() + model.rearTireOffset());
    double f1, f2, sigma_dot[2];
    model.bodyForces(full.data(), steer, tf, tr, &f1, &f2);
    model.solveChassisAccelerations(steer, f1, f2, interpolate(acceleration, here), sigma_dot);
    q_dot[0] = full_dot[kX];
    q_dot[1] = full_dot[kY];
    q_dot[2] = full_dot[kPsi];
    q_dot[3] = sigma_dot[0];
    q_dot[4] = sigma_dot[1];
    copyStates(full_dot.data() + front0, front_n + rear_n, q_dot.data() + 5);
    last_u = c.u;
  };

  const bool pose = log.has(C::kX) && log.has(C::kY) && log.has(C::kPsi);
  const bool course = real.psi_is_course;
  const std::vector<double> yaw_rate = smoothedDerivative(t, real.yaw_rate, kWindow, 0);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
  // The state the log shows at sample i (tires and an unmeasured lateral velocity at rest).
  auto fromLog = [&](std::size_t i) {
    q.setZero();
    if (pose) {
      q[0] = real.x[i];
      q[1] = real.y[i];
      q[2] = real.psi[i];
      if (log.has(C::kSigma1)) q[3] = log.samples(C::kSigma1)[i];
    }
    q[4] = yaw_rate[i];
  };
  const double t0 = log.start();
  fromLog(0);
  const double speed = log.fastestSpeed(nominal.vehicle.fastestSpeed());
  const double step = std::min({0.002, tireStep(model.frontTire(), speed), tireStep(model.rearTire(), speed)});
  Rk4 rk4(n);
  Eigen::VectorXd q_dot(n);
  GapLog out;
  out.source = real.source + " (noise reference, driven by its own steering)";
  out.t = t;
  out.unscaled = real.unscaled;
  out.mapping = real.mapping;
  out.psi_is_course = course;
  const double mass = nominal.vehicle.mass;
  double time = t0, restarted = -1e300;
  int restarts = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] > time) integrate(f, time, t[i], step, q, rk4);
    time = t[i];
    if (!q.allFinite() || std::fabs(q[3]) > 50.0 || std::fabs(q[4]) > 10.0) {
      // The nominal car cannot follow the real one's steering here (a real car near its grip limit, a
      // nominal that spins): it starts again from what the log shows, once in a while. The draws then
      // hold one jump, which their replays re-initialise over, like any interval's start.
      if (time - restarted < 1.0 || ++restarts > 10) {
        throw LaneKeepingError("noise reference for " + real.source + ": the nominal chassis driven by the log's steering "
                               "leaves the model's domain at t = " + std::to_string(t[i] - t0) + " s");
      }
      restarted = time;
      fromLog(i);
    }
    if (pose) {
      out.x.push_back(q[0]);
      out.y.push_back(q[1]);
      out.psi.push_back(q[2]);
    }
    out.yaw_rate.push_back(q[4]);
    if (real.hasLateralAcceleration() || course) f(time, q, q_dot);
    if (course && pose) out.psi.back() += std::atan2(q[3], last_u);  // the course: heading plus body slip
    if (real.hasLateralAcceleration()) {
      out.ay.push_back(q_dot[3] + q[4] * last_u - model.unsensedLateralForce(full.data()) / mass);
    }
    out.delta.push_back(delta[i]);
  }
  if (real.hasSteeringRate()) out.delta_rate = rate;
  out.v = smoothedDerivative(t, real.v, 0.1, 0);  // the car's speed, without the sensor's noise
  out.speed_of = real.speed_of;                   // (V of eq 1 once prepared: logged_speed.h)
  out.torque = real.torque;
  out.delta_des = real.delta_des;
  return out;
}

}  // namespace lane_keeping
