// The plant's sensors (sensor_model.h): what the tracker, the actuator and the log receive when the
// localisation, the steering-angle sensor, the gyro or the accelerometer do not report the truth.
// Each placement is checked against a run that differs from it only where the placement says.
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/loop_components.h"
#include "lane_keeping/sim/sensor_model.h"
#include "build_paths.h"

namespace lane_keeping {
namespace {

std::string scenario(const std::string& name) { return std::string(build_paths::sourceDir()) + "/config/scenarios/" + name; }

RunResult run(const std::string& file, const std::vector<std::string>& sets) {
  const RunResult r = ClosedLoop(loadSimConfig({scenario(file)}, sets)).run();
  EXPECT_FALSE(r.diverged()) << r.message;
  return r;
}

TEST(SensorModel, ExactSensorsLogTheTruth) {
  const RunResult r = run("lane_change.yaml", {"simulation.duration=6"});
  ASSERT_GT(r.rows.size(), 100u);
  for (const LogRow& row : r.rows) {
    ASSERT_EQ(row.state.x, row.x_true);
    ASSERT_EQ(row.state.y, row.y_true);
    ASSERT_EQ(row.state.psi, row.psi_true);
  }
}

TEST(SensorModel, LocalisationBiasMovesTheCarLikeATrackerBiasButTheLogRecordsIt) {
  // The same bias seen by the tracker alone (tracker.pose_bias_y) or by the localisation that the
  // tracker and the log share: the motion is the same, the logged y differs from the true y by b.
  const double b = 0.3;
  const RunResult shared = run("fig6.yaml", {"sensors.pose_bias_y=0.3"});
  const RunResult tracker_only = run("fig6.yaml", {"tracker.pose_bias_y=0.3"});
  ASSERT_EQ(shared.rows.size(), tracker_only.rows.size());
  for (std::size_t i = 0; i < shared.rows.size(); ++i) {
    ASSERT_NEAR(shared.rows[i].y_true, tracker_only.rows[i].state.y, 1e-9) << "row " << i;
    ASSERT_NEAR(shared.rows[i].state.y - shared.rows[i].y_true, b, 1e-12) << "row " << i;
    ASSERT_NEAR(tracker_only.rows[i].state.y, tracker_only.rows[i].y_true, 0.0);
  }
  // The tracker steers the reported position onto the straight lane: the true one settles at -b
  // (from y0 = 1 m with the slow pole at -0.2 1/s, fig6 test: within 3 cm after 20 s).
  const LogRow& last = shared.rows.back();
  EXPECT_NEAR(last.y_true, 0.0 - b, 0.03);
  EXPECT_NEAR(last.state.y, 0.0, 0.03);
  EXPECT_NEAR(last.e_y, -b, 0.03);  // the errors from the lane are the true ones
}

TEST(SensorModel, HeadingBiasIsAnOffsetInTheLoggedYawAngle) {
  const RunResult r = run("lane_change.yaml", {"sensors.pose_bias_psi=0.01", "simulation.duration=6"});
  for (const LogRow& row : r.rows) ASSERT_NEAR(row.state.psi - row.psi_true, 0.01, 1e-12);
}

TEST(SensorModel, LocalisationLatencyReportsThePoseOfEarlier) {
  // Latency 0.1 s, a multiple of the plant step and of the 100 Hz log period: the reported pose at a
  // row is the true pose ten rows before (exactly: the history holds the plant's steps).
  const RunResult r = run("lane_change.yaml", {"sensors.pose_latency=0.1", "simulation.duration=8",
                                               "simulation.log_rate=100"});
  ASSERT_GT(r.rows.size(), 500u);
  double largest_change = 0.0;
  for (std::size_t i = 10; i < r.rows.size(); ++i) {
    ASSERT_NEAR(r.rows[i].t - r.rows[i - 10].t, 0.1, 1e-9);
    ASSERT_NEAR(r.rows[i].state.y, r.rows[i - 10].y_true, 1e-9) << "t = " << r.rows[i].t;
    ASSERT_NEAR(r.rows[i].state.psi, r.rows[i - 10].psi_true, 1e-12) << "t = " << r.rows[i].t;
    largest_change = std::max(largest_change, std::fabs(r.rows[i].y_true - r.rows[i - 10].y_true));
  }
  EXPECT_GT(largest_change, 0.05);  // the lane change moves the car: the check above is not vacuous
}

TEST(SensorModel, YawRateBiasIsAddedToWhatTheTrackerAndTheLogRead) {
  SensorParams p;
  p.yaw_rate_bias = 0.002;
  const SensorModel sensors(p, false);
  EXPECT_FALSE(sensors.passThrough());
  PoseSample truth{1.0, 2.0, 0.1, 20.0, 1.0, 0.05};
  const PoseSample reported = sensors.pose(0, truth);
  EXPECT_DOUBLE_EQ(reported.yaw_rate, 0.052);
  EXPECT_DOUBLE_EQ(reported.y, 2.0);
  EXPECT_DOUBLE_EQ(reported.psi, 0.1);
}

TEST(SensorModel, GyroGainLatencyAndBiasReportAnEarlierScaledRate) {
  // Gain 0.85, latency 0.1 s, bias -0.007 rad/s: the rate reported at t is 0.85 r(t - 0.1) - 0.007
  // (records every 10 ms: the latency falls on one), the pose untouched.
  SensorParams p;
  p.yaw_rate_scale = 0.85;
  p.yaw_rate_latency = 0.1;
  p.yaw_rate_bias = -0.007;
  SensorModel sensors(p, false);
  auto truthAt = [](double t) { return PoseSample{t, 0.1 * t, 0.02 * t, 15.0, 0.0, 0.05 * std::sin(3.0 * t)}; };
  // (Read as the plant reads it: after recording each step; the history keeps only the latency's span.)
  int checked = 0;
  for (int k = 0; k <= 100; ++k) {
    const double t = 0.01 * k;
    sensors.record(secondsToNanoseconds(t), truthAt(t), {}, {}, 0.0);
    if (k != 30 && k != 55 && k != 100) continue;
    const PoseSample reported = sensors.pose(secondsToNanoseconds(t), truthAt(t));
    EXPECT_NEAR(reported.yaw_rate, 0.85 * truthAt(0.01 * (k - 10)).yaw_rate - 0.007, 1e-12) << "t = " << t;
    EXPECT_DOUBLE_EQ(reported.y, truthAt(t).y);
    EXPECT_DOUBLE_EQ(reported.psi, truthAt(t).psi);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

TEST(SensorModel, SteeringAngleOffsetAndGainReachTheActuatorAndTheLog) {
  // The actuator reads the angle through the sensor's gain and offset, and the log records the same
  // reading; undoing the sensor gives the wheel's angle back.
  SensorParams p;
  p.steering_angle_bias = 0.002;
  p.steering_angle_scale = 1.1;
  const SensorModel sensors(p, false);
  EXPECT_FALSE(sensors.passThrough());
  const SteeringMeasurement wheel{0.01, 0.2};
  const SteeringMeasurement read = sensors.actuatorAngle(0, wheel, wheel);
  EXPECT_DOUBLE_EQ(read.delta, 1.1 * 0.01 + 0.002);
  EXPECT_DOUBLE_EQ(read.delta_rate, 1.1 * 0.2);
  VehicleStateSample truth;
  truth.delta = 0.01;
  truth.sigma3 = 0.2;
  const VehicleStateSample logged = sensors.sample(0, truth, 0.0, 1000.0);
  EXPECT_DOUBLE_EQ(logged.delta, read.delta);
  EXPECT_DOUBLE_EQ(logged.sigma3, read.delta_rate);
  EXPECT_DOUBLE_EQ(p.trueSteeringAngle(logged.delta), 0.01);
}

TEST(SensorModel, AccelerometerOffsetAndLatency) {
  const RunResult exact = run("sinusoid.yaml", {"simulation.duration=6", "simulation.log_rate=100"});
  const RunResult r = run("sinusoid.yaml", {"sensors.lateral_acceleration_bias=0.07",
                                            "sensors.lateral_acceleration_latency=0.05", "simulation.duration=6",
                                            "simulation.log_rate=100"});
  for (std::size_t i = 5; i < r.rows.size(); ++i) {
    ASSERT_NEAR(r.rows[i].state.lateral_acceleration, exact.rows[i - 5].state.lateral_acceleration + 0.07, 1e-12);
    ASSERT_EQ(r.rows[i].state.y, exact.rows[i].state.y);
  }
}

TEST(SensorModel, ColumnSensorClosesTheActuatorOnTheMotorSide) {
  // A compliant column: with the sensor on the motor side the actuator's measurement is the column
  // angle, while the log's delta stays the road wheel's; the two differ by the twist M / k_c.
  const SimConfig c = loadSimConfig({scenario("sinusoid.yaml")},
                                    {"steering.column_stiffness=150", "steering.angle_sensor=column"});
  const LoopSchedule s = loopScheduleOf(c);
  VehiclePlant plant = createVehiclePlant(c, s);
  const int column = plant.model().steeringStateOffset();
  double largest_twist = 0.0;
  Nanoseconds next_stamp = 0;
  for (int i = 0; i < 2000; ++i) {
    while (!plant.readyToStep()) {
      plant.pushTorque(next_stamp, 0.5 * std::sin(0.01 * i));
      next_stamp += plant.stepSize();
    }
    plant.step();
    ASSERT_EQ(plant.measurement().delta, plant.state()[column]);
    ASSERT_EQ(plant.measurement().delta_rate, plant.state()[column + 1]);
    ASSERT_EQ(plant.sample().delta, plant.state()[kDelta]);
    largest_twist = std::max(largest_twist, std::fabs(plant.state()[column] - plant.state()[kDelta]));
  }
  EXPECT_GT(largest_twist, 1e-4);  // the column twists: the two sensors do differ
}

TEST(SensorModel, ColumnSensorNeedsACompliantColumn) {
  try {
    loadSimConfig({scenario("sinusoid.yaml")}, {"steering.angle_sensor=column"});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("steering.angle_sensor"), std::string::npos) << e.what();
  }
}

TEST(SensorModel, RoadBankMovesTheCarLikeWindButTheAccelerometerDoesNotSenseIt) {
  // A lateral force of 400 N from wind (a real acceleration, sensed) or from a banked road (gravity,
  // which an accelerometer does not sense): the same motion, the logged a_y lower by F / m.
  const std::vector<std::string> common = {"disturbance.lateral_force=400", "simulation.duration=10"};
  auto with = [&](const std::string& kind) {
    auto sets = common;
    sets.push_back("disturbance.kind=" + kind);
    return run("sinusoid.yaml", sets);
  };
  const RunResult wind = with("aerodynamic"), bank = with("road_bank");
  const double mass = loadSimConfig({scenario("sinusoid.yaml")}).vehicle.mass;
  ASSERT_EQ(wind.rows.size(), bank.rows.size());
  for (std::size_t i = 1; i < wind.rows.size(); ++i) {
    ASSERT_EQ(wind.rows[i].state.y, bank.rows[i].state.y);
    ASSERT_NEAR(wind.rows[i].state.lateral_acceleration - bank.rows[i].state.lateral_acceleration, 400.0 / mass, 1e-9);
  }
}

TEST(SensorModel, DisturbanceSetsInAtItsOnset) {
  // A crosswind from x = 60 m: identical to the undisturbed run until the car reaches x = 60 m, then the
  // force ramps in over 10 m, and the car drifts to the right of the undisturbed one.
  const RunResult calm = run("sinusoid.yaml", {"simulation.duration=10"});
  const RunResult windy = run("sinusoid.yaml", {"simulation.duration=10", "disturbance.lateral_force=-500",
                                                "disturbance.onset_x=60"});
  ASSERT_EQ(calm.rows.size(), windy.rows.size());
  const double mass = loadSimConfig({scenario("sinusoid.yaml")}).vehicle.mass;
  std::size_t before = 0, after = 0;
  double largest_shift = 0.0;
  for (std::size_t i = 0; i < calm.rows.size(); ++i) {
    const LogRow &c = calm.rows[i], &w = windy.rows[i];
    if (w.state.x < 60.0) {
      ASSERT_EQ(c.state.y, w.state.y) << "t = " << c.t;
      ++before;
    } else if (w.state.x > 70.0 && after++ == 0) {
      // The first sample past the ramp (~0.6 s after the onset): the force is whole; the tires have begun
      // to take it (the sideslip it builds), so the extra acceleration lies between 0 and F / m.
      const double extra = w.state.lateral_acceleration - c.state.lateral_acceleration;
      EXPECT_LT(extra, -0.2 * 500.0 / mass);
      EXPECT_GT(extra, -500.0 / mass);
    }
    largest_shift = std::min(largest_shift, w.state.y - c.state.y);
  }
  EXPECT_GT(before, 10u);
  EXPECT_GT(after, 10u);
  EXPECT_LT(largest_shift, -0.01);  // pushed right [m], then the tracker pulls it back
}

}  // namespace
}  // namespace lane_keeping
