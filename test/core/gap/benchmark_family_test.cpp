// The independent benchmark family's runs of different roads (benchmark_cases.h): the held-out run's
// scenario, as lk_gap reads it over the case's nominal, reproduces the configuration the held-out log
// was generated under; the family holds the set-ups docs/gap.md describes.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/gap/log/gap_run.h"

namespace lane_keeping {
namespace {

std::string printed(SimConfig c) {
  c.simulation.name = c.simulation.description = "";  // free text, not part of the run
  std::ostringstream out;
  c.print(out);
  return out.str();
}

TEST(BenchmarkFamily, HeldOutScenarioOverTheNominalIsTheConfigurationOfTheHeldOutLog) {
  int pairs = 0;
  for (const BenchmarkCase& c : independentCases()) {
    if (c.heldout_manoeuvre.empty()) continue;
    ++pairs;
    const BenchmarkCase h = heldoutRunOf(c);
    ASSERT_NE(h.manoeuvre, c.manoeuvre) << c.id << ": the held-out run is on another road";
    ASSERT_NE(h.seed, c.seed) << c.id;
    const std::string file = ::testing::TempDir() + "/" + h.id + ".yaml";
    std::ofstream(file) << benchmarkScenarioYaml(h);
    FlatParams nominal;
    std::ostringstream yaml;
    benchmarkCaseNominal(c).print(yaml);
    nominal.overlayText(yaml.str(), "case nominal");
    GapRun run = gapRun(generateBenchmarkLog(h, SensorNoise{}, 100.0), nominal, file);  // throws on a car key
    EXPECT_FALSE(run.initial_from_log) << c.id;
    EXPECT_EQ(printed(run.config), printed(benchmarkCaseNominal(h))) << c.id;
    EXPECT_NE(printed(run.config), printed(benchmarkCaseNominal(c))) << c.id << ": the scenario changes the road";
    std::remove(file.c_str());
  }
  EXPECT_GE(pairs, 8);
}

TEST(BenchmarkFamily, IndependentFamilySpansTheSetUpsItClaims) {
  int none = 0, onset = 0;
  std::set<std::string> manoeuvres;
  std::set<double> rates;
  for (const BenchmarkCase& c : independentCases()) {
    none += c.category == "none";
    manoeuvres.insert(c.manoeuvre);
    rates.insert(c.log_rate);
    for (const auto& a : c.truth_overlay) onset += a.rfind("disturbance.onset_x=", 0) == 0;
  }
  EXPECT_GE(none, 40);  // the false-alarm rate is measured over at least 40 no-effect logs
  EXPECT_GE(onset, 2);
  EXPECT_EQ(manoeuvres, (std::set<std::string>{"bend", "lane_change", "sinusoid", "straight"}));
  EXPECT_TRUE(rates.count(100.0) && rates.count(1000.0));
}

}  // namespace
}  // namespace lane_keeping
