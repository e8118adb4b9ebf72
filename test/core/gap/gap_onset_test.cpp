// A gap that sets in mid-run (gap_onset.h): a crosswind from x = 200 m of a 20 s run at 15 m/s is
// located from about t = 13.3 s, the whole-log fit of a constant force explains too little of it, and
// the diagnosis from the onset names it; the same crosswind from the start has no onset.
#include <gtest/gtest.h>

#include <cmath>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/gap_onset.h"

namespace lane_keeping {
namespace {

BenchmarkCase crosswind(const std::string& id, std::vector<std::string> overlay) {
  BenchmarkCase c{id, "in_list", "lateral_disturbance", "large", "sinusoid", std::move(overlay), 77};
  c.setup = {"simulation.duration=20", "actuator.p=1250"};
  return c;
}

GapReport diagnose(const BenchmarkCase& c) {
  DiagnosisOptions options;
  options.effects = {"lateral_disturbance", "cornering_stiffness", "road_friction"};
  options.closed_loop = false;
  return diagnoseGap(benchmarkCaseNominal(c), {generateBenchmarkLog(c, SensorNoise{}, 100.0)}, {}, options);
}

TEST(GapOnset, ACrosswindThatSetsInMidRunIsFoundFromItsOnset) {
  const GapReport r = diagnose(crosswind("onset", {"disturbance.lateral_force=500", "disturbance.yaw_moment=100",
                                                   "disturbance.onset_x=200"}));
  ASSERT_TRUE(std::isfinite(r.where.onset));
  EXPECT_NEAR(r.where.onset, 200.0 / 15.0, 1.0);  // x = 200 m at 15 m/s (the ramp adds 10 m)
  EXPECT_EQ(r.verdict.effect, "lateral_disturbance") << r.verdict.reason;
  EXPECT_GT(r.verdict.shrink, 0.6);
  EXPECT_NE(r.verdict.reason.find("the gap sets in at t = "), std::string::npos) << r.verdict.reason;
  ASSERT_FALSE(r.ranking.empty());
  EXPECT_NEAR(r.ranking[0].params.at("force"), 500.0, 150.0);
}

TEST(GapOnset, ACrosswindFromTheStartHasNoOnset) {
  const GapReport r = diagnose(crosswind("steady", {"disturbance.lateral_force=500", "disturbance.yaw_moment=100"}));
  EXPECT_FALSE(std::isfinite(r.where.onset)) << r.where.onset;
  EXPECT_EQ(r.verdict.effect, "lateral_disturbance") << r.verdict.reason;
  EXPECT_EQ(r.verdict.reason.find("sets in"), std::string::npos);
}

TEST(GapOnset, TheRunFromTheOnsetKeepsALeadInAndTakesItsStateFromTheLog) {
  const BenchmarkCase c = crosswind("cut", {});
  GapRun run = gapRun(generateBenchmarkLog(c, SensorNoise{}, 100.0), benchmarkCaseNominal(c));
  const GapRun cut = runFromOnset(run, 12.0);
  EXPECT_NEAR(cut.log.t.front(), 12.0 - kOnsetLeadIn, 0.011);
  EXPECT_EQ(cut.log.t.back(), run.log.t.back());
  EXPECT_TRUE(cut.initial_from_log);
}

}  // namespace
}  // namespace lane_keeping
