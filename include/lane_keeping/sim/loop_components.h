#pragma once
/// How one configuration maps onto the three lockstep components of the loop: their sample grids
/// and delays in integer nanoseconds, and factories for each component. The in-process runner
/// (closed_loop.cpp) and the ROS nodes build their components here, so both run the same objects
/// with the same grids.
#include "lane_keeping/common/time.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/sim/change_schedule.h"
#include "lane_keeping/sim/control_stages.h"
#include "lane_keeping/sim/delay_line.h"
#include "lane_keeping/sim/vehicle_plant.h"

namespace lane_keeping {

/// Grids and delays of a configuration, in nanoseconds.
struct LoopSchedule {
  Nanoseconds plant_step = 0;       ///< simulation.step
  Nanoseconds tracker_period = 0;   ///< 1 / tracker.rate
  Nanoseconds actuator_period = 0;  ///< 1 / actuator.rate
  Nanoseconds log_period = 0;       ///< 1 / simulation.log_rate
  Nanoseconds duration = 0;         ///< simulation.duration
  Nanoseconds pose_delay = 0;       ///< delays.pose_to_tracker (tau1)
  Nanoseconds desired_delay = 0;    ///< delays.desired_steering_to_actuator (tau2)
  Nanoseconds measured_delay = 0;   ///< delays.steering_angle_to_actuator (tau2)
  Nanoseconds torque_delay = 0;     ///< delays.torque_to_plant
  Hold hold = Hold::kLinear;        ///< delays.hold
};

/// Converts the configuration's seconds and rates to the nanosecond grids (rounded to 1 ns).
LoopSchedule loopScheduleOf(const SimConfig& config);

/// The vehicle plant at simulation.initial, with its torque delay line.
VehiclePlant createVehiclePlant(const SimConfig& config, const LoopSchedule& schedule);
/// The path tracker (Beregi eq 11) on the configured path, with its pose delay line (tau1).
PathTrackingStage createPathTrackingStage(const SimConfig& config, const LoopSchedule& schedule);
/// The PID steering actuator (Beregi eqs 12-16), with its two input delay lines (tau2).
SteeringActuatorStage createSteeringActuatorStage(const SimConfig& config, const LoopSchedule& schedule);

/// Hands a component the changes of `changes` it owns (change_owner.h) stamped at `from` [ns] or
/// later, replacing those it holds from `from` on: the parameters and delays in force from each stamp.
/// A component built from changes.start() already has the changes at stamp 0 (from = 1 skips them).
void scheduleChanges(PathTrackingStage& stage, const ChangeSchedule& changes, Nanoseconds from);
void scheduleChanges(SteeringActuatorStage& stage, const ChangeSchedule& changes, Nanoseconds from);
void scheduleChanges(VehiclePlant& plant, const ChangeSchedule& changes, Nanoseconds from);

}  // namespace lane_keeping
