// A delay that changes during a run (delay_line.h, change_schedule.h): the value for time t is the
// input at t - tau(t), tau(t) a right-continuous step function of the consumer's time. Checked against
// the closed form for a step through the delay (a shorter delay skips a stretch of the input, a longer
// one repeats one), a ramp with off-grid delays and linear interpolation, and a path tracker whose
// gain and delay both change.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/control_stages.h"
#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/delay_params.h"

namespace lane_keeping {
namespace {

constexpr Nanoseconds kMs = 1'000'000;

/// Unit step at 0.9 s, sampled every ms; read through a zero-order-hold line every ms from 0 to 2 s
/// (each read followed by discardBefore, as a stage does). `before_read(t, line)` may change the line.
std::vector<double> readStep(Nanoseconds delay, const std::function<void(Nanoseconds, DelayLine<TorqueCommand>&)>& before_read) {
  DelayLine<TorqueCommand> line("step", delay, Hold::kZeroOrder, kMs);
  std::vector<double> out;
  Nanoseconds produced = 0;
  for (Nanoseconds t = 0; t <= 2000 * kMs; t += kMs) {
    before_read(t, line);
    while (!line.covers(t)) {  // the producer runs just as far ahead as the read needs
      line.push(produced, TorqueCommand{produced >= 900 * kMs ? 1.0 : 0.0});
      produced += kMs;
    }
    out.push_back(line.at(t).torque);
    line.discardBefore(t);
  }
  return out;
}

/// y(t) = u(t - tau(t)) for the step u at 0.9 s and tau = tau0 before t_c, tau1 from t_c on.
double closedFormStep(Nanoseconds t, Nanoseconds tau0, Nanoseconds tau1, Nanoseconds t_c) {
  const Nanoseconds tau = t < t_c ? tau0 : tau1;
  return t - tau >= 900 * kMs ? 1.0 : 0.0;
}

TEST(DelayChange, AShorterDelaySkipsAStretchOfTheInput) {
  // tau 0.2 s, then 0.05 s from 1 s: the step reaches the output at 1.0 s (not 1.1 s); what the input
  // did in (0.8 s, 0.95 s) is never read.
  const auto y = readStep(200 * kMs, [](Nanoseconds t, DelayLine<TorqueCommand>& line) {
    if (t == 0) line.scheduleDelay(1000 * kMs, 50 * kMs);
  });
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_EQ(y[k], closedFormStep(static_cast<Nanoseconds>(k) * kMs, 200 * kMs, 50 * kMs, 1000 * kMs)) << k << " ms";
  }
  EXPECT_EQ(y[999], 0.0);
  EXPECT_EQ(y[1000], 1.0);
}

TEST(DelayChange, ALongerDelayRepeatsAStretchOfTheInput) {
  // tau 0.05 s, then 0.2 s from 1 s: the output is 1 on [0.95, 1.0), back to 0 on [1.0, 1.1) (the input
  // of (0.8, 0.9) read again), 1 from 1.1 s. The line keeps the older samples because it knows the
  // longer delay is coming.
  const auto y = readStep(50 * kMs, [](Nanoseconds t, DelayLine<TorqueCommand>& line) {
    if (t == 0) line.scheduleDelay(1000 * kMs, 200 * kMs);
  });
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_EQ(y[k], closedFormStep(static_cast<Nanoseconds>(k) * kMs, 50 * kMs, 200 * kMs, 1000 * kMs)) << k << " ms";
  }
  EXPECT_EQ(y[950], 1.0);
  EXPECT_EQ(y[1000], 0.0);
  EXPECT_EQ(y[1099], 0.0);
  EXPECT_EQ(y[1100], 1.0);
}

TEST(DelayChange, AChangeNotKnownInAdvanceNeedsTheRetainedHistory) {
  // The same longer delay, scheduled only when the consumer gets to 1 s (a live reconfigure request):
  // with the history kept for the largest delay allowed, the output is the closed form all the same.
  const auto y = readStep(50 * kMs, [](Nanoseconds t, DelayLine<TorqueCommand>& line) {
    if (t == 0) line.retainFor(secondsToNanoseconds(DelayParams::kMaxDelay));
    if (t == 1000 * kMs) line.scheduleDelay(t, 200 * kMs);
  });
  for (std::size_t k = 0; k < y.size(); ++k) {
    ASSERT_EQ(y[k], closedFormStep(static_cast<Nanoseconds>(k) * kMs, 50 * kMs, 200 * kMs, 1000 * kMs)) << k << " ms";
  }
}

TEST(DelayChange, RampThroughOffGridDelaysWithLinearInterpolation) {
  // u(t) = t [s] sampled every 0.1 ms; tau = 1.9019505 ms (1 901 951 ns), then 0.7003 ms from 5 ms,
  // then 3.33 ms from 8.05 ms; reads every 0.05 ms. Linear interpolation is exact on a ramp, so
  // y(t) = t - tau(t) to rounding.
  DelayLine<TorqueCommand> line("ramp", 1'901'951, Hold::kLinear, 100'000);
  line.scheduleDelay(5'000'000, 700'300);
  line.scheduleDelay(8'050'000, 3'330'000);
  for (Nanoseconds s = 0; s <= 20'000'000; s += 100'000) line.push(s, TorqueCommand{nanosecondsToSeconds(s)});
  for (Nanoseconds t = 2'000'000; t <= 15'000'000; t += 50'000) {
    const Nanoseconds tau = t < 5'000'000 ? 1'901'951 : t < 8'050'000 ? 700'300 : 3'330'000;
    ASSERT_EQ(line.delayAt(t), tau);
    ASSERT_NEAR(line.at(t).torque, nanosecondsToSeconds(t - tau), 1e-15) << t;
    line.discardBefore(t);
  }
  EXPECT_EQ(line.delay(), 3'330'000);  // the passed changes became the current delay
}

TEST(DelayChange, ReadsDeepInARetainedHistoryFindTheRightSamples) {
  // Random delays (0 to 50 ms) read from a line that keeps 60 ms of a ramp sampled at uneven stamps:
  // the search (from the newest sample back, then by halves) gives what a plain scan gives.
  std::mt19937 random(17);
  DelayLine<TorqueCommand> line("ramp", 0, Hold::kLinear, 100'000);
  line.retainFor(60 * kMs);
  std::vector<Nanoseconds> stamps;
  Nanoseconds s = 0;
  for (int k = 0; k < 20000; ++k) {
    stamps.push_back(s);
    line.push(s, TorqueCommand{static_cast<double>(k)});
    s += 50'000 + static_cast<Nanoseconds>(random() % 100'000);
  }
  const Nanoseconds last = stamps.back();
  for (int n = 0; n < 2000; ++n) {
    const Nanoseconds t = 100 * kMs + static_cast<Nanoseconds>(random() % static_cast<unsigned>(last - 100 * kMs));
    const Nanoseconds tau = static_cast<Nanoseconds>(random() % static_cast<unsigned>(50 * kMs));
    line.clearDelaysFrom(0);
    line.scheduleDelay(0, tau);
    const Nanoseconds q = t - tau;
    std::size_t k = 0;
    while (k + 1 < stamps.size() && stamps[k + 1] <= q) ++k;
    const double w = k + 1 < stamps.size() ? static_cast<double>(q - stamps[k]) / static_cast<double>(stamps[k + 1] - stamps[k]) : 0.0;
    ASSERT_DOUBLE_EQ(line.at(t).torque, static_cast<double>(k) + w) << "t " << t << " tau " << tau;
  }
}

TEST(DelayChange, TrackerGainAndDelayChangeAtTheirStamp) {
  // Beregi eq 11 on a straight lane with k_psi = 0: delta_des(t) = -k_y(t) y(t - tau1(t)). The pose is a
  // step y = 1 m from 0.5 s on; tau1 = 0.2 s, then 0.1 s from 1 s; k_y = 0.1 1/m, then 0.3 1/m from 1.2 s.
  TrackerParams params;
  params.k_psi = 0.0;
  params.k_y = 0.1;
  PathParams straight;
  PathTrackingStage stage(PathTracker(params, createPath(straight)), kMs, 200 * kMs, Hold::kZeroOrder, 100'000);
  TrackerParams later = params;
  later.k_y = 0.3;
  stage.scheduleChange(1000 * kMs, params, 100 * kMs);
  stage.scheduleChange(1200 * kMs, later, 100 * kMs);
  Nanoseconds produced = 0;
  while (stage.nextTime() <= 2000 * kMs) {
    while (!stage.ready()) {
      PoseSample pose;
      pose.x = 15.0 * nanosecondsToSeconds(produced);
      pose.y = produced >= 500 * kMs ? 1.0 : 0.0;
      pose.x_dot = 15.0;
      stage.pushPose(produced, pose);
      produced += 100'000;
    }
    const Nanoseconds t = stage.nextTime();
    const double k_y = t < 1200 * kMs ? 0.1 : 0.3;
    const Nanoseconds tau1 = t < 1000 * kMs ? 200 * kMs : 100 * kMs;
    const double y = t - tau1 >= 500 * kMs ? 1.0 : 0.0;
    ASSERT_DOUBLE_EQ(stage.produce().value.delta_des, -k_y * y) << t << " ns";
  }
  // Not for a sample already computed.
  EXPECT_THROW(stage.scheduleChange(1500 * kMs, params, 0), ScheduleError);
}

}  // namespace
}  // namespace lane_keeping
