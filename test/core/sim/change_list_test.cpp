// A list of runtime changes (lk_simulate --change, a node's ~changes) that cannot mean what it says: a
// change after the run's end was dropped without a word, and one key given twice at one time was
// reported as two changes to the later value.
#include <gtest/gtest.h>

#include <string>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/change_schedule.h"

namespace lane_keeping {
namespace {

std::string refusal(const std::vector<std::string>& texts) {
  SimConfig config;
  config.simulation.duration = 20.0;
  ChangeSchedule schedule(config);
  std::vector<TimedChange> list;
  for (const auto& text : texts) list.push_back(parseTimedChange(text));
  try {
    schedule.addAll(list, "--change");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ChangeList, AChangeAfterTheRunsEndIsRefused) {
  EXPECT_EQ(refusal({"100:steering.coulomb_friction=3"}),
            "invalid configuration (1 problem):\n  - --change '100:steering.coulomb_friction=3': "
            "steering.coulomb_friction at t = 100 s is after the run's end (simulation.duration = 20 s): it would "
            "never take effect");
  EXPECT_EQ(refusal({"20:steering.coulomb_friction=3"}), "");  // at the end: the last row holds it
}

TEST(ChangeList, OneKeyTwiceAtOneTimeIsRefused) {
  EXPECT_EQ(refusal({"5:steering.coulomb_friction=1", "5:steering.coulomb_friction=2"}),
            "invalid configuration (1 problem):\n  - --change '5:steering.coulomb_friction=2': "
            "steering.coulomb_friction is changed twice at t = 5 s ('5:steering.coulomb_friction=1' and "
            "'5:steering.coulomb_friction=2'): give one value");
  EXPECT_EQ(refusal({"5:steering.coulomb_friction=1", "6:steering.coulomb_friction=2"}), "");
}

}  // namespace
}  // namespace lane_keeping
