// The noise-only null's draws (noise_null.h): with fewer than ceil(1 / alpha) - 1 the Monte Carlo test's
// smallest p-value, 1 / (draws + 1), is above its level and no gap can be detected — `--noise-reference-draws
// 5` turned a steering-friction log's verdict into `unexplained`. Such counts are refused; 0 (no test) is
// allowed and said in the report.
#include <gtest/gtest.h>

#include <string>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/decision/noise_null.h"
#include "lane_keeping/gap/diagnosis.h"

namespace lane_keeping {
namespace {

TEST(NoiseDraws, TheFewestThatCanRejectAtTheTestsLevel) {
  EXPECT_EQ(diagnosis::minimumNoiseDraws(0.05), 19);
  EXPECT_EQ(diagnosis::minimumNoiseDraws(0.01), 99);
  EXPECT_EQ(diagnosis::minimumNoiseDraws(0.1), 9);
  EXPECT_EQ(diagnosis::minimumNoiseDraws(0.2), 4);
  EXPECT_THROW(diagnosis::minimumNoiseDraws(0.0), ConfigError);
}

TEST(NoiseDraws, TooFewAreRefusedAndNoneIsSaid) {
  BenchmarkCase c = benchmarkCase("steering_friction-large-lane_change");
  c.truth_overlay.push_back("simulation.duration=4");
  const GapLog log = generateBenchmarkLog(c, SensorNoise{}, 100.0);
  SimConfig nominal = benchmarkNominal(c.manoeuvre);
  nominal.simulation.duration = 4.0;
  DiagnosisOptions options;
  options.effects = {"steering_friction"};
  options.closed_loop = false;
  for (const int draws : {1, 5, 18}) {
    options.noise_reference_draws = draws;
    try {
      diagnoseGap(nominal, {log}, {}, options);
      ADD_FAILURE() << draws << " draws accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("needs at least 19 draws"), std::string::npos) << e.what();
    }
  }
  options.noise_reference_draws = 0;
  const GapReport r = diagnoseGap(nominal, {log}, {}, options);
  bool said = false;
  for (const auto& note : r.notes) said = said || note.find("no detection test ran") != std::string::npos;
  EXPECT_TRUE(said);
  EXPECT_EQ(r.detection.draws, 0);
}

}  // namespace
}  // namespace lane_keeping
