#pragma once
/// Every conversion between ROS messages and core values, time included (STYLE rule 6). Stamps are
/// integer nanoseconds on both sides, so the conversions are exact: a lockstep ROS run feeds the
/// core the same bits as the in-process runner.
#include <string>

#include <geometry_msgs/Quaternion.h>
#include <ros/time.h>

#include "lane_keeping/DesiredSteering.h"
#include "lane_keeping/MeasuredSteering.h"
#include "lane_keeping/ParameterChange.h"
#include "lane_keeping/SteeringTorque.h"
#include "lane_keeping/TrackingErrors.h"
#include "lane_keeping/VehicleState.h"
#include "lane_keeping/common/time.h"
#include "lane_keeping/control/path.h"
#include "lane_keeping/sim/change_schedule.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

// ---- time -------------------------------------------------------------------------------------

/// Exact: ROS time is (sec, nsec) of integer nanoseconds.
Nanoseconds toNanoseconds(const ros::Time& stamp);
/// Exact. Throws InputError for t < 0 or beyond ros::Time's range (ROS time cannot be negative).
ros::Time toRosTime(Nanoseconds t);

// ---- loop messages <-> core samples -----------------------------------------------------------

VehicleState toVehicleStateMsg(Nanoseconds stamp, const VehicleStateSample& sample, const std::string& frame_id);
VehicleStateSample fromVehicleStateMsg(const VehicleState& msg);

DesiredSteering toDesiredSteeringMsg(Nanoseconds stamp, const SteeringCommand& command);
SteeringCommand fromDesiredSteeringMsg(const DesiredSteering& msg);

MeasuredSteering toMeasuredSteeringMsg(Nanoseconds stamp, const SteeringMeasurement& measurement);
SteeringMeasurement fromMeasuredSteeringMsg(const MeasuredSteering& msg);

/// @param integral the actuator's z after this sample [rad s]
SteeringTorque toSteeringTorqueMsg(Nanoseconds stamp, const TorqueCommand& torque, double integral);
TorqueCommand fromSteeringTorqueMsg(const SteeringTorque& msg);

TrackingErrors toTrackingErrorsMsg(Nanoseconds stamp, const PathErrors& errors);

// ---- runtime changes --------------------------------------------------------------------------

/// header.stamp = the change's stamp (exact), `node` = the ROS name of the node that applies it.
ParameterChange toParameterChangeMsg(const ScheduledChange& change, const std::string& node);
/// The core record; the owner follows from the key (change_owner.h). Throws ConfigError for a key no
/// component owns.
ScheduledChange fromParameterChangeMsg(const ParameterChange& msg);
/// A number as YAML text for the configuration's reader: shortest round trip, and .nan / .inf / -.inf
/// (which the reader then refuses by name) for the values plain text would not read back.
std::string yamlNumber(double value);

// ---- input checks -----------------------------------------------------------------------------

/// "" if every number in the message is finite, else the name of the first field that is not
/// (e.g. "delta_des = nan"). Nodes reject such messages with a warning: one NaN in a delay line
/// would poison every later output.
std::string nonFiniteField(const VehicleState& msg);
std::string nonFiniteField(const DesiredSteering& msg);
std::string nonFiniteField(const MeasuredSteering& msg);
std::string nonFiniteField(const SteeringTorque& msg);

// ---- geometry (visualisation) -----------------------------------------------------------------

/// Rotation about z by `yaw` [rad].
geometry_msgs::Quaternion yawToQuaternion(double yaw);

}  // namespace lane_keeping
