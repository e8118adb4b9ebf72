#include "conversions.h"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <utility>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace {

constexpr Nanoseconds kNanosecondsPerSecond = 1000000000;

/// The first non-finite (name, value) pair, rendered, or "".
std::string firstNonFinite(std::initializer_list<std::pair<const char*, double>> fields) {
  for (const auto& field : fields) {
    if (!std::isfinite(field.second)) return std::string(field.first) + " = " + std::to_string(field.second);
  }
  return "";
}

void setHeader(std_msgs::Header& header, Nanoseconds stamp, const std::string& frame_id) {
  header.stamp = toRosTime(stamp);
  header.frame_id = frame_id;
}

}  // namespace

Nanoseconds toNanoseconds(const ros::Time& stamp) {
  return static_cast<Nanoseconds>(stamp.sec) * kNanosecondsPerSecond + static_cast<Nanoseconds>(stamp.nsec);
}

ros::Time toRosTime(Nanoseconds t) {
  if (t < 0 || t / kNanosecondsPerSecond > static_cast<Nanoseconds>(std::numeric_limits<std::uint32_t>::max())) {
    throw InputError("time " + std::to_string(t) + " ns cannot be a ROS time (0 to 2^32 s)");
  }
  ros::Time stamp;
  stamp.sec = static_cast<std::uint32_t>(t / kNanosecondsPerSecond);
  stamp.nsec = static_cast<std::uint32_t>(t % kNanosecondsPerSecond);
  return stamp;
}

VehicleState toVehicleStateMsg(Nanoseconds stamp, const VehicleStateSample& s, const std::string& frame_id) {
  VehicleState m;
  setHeader(m.header, stamp, frame_id);
  m.x = s.x;
  m.y = s.y;
  m.psi = s.psi;
  m.delta = s.delta;
  m.lateral_velocity = s.sigma1;
  m.yaw_rate = s.sigma2;
  m.steering_rate = s.sigma3;
  m.x_dot = s.x_dot;
  m.y_dot = s.y_dot;
  m.speed = s.speed;
  m.lateral_acceleration = s.lateral_acceleration;
  m.slip_angle_front = s.slip_angle_front;
  m.slip_angle_rear = s.slip_angle_rear;
  m.force_front = s.force_front;
  m.force_rear = s.force_rear;
  m.moment_front = s.moment_front;
  m.moment_rear = s.moment_rear;
  m.steering_torque = s.torque;
  return m;
}

VehicleStateSample fromVehicleStateMsg(const VehicleState& m) {
  VehicleStateSample s;
  s.x = m.x;
  s.y = m.y;
  s.psi = m.psi;
  s.delta = m.delta;
  s.sigma1 = m.lateral_velocity;
  s.sigma2 = m.yaw_rate;
  s.sigma3 = m.steering_rate;
  s.x_dot = m.x_dot;
  s.y_dot = m.y_dot;
  s.speed = m.speed;
  s.lateral_acceleration = m.lateral_acceleration;
  s.slip_angle_front = m.slip_angle_front;
  s.slip_angle_rear = m.slip_angle_rear;
  s.force_front = m.force_front;
  s.force_rear = m.force_rear;
  s.moment_front = m.moment_front;
  s.moment_rear = m.moment_rear;
  s.torque = m.steering_torque;
  return s;
}

DesiredSteering toDesiredSteeringMsg(Nanoseconds stamp, const SteeringCommand& c) {
  DesiredSteering m;
  setHeader(m.header, stamp, "");
  m.delta_des = c.delta_des;
  m.delta_des_rate = c.delta_des_rate;
  return m;
}

SteeringCommand fromDesiredSteeringMsg(const DesiredSteering& m) { return {m.delta_des, m.delta_des_rate}; }

MeasuredSteering toMeasuredSteeringMsg(Nanoseconds stamp, const SteeringMeasurement& s) {
  MeasuredSteering m;
  setHeader(m.header, stamp, "");
  m.delta = s.delta;
  m.delta_rate = s.delta_rate;
  return m;
}

SteeringMeasurement fromMeasuredSteeringMsg(const MeasuredSteering& m) { return {m.delta, m.delta_rate}; }

SteeringTorque toSteeringTorqueMsg(Nanoseconds stamp, const TorqueCommand& torque, double integral) {
  SteeringTorque m;
  setHeader(m.header, stamp, "");
  m.torque = torque.torque;
  m.integral = integral;
  return m;
}

TorqueCommand fromSteeringTorqueMsg(const SteeringTorque& m) { return TorqueCommand{m.torque}; }

TrackingErrors toTrackingErrorsMsg(Nanoseconds stamp, const PathErrors& e) {
  TrackingErrors m;
  setHeader(m.header, stamp, "");
  m.lateral_error = e.lateral;
  m.heading_error = e.heading;
  m.lateral_error_rate = e.lateral_rate;
  m.heading_error_rate = e.heading_rate;
  return m;
}

ParameterChange toParameterChangeMsg(const ScheduledChange& change, const std::string& node) {
  ParameterChange m;
  setHeader(m.header, change.stamp, "");
  m.node = node;
  m.key = change.key;
  m.old_value = change.old_value;
  m.new_value = change.new_value;
  m.origin = change.origin;
  m.change = change.argument();
  return m;
}

ScheduledChange fromParameterChangeMsg(const ParameterChange& m) {
  ScheduledChange change;
  change.stamp = toNanoseconds(m.header.stamp);
  change.key = m.key;
  change.old_value = m.old_value;
  change.new_value = m.new_value;
  change.origin = m.origin;
  change.owner = changeOwner(m.key);
  return change;
}

std::string yamlNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  return formatNumber(value);
}

std::string nonFiniteField(const VehicleState& m) {
  return firstNonFinite({{"x", m.x},
                         {"y", m.y},
                         {"psi", m.psi},
                         {"delta", m.delta},
                         {"lateral_velocity", m.lateral_velocity},
                         {"yaw_rate", m.yaw_rate},
                         {"steering_rate", m.steering_rate},
                         {"x_dot", m.x_dot},
                         {"y_dot", m.y_dot},
                         {"speed", m.speed},
                         {"lateral_acceleration", m.lateral_acceleration},
                         {"slip_angle_front", m.slip_angle_front},
                         {"slip_angle_rear", m.slip_angle_rear},
                         {"force_front", m.force_front},
                         {"force_rear", m.force_rear},
                         {"moment_front", m.moment_front},
                         {"moment_rear", m.moment_rear},
                         {"steering_torque", m.steering_torque}});
}

std::string nonFiniteField(const DesiredSteering& m) {
  return firstNonFinite({{"delta_des", m.delta_des}, {"delta_des_rate", m.delta_des_rate}});
}

std::string nonFiniteField(const MeasuredSteering& m) {
  return firstNonFinite({{"delta", m.delta}, {"delta_rate", m.delta_rate}});
}

std::string nonFiniteField(const SteeringTorque& m) {
  return firstNonFinite({{"torque", m.torque}, {"integral", m.integral}});
}

geometry_msgs::Quaternion yawToQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.x = 0.0;
  q.y = 0.0;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

}  // namespace lane_keeping
