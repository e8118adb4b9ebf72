// The motor side of a compliant column reconstructed from a log (column_observer.h): its exact
// discretisation against the closed form of a torque ramp, against a fine RK4 at the fit's stiffest
// bounds, and against the RK4 path it keeps for progressive columns.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/gap/replay/column_observer.h"

namespace lane_keeping {
namespace {

SimConfig column(double k, double c, double j) {
  SimConfig config;
  config.steering.column_stiffness = k;
  config.steering.column_damping = c;
  config.steering.column_inertia = j;
  config.steering.column_stiffening_angle = 0.0;
  config.steering.dead_band = 0.0;
  config.steering.torque_limit = 0.0;
  config.delays.torque_to_plant = 0.0;
  return config;
}

/// A log whose every column is `f` of t except the wheel and the torque.
template <class Wheel, class Torque>
GapLog makeLog(double rate, double duration, Wheel wheel, Torque torque) {
  GapLog log;
  log.source = "column_observer_test";
  for (int i = 0; i <= static_cast<int>(std::lround(duration * rate)); ++i) {
    const double t = i / rate;
    const auto [delta, delta_rate] = wheel(t);
    log.t.push_back(t);
    log.delta.push_back(delta);
    log.delta_rate.push_back(delta_rate);
    log.torque.push_back(torque(t));
    for (auto* column : {&log.x, &log.y, &log.psi, &log.yaw_rate, &log.delta_des}) column->push_back(0.0);
  }
  return log;
}

/// The column of `config` by RK4 at step h on the same linearly interpolated inputs.
std::vector<double> referenceAngles(const SimConfig& config, const LogSignals& log, double h) {
  const SteeringParams& p = config.steering;
  using C = LogSignals::Channel;
  const auto f = [&](double t, double q, double w, double& dq, double& dw) {
    const double twist = q - log.at(C::kDelta, t);
    double spring = p.column_stiffness * twist;
    if (p.column_stiffening_angle > 0.0) spring *= 1.0 + std::pow(twist / p.column_stiffening_angle, 2);
    dq = w;
    dw = (log.at(C::kTorque, t) - spring - p.column_damping * (w - log.at(C::kDeltaRate, t))) / p.column_inertia;
  };
  const auto& times = log.times();
  double q = log.samples(C::kDelta)[0] + log.samples(C::kTorque)[0] / p.column_stiffness;
  double w = log.samples(C::kDeltaRate)[0];
  std::vector<double> out{q};
  for (std::size_t i = 1; i < times.size(); ++i) {
    const int n = static_cast<int>(std::ceil((times[i] - times[i - 1]) / h));
    const double s = (times[i] - times[i - 1]) / n;
    for (int k = 0; k < n; ++k) {
      const double t = times[i - 1] + k * s;
      double q1, w1, q2, w2, q3, w3, q4, w4;
      f(t, q, w, q1, w1);
      f(t + 0.5 * s, q + 0.5 * s * q1, w + 0.5 * s * w1, q2, w2);
      f(t + 0.5 * s, q + 0.5 * s * q2, w + 0.5 * s * w2, q3, w3);
      f(t + s, q + s * q3, w + s * w3, q4, w4);
      q += s / 6.0 * (q1 + 2 * q2 + 2 * q3 + q4);
      w += s / 6.0 * (w1 + 2 * w2 + 2 * w3 + w4);
    }
    out.push_back(q);
  }
  return out;
}

TEST(ColumnObserver, ATorqueRampOnAHeldWheelFollowsTheClosedForm) {
  // J q'' + c q' + k q = a t from rest (q(0) = 0: no torque yet): q = a / k (t - c / k) plus the
  // decaying oscillation that meets q(0) = q'(0) = 0. A linear input is what the first-order hold
  // holds exactly, so the 100 Hz samples match to rounding, not to a step size.
  const double k = 1500.0, c = 15.0, j = 0.05, a = 20.0;
  const SimConfig config = column(k, c, j);
  const LogSignals log(makeLog(100.0, 2.0, [](double) { return std::pair{0.0, 0.0}; }, [&](double t) { return a * t; }));
  const ColumnObserver observer(config, log);
  const double sigma = c / (2 * j), wd = std::sqrt(k / j - sigma * sigma);
  const double c0 = a * c / (k * k), s0 = (sigma * c0 - a / k) / wd;
  double worst = 0.0;
  for (std::size_t i = 0; i < log.times().size(); ++i) {
    const double t = log.times()[i];
    const double q = a / k * (t - c / k) + std::exp(-sigma * t) * (c0 * std::cos(wd * t) + s0 * std::sin(wd * t));
    worst = std::max(worst, std::fabs(observer.angles()[i] - q));
  }
  EXPECT_LT(worst, 1e-10 * a * 2.0 / k) << "largest error " << worst << " rad on a twist of " << a * 2.0 / k;
  // Between samples the reading is linear: half-way between two samples, their mean.
  EXPECT_DOUBLE_EQ(observer.at(0.505).delta, 0.5 * (observer.angles()[50] + observer.angles()[51]));
}

TEST(ColumnObserver, TheFitsStiffestColumnMatchesAFineRk4) {
  // The candidate's bounds (k = 1e6, c = 100, J_c = 0.01): rates of 1e4 1/s, a hundred times the
  // 100 Hz sampling. Its exact discretisation must neither blow up nor lose the quasi-static twist.
  const SimConfig config = column(1e6, 100.0, 0.01);
  const LogSignals log(makeLog(
      100.0, 3.0, [](double t) { return std::pair{0.05 * std::sin(3 * t), 0.15 * std::cos(3 * t)}; },
      [](double t) { return 8.0 * std::sin(2 * t) + 3.0; }));
  const ColumnObserver observer(config, log);
  const std::vector<double> reference = referenceAngles(config, log, 2e-6);
  for (std::size_t i = 0; i < reference.size(); ++i) {
    ASSERT_NEAR(observer.angles()[i], reference[i], 1e-9) << "sample " << i;
  }
}

TEST(ColumnObserver, TheProgressiveColumnsRk4AgreesWithTheExactLinearOne) {
  // A stiffening angle of 100 rad changes the spring by (twist / 100)^2 < 1e-8: the RK4 path the
  // nonlinear column takes must give the linear column's exact answer on a 1 kHz log.
  SimConfig linear = column(1500.0, 15.0, 0.05);
  SimConfig progressive = linear;
  progressive.steering.column_stiffening_angle = 100.0;
  const LogSignals log(makeLog(
      1000.0, 2.0, [](double t) { return std::pair{0.03 * std::sin(5 * t), 0.15 * std::cos(5 * t)}; },
      [](double t) { return 5.0 * std::sin(7 * t); }));
  const ColumnObserver exact(linear, log), rk4(progressive, log);
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < log.times().size(); ++i) {
    worst = std::max(worst, std::fabs(exact.angles()[i] - rk4.angles()[i]));
    scale = std::max(scale, std::fabs(exact.angles()[i]));
  }
  EXPECT_LT(worst, 1e-7 * scale) << worst;
}

}  // namespace
}  // namespace lane_keeping
