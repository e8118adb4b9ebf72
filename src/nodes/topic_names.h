#pragma once
/// Default topic names and frames of the lane_keeping nodes, relative to the node handle's namespace
/// (the launch file puts every node in one namespace, default /lane_keeping). Remap in launch files.
namespace lane_keeping {
namespace topics {

// The loop (lockstep inputs and outputs). Each message holds consecutive samples, each sample stamped
// with the instant its values hold at.
constexpr char kVehicleState[] = "vehicle_state";                ///< VehicleStateArray: plant -> tracker
constexpr char kMeasuredSteering[] = "measured_steering";        ///< MeasuredSteeringArray: plant -> actuator
constexpr char kDesiredSteering[] = "desired_steering";          ///< DesiredSteeringArray: tracker -> actuator, plant (log)
constexpr char kSteeringTorque[] = "steering_torque";            ///< SteeringTorqueArray: actuator -> plant

// Runtime tuning: every change of the configuration during a run, with the time it takes effect.
constexpr char kParameterChanges[] = "parameter_changes";  ///< ParameterChange: each node -> the plant (summary), bags

// What the plant reports.
constexpr char kRunStatus[] = "run_status";            ///< RunStatus (latched): start and end of the run
constexpr char kTrackingErrors[] = "tracking_errors";  ///< TrackingErrors: e_y, e_psi of the actual state
constexpr char kOdometry[] = "odometry";               ///< nav_msgs/Odometry of base_link in map
constexpr char kLaneCenter[] = "lane_center";          ///< nav_msgs/Path (latched)
constexpr char kLaneMarkers[] = "lane_markers";        ///< visualization_msgs/MarkerArray (latched): lane boundaries
constexpr char kVehicleMarkers[] = "vehicle_markers";  ///< visualization_msgs/MarkerArray: body, wheels, trail, forces

}  // namespace topics

namespace frames {
constexpr char kMap[] = "map";                  ///< x along the straight road, y left, z up
constexpr char kBaseLink[] = "base_link";       ///< at the centre of gravity G, x forward
constexpr char kFrontWheel[] = "front_wheel";   ///< at the front axle F, rotated by the steering angle
constexpr char kRearWheel[] = "rear_wheel";     ///< at the rear axle R
}  // namespace frames

}  // namespace lane_keeping
