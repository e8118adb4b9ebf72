// Reading real logs as they come (issue 46 item 4): a heading that wraps at +-pi is unwrapped where it is
// read, a column logged late is moved back by the mapping's `shift:`, and a logged lateral velocity (`vy`)
// stands in for the one differentiated from the pose.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/log/angle_unwrap.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"
#include "lane_keeping/gap/log/log_signals.h"

namespace lane_keeping {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

bool noted(const GapLog& log, const std::string& part) {
  for (const auto& note : log.notes) {
    if (note.find(part) != std::string::npos) return true;
  }
  return false;
}

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

TEST(AngleUnwrap, RemovesSingleWrapsEitherWayAndLeavesOtherJumps) {
  std::vector<double> up{3.0, 3.1, -3.1, -3.0, 3.1};  // through +pi, then back through it
  EXPECT_EQ(unwrapAngle(&up), 2u);
  EXPECT_NEAR(up[2], 2.0 * M_PI - 3.1, 1e-12);
  EXPECT_NEAR(up[3], 2.0 * M_PI - 3.0, 1e-12);
  EXPECT_NEAR(up[4], 3.1, 1e-12);
  // Degrees wrapping at +-180 step by ~360: not a wrap of radians, left for the units check to name.
  std::vector<double> degrees{178.0, 179.5, -179.0, -178.0};
  EXPECT_EQ(unwrapAngle(&degrees), 0u);
  EXPECT_EQ(degrees[2], -179.0);
  // A jump of 4 rad (a glitch, not a wrap) stays.
  std::vector<double> glitch{0.0, 4.0, 0.1};
  EXPECT_EQ(unwrapAngle(&glitch), 0u);
}

TEST(RealLogReading, AHeadingThatWrapsAtPiIsUnwrappedWhereTheCsvIsRead) {
  // psi turns at 0.8 rad/s from 3 rad, as a localisation reports it: wrapped into (-pi, pi].
  std::string csv = "t,x,y,psi\n";
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.01 * i;
    csv += number(t) + "," + number(15.0 * t) + ",0," + number(std::remainder(3.0 + 0.8 * t, 2.0 * M_PI)) + "\n";
  }
  const GapLog log = readCsvLog(writeTemp("wrapping_heading.csv", csv));
  ASSERT_EQ(log.size(), 1000u);
  for (std::size_t i = 0; i < log.size(); ++i) ASSERT_NEAR(log.psi[i], 3.0 + 0.8 * log.t[i], 1e-9) << "row " << i;
  EXPECT_TRUE(noted(log, "psi unwrapped: 2 wraps at +-pi removed")) << (log.notes.empty() ? "" : log.notes[0]);
}

/// 10 s at 100 Hz of a yaw-rate channel logged `late` seconds late (its raw value at t is the true one at
/// t - late) beside a steering angle logged on time. The true signals: delta = 0.01 sin(2 t),
/// yaw_rate = 0.1 sin(2 t).
std::string lateYawRateCsv(double late) {
  std::string csv = "t,delta,yaw\n";
  for (int i = 0; i < 1000; ++i) {
    const double t = 0.01 * i;
    csv += number(t) + "," + number(0.01 * std::sin(2.0 * t)) + "," + number(0.1 * std::sin(2.0 * (t - late))) + "\n";
  }
  return csv;
}

TEST(RealLogReading, AColumnLoggedLateIsMovedBackOntoTheTimeBase) {
  const std::string csv = writeTemp("late_yaw.csv", lateYawRateCsv(0.2));
  const std::string map = writeTemp("late_yaw_map.yaml", "log:\n  columns:\n    yaw_rate: {column: yaw, shift: 0.2}\n");
  const GapLog as_logged = readCsvLog(csv, readLogMapping(writeTemp("plain_map.yaml", "log:\n  columns:\n    yaw_rate: yaw\n")));
  const GapLog log = readCsvLog(csv, readLogMapping(map));
  // The last 0.2 s have no yaw rate at t + 0.2: dropped (0.2 s = 20 rows of 1000), every column alike.
  ASSERT_EQ(log.size(), 980u);
  EXPECT_DOUBLE_EQ(log.t.back(), 9.79);
  double before = 0.0, after = 0.0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    const double truth = 0.1 * std::sin(2.0 * log.t[i]);
    after = std::max(after, std::fabs(log.yaw_rate[i] - truth));
    before = std::max(before, std::fabs(as_logged.yaw_rate[i] - truth));
    EXPECT_DOUBLE_EQ(log.delta[i], as_logged.delta[i]);  // unshifted columns keep their values
  }
  EXPECT_GT(before, 0.039);  // 0.1 * 2 * 0.2 at the steepest
  EXPECT_LT(after, 1e-12);   // the raw samples fall on the time base: interpolation is exact there
  EXPECT_TRUE(noted(log, "yaw_rate shifted by 0.2 s (log mapping " + map + ":3)"));
  EXPECT_TRUE(noted(log, "20 rows dropped where a shifted column would read beyond the log (0 at the start, 20 at the end)"));

  // A column logged early (negative shift), off the sample grid: interpolated, rows dropped at the start.
  const GapLog early = readCsvLog(writeTemp("early_yaw.csv", lateYawRateCsv(-0.125)),
                                  readLogMapping(writeTemp("early_map.yaml",
                                                           "log:\n  columns:\n    yaw_rate: {column: yaw, shift: -0.125}\n")));
  ASSERT_EQ(early.size(), 987u);  // rows with t - 0.125 < 0 dropped: t = 0 ... 0.12
  EXPECT_DOUBLE_EQ(early.t.front(), 0.13);
  double worst = 0.0;
  for (std::size_t i = 0; i < early.size(); ++i) {
    worst = std::max(worst, std::fabs(early.yaw_rate[i] - 0.1 * std::sin(2.0 * early.t[i])));
  }
  EXPECT_LT(worst, 0.1 * 4.0 * 0.01 * 0.01 / 8.0 + 1e-12);  // linear interpolation's error: f'' h^2 / 8
}

std::string configError(const std::string& yaml) {
  try {
    readLogMapping(writeTemp("shift_bad.yaml", yaml));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "(no ConfigError)";
}

TEST(RealLogReading, ABadShiftNamesTheFileLineAndKey) {
  for (const std::string shift : {".nan", ".inf", "abc", "11", "-30"}) {
    const std::string error = configError("log:\n  columns:\n    yaw_rate: {column: yaw, shift: " + shift + "}\n");
    EXPECT_NE(error.find("shift_bad.yaml:3"), std::string::npos) << shift << ": " << error;
    EXPECT_NE(error.find("log.columns.yaw_rate.shift"), std::string::npos) << shift << ": " << error;
  }
  EXPECT_NE(configError("log:\n  columns:\n    yaw_rate: {column: yaw, shift: 11}\n").find("a clock error"),
            std::string::npos);
  // A shift that leaves no log: an InputError naming the log and the mapping entry.
  std::string csv = "t,yaw\n";
  for (int i = 0; i < 20; ++i) csv += number(0.01 * i) + ",0\n";
  const std::string map = writeTemp("long_shift.yaml", "log:\n  columns:\n    yaw_rate: {column: yaw, shift: 0.5}\n");
  try {
    readCsvLog(writeTemp("short.csv", csv), readLogMapping(map));
    FAIL() << "a shift longer than the log was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("short.csv"), std::string::npos) << what;
    EXPECT_NE(what.find(map + ":3"), std::string::npos) << what;
  }
}

TEST(RealLogReading, ALoggedLateralVelocityIsSigma1) {
  EXPECT_TRUE(isSchemaColumn("vy"));
  // A car crabbing at 0.3 m/s while its pose says it drives straight along x: sigma1 is the logged one.
  std::string csv = "t,x,y,psi,lateral_velocity\n";
  for (int i = 0; i < 500; ++i) {
    const double t = 0.01 * i;
    csv += number(t) + "," + number(15.0 * t) + ",0,0," + number(0.3 + 0.1 * std::sin(t)) + "\n";
  }
  const std::string path = writeTemp("crab.csv", csv);
  const LogMapping map = readLogMapping(writeTemp("vy_map.yaml", "log:\n  columns:\n    vy: {column: lateral_velocity}\n"));
  const GapLog log = readCsvLog(path, map);
  ASSERT_TRUE(log.hasLateralVelocity());
  const LogSignals signals(log);
  EXPECT_NEAR(signals.at(LogSignals::kSigma1, 2.5), 0.3 + 0.1 * std::sin(2.5), 1e-9);
  // Without it the replays differentiate the pose: no lateral motion at all.
  const LogSignals from_pose(readCsvLog(path));
  EXPECT_NEAR(from_pose.at(LogSignals::kSigma1, 2.5), 0.0, 1e-9);
  // A lateral velocity without a pose is still one.
  GapLog no_pose = log;
  no_pose.x.clear();
  no_pose.y.clear();
  no_pose.psi.clear();
  EXPECT_TRUE(LogSignals(no_pose).has(LogSignals::kSigma1));
  // Beyond what a car does (|vy| <= 50 m/s): a units error naming the line.
  try {
    readCsvLog(writeTemp("fast_crab.csv", "t,vy\n0,0\n0.1,80\n"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fast_crab.csv:3: column 'vy' holds 80"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lane_keeping
