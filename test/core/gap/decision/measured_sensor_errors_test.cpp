// Sensor errors measured before any model, against the verdict's effects (decision/measured_sensor_errors.h).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gap_benchmark/benchmark_cases.h"
#include "lane_keeping/gap/decision/measured_sensor_errors.h"
#include "lane_keeping/gap/diagnosis.h"

namespace lane_keeping {
namespace diagnosis {
namespace {

InputCheckEntry check(const std::string& log, const std::string& channel, const std::string& kind) {
  InputCheckEntry c;
  c.log = log;
  c.channel = channel;
  c.kind = kind;
  c.detail = "the gyro reads 0.84";
  return c;
}

VerdictEffect effect(const std::string& name, const std::string& form) {
  VerdictEffect e;
  e.effect = name;
  e.form = form;
  return e;
}

MeasuredSensorError gyroScale(double value, double sigma, std::size_t logs) {
  MeasuredSensorError m;
  m.effect = "sensor_scale";
  m.form = "yaw_rate";
  m.parameter = "scale";
  m.key = "sensors.yaw_rate_scale";
  m.value = value;
  m.sigma = sigma;
  m.logs = logs;
  m.detail = "the gyro reads " + std::to_string(value);
  return m;
}

TEST(MeasuredSensorErrors, AGyroScaleTheVerdictDoesNotNameIsSaidOnceForAllLogs) {
  GapReport r;
  r.input_checks = {check("lap6.csv", "yaw_rate", "scale"), check("lap7.csv", "yaw_rate", "scale"),
                    check("lap7.csv", "t", "hole")};
  r.verdict.effect = "sensor_scale";
  r.verdict.form = "steering_angle";
  r.verdict.effects = {effect("sensor_scale", "steering_angle")};
  const auto notes = measuredSensorErrorNotes(r);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("a scale error on yaw_rate (2 logs; lap6.csv: the gyro reads 0.84)"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("sensor_scale (yaw_rate) is not among them"), std::string::npos) << notes[0];
}

TEST(MeasuredSensorErrors, NothingWhereTheVerdictHoldsItOrNothingWasMeasured) {
  GapReport r;
  r.input_checks = {check("run.csv", "yaw_rate", "bias")};
  r.verdict.effects = {effect("cornering_stiffness", ""), effect("sensor_offset", "yaw_rate")};
  EXPECT_TRUE(measuredSensorErrorNotes(r).empty());
  r.input_checks = {check("run.csv", "t", "hole"), check("run.csv", "delta", "stuck")};
  EXPECT_TRUE(measuredSensorErrorNotes(r).empty());
}

// A heading's or an accelerometer's scale is no candidate's (the sensor candidates scale the yaw rate and the
// steering angle): the note says no candidate models it, and names no label a fit could not have.
TEST(MeasuredSensorErrors, AScaleNoCandidateModelsIsSaidSoNotNamedAsACandidate) {
  GapReport r;
  r.input_checks = {check("run.csv", "psi", "scale"), check("run.csv", "ay", "scale"), check("run.csv", "delta", "scale")};
  r.verdict.effects = {effect("cornering_stiffness", "")};
  const auto notes = measuredSensorErrorNotes(r);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_NE(notes[0].find("no candidate models a scale error of psi"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("no candidate models a scale error of ay"), std::string::npos) << notes[1];
  EXPECT_NE(notes[2].find("sensor_scale (steering_angle) is not among them"), std::string::npos) << notes[2];
  for (const auto& note : notes) {
    EXPECT_EQ(note.find("sensor_scale (heading)"), std::string::npos) << note;
    EXPECT_EQ(note.find("sensor_scale (lateral_acceleration)"), std::string::npos) << note;
  }
}

TEST(MeasuredSensorErrors, TheMeasuredErrorLeadsWhereItRemovesMostAndTheSharesAreOfTheGapAsLogged) {
  const MeasuredSensorError m = gyroScale(0.84, 0.01, 3);
  // The diagnosis of the corrected logs named a side force removing 90 % of its gap (0.5 -> 0.05).
  GapReport r;
  r.verdict.effect = "lateral_disturbance";
  r.verdict.form = "aerodynamic";
  r.verdict.gap_before = 0.5;
  r.verdict.gap_after = 0.05;
  r.verdict.combined_gap_after = 0.05;
  VerdictEffect side = effect("lateral_disturbance", "aerodynamic");
  side.share = 0.9;
  side.gap_after = 0.05;
  r.verdict.effects = {side};
  GapReport led = r;
  // As logged 0.6, corrected 0.5 on the nominal's reference (= the diagnosis's 0.5): the correction 16.7 %.
  withMeasuredErrors(&r, {m}, 0.6, 0.5);
  ASSERT_EQ(r.verdict.effects.size(), 2u);
  EXPECT_EQ(r.verdict.effect, "lateral_disturbance");  // 0.9 * 5/6 = 75 % against 16.7 %
  EXPECT_EQ(r.verdict.effects[0].effect, "lateral_disturbance");
  EXPECT_NEAR(r.verdict.effects[0].share, 0.75, 1e-12);
  EXPECT_TRUE(r.verdict.effects[1].measured);
  EXPECT_NEAR(r.verdict.effects[1].share, 1.0 / 6.0, 1e-12);
  EXPECT_EQ(r.verdict.effects[1].config.at("sensors.yaw_rate_scale"), "0.84");
  EXPECT_NEAR(r.verdict.gap_before, 0.6, 1e-12);
  EXPECT_NEAR(r.verdict.shrink, 1.0 - 0.05 / 0.6, 1e-12);
  EXPECT_NE(r.verdict.reason.find("besides, measured before any model"), std::string::npos) << r.verdict.reason;
  // Nothing named on the corrected logs: the measured error is the verdict, its share the whole shrink.
  led.verdict = GapVerdict{};
  led.verdict.effect = "unexplained";
  led.verdict.gap_before = 0.1;
  led.verdict.reason = "nothing to explain";
  withMeasuredErrors(&led, {m}, 0.6, 0.1);
  EXPECT_EQ(led.verdict.effect, "sensor_scale");
  EXPECT_EQ(led.verdict.form, "yaw_rate");
  EXPECT_EQ(led.verdict.basis, "measured");
  EXPECT_NEAR(led.verdict.shrink, 1.0 - 0.1 / 0.6, 1e-12);
  EXPECT_NEAR(led.verdict.confidence, 1.0 - 0.1 / 0.6, 1e-12);
  ASSERT_EQ(led.verdict.effects.size(), 1u);
  EXPECT_TRUE(std::isnan(led.verdict.effects[0].evidence));
}

// Where nothing explains the gap and the correction does not shrink it, the measured error is a fact about the
// sensor, not the gap's cause: the verdict stays unexplained (the race car's lap 6: its gyro's 0.829 raised the
// held-out gap 0.626 -> 0.773, and was named the verdict with a shrink of -23 %).
TEST(MeasuredSensorErrors, ACorrectionThatDoesNotShrinkTheGapNamesNoCause) {
  const MeasuredSensorError gyro = gyroScale(0.829, 0.015, 1);
  for (const double corrected : {0.773, 0.5}) {
    GapReport r;
    r.verdict.effect = "unexplained";
    r.verdict.reason = "a gap that no candidate explains";
    r.verdict.gap_before = r.verdict.gap_after = 0.8247;
    withMeasuredErrors(&r, {gyro}, 0.626, corrected);
    if (corrected > 0.626) {
      EXPECT_EQ(r.verdict.effect, "unexplained") << r.verdict.reason;
      EXPECT_TRUE(r.verdict.effects.empty());
      EXPECT_DOUBLE_EQ(r.verdict.gap_before, 0.626);
      EXPECT_DOUBLE_EQ(r.verdict.gap_after, 0.626);
      EXPECT_DOUBLE_EQ(r.verdict.shrink, 0.0);
      EXPECT_NE(r.verdict.reason.find("the correction does not shrink the gap, so it names no cause of it"),
                std::string::npos)
          << r.verdict.reason;
      ASSERT_FALSE(r.notes.empty());
      EXPECT_NE(r.notes.back().find("a sensor fact, not the gap's cause"), std::string::npos) << r.notes.back();
    } else {
      // Where it does shrink it, the measured error leads (as before).
      EXPECT_EQ(r.verdict.effect, "sensor_scale") << r.verdict.reason;
      EXPECT_NEAR(r.verdict.shrink, 1.0 - 0.5 / 0.626, 1e-12);
    }
  }
}

TEST(MeasuredSensorErrors, AGyroBiasMeasuredBeforeAnyModelIsCorrectedAndNamed) {
  // The independent family's gyro bias on the bend (0.008 rad/s), one 100 Hz log in blocks.
  BenchmarkCase c;
  for (const BenchmarkCase& k : familyCases("independent")) {
    if (k.id == "yaw_rate_bias-large-bend") c = k;
  }
  ASSERT_FALSE(c.id.empty());
  const GapLog log = generateBenchmarkLog(c, SensorNoise{}, 100.0);
  const SimConfig nominal = benchmarkCaseNominal(c);
  DiagnosisOptions options;
  options.threads = 2;
  options.correct_measured_sensor_errors = true;
  const GapReport on = diagnoseGap(nominal, {log}, {}, options);
  EXPECT_EQ(on.verdict.effect, "sensor_offset") << on.verdict.reason;
  EXPECT_EQ(on.verdict.form, "yaw_rate");
  EXPECT_EQ(on.verdict.basis, "measured") << on.verdict.reason;
  ASSERT_FALSE(on.verdict.effects.empty());
  EXPECT_TRUE(on.verdict.effects[0].measured);
  EXPECT_NEAR(on.verdict.effects[0].params.at("bias"), 0.008, 0.0005);
  EXPECT_GT(on.verdict.shrink, 0.8) << on.verdict.reason;
  // Off: the diagnosis fits it itself, and the check's finding is reported beside it.
  options.correct_measured_sensor_errors = false;
  const GapReport off = diagnoseGap(nominal, {log}, {}, options);
  EXPECT_EQ(off.verdict.effect, "sensor_offset");
  EXPECT_EQ(off.verdict.basis, "replays");
  bool reported = false;
  for (const auto& check : off.input_checks) reported = reported || (check.channel == "yaw_rate" && check.kind == "bias");
  EXPECT_TRUE(reported);
}

}  // namespace
}  // namespace diagnosis
}  // namespace lane_keeping
