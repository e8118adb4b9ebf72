// A real car's log (data/comma2k19: one minute of a Toyota RAV4, imported by scripts/lk_import.py): the
// importer's decoding, the log read through the vehicle file's mapping, the nominal RAV4's chassis replay
// on it, and a diagnosis that is the same run to run. Figures in docs/real_car.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "lane_keeping/config/param_readers.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_reader.h"
#include "lane_keeping/gap/replay/chassis_replay.h"

namespace lane_keeping {
namespace {

const std::string kSource = LANE_KEEPING_SOURCE_DIR;
const std::string kVehicle = kSource + "/config/vehicles/rav4_2018.yaml";
const std::string kLog = kSource + "/data/comma2k19/rav4_segment40.csv";
const std::string kScenario = kSource + "/data/comma2k19/rav4_segment40.yaml";

GapRun realRun() {
  FlatParams nominal;
  nominal.overlayFile(kVehicle);
  nominal.erasePrefix("log.");
  return gapRun(readLog(kLog, readLogMapping(kVehicle)), nominal, kScenario);
}

TEST(RealCar, ImporterUnitTests) {
  // The DBC decoding on known frames and the geodesy (test/tools/test_lk_import.py).
  const std::string command = "cd '" + kSource + "' && /usr/bin/python3 -m unittest discover -s test/tools 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(RealCar, TheMinuteReadsThroughTheVehiclesMapping) {
  const GapRun run = realRun();
  const GapLog& log = run.log;
  ASSERT_EQ(log.size(), 5991u);  // 59.9 s at 100 Hz
  // The road-wheel angle is the steering-wheel angle over the steer ratio 16.88: the logged wheel turns
  // -4.6 to 2.5 degrees on this straight, the road wheel -0.27 to 0.15 (resampled to 100 Hz from 83 Hz:
  // the extremes within 0.05 degrees of the wheel).
  double lo = 1.0, hi = -1.0;
  for (double d : log.delta) {
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  EXPECT_NEAR(lo, -4.6 * M_PI / 180.0 / 16.88, 0.05 * M_PI / 180.0 / 16.88);
  EXPECT_NEAR(hi, 2.5 * M_PI / 180.0 / 16.88, 0.05 * M_PI / 180.0 / 16.88);
  EXPECT_TRUE(log.delta_des.empty());  // openpilot's desired angle is not on the bus
  EXPECT_EQ(run.config.vehicle.mass, 1791.6);
  EXPECT_EQ(run.config.path.type, "waypoints");  // the driven path, from the scenario
}

TEST(RealCar, TheNominalChassisReplayIsFiniteAndItsResidualMeasured) {
  const GapRun run = realRun();
  const LogSignals signals(run.log);
  ASSERT_TRUE(signals.speedVaries());  // 8 to 20 m/s: the replay takes V from the log
  const SubsystemReplay replay = replayChassis(run.config, signals, {{signals.start() + 0.6, signals.end()}});
  ASSERT_EQ(replay.traces.size(), 4u);  // yaw rate, psi, y, a_y
  for (const auto& trace : replay.traces) {
    ASSERT_GT(trace.predicted.size(), 1000u) << trace.name;
    for (double p : trace.predicted) ASSERT_TRUE(std::isfinite(p)) << trace.name;
  }
  const SubsystemScore score = scoreReplay(replay);
  EXPECT_TRUE(std::isfinite(score.nrmse));
  // The real car departs from the nominal single-track model well beyond the noise (docs/real_car.md:
  // a constant yaw-rate offset and a heading offset of the phone's mount dominate).
  EXPECT_GT(score.nrmse, 5.0 * score.floor);
}

TEST(RealCar, TheVerdictOnTheMinuteIsTheSameRunToRun) {
  DiagnosisOptions options;
  options.effects = {"pose_bias", "lateral_disturbance"};
  options.noise_reference_draws = 0;  // no noise-only null: fast (1-18 draws are refused: no test at 5 %)
  const GapReport a = diagnoseGap(realRun().config, {realRun()}, {}, options);
  const GapReport b = diagnoseGap(realRun().config, {realRun()}, {}, options);
  EXPECT_EQ(a.where.subsystem, "chassis");
  EXPECT_EQ(a.verdict.effect, b.verdict.effect);
  EXPECT_EQ(a.verdict.form, b.verdict.form);
  EXPECT_EQ(a.verdict.shrink, b.verdict.shrink);
  ASSERT_EQ(a.ranking.size(), b.ranking.size());
  for (std::size_t i = 0; i < a.ranking.size(); ++i) EXPECT_EQ(a.ranking[i].params, b.ranking[i].params);
  // Tracker, actuator and steering replays cannot be fed (no desired angle, torque in bus counts).
  EXPECT_EQ(a.skipped_subsystems.size(), 3u);
}

}  // namespace
}  // namespace lane_keeping
