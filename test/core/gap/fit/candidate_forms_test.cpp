// Effects where real cars have them (candidate_forms.h): each form is fitted and the training data
// choose; on logs whose effect sits in the placement the first form does not model, the second one
// is found, named in the report, and explains the gap.
#include <gtest/gtest.h>

#include <cmath>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/fit/candidate_effects.h"
#include "lane_keeping/gap/fit/candidate_forms.h"

namespace lane_keeping {
namespace {

const CandidateEffect& form(const std::string& name, const std::string& form) {
  for (const auto& c : candidateEffects()) {
    if (c.name == name && c.form == form) return c;
  }
  throw std::runtime_error("no form " + form + " of " + name);
}

diagnosis::CandidateFit fitOf(const CandidateEffect& effect, bool ok, double train_after) {
  diagnosis::CandidateFit fit;
  fit.effect = &effect;
  fit.ok = ok;
  fit.train_after = train_after;
  return fit;
}

TEST(CandidateForms, EveryFormKeepsTheEffectNameAndSaysWhereItActs) {
  int forms = 0;
  for (const auto& c : candidateEffects()) {
    if (!c.form.empty()) ++forms;
    EXPECT_FALSE(c.subsystems.empty()) << c.label();
  }
  // Two each of steering_compliance and lateral_disturbance, pose_bias's tracker form, and the ten sensor
  // errors, each named by its channel (a localisation's heading bias is sensor_offset (heading) now).
  EXPECT_EQ(forms, 15);
  EXPECT_EQ(form("sensor_offset", "heading").subsystems, (std::vector<std::string>{"chassis", "steering"}));
  // The steering replay takes the lateral velocity from the chassis replay's estimate, which the gyro feeds.
  EXPECT_EQ(form("sensor_offset", "yaw_rate").subsystems, (std::vector<std::string>{"chassis", "steering"}));
  EXPECT_TRUE(effectChangesSubsystem("pose_bias", "tracker"));
  EXPECT_FALSE(effectChangesSubsystem("pose_bias", "chassis"));
  EXPECT_TRUE(effectChangesSubsystem("sensor_offset", "chassis"));
  EXPECT_TRUE(effectChangesSubsystem("steering_compliance", "actuator"));
  EXPECT_FALSE(effectChangesSubsystem("sensing_delay", "chassis"));
  SimConfig c;
  form("steering_compliance", "motor_sensor").apply({3000.0, 10.0, 0.05}, c);
  EXPECT_TRUE(c.steering.columnSensor());
  EXPECT_TRUE(c.problems().empty());
}

TEST(CandidateForms, TheFormWithTheSmallerTrainingGapStandsForTheEffect) {
  std::vector<diagnosis::CandidateFit> fits{fitOf(form("lateral_disturbance", "aerodynamic"), true, 0.02),
                                            fitOf(candidateEffect("inertia"), true, 0.03),
                                            fitOf(form("lateral_disturbance", "road_bank"), true, 0.01),
                                            fitOf(form("steering_compliance", "wheel_sensor"), true, 0.5),
                                            fitOf(form("steering_compliance", "motor_sensor"), false, 0.0)};
  std::vector<std::string> notes;
  diagnosis::keepBestForms(&fits, &notes);
  ASSERT_EQ(fits.size(), 3u);
  EXPECT_EQ(fits[0].effect->name, "inertia");  // order kept
  EXPECT_EQ(fits[1].effect->label(), "lateral_disturbance (road_bank)");
  EXPECT_EQ(fits[2].effect->label(), "steering_compliance (wheel_sensor)");  // a failed fit never wins
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("aerodynamic 0.02, road_bank 0.01"), std::string::npos) << notes[0];
}

GapReport diagnose(BenchmarkCase c, const std::vector<std::string>& effects, double duration, double log_rate) {
  c.setup.push_back("simulation.duration=" + std::to_string(duration));
  const GapLog log = generateBenchmarkLog(c, SensorNoise{}, log_rate);
  DiagnosisOptions options;
  options.effects = effects;
  options.closed_loop = false;
  return diagnoseGap(benchmarkCaseNominal(c), {log}, {}, options);
}

const RankedEffect& ranked(const GapReport& r, const std::string& effect, const std::string& form = "") {
  for (const auto& e : r.ranking) {
    if (e.effect == effect && (form.empty() || e.form == form)) return e;
  }
  throw std::runtime_error("effect not ranked: " + effect + " " + form);
}

TEST(CandidateForms, AColumnSensedOnTheMotorSideIsFoundInTheActuatorReplay) {
  // The PID closes on the column's motor side, the log shows the road wheel: the actuator replay on the
  // logged wheel angle carries a gap that the wheel-sensor column cannot change.
  BenchmarkCase c{"column-motor", "in_list", "steering_compliance", "large", "lane_change",
                  {"steering.column_stiffness=1500", "steering.column_damping=15", "steering.column_inertia=0.05",
                   "steering.angle_sensor=column"},
                  7};
  const GapReport r = diagnose(c, {"steering_compliance", "actuation_delay", "steering_friction"}, 16.0, 500.0);
  EXPECT_EQ(r.where.subsystem, "actuator");
  EXPECT_EQ(r.verdict.effect, "steering_compliance") << r.verdict.reason;
  EXPECT_EQ(r.verdict.form, "motor_sensor");
  EXPECT_GT(r.verdict.shrink, 0.8);
  EXPECT_GT(ranked(r, "steering_compliance").params.at("stiffness"), 1000.0);
  EXPECT_LT(ranked(r, "steering_compliance").params.at("stiffness"), 2500.0);
}

TEST(CandidateForms, AHeadingBiasTheLogRecordsIsFoundInTheChassisReplay) {
  // The tracker and the log share a localisation 6 mrad off in heading: the tracker replay matches (it
  // sees the logged pose), the chassis replay integrates the biased heading into y. A sensor error, named
  // as one (sensor_offset of the heading), not as the tracker's pose bias or a side force.
  BenchmarkCase c{"localisation", "in_list", "sensor_offset", "large", "bend", {"sensors.pose_bias_psi=0.006"}, 8};
  const GapReport r = diagnose(c, {"pose_bias", "sensor_offset", "lateral_disturbance", "sensing_delay"}, 16.0, 200.0);
  // (The steering replay takes its lateral velocity from the chassis replay: the gap may show there.)
  EXPECT_TRUE(r.where.subsystem == "chassis" || r.where.subsystem == "steering") << r.where.subsystem;
  EXPECT_EQ(r.verdict.effect, "sensor_offset") << r.verdict.reason;
  EXPECT_EQ(r.verdict.form, "heading");
  EXPECT_GT(r.verdict.shrink, 0.8);
  EXPECT_NEAR(ranked(r, "sensor_offset", "heading").params.at("bias"), 0.006, 0.0006);
}

}  // namespace
}  // namespace lane_keeping
