// The ROS parameter adapter without a master: an XmlRpc tree (what the parameter server hands a
// node after `rosparam load`) reads into exactly the configuration the YAML file gives lk_simulate,
// and a bad value fails with the key named.
#include <gtest/gtest.h>

#include <string>

#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/sim_config.h"
#include "ros_config.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

SimConfig fromTree(const XmlRpc::XmlRpcValue& tree) {
  FlatParams source;
  source.overlayNode(toYaml(tree), "ROS parameters /test/config");
  return simConfigFromFlat(source);
}

std::string scenario(const std::string& name) {
  return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name;
}

/// Fig 9's keys as the parameter server holds them after `rosparam load` (PyYAML types).
XmlRpc::XmlRpcValue fig9Tree() {
  XmlRpc::XmlRpcValue t;
  t["simulation"]["name"] = std::string("fig9");
  t["simulation"]["description"] =
      std::string("Beregi Fig 9: k_psi=0.8, k_y=0.01 1/m, p=2000, tau1=0.2 s, tau2=1.9019505 ms, brush tires (unstable)");
  t["simulation"]["duration"] = 2.0;
  t["simulation"]["initial"]["y"] = 1.0;
  t["tire"]["front"]["model"] = std::string("brush");
  t["tire"]["rear"]["model"] = std::string("brush");
  t["tracker"]["k_psi"] = 0.8;
  t["tracker"]["k_y"] = 0.01;
  t["actuator"]["p"] = 2000.0;
  t["delays"]["pose_to_tracker"] = 0.2;
  t["delays"]["desired_steering_to_actuator"] = 1.9019505e-3;
  t["delays"]["steering_angle_to_actuator"] = 1.9019505e-3;
  return t;
}

TEST(RosConfig, ParameterTreeGivesTheSameConfigurationAsTheFile) {
  const SimConfig from_file = loadSimConfig({scenario("fig9.yaml")});
  const SimConfig from_params = fromTree(fig9Tree());
  std::ostringstream a, b;
  from_file.print(a);
  from_params.print(b);
  EXPECT_EQ(a.str(), b.str());
  // Bit-identical numbers, not just equal printouts.
  EXPECT_EQ(from_file.delays.desired_steering_to_actuator, from_params.delays.desired_steering_to_actuator);
  EXPECT_EQ(from_file.tracker.k_y, from_params.tracker.k_y);
}

TEST(RosConfig, ScalarTypesConvertLikeTheYamlReader) {
  XmlRpc::XmlRpcValue t;
  t["tire"]["front"]["lugre"]["bristles"] = 50;                    // int
  t["tire"]["front"]["lugre"]["turn_slip"] = true;                 // bool
  t["tire"]["front"]["lugre"]["sigma0y"] = std::string("auto");    // string
  t["tire"]["front"]["lateral_stiffness"] = std::string("2e+06");  // PyYAML reads 2e+06 as a string
  t["path"]["type"] = std::string("waypoints");
  XmlRpc::XmlRpcValue points;
  for (int i = 0; i < 3; ++i) {
    points[i][0] = 50.0 * i;
    points[i][1] = i == 2 ? 1 : 0;  // ints inside lists too
  }
  t["path"]["waypoints"] = points;
  const SimConfig c = fromTree(t);
  EXPECT_EQ(c.tire_front.lugre.bristles, 50);
  EXPECT_TRUE(c.tire_front.lugre.turn_slip);
  EXPECT_EQ(c.tire_front.lateral_stiffness, 2e6);
  ASSERT_EQ(c.path.waypoints.size(), 3u);
  EXPECT_EQ(c.path.waypoints[2][1], 1.0);
}

TEST(RosConfig, BadValueIsReportedWithItsKey) {
  XmlRpc::XmlRpcValue t = fig9Tree();
  t["vehicle"]["mass"] = -1100.0;
  t["delays"]["hold"] = std::string("cubic");
  try {
    fromTree(t);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("vehicle.mass"), std::string::npos) << what;
    EXPECT_NE(what.find("delays.hold"), std::string::npos) << what;
    EXPECT_NE(what.find("ROS parameters /test/config"), std::string::npos) << what;
  }
  XmlRpc::XmlRpcValue typo = fig9Tree();
  typo["tracker"]["k_yy"] = 0.1;
  try {
    fromTree(typo);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("tracker.k_yy"), std::string::npos) << e.what();
  }
}

TEST(RosConfig, NonNumericValueIsReportedWithItsKey) {
  XmlRpc::XmlRpcValue t;
  t["actuator"]["p"] = std::string("strong");
  try {
    fromTree(t);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("actuator.p"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lane_keeping
