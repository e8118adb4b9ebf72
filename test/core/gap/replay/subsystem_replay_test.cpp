// The open-loop steering (and chassis) replays (gap/replay/subsystem_replay.h) under the configuration that
// made a noise-free log reproduce it — also for compliant columns and distributed tires, whose fast
// modes set the integration step, and with the tire states each interval starts from.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/evaluation/noise_reference.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/replay_shooting.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace {

const SensorNoise kNoNoise{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};

/// A benchmark case by id, shortened to `duration` seconds.
BenchmarkCase shortCase(const std::string& id, double duration) {
  BenchmarkCase c;
  for (const auto& candidate : benchmarkCases()) {
    if (candidate.id == id) c = candidate;
  }
  if (c.id.empty()) throw std::runtime_error("no benchmark case " + id);
  c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
  return c;
}

/// A lane change of `duration` seconds whose truth has this steering column (benchmark overlays).
BenchmarkCase columnCase(const std::string& id, const std::vector<std::string>& column, double duration) {
  BenchmarkCase c;
  c.id = id;
  c.manoeuvre = "lane_change";
  c.truth_overlay = column;
  c.truth_overlay.push_back("simulation.duration=" + std::to_string(duration));
  return c;
}

/// RMS of the normalised residual of the replay's delta trace, over all shooting intervals.
double steeringMismatch(const std::vector<std::string>& column) {
  const BenchmarkCase c = columnCase("column-replay", column, 8.0);
  const LogSignals log(generateBenchmarkLog(c, kNoNoise, 500.0));
  const SimConfig config = benchmarkTruth(c);
  const SubsystemReplay replay = replaySteering(config, log, {{0.6, 8.0}});
  EXPECT_EQ(replay.diverged_intervals, 0);
  const std::vector<double> r = replay.traces.at(0).residual();
  double s = 0.0;
  for (double x : r) s += x * x;
  return std::sqrt(s / std::max<std::size_t>(1, r.size()));
}

TEST(Replay, RigidColumnReproducesTheLog) {
  // (The logged torque is interpolated between 500 Hz samples of a 10 kHz PD loop: not zero.)
  EXPECT_LT(steeringMismatch({}), 0.01);
}

TEST(Replay, WellDampedColumnReproducesTheLog) {
  // c (1/J_c + 1/J_F) = 40 * 54 = 2160 1/s: with the 2 ms step sized by the column's frequency alone
  // (1 / 402 rad/s) RK4 was past its stability limit (2.8) and the replay blew up.
  EXPECT_LT(steeringMismatch({"steering.column_stiffness=3000", "steering.column_damping=40",
                              "steering.column_inertia=0.02"}),
            0.01);
}

TEST(Replay, ColumnsUpToTheFitsStiffestBoundReproduceTheLog) {
  // The linear column's spring-damper is stepped exactly (sim/etdrk4.h) at the tire's step: at
  // k = 1e5 and 1e6 N m/rad (the fit's bound; w = 7,400 rad/s on J_c = 0.02, w h = 15 at 2 ms, where
  // RK4 diverges) the replay matches the noise-free truth log as the rigid column's does. (With
  // c = 5 the truth's own loop is unstable at k = 2e4 and 1e5: the PD closing on the wheel through a
  // lightly damped column; c = 40 keeps it stable.)
  for (const char* k : {"steering.column_stiffness=1e5", "steering.column_stiffness=1e6"}) {
    EXPECT_LT(steeringMismatch({k, "steering.column_damping=40", "steering.column_inertia=0.02"}), 0.01) << k;
  }
}

TEST(Replay, ProgressiveColumnReproducesTheLog) {
  // The benchmark's large compliance truth: each interval starts from the column's static twist
  // under the logged torque (the root of the cubic spring law).
  EXPECT_LT(steeringMismatch({"steering.column_stiffness=1500", "steering.column_damping=15",
                              "steering.column_inertia=0.05", "steering.column_stiffening_angle=0.03"}),
            0.01);
}

TEST(Replay, LugreKingpinFrictionReproducesTheLog) {
  // The benchmark's large steering-friction truth (Deur eq 9, sigma0 = 2e4 N m/rad). The bristle state
  // relaxes at sigma0 |delta_dot| / g, 1.3e4 1/s at 1 rad/s: with the step sized by the bristle
  // oscillation alone (sqrt(sigma0 / J_F) = 283 rad/s, so the 2 ms step) RK4 blew up (mismatch ~3e3).
  EXPECT_LT(steeringMismatch({"steering.friction_model=lugre", "steering.coulomb_friction=4",
                              "steering.breakaway_friction=6", "steering.friction_velocity=0.02",
                              "steering.friction_stiffness=2e4"}),
            0.01);
}

TEST(Replay, SamplesInsideAStepTakeTheHermiteInterpolantOfItsEnds) {
  // A 1 kHz log against the 2 ms step: on a rigid column every other sample lies inside a step, its
  // angle interpolated from the angle and rate at the step's ends; on a compliant one (a mode faster
  // than the step) every sample ends a step unless it is taken from the step's dense output (the next
  // test; off here). Against the same replay with a 1 ms step (every sample a
  // step's end): the samples inside a step may differ from it no more than the step ends do, by the
  // integration's own difference between the two steps (~1e-6 rad, where the angle moves up to ~1e-4
  // rad per millisecond; an interpolant taking an end's value, or a linear one, would differ more
  // inside than at the ends, and so would interpolating across the compliant column's 360 Hz mode).
  for (const std::vector<std::string>& column :
       {std::vector<std::string>{},
        std::vector<std::string>{"steering.column_stiffness=1e5", "steering.column_damping=40",
                                 "steering.column_inertia=0.02"}}) {
    const BenchmarkCase c = columnCase("column-replay-1khz", column, 6.0);
    const LogSignals log(generateBenchmarkLog(c, kNoNoise, 1000.0));
    const SimConfig config = benchmarkTruth(c);
    ReplayOptions interpolated, stepped;
    interpolated.steering_step = 2e-3;
    interpolated.steering_midpoint_output = false;
    stepped.steering_step = 1e-3;
    const std::vector<TimeSegment> segments{{0.6, 6.0}};
    const ReplayTrace a = replaySteering(config, log, segments, interpolated).traces.at(0);
    const ReplayTrace b = replaySteering(config, log, segments, stepped).traces.at(0);
    ASSERT_EQ(a.t.size(), b.t.size());
    ASSERT_GT(a.t.size(), 5000u);
    // The 2 ms steps' ends: from each shooting interval's start, the furthest sample within 2 ms.
    const std::vector<TimeSegment> intervals = replay::shootingIntervals(segments, interpolated.steering_horizon);
    ASSERT_EQ(a.breaks.size(), intervals.size());
    double ends = 0.0, inside = 0.0, moved = 0.0;
    for (std::size_t k = 0; k < intervals.size(); ++k) {
      const std::size_t begin = a.breaks[k], stop = k + 1 < a.breaks.size() ? a.breaks[k + 1] : a.t.size();
      double step_start = intervals[k].t0;
      for (std::size_t i = begin; i < stop; ++i) {
        const bool end = i + 1 == stop || a.t[i + 1] - step_start > 2e-3 * (1.0 + 1e-9);
        if (end) step_start = a.t[i];
        double& worst = end || !column.empty() ? ends : inside;
        worst = std::max(worst, std::fabs(a.predicted[i] - b.predicted[i]));
        if (i > begin) moved = std::max(moved, std::fabs(b.predicted[i] - b.predicted[i - 1]));
      }
    }
    EXPECT_LT(ends, 1e-5) << column.size();
    EXPECT_LT(inside, 1.5 * ends + 1e-9) << column.size();  // (the compliant column: all are ends)
    EXPECT_GT(moved, 3e-5) << column.size();
  }
}

TEST(Replay, ALinearColumnTakesTwoSamplesAStepTheFirstFromTheStepsDenseOutput) {
  // A 1 kHz log of a stiff linear column (360 and 1,100 Hz modes, beyond the 2 ms step, stepped exactly):
  // two samples a step, the first at the step's midpoint from its dense output (Etdrk4::stepWithMidpoint),
  // against every sample ending a 1 ms step, and both against a 0.25 ms replay. Hermite interpolation
  // of the ends missed the 360 Hz mode by 3e-5 rad; the dense output carries it.
  for (const char* k : {"steering.column_stiffness=1e5", "steering.column_stiffness=1e6"}) {
    const BenchmarkCase c =
        columnCase("column-replay-1khz", {k, "steering.column_damping=40", "steering.column_inertia=0.02"}, 6.0);
    const LogSignals log(generateBenchmarkLog(c, kNoNoise, 1000.0));
    const SimConfig config = benchmarkTruth(c);
    ReplayOptions paired, each, fine;
    paired.steering_step = each.steering_step = 2e-3;
    each.steering_midpoint_output = false;
    fine.steering_step = 2.5e-4;
    const std::vector<TimeSegment> segments{{0.6, 6.0}};
    const ReplayTrace a = replaySteering(config, log, segments, paired).traces.at(0);
    const ReplayTrace b = replaySteering(config, log, segments, each).traces.at(0);
    const ReplayTrace r = replaySteering(config, log, segments, fine).traces.at(0);
    ASSERT_EQ(a.t.size(), b.t.size());
    ASSERT_EQ(a.t.size(), r.t.size());
    ASSERT_GT(a.t.size(), 5000u);
    double paired_error = 0.0, each_error = 0.0, apart = 0.0, moved = 0.0;
    for (std::size_t i = 0; i < a.t.size(); ++i) {
      paired_error = std::max(paired_error, std::fabs(a.predicted[i] - r.predicted[i]));
      each_error = std::max(each_error, std::fabs(b.predicted[i] - r.predicted[i]));
      apart = std::max(apart, std::fabs(a.predicted[i] - b.predicted[i]));
      if (i > 0) moved = std::max(moved, std::fabs(r.predicted[i] - r.predicted[i - 1]));
    }
    // Measured: 1.4e-6 and 1.8e-6 rad paired, 0.5e-6 and 0.9e-6 sample by sample, where the angle moves
    // up to 8.4e-4 rad per sample: the steps' length (2 ms against 1 ms) shows, three orders of
    // magnitude below the 1e-3 rad of an encoder's resolution.
    EXPECT_LT(paired_error, 5e-6) << k;
    EXPECT_LT(paired_error, 4.0 * each_error) << k;
    EXPECT_GT(apart, 0.0) << k;  // the pairing took place
    EXPECT_GT(moved, 3e-5) << k;
  }
}

TEST(Replay, ShorterStepsAreTriedOnlyWhileTheyMoveTheDeparture) {
  // attempt(h) answers from a script: the sample at which the run leaves the domain, or none. The steps
  // it is asked for and the answer are recorded.
  auto run = [](std::vector<std::optional<std::size_t>> script, std::vector<double>* steps) {
    std::size_t k = 0;
    const bool inside = replay::withShorterStepsWhereTheyHelp(0.002, [&](double h) {
      steps->push_back(h);
      return script.at(k++);
    });
    return inside;
  };
  std::vector<double> steps;
  EXPECT_TRUE(run({std::nullopt}, &steps));  // inside at the first step: one run
  EXPECT_EQ(steps, (std::vector<double>{0.002}));
  steps.clear();
  // Leaves at the same sample at h and h/4: the model's own departure, no third run.
  EXPECT_FALSE(run({5, 5}, &steps));
  EXPECT_EQ(steps, (std::vector<double>{0.002, 0.0005}));
  steps.clear();
  // The departure moved with the step (an instability of the step): h/16 is tried, and stays inside.
  EXPECT_TRUE(run({5, 9, std::nullopt}, &steps));
  EXPECT_EQ(steps, (std::vector<double>{0.002, 0.0005, 0.000125}));
  steps.clear();
  EXPECT_TRUE(run({5, std::nullopt}, &steps));  // a quarter of the step is enough (the LuGre rate reversal)
  EXPECT_EQ(steps.size(), 2u);
  steps.clear();
  EXPECT_FALSE(run({5, 9, 9}, &steps));  // never more than three runs
  EXPECT_EQ(steps.size(), 3u);
  steps.clear();
  EXPECT_FALSE(run({9, 5, 2}, &steps));
  EXPECT_EQ(steps.size(), 3u);
}

TEST(Replay, DistributedTreadWithCarcassLagReproducesTheLog) {
  // The benchmark's large tire-lag truth (Deur's distributed tread, 40 bristles, plus 0.6 m carcass
  // relaxation), replayed with itself: the chassis and steering replays step below the transport time
  // across one bristle spacing (0.34 ms). With the replays' usual 2-3 ms steps they blew up
  // (normalised mismatch 79 and 40).
  const BenchmarkCase c = shortCase("tire_lag-large-lane_change", 8.0);
  const LogSignals log(generateBenchmarkLog(c, kNoNoise, 500.0));
  const SimConfig truth = benchmarkTruth(c);
  ASSERT_EQ(truth.tire_front.model, "lugre_distributed");
  const std::vector<TimeSegment> segments{{0.6, 8.0}};
  const SubsystemReplay chassis = replayChassis(truth, log, segments);
  const SubsystemReplay steering = replaySteering(truth, log, segments, {}, &chassis.sigma1_estimate);
  EXPECT_EQ(chassis.diverged_intervals + steering.diverged_intervals, 0);
  EXPECT_LT(scoreReplay(chassis).nrmse, 0.005);
  EXPECT_LT(scoreReplay(steering).nrmse, 0.01);
}

TEST(Replay, FitsALoggedTorqueDelayAtItsTrueValue) {
  // The benchmark's large actuation delay (2.43 ms, not a multiple of the 0.1 ms step), noise-free.
  // Each interval's front tire state comes from its own equations over the logged motion before the
  // interval; settled at the interval start instead, the replay fitted best 0.13 ms short (2.30 ms),
  // with a floor of 1.2e-3 at the true delay.
  const BenchmarkCase c = shortCase("actuation_delay-large-lane_change", 10.0);
  const LogSignals log(generateBenchmarkLog(c, kNoNoise, 500.0));
  const SimConfig truth = benchmarkTruth(c);
  ASSERT_NEAR(truth.delays.torque_to_plant, 2.43e-3, 1e-9);
  const std::vector<TimeSegment> segments{{0.6, 10.0}};
  auto mismatch = [&](double delay) {
    SimConfig config = truth;
    config.delays.torque_to_plant = delay;
    const SubsystemReplay chassis = replayChassis(config, log, segments);
    const std::vector<double> r = replaySteering(config, log, segments, {}, &chassis.sigma1_estimate).traces.at(0).residual();
    double s = 0.0;
    for (double x : r) s += x * x;
    return std::sqrt(s / r.size());
  };
  const double at_truth = mismatch(2.43e-3);
  EXPECT_LT(at_truth, 3e-4);
  EXPECT_LT(at_truth, mismatch(2.30e-3));
  EXPECT_LT(at_truth, mismatch(2.56e-3));
}

TEST(Replay, TrackerDelayFitOnANoisyPoseIsNotDrawnToHalfSampleOffsets) {
  // A noise-only 500 Hz sinusoid log (2 ms samples): the tracker residual must be smallest at the true
  // delay. Interpolated between noisy samples, the pose's noise was smallest midway between them: the
  // residual was 0.039 at the true delay and 0.028 at +5 ms (2.5 samples), and the fitted extra
  // sensing delay was 18.9 ms on every noise-only sinusoid of the benchmark.
  const BenchmarkCase c = shortCase("none-1-sinusoid", 16.0);
  const LogSignals log(generateBenchmarkLog(c, SensorNoise{}, 500.0));
  const SimConfig nominal = benchmarkNominal(c.manoeuvre);
  auto mismatch = [&](double extra) {
    SimConfig config = nominal;
    config.delays.pose_to_tracker += extra;
    const std::vector<double> r = replayTracker(config, log, {{1.0, 16.0}}).traces.at(0).residual();
    double s = 0.0;
    for (double x : r) s += x * x;
    return std::sqrt(s / r.size());
  };
  const double at_truth = mismatch(0.0);
  for (double extra : {-0.005, -0.003, -0.001, 0.001, 0.003, 0.005}) EXPECT_LT(at_truth, mismatch(extra)) << extra;
}

TEST(Replay, ActuatorReplayOfANoiseOnlyLogLeavesNoExcess) {
  // The actuator reads the measured angle and rate 0.1 ms back. Interpolated on a 1 kHz log that is
  // 0.9 / 0.1 of two noisy samples: the residual's second differences then put its floor at 0.70 of its
  // variance (nrmse^2 / floor^2 = 1.17 > the 1.1 tolerance), and noise read as a gap of ~0.02 that,
  // on a 60 s column log, outweighed the steering's and placed the gap in the actuator.
  const BenchmarkCase c = shortCase("none-1-lane_change", 10.0);
  const LogSignals log(generateBenchmarkLog(c, SensorNoise{}, 1000.0));
  const SubsystemScore s = scoreReplay(replayActuator(benchmarkNominal(c.manoeuvre), log, {{0.5, 10.0}}));
  ASSERT_GT(s.floor, 0.0);
  EXPECT_LT(s.nrmse * s.nrmse / (s.floor * s.floor), 1.05);
  EXPECT_EQ(s.excess, 0.0);
}

TEST(Replay, ActuatorReplayOfANoiseFree100HzLogMatchesTheLoggedTorque) {
  // The actuator's derivative term takes the rate of delta_des, differentiated from the log. With the
  // 0.5-12 Hz excitation at 100 Hz (8 samples per period at the top) the 5-point quadratic fit lost 29 %
  // of the rate there: nrmse 0.069 on this log. Through a cubic spline: 4e-4.
  const BenchmarkCase c = shortCase("none-1-lane_change", 16.0);
  const SensorNoise none{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const LogSignals log(generateBenchmarkLog(c, none, 100.0));
  const SubsystemScore s = scoreReplay(replayActuator(benchmarkNominal(c.manoeuvre), log, {{0.5, 16.0}}));
  EXPECT_LT(s.nrmse, 0.005);
}

TEST(LogSignals, SplineDerivativeKeepsTheRateOfA12HzSineAt100Hz) {
  std::vector<double> t, y;
  const double w = 2.0 * M_PI * 12.0;
  for (int i = 0; i <= 200; ++i) {
    t.push_back(0.01 * i);
    y.push_back(std::sin(w * t.back()));
  }
  const std::vector<double> d = splineDerivative(t, y);
  double worst = 0.0;
  for (int i = 20; i <= 180; ++i) worst = std::max(worst, std::fabs(d[i] - w * std::cos(w * t[i])));
  EXPECT_LT(worst, 0.03 * w);  // the 5-point quadratic fit: 0.29 w
  const std::vector<double> quadratic = smoothedDerivative(t, y, 0.025, 1);
  double worst_quadratic = 0.0;
  for (int i = 20; i <= 180; ++i) worst_quadratic = std::max(worst_quadratic, std::fabs(quadratic[i] - w * std::cos(w * t[i])));
  EXPECT_GT(worst_quadratic, 0.2 * w);
}

/// The local quadratic least-squares fit at sample i over [t_i - w, t_i + w] (at least two samples a side),
/// solved directly: the reference for the filter form.
double directQuadraticFit(const std::vector<double>& t, const std::vector<double>& y, double w, std::size_t i, int order) {
  std::size_t a = i, b = i;
  while (a > 0 && (t[i] - t[a - 1] <= w || i - a < 2)) --a;
  while (b + 1 < t.size() && (t[b + 1] - t[i] <= w || b - i < 2)) ++b;
  Eigen::MatrixXd basis(b - a + 1, 3);
  Eigen::VectorXd v(b - a + 1);
  for (std::size_t j = a; j <= b; ++j) {
    const double s = t[j] - t[i];
    basis.row(j - a) << 1.0, s, s * s;
    v[j - a] = y[j];
  }
  const Eigen::Vector3d c = basis.colPivHouseholderQr().solve(v);
  return order == 0 ? c[0] : (order == 1 ? c[1] : 2.0 * c[2]);
}

TEST(LogSignals, TheSmoothingFilterIsTheLocalQuadraticFitOnUniformAndJitteredSampling) {
  // On a uniform log the weights are solved once per window shape and applied as a filter; on a
  // jittered one, per sample. Both must be the least-squares fit, and exact on a quadratic.
  for (const bool jitter : {false, true}) {
    std::vector<double> t, y, quadratic;
    for (int i = 0; i <= 3000; ++i) {
      t.push_back(0.001 * i + (jitter ? 2e-4 * std::sin(1.7 * i) : 0.0));
      y.push_back(std::sin(7.0 * t.back()) + 0.01 * std::cos(911.0 * i));
      quadratic.push_back(2.0 - 3.0 * t.back() + 4.0 * t.back() * t.back());
    }
    for (int order = 0; order <= 2; ++order) {
      const std::vector<double> d = smoothedDerivative(t, y, 0.0151, order);
      const std::vector<double> q = smoothedDerivative(t, quadratic, 0.0151, order);
      double worst = 0.0, worst_quadratic = 0.0;
      for (std::size_t i = 0; i < t.size(); i += 7) {
        worst = std::max(worst, std::fabs(d[i] - directQuadraticFit(t, y, 0.0151, i, order)));
        const double exact = order == 0 ? quadratic[i] : (order == 1 ? -3.0 + 8.0 * t[i] : 8.0);
        worst_quadratic = std::max(worst_quadratic, std::fabs(q[i] - exact));
      }
      const double scale = order == 0 ? 1.0 : (order == 1 ? 7.0 : 49.0);
      EXPECT_LT(worst, 1e-9 * scale * std::pow(1000.0, order)) << "jitter " << jitter << " order " << order;
      EXPECT_LT(worst_quadratic, 1e-9 * 8.0 * std::pow(1000.0, order)) << "jitter " << jitter << " order " << order;
    }
  }
}

TEST(LogSignals, TheSmoothingFilterGivesEachSampleTheSameBitsWhereverItFallsInABatch) {
  // The filter sums four neighbouring samples' windows side by side. A sample's output must not depend
  // on which of the four it is: the same log started k samples later puts each interior sample in
  // another place of its batch, and its output must be the same to the last bit. (Dyadic stamps keep
  // the step, the windows and so the weights exactly the same in both.)
  std::vector<double> t, y;
  for (int i = 0; i < 4000; ++i) {
    t.push_back(i / 1024.0);
    y.push_back(std::sin(7.0 * t.back()) + 0.01 * std::cos(911.0 * i));
  }
  for (const double half_width : {0.0151, 0.1}) {
    for (int order = 0; order <= 2; ++order) {
      const std::vector<double> all = smoothedDerivative(t, y, half_width, order);
      for (std::size_t k = 1; k <= 7; ++k) {
        const std::vector<double> later =
            smoothedDerivative(std::vector<double>(t.begin() + k, t.end()), std::vector<double>(y.begin() + k, y.end()),
                               half_width, order);
        const std::size_t margin = 2 * static_cast<std::size_t>(half_width * 1024.0) + 4;
        std::size_t compared = 0, differing = 0;
        for (std::size_t i = margin; i + margin < later.size(); ++i, ++compared) {
          if (later[i] != all[i + k]) ++differing;
        }
        EXPECT_GT(compared, 3000u);
        EXPECT_EQ(differing, 0u) << "half width " << half_width << " order " << order << " shifted by " << k;
      }
    }
  }
  // And each output is its window's dot product summed from the window's first sample on, as one
  // sample alone: the weights read back exactly as the responses to unit impulses (a sum of zeros and
  // one weight), summed in that order, give the same bits. On 1 ms stamps and a 15 ms half-width,
  // rounding moves a sample across the half-width here and there, so neighbours in a batch have
  // windows of different lengths (checked below).
  std::vector<double> t_ms, y_ms;
  for (int i = 0; i < 4000; ++i) {
    t_ms.push_back(0.001 * i);
    y_ms.push_back(std::sin(7.0 * t_ms.back()) + 0.01 * std::cos(911.0 * i));
  }
  const double half_width = 0.015;
  const std::size_t from = 1000, count = 64, reach = 24;  // samples from .. from + count; windows within reach
  std::vector<std::vector<double>> weight_of(count);        // weight_of[k][j - (from - reach)]
  for (std::size_t j = from - reach; j < from + count + reach; ++j) {
    std::vector<double> impulse(t_ms.size(), 0.0);
    impulse[j] = 1.0;
    const std::vector<double> response = smoothedDerivative(t_ms, impulse, half_width, 1);
    for (std::size_t k = 0; k < count; ++k) weight_of[k].push_back(response[from + k]);
  }
  const std::vector<double> filtered = smoothedDerivative(t_ms, y_ms, half_width, 1);
  std::set<std::size_t> lengths;
  for (std::size_t k = 0; k < count; ++k) {
    double sum = 0.0;  // (the zero weights outside the window add nothing, not even rounding)
    std::size_t length = 0;
    for (std::size_t j = from - reach; j < from + count + reach; ++j) {
      const double w = weight_of[k][j - (from - reach)];
      sum += w * y_ms[j];
      length += w != 0.0;
    }
    lengths.insert(length);
    EXPECT_EQ(sum, filtered[from + k]) << "sample " << from + k;
    // and those are the sample's own window's weights (the least-squares fit over it, as in the test above)
    EXPECT_NEAR(filtered[from + k], directQuadraticFit(t_ms, y_ms, half_width, from + k, 1), 7e-6) << "sample " << from + k;
  }
  EXPECT_GE(lengths.size(), 2u);  // neighbours with windows of different lengths were among them
}

TEST(LogSignals, NearestAlongSmoothedKeepsOneSamplesNoiseAndFollowsTheSignal) {
  // A smooth signal comes out as interpolated; white noise keeps its variance midway between samples
  // (linear interpolation halves it there).
  GapLog g;
  const int n = 4001;
  for (int i = 0; i < n; ++i) {
    const double t = 0.002 * i;
    g.t.push_back(t);
    g.x.push_back(15.0 * t);
    g.y.push_back(std::sin(t));
    g.psi.push_back(0.0);
    g.yaw_rate.push_back(0.0);
    g.delta.push_back(0.0);
    g.delta_des.push_back(0.0);
    g.torque.push_back(0.0);
  }
  GapLog noisy = g;
  SensorNoise only_psi{0.0, 1e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  addSensorNoise(noisy, only_psi, 3);
  const LogSignals clean(g), log(noisy);
  double max_error = 0.0, midway = 0.0, at_samples = 0.0, interpolated = 0.0;
  for (int i = 100; i + 100 < n; ++i) {
    const double t = 0.002 * i + 0.001;  // midway
    max_error = std::max(max_error, std::fabs(clean.nearestAlongSmoothed(LogSignals::kY, t) - std::sin(t)));
    midway += std::pow(log.nearestAlongSmoothed(LogSignals::kPsi, t), 2);
    at_samples += std::pow(log.nearestAlongSmoothed(LogSignals::kPsi, t - 0.001), 2);
    interpolated += std::pow(log.at(LogSignals::kPsi, t), 2);
  }
  EXPECT_LT(max_error, 1e-6);  // (the interpolation of the smoothed curve: dt^2 / 8 |y''| = 5e-7)
  EXPECT_NEAR(midway / at_samples, 1.0, 0.1);
  EXPECT_NEAR(interpolated / at_samples, 0.5, 0.05);
}

}  // namespace
}  // namespace lane_keeping
