// Logs of real cars (issue 14): a column mapping (names, scale and offset, time unit, unscaled columns),
// and partial logs: the diagnosis replays the subsystems whose inputs and outputs are present, says which
// it skipped and why, and lists the candidates acting only on skipped ones as not testable.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "build_paths.h"
#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/evaluation/gap_metrics.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_signals.h"
#include "lane_keeping/gap/replay/subsystem_replay.h"

namespace lane_keeping {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string configError(const std::string& yaml) {
  try {
    readLogMapping(writeTemp("map_bad.yaml", yaml));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

TEST(LogMapping, MapsNamesScalesOffsetsAndTheTimeUnit) {
  const std::string map = writeTemp("map.yaml",
                                    "log:\n"
                                    "  time: {column: stamp_ms, unit: ms}\n"
                                    "  columns:\n"
                                    "    delta: {column: steering_wheel_angle, scale: 0.0625, offset: 0.001}\n"
                                    "    torque: {column: eps_counts, unscaled: true}\n"
                                    "    yaw_rate: gyro_z\n");
  const LogMapping m = readLogMapping(map);
  EXPECT_EQ(m.columnFor("t"), "stamp_ms");
  EXPECT_EQ(m.columnFor("delta"), "steering_wheel_angle");
  EXPECT_EQ(m.columnFor("yaw_rate"), "gyro_z");
  EXPECT_EQ(m.columnFor("x"), "x");
  std::string csv = "stamp_ms,steering_wheel_angle,eps_counts,gyro_z,x,y,psi\n";
  for (int i = 0; i < 20; ++i) {
    csv += std::to_string(1000 + 10 * i) + "," + std::to_string(0.16 * i) + ",37,0.01," + std::to_string(0.15 * i) +
           ",0,0\n";
  }
  const GapLog log = readCsvLog(writeTemp("mapped.csv", csv), m);
  ASSERT_EQ(log.size(), 20u);
  EXPECT_DOUBLE_EQ(log.t[3], 1.03);                        // ms -> s
  EXPECT_NEAR(log.delta[5], 0.0625 * 0.8 + 0.001, 1e-15);  // steering-wheel angle / 16 + offset
  EXPECT_DOUBLE_EQ(log.torque[0], 37.0);                   // kept, in its own units ...
  EXPECT_TRUE(log.has("torque"));
  EXPECT_FALSE(log.has("torque", true));                   // ... and marked unscaled
  EXPECT_EQ(log.mapping, map);
}

// The key rule the configuration reader broke under fuzzing (fuzz/regressions/sim_config/complex_key.yaml),
// here too (fuzz/regressions/csv_log/mapping_complex_key): a list as a key was yaml-cpp's BadConversion.
TEST(LogMapping, AListAsAKeyIsAConfigErrorNamingFileAndLine) {
  const std::string error = configError("log:\n  columns:\n    ? [delta]\n    : steering\n");
  EXPECT_NE(error.find("map_bad.yaml:3"), std::string::npos) << error;
  EXPECT_NE(error.find("a key must be a name"), std::string::npos) << error;
}

// Found by the log_mapping fuzz target (fuzz/regressions/log_mapping/duplicate_columns_key.yaml): a
// `columns:` given twice. The mapping's reader looked up the first and accepted it, the configuration's
// reader iterated both and refused a key of the second: the two readers of one `log:` section disagreed,
// and a mapping could hold what its author did not mean. Both refuse it now, naming both lines.
TEST(LogMapping, AKeyGivenTwiceIsRefusedByBothReaders) {
  std::string error = configError("log:\n  columns:\n    x: {column: east}\n  columns:\n    y: {column: north}\n");
  EXPECT_NE(error.find("map_bad.yaml:4"), std::string::npos) << error;
  EXPECT_NE(error.find("log.columns is given twice in one mapping (first at line 2)"), std::string::npos) << error;
  const std::string regression = std::string(build_paths::sourceDir()) + "/fuzz/regressions/log_mapping/duplicate_columns_key.yaml";
  try {
    readLogMapping(regression);
    FAIL() << "readLogMapping accepted a log: section with two columns: keys";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("duplicate_columns_key.yaml:7"), std::string::npos) << e.what();
  }
  try {
    loadSimConfig({regression}, {});
    FAIL() << "loadSimConfig accepted a log: section with two columns: keys";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("log.columns is given twice"), std::string::npos) << e.what();
  }
}

TEST(LogMapping, BadMappingsNameTheFileLineAndKey) {
  EXPECT_NE(configError("log:\n  columns:\n    steer: {column: a}\n").find("map_bad.yaml:3"), std::string::npos);
  EXPECT_NE(configError("log:\n  columns:\n    steer: {column: a}\n").find("log.columns.steer"), std::string::npos);
  EXPECT_NE(configError("log:\n  time: {column: t, unit: minutes}\n").find("is not a time unit"), std::string::npos);
  EXPECT_NE(configError("log:\n  columns:\n    delta: {column: a, scale: 0}\n").find("log.columns.delta.scale"),
            std::string::npos);
  EXPECT_NE(configError("log:\n  columns:\n    delta: {column: a}\n    torque: {column: a}\n").find("mapped twice"),
            std::string::npos);
  EXPECT_NE(configError("log:\n  columns:\n    delta: {scale: 2}\n").find("needs column"), std::string::npos);
  // A mapped column the file does not have.
  const LogMapping m = readLogMapping(writeTemp("map2.yaml", "log:\n  columns:\n    delta: {column: swa}\n"));
  try {
    readCsvLog(writeTemp("nomap.csv", "t,delta\n0,0\n0.1,0\n"), m);
    FAIL() << "a missing mapped column was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("column 'swa' (mapped to delta by"), std::string::npos) << e.what();
  }
}

/// A benchmark log (lane change, hidden effect `truth`) with the tracker's output and the torque removed.
GapLog chassisOnlyLog(const std::vector<std::string>& truth, unsigned seed) {
  BenchmarkCase c;
  c.id = "partial";
  c.manoeuvre = "lane_change";
  c.truth_overlay = truth;
  c.truth_overlay.push_back("simulation.duration=16");
  c.seed = seed;
  GapLog log = generateBenchmarkLog(c, SensorNoise{}, 200.0);
  log.delta_des.clear();
  log.torque.clear();
  return log;
}

TEST(PartialLog, LogSignalsAndReplaysKnowWhatIsMissing) {
  const GapLog log = chassisOnlyLog({}, 5u);
  const LogSignals signals(log);
  EXPECT_TRUE(signals.has(LogSignals::kSigma1));
  EXPECT_FALSE(signals.has(LogSignals::kDeltaDes));
  EXPECT_FALSE(signals.has(LogSignals::kDeltaDesRate));
  EXPECT_THROW(signals.at(LogSignals::kTorque, 1.0), LaneKeepingError);  // a clear error, not a crash
  EXPECT_EQ(replayUnavailable("chassis", log), "");
  EXPECT_EQ(replayUnavailable("tracker", log), "the log has no delta_des");
  EXPECT_EQ(replayUnavailable("actuator", log), "the log has no delta_des, torque");
  EXPECT_EQ(replayUnavailable("steering", log), "the log has no torque");
}

TEST(PartialLog, TheDiagnosisRunsWhatTheLogFeedsAndSaysWhatItSkipped) {
  // Road friction hidden in a log with no desired steering angle and no torque: only the chassis can be
  // replayed; effects that change only the steering or the tracker are not testable, not rejected.
  const GapLog log = chassisOnlyLog({"tire.front.mu=0.45", "tire.rear.mu=0.45", "tire.front.mu0=0.6",
                                     "tire.rear.mu0=0.6"},
                                    6u);
  SimConfig nominal = benchmarkNominal("lane_change");
  nominal.simulation.duration = 16.0;
  DiagnosisOptions options;
  options.effects = {"road_friction", "torque_limit", "sensing_delay", "cornering_stiffness"};
  GapReport r;
  ASSERT_NO_THROW(r = diagnoseGap(nominal, {log}, {}, options));
  std::set<std::string> skipped, untestable, ranked;
  for (const auto& s : r.skipped_subsystems) skipped.insert(s.name);
  for (const auto& e : r.not_testable) untestable.insert(e.effect);
  for (const auto& e : r.ranking) ranked.insert(e.effect);
  EXPECT_EQ(skipped, (std::set<std::string>{"actuator", "steering", "tracker"}));
  EXPECT_EQ(untestable, (std::set<std::string>{"sensing_delay", "torque_limit"}));
  EXPECT_EQ(ranked, (std::set<std::string>{"cornering_stiffness", "road_friction"}));
  EXPECT_EQ(r.where.subsystem, "chassis");
  EXPECT_EQ(r.verdict.effect, "road_friction") << r.verdict.reason;
  // No closed loop without the tracker's output: "not run (why)", not "0 -> 0" (issue 46).
  EXPECT_TRUE(std::isnan(r.how_far.before) && std::isnan(r.how_far.after));
  EXPECT_EQ(r.how_far.not_run, "the logs cannot drive the closed loop: partial.csv: the log has no delta_des");
  // Round trip of the new fields.
  const std::string path = testing::TempDir() + "partial_report.json";
  writeGapReportJson(path, r);
  const GapReport back = readGapReportJson(path);
  ASSERT_EQ(back.skipped_subsystems.size(), 3u);
  EXPECT_EQ(back.skipped_subsystems[0].reason, r.skipped_subsystems[0].reason);
  ASSERT_EQ(back.not_testable.size(), 2u);
}

TEST(PartialLog, AVehicleBusLogWithoutAnyPoseIsDiagnosedOnTheChassis) {
  // What a vehicle bus gives: time, speed, steering angle, yaw rate, lateral acceleration; no pose, no
  // lateral velocity (issue 46: "the log has no sigma1" ended lk_gap with exit 1). The chassis replay
  // needs no pose (the lateral velocity is a nuisance state), and a cornering-stiffness loss is found.
  GapLog log = chassisOnlyLog({"tire.front.lateral_stiffness=1.2e6", "tire.rear.lateral_stiffness=1.2e6"}, 7u);
  log.x.clear();
  log.y.clear();
  log.psi.clear();
  log.vy.clear();
  SimConfig nominal = benchmarkNominal("lane_change");
  nominal.simulation.duration = 16.0;
  DiagnosisOptions options;
  options.effects = {"cornering_stiffness", "sensing_delay", "sensor_offset", "sensor_latency"};
  GapReport r;
  ASSERT_NO_THROW(r = diagnoseGap(nominal, {log}, {}, options));
  EXPECT_EQ(r.where.subsystem, "chassis");
  std::set<std::string> untestable;
  for (const auto& e : r.not_testable) untestable.insert(e.effect);
  EXPECT_TRUE(untestable.count("sensing_delay"));
  EXPECT_TRUE(untestable.count("sensor_offset (heading)") || untestable.count("sensor_offset")) << r.verdict.reason;
  EXPECT_TRUE(untestable.count("sensor_latency (pose)") || untestable.count("sensor_latency")) << r.verdict.reason;
  EXPECT_EQ(r.verdict.effect, "cornering_stiffness") << r.verdict.reason;
}

TEST(PartialLog, ALogThatFeedsNoReplayIsAClearError) {
  GapLog log = chassisOnlyLog({}, 7u);
  log.delta.clear();
  log.delta_rate.clear();
  try {
    diagnoseGap(benchmarkNominal("lane_change"), {log}, {}, DiagnosisOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the logs feed no subsystem's replay"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chassis: partial.csv: the log has no delta"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lane_keeping

namespace lane_keeping {
namespace {

/// The chassis replay's excess on a log of a speed varying along the road (+-15 %), with and without
/// the log's speed column.
TEST(SpeedFromTheLog, TheReplaysFollowALoggedSpeedThatVaries) {
  BenchmarkCase c;
  c.id = "speed";
  c.manoeuvre = "sinusoid";
  c.truth_overlay = {"vehicle.speed_variation=0.15", "vehicle.speed_wavelength=110", "simulation.duration=16"};
  c.seed = 9u;
  const GapLog with_speed = generateBenchmarkLog(c, SensorNoise{}, 200.0);
  GapLog without_speed = with_speed;
  without_speed.v.clear();
  SimConfig nominal = benchmarkNominal("sinusoid");  // constant 15 m/s
  const LogSignals signals(with_speed);
  EXPECT_TRUE(signals.speedVaries());
  EXPECT_FALSE(LogSignals(generateBenchmarkLog(BenchmarkCase{"still", "none", "none", "", "sinusoid",
                                                             {"simulation.duration=16"}, 9u},
                                               SensorNoise{}, 200.0))
                   .speedVaries());  // a constant speed with noise on it does not count as varying
  const std::vector<TimeSegment> all{{1.0, 16.0}};
  const LogSignals constant_signals(without_speed);
  const SubsystemReplay chassis_followed = replayChassis(nominal, signals, all);
  const SubsystemReplay chassis_constant = replayChassis(nominal, constant_signals, all);
  const double followed = scoreReplay(chassis_followed).excess;
  const double constant = scoreReplay(chassis_constant).excess;
  EXPECT_GT(constant, 0.02) << "a 15 % speed variation the replay does not know of";
  EXPECT_LT(followed, 0.2 * constant) << "followed " << followed << ", constant " << constant;
  // The steering replay, with its lateral velocity from the chassis replay as the diagnosis runs it.
  const double steering_followed =
      scoreReplay(replaySteering(nominal, signals, all, {}, &chassis_followed.sigma1_estimate)).excess;
  const double steering_constant =
      scoreReplay(replaySteering(nominal, constant_signals, all, {}, &chassis_constant.sigma1_estimate)).excess;
  EXPECT_LT(steering_followed, 0.5 * steering_constant)
      << "followed " << steering_followed << ", constant " << steering_constant;
}

}  // namespace
}  // namespace lane_keeping
