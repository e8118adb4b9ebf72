// The independent benchmark family's runs of different roads (benchmark_cases.h): the held-out run's
// scenario, as lk_gap reads it over the case's nominal, reproduces the configuration the held-out log
// was generated under; the family holds the set-ups docs/gap.md describes; the groups of issues 46 and
// 47 (independent_groups.h) are well-formed: ids and seeds unique, every truth a candidate (in its form)
// or an out-of-list name, onsets that are runtime changes at the onset, and nominal loops that run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "gap_benchmark/benchmark_cases.h"
#include "gap_benchmark/independent_groups.h"
#include "lane_keeping/config/flat_params.h"
#include "lane_keeping/config/timed_change.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/report/gap_report.h"
#include "lane_keeping/sim/closed_loop.h"

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

TEST(BenchmarkFamily, IdsAndSeedsAreUnique) {
  std::set<std::string> ids;
  std::map<unsigned, std::string> seeds;  // every run's noise seed, held-out runs' included
  for (const BenchmarkCase& c : independentCases()) {
    EXPECT_TRUE(ids.insert(c.id).second) << "duplicate id " << c.id;
    EXPECT_EQ(c.id.find_first_of("/ \\"), std::string::npos) << c.id << ": an id names files";
    std::vector<BenchmarkCase> runs{c};
    if (!c.heldout_manoeuvre.empty()) runs.push_back(heldoutRunOf(c));
    for (const BenchmarkCase& run : runs) {
      const auto [it, fresh] = seeds.emplace(run.seed, run.id);
      EXPECT_TRUE(fresh) << run.id << " shares seed " << run.seed << " with " << it->second;
    }
  }
  EXPECT_GE(ids.size(), 150u);  // 77 first cases, 77 of the groups
}

TEST(BenchmarkFamily, EveryTruthIsACandidateInItsFormOrAnOutOfListName) {
  const std::vector<std::string>& names = candidateEffectNames();
  auto isCandidate = [&](const std::string& n) { return std::find(names.begin(), names.end(), n) != names.end(); };
  auto hasForm = [](const std::string& effect, const std::string& form) {
    for (const auto& e : candidateEffects()) {
      if (e.name == effect && e.form == form) return true;
    }
    return false;
  };
  for (const BenchmarkCase& c : independentCases()) {
    if (c.category == "none") {
      EXPECT_EQ(c.truth, "none") << c.id;
      EXPECT_TRUE(c.truth_overlay.empty() && c.truth_changes.empty()) << c.id << ": a no-effect log hides nothing";
      continue;
    }
    if (c.category == "out_of_list") {
      EXPECT_FALSE(isCandidate(c.truth)) << c.id;
      continue;
    }
    ASSERT_EQ(c.category, "in_list") << c.id;
    const auto truths = c.truthEffects();
    EXPECT_EQ(truths.front().effect, c.truth) << c.id << ": truth is the first of truths";
    EXPECT_TRUE(c.truths.empty() || c.truths.size() >= 2) << c.id << ": truths lists several";
    for (const auto& t : truths) {
      EXPECT_TRUE(isCandidate(t.effect)) << c.id << ": " << t.effect;
      if (!t.form.empty()) EXPECT_TRUE(hasForm(t.effect, t.form)) << c.id << ": " << t.effect << " (" << t.form << ")";
      // A sensor error is scored with its channel: "sensor_offset" alone would accept the wrong sensor.
      if (isSensorEffect(t.effect)) EXPECT_FALSE(t.form.empty()) << c.id << ": " << t.effect << " without its channel";
    }
  }
}

TEST(BenchmarkFamily, GroupsHoldWhatTheIssuesAskFor) {
  std::map<std::string, int> in_list, none, several, onsets, pairs;
  std::set<double> group_rates;
  for (const BenchmarkCase& c : independentCases()) {
    if (c.group.empty()) {
      // The family's first cases stay as they were: none of the groups' fields.
      EXPECT_TRUE(c.truths.empty() && c.onset == 0.0 && c.truth_changes.empty() && c.car.empty() &&
                  c.sensor_character.empty() && c.stamp_jitter == 0.0)
          << c.id;
      continue;
    }
    const auto& groups = independentGroupNames();
    ASSERT_NE(std::find(groups.begin(), groups.end(), c.group), groups.end()) << c.id << ": group " << c.group;
    in_list[c.group] += c.category == "in_list" && c.truths.empty();
    none[c.group] += c.category == "none";
    several[c.group] += c.truths.size() >= 2;
    pairs[c.group] += !c.heldout_manoeuvre.empty();
    if (c.onset > 0.0) {
      ++onsets[c.group];
      ASSERT_FALSE(c.truth_changes.empty()) << c.id << ": an onset is a runtime change of the truth";
      for (const auto& text : c.truth_changes) {
        EXPECT_DOUBLE_EQ(parseTimedChange(text).t, c.onset) << c.id << ": " << text;
      }
      EXPECT_GE(benchmarkCaseNominal(c).simulation.duration, c.onset + 5.0) << c.id << ": 5 s of the effect at least";
      if (!c.heldout_manoeuvre.empty()) EXPECT_GE(benchmarkCaseNominal(heldoutRunOf(c)).simulation.duration, c.onset + 5.0);
    }
    if (c.stamp_jitter > 0.0) {
      EXPECT_EQ(c.log_rate, 50.0) << c.id;
      EXPECT_LT(c.stamp_jitter, 0.5 / c.log_rate) << c.id;
    }
    if (c.group == "another car") EXPECT_EQ(c.car, suvCar()) << c.id;
  }
  EXPECT_GE(in_list["sensor errors"], 16);  // 8 sensor errors x 2 manoeuvres
  EXPECT_GE(none["sensor errors"], 8);      // no-effect logs through bus-like sensors
  EXPECT_GE(several["sensor errors"], 3);   // a sensor error with a physical effect
  EXPECT_EQ(several["two at once"], 8);
  EXPECT_EQ(pairs["two at once"], 8);
  EXPECT_GE(onsets["onsets"], 5);
  EXPECT_GE(pairs["onsets"], 2);
  EXPECT_GE(in_list["start of a log"], 4);
  EXPECT_GE(in_list["delays near the margin"], 3);
  EXPECT_GE(in_list["varying speed"], 5);
  EXPECT_GE(in_list["another car"], 4);
  EXPECT_GE(none["another car"], 2);
  EXPECT_GE(in_list["50 Hz jittered"], 5);
}

TEST(BenchmarkFamily, NewSetUpsRunTheirNominalLoopWithoutDiverging) {
  // Each distinct set-up (road, car, set-up keys, held-out runs' too) over its first 3 s: where a start
  // transient (a 2-3 m correction, a heading error) or another car's gains would make the nominal loop
  // leave its bounds. `lk_gap_benchmark generate` runs the whole truths.
  std::set<std::string> seen;
  int runs = 0;
  for (const BenchmarkCase& c : independentCases()) {
    if (c.group.empty()) continue;
    std::vector<BenchmarkCase> set_ups{c};
    if (!c.heldout_manoeuvre.empty()) set_ups.push_back(heldoutRunOf(c));
    for (const BenchmarkCase& run : set_ups) {
      SimConfig nominal = benchmarkCaseNominal(run);
      nominal.simulation.duration = 3.0;
      std::ostringstream key;
      nominal.simulation.name = nominal.simulation.description = "";
      nominal.print(key);
      if (!seen.insert(key.str()).second) continue;
      ++runs;
      const RunResult result = ClosedLoop(nominal).run();
      EXPECT_FALSE(result.diverged()) << run.id << ": " << result.message;
    }
  }
  EXPECT_GE(runs, 30);
}

TEST(BenchmarkFamily, GroupLogsCarryTheirSensorsAndStamps) {
  BenchmarkCase bus, jittered;
  for (const BenchmarkCase& c : independentCases()) {
    if (bus.id.empty() && c.category == "none" && c.sensor_character.count("yaw_rate") &&
        c.sensor_character.at("yaw_rate").quantum > 0.0 && c.sensor_character.at("yaw_rate").hold == 1) {
      bus = c;
    }
    if (jittered.id.empty() && c.stamp_jitter > 0.0) jittered = c;
  }
  ASSERT_FALSE(bus.id.empty());
  ASSERT_FALSE(jittered.id.empty());
  bus.setup.push_back("simulation.duration=2");
  const GapLog log = generateBenchmarkLog(bus, SensorNoise{}, 500.0);
  const double q = bus.sensor_character.at("yaw_rate").quantum;
  for (double r : log.yaw_rate) EXPECT_NEAR(r / q, std::round(r / q), 1e-6) << bus.id << ": a quantised yaw rate";

  jittered.setup.push_back("simulation.duration=2");
  const GapLog stamped = generateBenchmarkLog(jittered, SensorNoise{}, 500.0);
  BenchmarkCase plain = jittered;
  plain.stamp_jitter = 0.0;
  const GapLog exact = generateBenchmarkLog(plain, SensorNoise{}, 500.0);
  ASSERT_EQ(stamped.size(), exact.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < stamped.size(); ++i) {
    if (i > 0) EXPECT_GT(stamped.t[i], stamped.t[i - 1]);
    largest = std::max(largest, std::fabs(stamped.t[i] - exact.t[i]));
    EXPECT_EQ(stamped.y[i], exact.y[i]) << "the jitter moves the stamps, not the noise draws";
  }
  EXPECT_LE(largest, jittered.stamp_jitter);
  EXPECT_GT(largest, 0.5 * jittered.stamp_jitter);
  EXPECT_EQ(stamped.t[0], exact.t[0]);
  GapLog copy = exact;
  EXPECT_THROW(jitterStamps(copy, 0.011, 1), std::invalid_argument);  // half of 20 ms is 10 ms
}

}  // namespace
}  // namespace lane_keeping
