// Path geometry, the path tracker (eq 11 and its exact rate) and the PID actuator (eqs 12-16).
#include <gtest/gtest.h>

#include <cmath>

#include "lane_keeping/control/path.h"
#include "lane_keeping/control/path_tracker.h"
#include "lane_keeping/control/steering_actuator.h"

namespace lane_keeping {
namespace {

TEST(PathTracker, Eq11OnTheStraightRoad) {
  TrackerParams p;  // k_psi = 0.8, k_y = 0.01
  PathParams straight;
  const PathTracker tracker(p, createPath(straight));
  PoseSample pose{12.0, 0.7, 0.05, 15.0, 0.75, 0.02};
  const SteeringCommand c = tracker.command(pose);
  EXPECT_NEAR(c.delta_des, -0.8 * std::sin(0.05) - 0.01 * 0.7, 1e-15);
  EXPECT_NEAR(c.delta_des_rate, -0.8 * std::cos(0.05) * 0.02 - 0.01 * 0.75, 1e-15);
}

// The command's rate equals the time derivative of the command along a motion (all path types).
TEST(PathTracker, RateIsTheExactDerivative) {
  for (const std::string type : {"straight", "lane_change", "sinusoid", "waypoints"}) {
    SCOPED_TRACE(type);
    PathParams params;
    params.type = type;
    params.lane_change_start = 0.0;
    params.sinusoid_start = -100.0;
    TrackerParams gains;
    gains.k_y = 0.1;
    const PathTracker tracker(gains, createPath(params));
    // A body moving on a curve: x = 15 t, y = 0.5 + 0.3 sin(t) + 0.02 t^2, psi = 0.1 cos(2 t).
    auto pose = [](double t) {
      return PoseSample{20.0 + 15 * t, 0.5 + 0.3 * std::sin(t) + 0.02 * t * t, 0.1 * std::cos(2 * t),
                        15.0,          0.3 * std::cos(t) + 0.04 * t,            -0.2 * std::sin(2 * t)};
    };
    for (double t : {0.3, 1.1, 2.5, 4.0}) {
      const double h = 1e-5;
      const double numeric = (tracker.command(pose(t + h)).delta_des - tracker.command(pose(t - h)).delta_des) / (2 * h);
      EXPECT_NEAR(tracker.command(pose(t)).delta_des_rate, numeric, 1e-7) << "t = " << t;
    }
  }
}

TEST(Path, ErrorsAreSignedDistanceAndHeading) {
  PathParams params;
  params.type = "lane_change";  // y = 3.5 s((x - 30)/60)
  const auto path = createPath(params);
  double y, slope, second;
  path->evaluate(60.0, &y, &slope, &second);  // midpoint: y = 1.75, slope = 3.5 * 1.875 / 60
  EXPECT_NEAR(y, 1.75, 1e-12);
  EXPECT_NEAR(slope, 3.5 * 1.875 / 60.0, 1e-12);
  // A point 0.5 m to the left of the path along the normal has e_y = +0.5.
  const double norm = std::hypot(1.0, slope);
  const PathErrors e = path->errors(60.0 - 0.5 * slope / norm, 1.75 + 0.5 / norm, std::atan(slope) + 0.1, 0, 0, 0);
  EXPECT_NEAR(e.lateral, 0.5, 1e-9);
  EXPECT_NEAR(e.heading, 0.1, 1e-9);
  EXPECT_NEAR(e.foot_x, 60.0, 1e-9);
}

TEST(Path, WaypointSplinePassesThroughThePoints) {
  PathParams params;
  params.type = "waypoints";
  const auto path = createPath(params);
  for (const auto& p : params.waypoints) {
    double y, slope, second;
    path->evaluate(p[0], &y, &slope, &second);
    EXPECT_NEAR(y, p[1], 1e-12);
  }
}

TEST(Path, WaypointsWithDecreasingXAreRejected) {
  PathParams params;
  params.type = "waypoints";
  params.waypoints = {{0, 0}, {10, 1}, {5, 2}};
  EXPECT_THROW(createPath(params), ConfigError);
}

TEST(SteeringActuator, PidOfEqs12To16) {
  ActuatorParams p;  // p = 2000: k_p = 16000, k_d = 200, k_i = 1000
  SteeringActuator actuator(p);
  // Constant error 0.01 rad, zero rate: z grows by 0.01 * dt per sample (trapezoid).
  const double first = actuator.update(0.0, SteeringCommand{0.01, 0.0}, SteeringMeasurement{0.0, 0.0});
  EXPECT_DOUBLE_EQ(first, 16000 * 0.01);
  double torque = 0.0;
  for (int k = 1; k <= 1000; ++k) torque = actuator.update(k * 1e-3, SteeringCommand{0.01, 0.0}, SteeringMeasurement{0.0, 0.0});
  EXPECT_NEAR(actuator.integral(), 0.01 * 1.0, 1e-15);
  EXPECT_NEAR(torque, 16000 * 0.01 + 1000 * 0.01, 1e-9);
  // Derivative term acts on the rate error.
  SteeringActuator fresh(p);
  EXPECT_DOUBLE_EQ(fresh.update(0.0, SteeringCommand{0.0, 0.5}, SteeringMeasurement{0.0, 0.2}), 200 * 0.3);
}

}  // namespace
}  // namespace lane_keeping
