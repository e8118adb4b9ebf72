// Message <-> core conversions, without a master (STYLE rule 6): exact time, field-by-field round
// trips, non-finite detection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "conversions.h"
#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

TEST(TimeConversion, NanosecondsRoundTripExactly) {
  for (Nanoseconds t : {Nanoseconds{0}, Nanoseconds{1}, Nanoseconds{999999999}, Nanoseconds{1000000000},
                        Nanoseconds{1901951}, Nanoseconds{123456789012345}}) {
    const ros::Time stamp = toRosTime(t);
    EXPECT_EQ(toNanoseconds(stamp), t);
    EXPECT_EQ(stamp.toNSec(), static_cast<std::uint64_t>(t));
  }
  EXPECT_EQ(toRosTime(1500000001).sec, 1u);
  EXPECT_EQ(toRosTime(1500000001).nsec, 500000001u);
}

TEST(TimeConversion, NegativeTimeIsRejected) { EXPECT_THROW(toRosTime(-1), InputError); }

TEST(TimeConversion, PhysicsTimeOfAStampEqualsTheCoreConversion) {
  // The nodes hand the core integer nanoseconds; seconds come from the one core function.
  const ros::Time stamp(12, 345678901);
  EXPECT_EQ(nanosecondsToSeconds(toNanoseconds(stamp)), 12.345678901);
}

TEST(MessageConversion, VehicleStateRoundTripsEveryField) {
  VehicleStateSample s;
  double v = 0.5;
  for (double* field : {&s.x, &s.y, &s.psi, &s.delta, &s.sigma1, &s.sigma2, &s.sigma3, &s.x_dot, &s.y_dot, &s.speed,
                        &s.lateral_acceleration, &s.slip_angle_front, &s.slip_angle_rear, &s.force_front,
                        &s.force_rear, &s.moment_front, &s.moment_rear, &s.torque}) {
    *field = (v += 1.0 / 3.0);  // distinct, not exactly representable
  }
  const VehicleState m = toVehicleStateMsg(42, s, "map");
  EXPECT_EQ(m.header.stamp.toNSec(), 42u);
  EXPECT_EQ(m.header.frame_id, "map");
  EXPECT_EQ(m.lateral_velocity, s.sigma1);
  EXPECT_EQ(m.yaw_rate, s.sigma2);
  EXPECT_EQ(m.steering_rate, s.sigma3);
  EXPECT_EQ(m.steering_torque, s.torque);
  const VehicleStateSample r = fromVehicleStateMsg(m);
  EXPECT_EQ(0, std::memcmp(&r, &s, sizeof(s)));
  // The tracker's view of it equals the plant's pose() (what the in-process loop feeds it).
  const PoseSample p = PoseSample::of(r);
  EXPECT_EQ(p.x_dot, s.x_dot);
  EXPECT_EQ(p.yaw_rate, s.sigma2);
}

TEST(MessageConversion, SteeringMessagesRoundTrip) {
  const SteeringCommand c{0.1 / 3.0, -2.0 / 7.0};
  const SteeringCommand c2 = fromDesiredSteeringMsg(toDesiredSteeringMsg(7, c));
  EXPECT_EQ(c2.delta_des, c.delta_des);
  EXPECT_EQ(c2.delta_des_rate, c.delta_des_rate);
  const SteeringMeasurement m{1.0 / 9.0, 5.0 / 11.0};
  const MeasuredSteering mm = toMeasuredSteeringMsg(8, m);
  EXPECT_EQ(mm.header.stamp.toNSec(), 8u);
  EXPECT_EQ(fromMeasuredSteeringMsg(mm).delta, m.delta);
  EXPECT_EQ(fromMeasuredSteeringMsg(mm).delta_rate, m.delta_rate);
  const SteeringTorque t = toSteeringTorqueMsg(9, TorqueCommand{13.0 / 3.0}, 0.25);
  EXPECT_EQ(fromSteeringTorqueMsg(t).torque, 13.0 / 3.0);
  EXPECT_EQ(t.integral, 0.25);
}

TEST(MessageConversion, TrackingErrors) {
  PathErrors e;
  e.lateral = 0.3;
  e.heading = -0.02;
  e.lateral_rate = 1.5;
  e.heading_rate = 0.1;
  const TrackingErrors m = toTrackingErrorsMsg(1000, e);
  EXPECT_EQ(m.lateral_error, 0.3);
  EXPECT_EQ(m.heading_error, -0.02);
  EXPECT_EQ(m.header.stamp.toNSec(), 1000u);
}

TEST(MessageConversion, ParameterChangeRoundTripsAndReproduces) {
  ScheduledChange change;
  change.stamp = 10'000'100'000;
  change.key = "steering.coulomb_friction";
  change.old_value = "0";
  change.new_value = "3";
  change.owner = LoopRole::kPlant;
  change.origin = "~changes";
  const ParameterChange m = toParameterChangeMsg(change, "/lane_keeping/vehicle_plant");
  EXPECT_EQ(m.header.stamp.sec, 10u);
  EXPECT_EQ(m.header.stamp.nsec, 100'000u);
  EXPECT_EQ(m.node, "/lane_keeping/vehicle_plant");
  EXPECT_EQ(m.change, "10.0001:steering.coulomb_friction=3");  // the lk_simulate --change argument
  const ScheduledChange back = fromParameterChangeMsg(m);
  EXPECT_EQ(back.stamp, change.stamp);
  EXPECT_EQ(back.owner, LoopRole::kPlant);
  EXPECT_EQ(back.describe(), change.describe());
  ParameterChange foreign = m;
  foreign.key = "simulation.step";  // no component owns it
  EXPECT_THROW(fromParameterChangeMsg(foreign), ConfigError);
}

TEST(MessageConversion, NumbersForTheConfigurationReader) {
  EXPECT_EQ(yamlNumber(0.8), "0.8");
  EXPECT_EQ(yamlNumber(1.9019505e-3), "0.0019019505");
  EXPECT_EQ(yamlNumber(std::nan("")), ".nan");  // read as NaN, then refused by name
  EXPECT_EQ(yamlNumber(std::numeric_limits<double>::infinity()), ".inf");
  EXPECT_EQ(yamlNumber(-std::numeric_limits<double>::infinity()), "-.inf");
}

TEST(InputChecks, NonFiniteFieldsAreNamed) {
  VehicleState v;
  EXPECT_EQ(nonFiniteField(v), "");
  v.force_rear = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(nonFiniteField(v).find("force_rear"), std::string::npos);
  DesiredSteering d;
  d.delta_des_rate = std::numeric_limits<double>::infinity();
  EXPECT_NE(nonFiniteField(d).find("delta_des_rate"), std::string::npos);
  MeasuredSteering m;
  m.delta = -std::numeric_limits<double>::infinity();
  EXPECT_NE(nonFiniteField(m).find("delta"), std::string::npos);
  SteeringTorque t;
  EXPECT_EQ(nonFiniteField(t), "");
  t.torque = std::nan("");
  EXPECT_NE(nonFiniteField(t).find("torque"), std::string::npos);
}

TEST(Geometry, YawQuaternion) {
  const geometry_msgs::Quaternion q = yawToQuaternion(M_PI / 2);
  EXPECT_NEAR(q.z, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(q.w, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(q.x, 0.0);
}

}  // namespace
}  // namespace lane_keeping
