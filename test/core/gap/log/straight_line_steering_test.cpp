// The steering angle at which the car goes straight (log/straight_line_steering.h): the offset in closed form,
// the slight curvature's kinematic steer taken out, straights in opposite directions telling a sensor's zero from a
// crosswind, nothing on the benchmark's no-effect runs, the benchmark's steering offset with its truth, and the
// race car's zero on each lap where the straights put it by hand (docs/real_logs/super_fj_fuji.md).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_reader.h"
#include "lane_keeping/gap/log/straight_line_steering.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

constexpr double kWheelbase = 2.7;

/// 30 s at 50 Hz and 20 m/s: straight (course `first`) for 10 s, a 5 s turn at 0.3 rad/s (1.5 g-free: only
/// its yaw), straight again (course `first` + 1.5 rad) ... with the road wheels at `offset` plus the kinematic steer
/// of a slight constant curvature `curve` [1/m] on the straights, and white noise.
GapLog run(double offset, double curve = 0.0, unsigned seed = 3u, double turn_rate = 0.3) {
  GapLog log;
  log.source = "straights.csv";
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  const double v = 20.0;
  double psi = 0.0;
  for (int i = 0; i <= 1500; ++i) {
    const double t = 0.02 * i;
    const bool turning = t >= 10.0 && t < 15.0;
    const double r = turning ? turn_rate : v * curve;
    psi += 0.02 * r;
    log.t.push_back(t);
    log.v.push_back(v);
    log.psi.push_back(psi);
    log.yaw_rate.push_back(r + 0.002 * unit(rng));
    log.ay.push_back(v * r + 0.05 * unit(rng));
    log.delta.push_back(offset + kWheelbase * r / v + 2e-4 * unit(rng));
  }
  return log;
}

TEST(StraightLineSteering, TheOffsetIsTheRoadWheelAngleLessTheKinematicSteer) {
  const StraightLineSteering s = straightLineSteering(run(0.004), kWheelbase);
  ASSERT_EQ(s.stretches.size(), 2u);  // before and after the turn; the turn itself is not straight
  EXPECT_NEAR(s.offset, 0.004, 5e-5);
  EXPECT_TRUE(s.found);
  // A slight curve (V r = 0.1 m/s^2) asks for l r / V = 0.27 mrad of steer: taken out, the same offset.
  const StraightLineSteering curved = straightLineSteering(run(0.004, 2.5e-4), kWheelbase);
  EXPECT_NEAR(curved.offset, 0.004, 5e-5);
  // Without the kinematic term the estimate would be 0.34 mrad off: the test can fail.
  EXPECT_GT(std::fabs(straightLineSteering(run(0.004, 2.5e-4), 0.0).offset - 0.004), 3e-4);
  // No offset, or one below 1 mrad: nothing reported.
  EXPECT_FALSE(straightLineSteering(run(0.0), kWheelbase).found);
  EXPECT_FALSE(straightLineSteering(run(0.0006), kWheelbase).found);
}

TEST(StraightLineSteering, StraightsInOppositeDirectionsThatAgreeAreNoCrosswind) {
  // A turn of 3.14 rad between the straights: they run 180 degrees apart.
  auto found = straightLineSteeringChecks(run(0.004, 0.0, 3u, M_PI / 5.0), kWheelbase);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].channel, "delta");
  EXPECT_EQ(found[0].kind, "offset");
  EXPECT_NE(found[0].detail.find("+4.00 +- 0.0"), std::string::npos) << found[0].detail;
  EXPECT_NE(found[0].detail.find("so not a crosswind"), std::string::npos) << found[0].detail;
  // 86 degrees apart: a crosswind is not excluded.
  found = straightLineSteeringChecks(run(0.004), kWheelbase);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NE(found[0].detail.find("such as a crosswind"), std::string::npos) << found[0].detail;
}

TEST(StraightLineSteering, TheBenchmarksSteeringOffsetIsFoundAndItsNoEffectRunsShowNothing) {
  for (const std::string manoeuvre : {"lane_change", "sinusoid", "bend"}) {
    BenchmarkCase c{"checks", "none", "none", "", manoeuvre, {"simulation.duration=20"}, 6u};
    const GapLog log = generateBenchmarkLog(c, SensorNoise{}, 100.0);
    EXPECT_FALSE(straightLineSteering(log, benchmarkNominal(manoeuvre).vehicle.wheelbase).found) << manoeuvre;
  }
  std::size_t seen = 0;
  for (const BenchmarkCase& c : familyCases("independent")) {
    if (c.id != "sensor-steering_offset-sinusoid") continue;
    ++seen;
    const StraightLineSteering s = straightLineSteering(generateBenchmarkLog(c, SensorNoise{}, 100.0),
                                                        benchmarkCaseNominal(c).vehicle.wheelbase);
    EXPECT_TRUE(s.found);
    EXPECT_NEAR(s.offset, 0.3 * M_PI / 180.0, 3.0 * s.sigma + 2e-4);  // the truth: 0.3 degrees, 5.24 mrad
  }
  EXPECT_EQ(seen, 1u);
}

TEST(StraightLineSteering, TheRaceCarsZeroIsWhereTheStraightsPutItByHand) {
  // By hand (lk_log_checks.py, the first straight up to the braking point): +4.46, +5.23, +5.57 mrad.
  const std::string source = build_paths::sourceDir();
  const std::string vehicle = source + "/config/vehicles/super_fj.yaml";
  FlatParams params;
  params.overlayFile(vehicle);
  params.erasePrefix("log.");
  const double wheelbase = simConfigFromFlat(params).vehicle.wheelbase;
  const std::vector<std::pair<std::string, double>> laps{
      {"super_fj_fuji_t1_lap6", 4.46e-3}, {"super_fj_fuji_t1", 5.23e-3}, {"super_fj_fuji_t1_lap8", 5.57e-3}};
  for (const auto& [lap, by_hand] : laps) {
    const GapLog log = readLog(source + "/data/aim_super_fj/" + lap + ".csv", readLogMapping(vehicle));
    const StraightLineSteering s = straightLineSteering(log, wheelbase);
    EXPECT_TRUE(s.found) << lap;
    EXPECT_NEAR(s.offset, by_hand, 0.8e-3) << lap;  // 3.92, 5.19, 5.94 mrad
  }
}

}  // namespace
}  // namespace lane_keeping
