// Configurations that are not one: a directory, a device, a file of millions of inline waypoints, a
// hundred thousand unknown keys, a lane the car cannot follow, a log rate above the plant's. Each is
// refused quickly, naming the file and the key, where they used to end in "basic_filebuf::underflow",
// a read without end, std::bad_alloc at 7.9 GB, minutes of validation, or "spinning out".
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "lane_keeping/config/config_text_limits.h"
#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/points_file.h"
#include "lane_keeping/config/sim_config.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string errorOf(const std::vector<std::string>& files, const std::vector<std::string>& sets = {}) {
  try {
    loadSimConfig(files, sets);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

TEST(ConfigLimits, ADirectoryOrADeviceIsNotAConfigurationFile) {
  const std::string dir = testing::TempDir() + "lk_config_dir";
  fs::create_directories(dir);
  EXPECT_NE(errorOf({dir}).find(dir + ": cannot read it as a configuration file: it is a directory"), std::string::npos)
      << errorOf({dir});
  const auto start = Clock::now();
  EXPECT_NE(errorOf({"/dev/zero"}).find("/dev/zero: cannot read it as a configuration file: it is a character device"),
            std::string::npos);
  EXPECT_LT(secondsSince(start), 1.0);
}

TEST(ConfigLimits, WaypointsFromADeviceAreRefusedAndABomIsSkipped) {
  const std::string yaml = writeTemp("lk_zero_lane.yaml", "path:\n  type: waypoints\n  waypoints: /dev/zero\n");
  const auto start = Clock::now();
  const std::string error = errorOf({yaml});
  EXPECT_LT(secondsSince(start), 1.0);  // was a read without end
  EXPECT_NE(error.find("path.waypoints = /dev/zero: /dev/zero: cannot read it as a points file: it is a character device"),
            std::string::npos)
      << error;
  // A spreadsheet's UTF-8 byte order mark before the header: read, not "expected 'x,y', got '﻿x,y'".
  writeTemp("lk_bom_lane.csv", "\xEF\xBB\xBFx,y\n0,0\n50,0.5\n100,2\n");
  const std::string bom = writeTemp("lk_bom_lane.yaml", "path:\n  type: waypoints\n  waypoints: lk_bom_lane.csv\n");
  EXPECT_EQ(errorOf({bom}), "");
  // A byte that does not print is shown by its code.
  std::vector<Point2> points;
  std::string why;
  EXPECT_FALSE(readPointsCsv(writeTemp("lk_nbsp_lane.csv", "0,0\n1\xC2\xA0,2\n"), &points, &why));
  EXPECT_NE(why.find("got '1\\xC2\\xA0,2'"), std::string::npos) << why;
}

TEST(ConfigLimits, MillionsOfInlineWaypointsAreRefusedNamingFileLineAndKey) {
  // 250,000 points [x, 0], x increasing: a valid lane, too long to hold inline (about 1 kB of yaml-cpp
  // nodes per number). Before: accepted after ~0.6 GB of nodes; 7 million ended in std::bad_alloc.
  std::string text = "simulation:\n  duration: 1\npath:\n  type: waypoints\n  waypoints: [";
  for (int i = 0; i < 250000; ++i) text += (i ? ",[" : "[") + std::to_string(i) + ",0]";
  text += "]\n";
  const std::string file = writeTemp("lk_inline_lane.yaml", text);
  const auto start = Clock::now();
  const std::string error = errorOf({file});
  EXPECT_LT(secondsSince(start), 20.0);  // a few seconds (yaml-cpp's event parser), even beside builds
  EXPECT_NE(error.find(file + ":5: path.waypoints holds more than 600000 values inline"), std::string::npos) << error;
  EXPECT_NE(error.find("put the points in a CSV file"), std::string::npos) << error;
  // 100,000 points inline (docs/benchmarks.md's longest YAML lane) still load.
  std::string ok = "path:\n  type: waypoints\n  waypoints: [";
  for (int i = 0; i < 100000; ++i) ok += (i ? ",[" : "[") + std::to_string(i) + ",0]";
  ok += "]\n";
  EXPECT_EQ(errorOf({writeTemp("lk_inline_lane_ok.yaml", ok)}), "");
}

TEST(ConfigLimits, AFileTooLargeToReadNamesTheListThatMakesItSo) {
  // 97 MB of 7 million waypoints inline ended in std::bad_alloc at 7.9 GB; 70 MB here, refused after the
  // first 600,000 values (about 3 MB read), naming the key.
  const std::string file = testing::TempDir() + "lk_huge_lane.yaml";
  {
    std::ofstream out(file, std::ios::binary);
    out << "path:\n  type: waypoints\n  waypoints:\n";
    std::string block;
    for (int i = 0; i < 100000; ++i) block += "    - [" + std::to_string(i) + ", 0.5]\n";
    while (out.tellp() < (70LL << 20)) out << block;
  }
  const auto start = Clock::now();
  const std::string error = errorOf({file});
  EXPECT_LT(secondsSince(start), 20.0);
  EXPECT_NE(error.find(file + ":4: path.waypoints holds more than 600000 values inline"), std::string::npos)
      << error.substr(0, 300);
  fs::remove(file);
}

TEST(ConfigLimits, HundredThousandUnknownKeysAreReadInLinearTimeAndCounted) {
  // Each key used to scan every entry read before it: 100,000 keys took over 2 minutes, and printed
  // every problem.
  std::string text = "typos:\n";
  for (int i = 0; i < 100000; ++i) text += "  key_" + std::to_string(i) + ": " + std::to_string(i) + "\n";
  const std::string file = writeTemp("lk_unknown_keys.yaml", text);
  const auto start = Clock::now();
  const std::string error = errorOf({file});
  EXPECT_LT(secondsSince(start), 30.0);  // 3 s on a quiet machine (yaml-cpp's parse); was over 2 minutes
  EXPECT_NE(error.find("invalid configuration (100000 problems):"), std::string::npos) << error.substr(0, 200);
  EXPECT_NE(error.find("... and 99980 more problems not shown"), std::string::npos);
  EXPECT_LT(error.size(), 4000u);
}

TEST(ConfigLimits, ALaneTheCarCannotFollowIsRefusedAgainstItsTurningRadius) {
  const std::string error = errorOf({}, {"path.type=sinusoid", "path.sinusoid.wavelength=1e-9"});
  EXPECT_NE(error.find("path.sinusoid.wavelength = 1e-09 m with path.sinusoid.amplitude = 1 m bends the lane to a "
                       "radius of "),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("the car turns no tighter than a radius of vehicle.wheelbase / "
                       "tan(simulation.divergence.max_steering_angle) = 0.999 m"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("the wavelength must be at least 6.28 m for this amplitude"), std::string::npos) << error;
  EXPECT_NE(errorOf({}, {"path.type=lane_change", "path.lane_change.length=0.5"}).find("path.lane_change.length = 0.5 m"),
            std::string::npos);
  EXPECT_NE(errorOf({}, {"path.type=sinusoid", "path.sinusoid.amplitude=1e12"}).find("beyond 1e8 m"), std::string::npos);
  // Without an offset no bend, but a length of 3.5e-310 m made the lane NaN (found by fuzzing).
  EXPECT_NE(errorOf({}, {"path.type=lane_change", "path.lane_change.offset=0", "path.lane_change.length=3.5e-310"})
                .find("path.lane_change.length = 3.5e-310 m is shorter than 0.001 m"),
            std::string::npos);
  EXPECT_EQ(errorOf({}, {"path.type=sinusoid", "path.sinusoid.wavelength=7"}), "");  // tight, but a car steers it
  EXPECT_EQ(errorOf({}, {"path.type=lane_change", "path.lane_change.length=5"}), "");
}

TEST(ConfigLimits, ALogRateAboveThePlantRateIsRefused) {
  const std::string error = errorOf({}, {"simulation.log_rate=20000"});
  EXPECT_NE(error.find("simulation.log_rate = 2e+04 Hz is above the plant's rate 1 / simulation.step = 1e+04 Hz"),
            std::string::npos)
      << error;
  EXPECT_EQ(errorOf({}, {"simulation.log_rate=10000"}), "");
}

}  // namespace
}  // namespace lane_keeping
