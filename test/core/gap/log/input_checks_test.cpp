// What is odd about a log, found before its diagnosis (issue 48; log/input_checks.h): holes in the time
// axis, stuck channels, a rate too low for a subsystem's band, units that look wrong, a speed that is not
// the configured one; and no finding at all on the logs the benchmark families generate.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/input_checks.h"

namespace lane_keeping {
namespace {

const std::vector<std::string> kColumns{"x", "y", "psi", "yaw_rate", "v", "ay", "delta", "delta_rate", "delta_des",
                                        "torque"};

/// A generated lane change (the benchmark's nominal, no effect) of `duration` s at `rate` Hz.
GapLog laneChange(double rate = 500.0, double duration = 16.0, unsigned seed = 3u) {
  BenchmarkCase c{"checks", "none", "none", "", "lane_change", {"simulation.duration=" + std::to_string(duration)}, seed};
  GapLog log = generateBenchmarkLog(c, SensorNoise{}, rate);
  log.source = "run.csv";
  return log;
}

SimConfig nominal() {
  SimConfig c = benchmarkNominal("lane_change");
  c.simulation.duration = 16.0;
  return c;
}

/// Every `k`-th row of `log` (a log sampled k times more coarsely).
GapLog decimated(const GapLog& log, std::size_t k) {
  GapLog out = log;
  out.t.clear();
  for (std::size_t i = 0; i < log.size(); i += k) out.t.push_back(log.t[i]);
  for (const std::string& name : kColumns) {
    const std::vector<double>& from = *log.column(name);
    std::vector<double>& to = *out.column(name);
    to.clear();
    for (std::size_t i = 0; i < from.size(); i += k) to.push_back(from[i]);
  }
  return out;
}

/// The rows of `log` outside [from, to).
GapLog withoutRows(const GapLog& log, double from, double to) {
  GapLog out = log;
  out.t.clear();
  for (const std::string& name : kColumns) out.column(name)->clear();
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (log.t[i] >= from && log.t[i] < to) continue;
    out.t.push_back(log.t[i]);
    for (const std::string& name : kColumns) out.column(name)->push_back((*log.column(name))[i]);
  }
  return out;
}

std::vector<InputCheck> ofKind(const std::vector<InputCheck>& checks, const std::string& kind) {
  std::vector<InputCheck> out;
  for (const auto& c : checks) {
    if (c.kind == kind) out.push_back(c);
  }
  return out;
}

std::string listed(const std::vector<InputCheck>& checks) {
  std::string out;
  for (const auto& c : checks) out += "\n  " + c.channel + " (" + c.kind + "): " + c.detail;
  return out.empty() ? " none" : out;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(InputChecks, TheBenchmarksLogsShowNothingOdd) {
  // No-effect logs of both manoeuvres at 500 Hz, and at 200 and 100 Hz (the independent family's rates).
  for (const double rate : {500.0, 200.0, 100.0}) {
    const auto checks = inputChecks(laneChange(rate), nominal());
    EXPECT_TRUE(checks.empty()) << rate << " Hz:" << listed(checks);
  }
  BenchmarkCase s{"checks", "none", "none", "", "sinusoid", {"simulation.duration=16"}, 4u};
  const auto checks = inputChecks(generateBenchmarkLog(s, SensorNoise{}, 500.0), benchmarkNominal("sinusoid"));
  EXPECT_TRUE(checks.empty()) << listed(checks);
  // Steering that asks for more than the tires give, at the start of a straight run with a 3 m offset at
  // p = 500 and in a saturating lane change: real, not a unit (a rule on delta's size alone named them).
  std::vector<BenchmarkCase> cases{benchmarkCase("torque_limit-large-lane_change")};
  for (const BenchmarkCase& c : familyCases("independent")) {
    if (c.id == "none-13-straight-p500-100Hz") cases.push_back(c);
  }
  ASSERT_EQ(cases.size(), 2u);
  for (const BenchmarkCase& c : cases) {
    const auto found = inputChecks(generateBenchmarkLog(c, SensorNoise{}, 500.0), benchmarkCaseNominal(c));
    EXPECT_TRUE(found.empty()) << c.id << ":" << listed(found);
  }
}

TEST(InputChecks, AHoleIsFoundWithWhereAndHowLong) {
  const GapLog log = withoutRows(laneChange(), 6.0, 11.0);
  const std::vector<TimeHole> holes = timeHoles(log);
  ASSERT_EQ(holes.size(), 1u);
  EXPECT_NEAR(holes[0].t0, 5.998, 1e-9);
  EXPECT_NEAR(holes[0].t1, 11.0, 1e-9);
  const auto found = ofKind(inputChecks(log, nominal()), "hole");
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].log, "run.csv");
  EXPECT_EQ(found[0].channel, "t");
  EXPECT_NEAR(found[0].t1 - found[0].t0, 5.002, 1e-9);
  EXPECT_TRUE(contains(found[0].detail, "no samples for 5 s (2501 median steps) from 5.998 s to 11 s after the log's "
                                        "start"))
      << found[0].detail;
  // Three rows skipped for NaN (a step of four) are no hole.
  EXPECT_TRUE(timeHoles(withoutRows(laneChange(), 6.0, 6.005)).empty());
}

TEST(InputChecks, AStuckSteeringAngleOrTorqueIsUnusable) {
  GapLog log = laneChange();
  for (double& d : log.delta) d = 0.0;  // the steering-angle sensor stuck at 0
  auto stuck = ofKind(inputChecks(log, nominal()), "stuck");
  ASSERT_EQ(stuck.size(), 1u) << listed(stuck);
  EXPECT_EQ(stuck[0].channel, "delta");
  EXPECT_TRUE(stuck[0].unusable);
  EXPECT_TRUE(contains(stuck[0].detail, "delta is constant at 0 rad while")) << stuck[0].detail;

  log = laneChange();
  for (double& m : log.torque) m = 4.0;  // a constant torque
  stuck = ofKind(inputChecks(log, nominal()), "stuck");
  ASSERT_EQ(stuck.size(), 1u) << listed(stuck);
  EXPECT_EQ(stuck[0].channel, "torque");
  EXPECT_TRUE(stuck[0].unusable);

  // Stuck with a little noise on it (a frozen value, re-sent with its quantisation) is nearly constant.
  log = laneChange();
  for (std::size_t i = 0; i < log.size(); ++i) log.yaw_rate[i] = 0.01 + 1e-5 * std::sin(0.7 * static_cast<double>(i));
  stuck = ofKind(inputChecks(log, nominal()), "stuck");
  ASSERT_EQ(stuck.size(), 1u) << listed(stuck);
  EXPECT_EQ(stuck[0].channel, "yaw_rate");
  EXPECT_TRUE(contains(stuck[0].detail, "nearly constant")) << stuck[0].detail;
}

TEST(InputChecks, TheSteeringLoopsAndTheChassisModesAreThoseOfTheirEquations) {
  SimConfig c;  // the paper's p = 2000: 0.25 s^2 + 200 s + 16000 = 0, s = -90 and -710 1/s
  const Modes steering = steeringLoopModes(c);
  EXPECT_NEAR(steering.slow, 90.0 / (2.0 * M_PI), 0.05);
  EXPECT_NEAR(steering.fast, 710.0 / (2.0 * M_PI), 0.05);
  c.actuator.p = 0.0;
  EXPECT_EQ(steeringLoopModes(c).slow, 0.0);  // no loop
  // The chassis: a yaw mode of about 1 Hz at 15 m/s, faster at lower speed.
  const Modes chassis = chassisModes(SimConfig{}, 15.0);
  EXPECT_GT(chassis.slow, 0.5);
  EXPECT_LT(chassis.fast, 3.0);
  EXPECT_GT(chassisModes(SimConfig{}, 5.0).fast, chassis.fast);
}

TEST(InputChecks, ARateBelowTheSteeringLoopsBandSkipsTheSteeringAndActuatorReplays) {
  const GapLog fine = laneChange();
  // 10 Hz (Nyquist 5 Hz) is below the loop's modes at p = 1000 (17.6 and 46.1 Hz): skipped.
  auto rate = ofKind(inputChecks(decimated(fine, 50), nominal()), "rate");
  ASSERT_FALSE(rate.empty());
  EXPECT_EQ(rate[0].skip, (std::vector<std::string>{"steering", "actuator"})) << listed(rate);
  EXPECT_TRUE(contains(rate[0].detail, "at 10 Hz (Nyquist 5 Hz) the steering loop's modes (17.6 and 46.1 Hz")) << rate[0].detail;
  // 50 Hz (Nyquist 25 Hz) resolves the slow mode, not the fast one: said, not skipped.
  rate = ofKind(inputChecks(decimated(fine, 10), nominal()), "rate");
  ASSERT_EQ(rate.size(), 1u) << listed(rate);
  EXPECT_TRUE(rate[0].skip.empty());
  EXPECT_TRUE(contains(rate[0].detail, "fast mode (46.1 Hz")) << rate[0].detail;
  // 1 Hz is below the chassis' modes too, and its step longer than the tracker's delay (0.2 s).
  rate = ofKind(inputChecks(decimated(fine, 500), nominal()), "rate");
  std::set<std::string> skipped;
  for (const auto& c : rate) skipped.insert(c.skip.begin(), c.skip.end());
  EXPECT_EQ(skipped, (std::set<std::string>{"actuator", "chassis", "steering", "tracker"})) << listed(rate);
}

TEST(InputChecks, AnglesInDegreesAndSpeedsInKmhLookWrong) {
  const GapLog clean = laneChange();
  GapLog log = clean;
  for (double& d : log.delta) d *= 180.0 / M_PI;
  auto units = ofKind(inputChecks(log, nominal()), "units");
  ASSERT_FALSE(units.empty());
  EXPECT_EQ(units[0].channel, "delta");
  EXPECT_TRUE(contains(units[0].detail, "a road-wheel angle in degrees would move 57-170 times")) << units[0].detail;

  // Without a yaw rate to compare with: by what it asks of the tires.
  log.yaw_rate.clear();
  units = ofKind(inputChecks(log, nominal()), "units");
  ASSERT_FALSE(units.empty());
  EXPECT_EQ(units[0].channel, "delta");
  EXPECT_TRUE(contains(units[0].detail, "beyond any tire's 20 m/s^2")) << units[0].detail;

  log = clean;
  for (double& p : log.psi) p *= 180.0 / M_PI;
  units = ofKind(inputChecks(log, nominal()), "units");
  ASSERT_EQ(units.size(), 1u) << listed(units);
  EXPECT_EQ(units[0].channel, "psi");

  log = clean;
  for (double& r : log.yaw_rate) r *= 180.0 / M_PI;
  units = ofKind(inputChecks(log, nominal()), "units");
  ASSERT_FALSE(units.empty());
  EXPECT_EQ(units[0].channel, "yaw_rate") << listed(units);

  log = clean;
  for (double& v : log.v) v *= 3.6;
  units = ofKind(inputChecks(log, nominal()), "units");
  ASSERT_EQ(units.size(), 1u) << listed(units);
  EXPECT_EQ(units[0].channel, "v");
  EXPECT_TRUE(contains(units[0].detail, "km/h")) << units[0].detail;
}

TEST(InputChecks, TimeInMillisecondsIsNamedAndOverALongSpanRefused) {
  GapLog log = laneChange(100.0);
  for (double& t : log.t) t *= 1000.0;  // 16 s at 100 Hz read as 16,000 s at 0.1 Hz
  const auto checks = inputChecks(log, nominal());
  const auto units = ofKind(checks, "units");
  ASSERT_FALSE(units.empty());
  EXPECT_EQ(units[0].channel, "t");
  EXPECT_TRUE(contains(units[0].detail, "looks like milliseconds (log mapping: `log: time: {unit: ms}`)"))
      << units[0].detail;
  try {
    refuseImplausibleLog(checks);
    FAIL() << "a log of 16,000 s at 0.1 Hz was not refused";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "run.csv: column 't': refused")) << e.what();
    EXPECT_TRUE(contains(e.what(), "`log: time: {unit: ms}`")) << e.what();
  }
  // A short one (0.5 s read as 500 s) is named, not refused.
  GapLog short_log = laneChange(100.0, 0.5);
  for (double& t : short_log.t) t *= 1000.0;
  const auto short_checks = inputChecks(short_log, nominal());
  EXPECT_FALSE(ofKind(short_checks, "units").empty());
  EXPECT_NO_THROW(refuseImplausibleLog(short_checks));
}

TEST(InputChecks, ASpeedAtOrBelowZeroOrFarFromTheConfigurationIsSaid) {
  GapLog log = laneChange();
  for (std::size_t i = 0; i < 100; ++i) log.v[i] = 0.0;
  auto speed = ofKind(inputChecks(log, nominal()), "speed");
  ASSERT_EQ(speed.size(), 1u) << listed(speed);
  EXPECT_TRUE(contains(speed[0].detail, "v <= 0 in 100 of 8001 samples (the first 0 s after the start)"))
      << speed[0].detail;
  SimConfig slower = nominal();
  slower.vehicle.speed = 10.0;  // the log drives at 15 m/s
  speed = ofKind(inputChecks(laneChange(), slower), "speed");
  ASSERT_EQ(speed.size(), 1u) << listed(speed);
  EXPECT_TRUE(contains(speed[0].detail, "is 50 % off vehicle.speed = 10 m/s")) << speed[0].detail;
}

}  // namespace
}  // namespace lane_keeping
