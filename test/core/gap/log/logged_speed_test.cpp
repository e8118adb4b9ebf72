// The logged speed as the model needs it (gap/log/logged_speed.h): `v` holds the speed of the centre of
// gravity unless the mapping says front_axle; the diagnosis converts it to V of Beregi eq 1 where the run's
// geometry is known, and takes a profile in time from it for the closed-loop runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include <yaml-cpp/yaml.h>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/diagnosis_data.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/logged_speed.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/vehicle/speed_profile.h"

namespace lane_keeping {
namespace {

/// A tight sinusoidal lane at 10 m/s (3.2 m/s^2 peak, steering up to 0.11 rad): the speeds of G and of the
/// front axle differ by centimetres per second. Noise-free, logged at 200 Hz (lk_simulate's machinery).
SimConfig tightLane() {
  SimConfig c;
  c.path.type = "sinusoid";
  c.path.sinusoid_amplitude = 2.0;
  c.path.sinusoid_wavelength = 60.0;
  c.path.sinusoid_start = 10.0;
  c.tracker.k_y = 0.05;
  c.vehicle.speed = 10.0;
  c.simulation.duration = 14.0;
  c.simulation.log_rate = 200.0;
  return c;
}

RunResult runOf(const SimConfig& c) {
  const RunResult run = ClosedLoop(c).run();
  EXPECT_FALSE(run.diverged()) << run.message;
  return run;
}

TEST(LoggedSpeed, FrontAxleSpeedInvertsTheSpeedOfGExactly) {
  // A state of the model: V = 12 m/s; u from row 1 of eq 1, |v_G| = hypot(u, sigma1).
  const double V = 12.0, delta = 0.08, sigma1 = 0.4, r = 0.3, b = 1.03;
  const double u = (V - (sigma1 + b * r) * std::sin(delta)) / std::cos(delta);
  EXPECT_NEAR(frontAxleSpeed(std::hypot(u, sigma1), sigma1, r, delta, b), V, 1e-12);
  EXPECT_EQ(frontAxleSpeed(10.0, 0.0, 0.0, 0.0, b), 10.0);  // straight running: the two speeds agree
  EXPECT_EQ(frontAxleSpeed(0.1, 0.3, 0.0, 0.0, b), 0.0);    // |sigma1| > v_G (noise at a standstill): u = 0, no NaN
}

TEST(LoggedSpeed, ALogOfTheSpeedOfGIsConvertedToVOfEq1) {
  const SimConfig c = tightLane();
  const GapLog log = gapLogFromRows(runOf(c).rows, "tight.csv");
  ASSERT_EQ(log.speed_of, LoggedSpeed::kCentreOfGravity);  // what lk_simulate writes
  const LogSignals signals(log);
  const GapLog converted = withFrontAxleSpeed(signals, c.vehicle);
  EXPECT_EQ(converted.speed_of, LoggedSpeed::kFrontAxle);
  double raw = 0.0, worst = 0.0;
  for (std::size_t i = 200; i + 200 < log.size(); ++i) {  // away from the smoothing's ends
    raw = std::max(raw, std::fabs(log.v[i] - c.vehicle.speed));
    worst = std::max(worst, std::fabs(converted.v[i] - c.vehicle.speed));
  }
  // Measured: the speed of G departs from V by 0.017 m/s; converted, with sigma1 from the differentiated
  // pose, by 2.2e-4 m/s.
  std::printf("speed of G off V by %.3g m/s, converted %.3g\n", raw, worst);
  EXPECT_GT(raw, 0.01);
  EXPECT_LT(worst, 0.05 * raw);
  // Converted once: a log that holds V already is left as it is.
  EXPECT_FALSE(holdsCentreOfGravitySpeed(converted));
  EXPECT_EQ(withFrontAxleSpeed(LogSignals(converted), c.vehicle).v, converted.v);
}

TEST(LoggedSpeed, PreparedRunsHoldVWhateverTheirLogHeld) {
  const SimConfig c = tightLane();
  GapLog cg = gapLogFromRows(runOf(c).rows, "tight.csv");
  GapLog front = cg;
  front.speed_of = LoggedSpeed::kFrontAxle;  // a log mapped with `speed_of: front_axle` is taken at its word
  const std::vector<diagnosis::RunData> runs = diagnosis::prepareRuns({gapRun(cg, c), gapRun(front, c)});
  const std::vector<double>& from_cg = runs[0].log->samples(LogSignals::kSpeed);
  const std::vector<double>& from_front = runs[1].log->samples(LogSignals::kSpeed);
  EXPECT_EQ(runs[0].log->log().speed_of, LoggedSpeed::kFrontAxle);
  EXPECT_EQ(from_front, cg.v);
  double converted = 0.0;
  for (std::size_t i = 200; i + 200 < cg.size(); ++i) converted = std::max(converted, std::fabs(from_cg[i] - 10.0));
  EXPECT_LT(converted, 5e-4);
  // A log without a speed is left without one.
  GapLog none = cg;
  none.v.clear();
  EXPECT_FALSE(diagnosis::prepareRuns({gapRun(none, c)})[0].log->has(LogSignals::kSpeed));
}

TEST(LoggedSpeed, TheMappingSaysWhichSpeedALogHolds) {
  const YAML::Node front = YAML::Load("columns: {v: {column: wheel_speed, speed_of: front_axle}}\n");
  auto speedOf = [](const LogMapping& m) { return m.columns.at("v").speed_of; };
  EXPECT_EQ(speedOf(logMappingFromYaml(front, "map.yaml")), LoggedSpeed::kFrontAxle);
  EXPECT_EQ(speedOf(logMappingFromYaml(YAML::Load("columns: {v: {column: s, speed_of: cg}}\n"), "map.yaml")),
            LoggedSpeed::kCentreOfGravity);
  EXPECT_EQ(speedOf(logMappingFromYaml(YAML::Load("columns: {v: s}\n"), "map.yaml")), LoggedSpeed::kCentreOfGravity);
  auto refused = [](const std::string& yaml, const std::string& key, const std::string& where) {
    try {
      logMappingFromYaml(YAML::Load(yaml), "map.yaml");
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_NE(what.find(where), std::string::npos) << what;
    }
  };
  refused("time: {unit: s}\ncolumns:\n  v: {column: s, speed_of: rear_axle}\n", "log.columns.v.speed_of", "map.yaml:3");
  refused("columns:\n  yaw_rate: {column: r, speed_of: cg}\n", "log.columns.yaw_rate.speed_of", "map.yaml:2");
  refused("speed: front_axle\n", "log.speed", "map.yaml:1");  // not a top-level key: it belongs to v
  // Read with a CSV log, the meaning travels with it (and with its slices).
  const std::string path = testing::TempDir() + "speed_mapped.csv";
  {
    std::ofstream out(path);
    out << "t,x,y,psi,yaw_rate,delta,delta_des,torque,wheel_speed\n";
    for (int i = 0; i < 20; ++i) out << 0.01 * i << "," << 0.15 * i << ",0,0,0,0,0,0,15\n";
  }
  const GapLog log = readCsvLog(path, logMappingFromYaml(front, "map.yaml"));
  EXPECT_EQ(log.speed_of, LoggedSpeed::kFrontAxle);
  EXPECT_EQ(log.slice(2, 15).speed_of, LoggedSpeed::kFrontAxle);
  EXPECT_EQ(readCsvLog(path, logMappingFromYaml(YAML::Load("columns: {v: wheel_speed}\n"), "m.yaml")).speed_of,
            LoggedSpeed::kCentreOfGravity);
}

TEST(LoggedSpeed, AProfileInTimeFromTheLoggedSpeed) {
  SimConfig c = tightLane();
  c.path.sinusoid_amplitude = 0.5;  // 1.4 m/s^2 at 16 m/s
  c.vehicle.speed_profile = PointList{{2.0, 8.0}, {10.0, 16.0}};
  const RunResult run = runOf(c);
  GapLog log = gapLogFromRows(run.rows, "ramp.csv");
  for (double& t : log.t) t += 100.0;  // a log's own clock: the profile counts from its start
  const diagnosis::RunData prepared = diagnosis::prepareRuns({gapRun(log, c)})[0];
  ASSERT_TRUE(prepared.log->speedVaries());
  const PointList points = speedProfileFromLog(*prepared.log);
  ASSERT_EQ(points.size(), 141u);  // 0 to 14 s at 10 Hz
  EXPECT_EQ(points[0][0], 0.0);
  EXPECT_NEAR(points.points().back()[0], 14.0, 1e-9);
  const SpeedProfile followed(points), truth(c.vehicle.speed_profile);
  double worst = 0.0;
  for (double t = 0.0; t <= 14.0; t += 0.01) worst = std::max(worst, std::fabs(followed.at(t).speed - truth.at(t).speed));
  std::printf("profile from the log off the truth by %.3g m/s\n", worst);
  EXPECT_LT(worst, 3e-3);  // measured 2.9e-4 m/s
  // The closed loops take it; a constant speed leaves the configuration as it was.
  const SimConfig followed_config = withLoggedSpeed(tightLane(), *prepared.log);
  EXPECT_EQ(followed_config.vehicle.speed_profile, points);
  GapLog constant = gapLogFromRows(runOf(tightLane()).rows, "constant.csv");
  EXPECT_TRUE(withLoggedSpeed(tightLane(), LogSignals(constant)).vehicle.speed_profile.empty());
  constant.v.clear();
  EXPECT_THROW(speedProfileFromLog(LogSignals(constant)), InputError);
}

}  // namespace
}  // namespace lane_keeping
