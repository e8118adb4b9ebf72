// lk_gap_benchmark's `ceiling` end to end: the truth model of each log scored as the diagnosis scores a verdict,
// held out (its shrink) and in closed loop (its how far, net of the logs' noise), and set beside the verdicts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "build_paths.h"
#include "lane_keeping/common/child_process.h"

namespace lane_keeping {
namespace {

namespace fs = std::filesystem;

// `ceiling` scores the truth model in closed loop as a verdict's how far is scored, and `score` sets it beside
// the verdicts' in the group tables: the three-run groups' verdicts closed 73.8 % and 41.9 % net on the second
// fresh draw, their truth models 73.8 % and 42.8 % — a ceiling of the measure, not the diagnosis's miss.
TEST(GapBenchmarkCeiling, TheCeilingGivesTheTruthModelsHowFarBesideTheVerdicts) {
  const std::string bin = std::string(build_paths::toolsDir()) + "/lk_gap_benchmark";
  const fs::path dir = fs::path(testing::TempDir()) / "lk_ceiling_how_far";
  fs::remove_all(dir);
  const std::string id = "torque_limit-start-2m-straight-500Hz";
  for (const std::vector<std::string>& step :
       {std::vector<std::string>{"generate", "--out", dir.string(), "--family", "independent", "--cases", id},
        {"diagnose", "--dir", dir.string(), "--cases", id}, {"ceiling", "--dir", dir.string(), "--cases", id}}) {
    std::vector<std::string> args{bin};
    args.insert(args.end(), step.begin(), step.end());
    const ChildResult done = runChild(args, true);
    ASSERT_TRUE(done.ok()) << step.front() << ": " << done.error_output;
  }
  std::ifstream in(dir / "reports" / id / "ceiling.json");
  const nlohmann::json ceiling = nlohmann::json::parse(in);
  ASSERT_TRUE(ceiling["how_far"]["net_shrink"].is_number()) << ceiling.dump();
  const double truth = ceiling["how_far"]["net_shrink"].get<double>();
  EXPECT_GT(truth, 0.5);  // the truth's torque limit, which the initial correction reaches, closes most of it
  EXPECT_LE(truth, 1.0);
  std::ifstream report_in(dir / "reports" / id / "report.json");
  const nlohmann::json report = nlohmann::json::parse(report_in);
  EXPECT_DOUBLE_EQ(ceiling["how_far"]["net_before"].get<double>(), report["how_far"]["net_before"].get<double>());
  const ChildResult scored = runChild({bin, "score", "--dir", dir.string()}, true);
  ASSERT_TRUE(scored.ok()) << scored.error_output;
  EXPECT_NE(scored.output.find("| the truth model's own on the same logs (`ceiling`, net) |"), std::string::npos)
      << scored.output;
  EXPECT_NE(scored.output.find("; the truth model's "), std::string::npos) << scored.output;
}

}  // namespace
}  // namespace lane_keeping
