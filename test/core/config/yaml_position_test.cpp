// Where in a YAML file something is (yaml_position.h): the 1-based line yaml-cpp's 0-based mark points at, and
// the file alone for a node without a position.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>

#include "lane_keeping/config/yaml_position.h"

namespace lane_keeping {
namespace {

TEST(YamlPosition, NamesTheLineOfAParsedNodeAndOnlyTheFileOfABuiltOne) {
  const YAML::Node root = YAML::Load("vehicle:\n  mass: 1500\n  speed: 20\n");
  EXPECT_EQ(yamlPosition("car.yaml", root["vehicle"]["speed"].Mark()), "car.yaml:3");
  EXPECT_EQ(yamlPosition("car.yaml", root["vehicle"]["mass"].Mark()), "car.yaml:2");
  YAML::Node built;
  built["mass"] = 1500;
  EXPECT_EQ(yamlPosition("--set", built.Mark()), "--set");
  EXPECT_EQ(yamlPosition("car.yaml", YAML::Mark::null_mark()), "car.yaml");
}

}  // namespace
}  // namespace lane_keeping
