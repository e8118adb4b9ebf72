// Reading bags for the gap diagnosis: the suite's topics in any namespace, thinning, and clear errors
// for bags without them.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include <rosbag/bag.h>
#include <std_msgs/Float64.h>

#include <lane_keeping/DesiredSteeringArray.h>
#include <lane_keeping/SteeringTorqueArray.h>
#include <lane_keeping/VehicleStateArray.h>

#include "bag_log_reader.h"
#include "lane_keeping/common/errors.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string tempBag(const std::string& name) { return testing::TempDir() + name; }

/// 2 s of a plant at 1 kHz in namespace /car, desired steering at 100 Hz, optional torque commands; with
/// `wrapping_heading` psi turns at 0.8 rad/s from 3 rad and is wrapped into [-pi, pi] (crosses pi at 0.177 s).
void writeSuiteBag(const std::string& path, bool with_torque, bool nan_sample = false, bool wrapping_heading = false) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  for (int k = 0; k < 2000; k += 10) {
    lane_keeping::VehicleStateArray states;
    for (int i = k; i < k + 10; ++i) {
      lane_keeping::VehicleState s;
      s.header.stamp.fromNSec(static_cast<uint64_t>(i) * 1000000ull);
      s.x = 15.0 * i * 1e-3;
      s.y = 0.5;
      s.yaw_rate = 0.01;
      s.delta = 0.002 * i * 1e-3;
      s.speed = 15.0;
      s.steering_torque = 3.0;
      if (wrapping_heading) s.psi = std::remainder(3.0 + 0.8 * i * 1e-3, 2.0 * M_PI);
      if (nan_sample && i == 500) s.y = std::nan("");
      states.samples.push_back(s);
    }
    const ros::Duration receipt(1.0);  // record times must be > 0; the reader uses header stamps
    bag.write("/car/vehicle_state", states.samples.front().header.stamp + receipt, states);
    lane_keeping::DesiredSteeringArray desired;
    lane_keeping::DesiredSteering d;
    d.header.stamp.fromNSec(static_cast<uint64_t>(k) * 1000000ull);
    d.delta_des = 0.001 * k * 1e-3;
    desired.samples.push_back(d);
    bag.write("/car/desired_steering", d.header.stamp + receipt, desired);
    if (with_torque) {
      lane_keeping::SteeringTorqueArray torque;
      lane_keeping::SteeringTorque t;
      t.header.stamp = d.header.stamp;
      t.torque = 7.0;
      torque.samples.push_back(t);
      bag.write("/car/steering_torque", t.header.stamp + receipt, torque);
    }
  }
  bag.close();
}

TEST(BagLogReader, ReadsTheSuiteTopicsInAnyNamespace) {
  const std::string path = tempBag("suite.bag");
  writeSuiteBag(path, true);
  const GapLog log = readBagLog(path, 100.0);  // thinned from 1 kHz to 100 Hz
  ASSERT_GT(log.size(), 150u);
  EXPECT_LT(log.size(), 210u);
  EXPECT_NEAR(log.t[1] - log.t[0], 0.01, 1e-9);
  EXPECT_DOUBLE_EQ(log.y[3], 0.5);
  EXPECT_DOUBLE_EQ(log.torque[3], 7.0);  // the command, not the applied torque
  EXPECT_NEAR(log.delta_des[10], 0.001 * log.t[10], 1e-12);  // interpolated desired steering
  EXPECT_TRUE(log.hasSpeed() && log.hasLateralAcceleration() && log.hasSteeringRate());
}

TEST(BagLogReader, AHeadingThatWrapsAtPiIsUnwrappedAndTheNotesSaySo) {
  const std::string path = tempBag("wrapping.bag");
  writeSuiteBag(path, true, false, true);
  const GapLog log = readBagLog(path, 100.0);
  ASSERT_GT(log.size(), 150u);
  for (std::size_t i = 0; i < log.size(); ++i) {
    ASSERT_NEAR(log.psi[i], 3.0 + 0.8 * log.t[i], 1e-9) << "sample " << i;  // continuous through pi
  }
  bool said = false;
  for (const auto& note : log.notes) said = said || note.find("psi unwrapped: 1 wrap") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(BagLogReader, WithoutTorqueCommandsUsesTheAppliedTorqueAndSaysSo) {
  const std::string path = tempBag("no_torque.bag");
  writeSuiteBag(path, false, true);
  const GapLog log = readBagLog(path, 1000.0);
  EXPECT_DOUBLE_EQ(log.torque[3], 3.0);
  EXPECT_EQ(log.rows_skipped, 10u);  // the NaN sample, and 9 after the last desired steering (1.99 s)
  bool torque_noted = false, nan_noted = false;
  for (const auto& note : log.notes) {
    torque_noted = torque_noted || note.find("steering_torque") != std::string::npos;
    nan_noted = nan_noted || note.find("1 samples holding NaN") != std::string::npos;
  }
  EXPECT_TRUE(torque_noted);
  EXPECT_TRUE(nan_noted);
}

TEST(BagLogReader, BagWithoutTheSuiteTopicsNamesWhatIsMissing) {
  const std::string path = tempBag("other.bag");
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    std_msgs::Float64 value;
    value.data = 1.0;
    bag.write("/speedometer", ros::Time(1.0), value);
    bag.close();
  }
  try {
    readBagLog(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("other.bag"), std::string::npos) << what;
    EXPECT_NE(what.find("vehicle_state"), std::string::npos) << what;
    EXPECT_NE(what.find("/speedometer"), std::string::npos) << what;  // lists what the bag holds
  }
  EXPECT_THROW(readBagLog(tempBag("does_not_exist.bag")), InputError);
}


/// readBagLog's error for `path`, or "(no InputError)"; rosbag's own exceptions fail the test by escaping.
std::string bagError(const std::string& path) {
  try {
    readBagLog(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Found by fuzzing (fuzz/regressions/bag_log/): rosbag allocates what a bag's length fields state (4 GiB for
// a corrupt header length: out of memory, not an error) and takes any first line "#ROS... V2.0". The
// reader walks the records first and names the bag and the byte.
TEST(BagLogReaderFuzzRegressions, CorruptOrTruncatedBagsAreInputErrorsNamingTheBag) {
  const std::string good = tempBag("fuzz_good.bag");
  writeSuiteBag(good, true);
  const std::string bytes = readBytes(good);
  ASSERT_EQ(bytes.compare(0, 13, "#ROSBAG V2.0\n"), 0);

  std::string corrupt = bytes;
  corrupt.replace(13, 4, "\xff\xff\xff\xff");  // the file header record's header length
  const std::string header_length = tempBag("fuzz_header_length.bag");
  writeBytes(header_length, corrupt);
  std::string error = bagError(header_length);
  EXPECT_NE(error.find(header_length + ": not a readable bag (corrupt or truncated): byte 13"), std::string::npos) << error;

  const std::string truncated = tempBag("fuzz_truncated.bag");
  writeBytes(truncated, bytes.substr(0, bytes.size() / 2));
  error = bagError(truncated);
  EXPECT_NE(error.find(truncated + ": not a readable bag"), std::string::npos) << error;

  const std::string prefixed = tempBag("fuzz_version_line.bag");
  writeBytes(prefixed, "#ROS" + bytes);  // rosbag reads "#ROS#ROSBAG V2.0" as version 2.0
  error = bagError(prefixed);
  EXPECT_NE(error.find(prefixed + ": not a readable bag"), std::string::npos) << error;
  EXPECT_NE(error.find("#ROSBAG V2.0"), std::string::npos) << error;

  EXPECT_GT(readBagLog(good).size(), 10u);  // the walk accepts what rosbag writes
}

// Every bag that once crashed the fuzz target (fuzz/regressions/bag_log/: a 4 GiB header length, a
// connection header whose field runs past it - a heap overflow in ros::Header::parse -, a truncated bag,
// a prefixed version line, a message stating more samples than it holds - roscpp allocated 131 GB -, an index
// entry pointing outside its chunk - rosbag read there: SEGV, found in CI -, an index of a connection the bag
// does not define - rosbag read through a null pointer: SEGV at the 453,574th input of a 1,000,000-input run -,
// an index entry whose nanoseconds overflow the seconds - ros::Time threw std::runtime_error -) is an
// InputError naming it.
TEST(BagLogReaderFuzzRegressions, EveryRegressionInputIsAnInputErrorNamingTheBag) {
  const std::string dir = std::string(build_paths::sourceDir()) + "/fuzz/regressions/bag_log/";
  for (const char* name : {"header_length_4gib.bag", "connection_header_field.bag", "truncated.bag",
                           "version_line_prefix.bag", "sample_count.bag", "index_offset.bag",
                           "index_connection.bag", "index_time.bag"}) {
    const std::string error = bagError(dir + name);
    EXPECT_NE(error.find(dir + name + ": not a readable bag"), std::string::npos) << name << ": " << error;
  }
}

}  // namespace
}  // namespace lane_keeping
