// Where the gap lies (decision/where_analysis.h): the operating-regime bins of a real run, whose speed is
// not the configured one (issue 46).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/decision/where_analysis.h"
#include "lane_keeping/gap/evaluation/evaluation.h"

namespace lane_keeping {
namespace {

TEST(WhereAnalysis, TheRegimeBinsTakeTheLoggedSpeed) {
  // A lane change logged with a constant speed column of 30 m/s (twice the configured 15 m/s; constant,
  // so the replays keep the configured speed) and no ay: |a_y| is binned as |v yaw_rate|, not |V yaw_rate|.
  BenchmarkCase c{"regimes", "none", "none", "", "lane_change", {"simulation.duration=16"}, 5u};
  GapLog log = generateBenchmarkLog(c, SensorNoise{}, 200.0);
  log.ay.clear();
  for (double& v : log.v) v = 30.0;
  SimConfig nominal = benchmarkNominal("lane_change");
  nominal.simulation.duration = 16.0;
  diagnosis::RunData run;
  run.log = std::make_shared<const LogSignals>(log);
  run.config = std::make_shared<const SimConfig>(nominal);
  const std::vector<diagnosis::Dataset> data = diagnosis::wholeLogs({run}, 0.6);
  const diagnosis::Evaluation ev = diagnosis::evaluate(nullptr, data, {"chassis"}, ReplayOptions{});
  const GapWhere where = diagnosis::whereAnalysis(ev, data, 0.2, nullptr);
  ASSERT_EQ(where.subsystem, "chassis");
  double binned = -1.0;
  for (const auto& r : where.regimes) {
    if (r.variable == "lateral_acceleration" && r.lo == 0.0) binned = r.time_share;
  }
  // The share of samples with |a_y| < 0.5 m/s^2, with the logged and with the configured speed.
  double logged = 0.0, configured = 0.0, n = 0.0;
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (log.t[i] < 0.6) continue;
    logged += std::fabs(30.0 * log.yaw_rate[i]) < 0.5;
    configured += std::fabs(15.0 * log.yaw_rate[i]) < 0.5;
    n += 1.0;
  }
  logged /= n;
  configured /= n;
  ASSERT_GT(configured - logged, 0.1) << "the test needs speeds that bin apart";
  EXPECT_NEAR(binned, logged, 0.02) << "configured-speed share " << configured;
}

}  // namespace
}  // namespace lane_keeping
