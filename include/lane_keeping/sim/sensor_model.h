#pragma once
/// The plant's sensors (sensor_params.h): from the true motion to what the tracker, the actuator and
/// the log receive — a localisation bias and latency, a steering-angle sensor's offset, gain, latency and
/// placement (road wheel, or the motor side of a compliant column), a gyro's bias, gain and latency, and
/// an accelerometer's offset and latency (it does not sense a road bank). It keeps the history of the true motion its latencies need; with exact
/// sensors at the road wheel it passes the truth through untouched.
#include <deque>

#include "lane_keeping/common/time.h"
#include "lane_keeping/sim/sensor_params.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

class SensorModel {
 public:
  /// @param column_sensor the actuator's angle sensor sits on the motor side of the column.
  SensorModel(const SensorParams& params, bool column_sensor);

  /// Nothing to model: every reading is the truth.
  bool passThrough() const { return pass_through_; }

  /// Records the true motion at time t (t increasing): the pose and velocities of G, the road wheel's
  /// angle and rate, the column's (motor side) angle and rate, and the lateral acceleration an exact
  /// accelerometer would sense.
  void record(Nanoseconds t, const PoseSample& pose, const SteeringMeasurement& wheel, const SteeringMeasurement& column,
              double sensed_lateral_acceleration);

  /// What the localisation reports at t: the pose at t - pose_latency, biased; the yaw rate as the gyro
  /// reports it.
  PoseSample pose(Nanoseconds t, const PoseSample& truth) const;
  /// What the actuator's angle sensor reads at t: the wheel's or the column's angle and rate, at t minus
  /// the sensor latency, through its gain and offset.
  SteeringMeasurement actuatorAngle(Nanoseconds t, const SteeringMeasurement& wheel,
                                    const SteeringMeasurement& column) const;
  /// The state sample as the sensors (and so the log) report it: the pose from pose(), the yaw rate as
  /// the gyro reports it, the road wheel's angle and rate (through the angle sensor when that sensor is
  /// the actuator's, at the wheel), and a_y without `unsensed_force` / `mass` (a road bank's gravity
  /// component), at the accelerometer's latency and with its offset.
  VehicleStateSample sample(Nanoseconds t, const VehicleStateSample& truth, double unsensed_force, double mass) const;

 private:
  struct Record {
    Nanoseconds t;
    PoseSample pose;
    SteeringMeasurement wheel, column;
    double lateral_acceleration = 0.0;  ///< as an exact accelerometer senses it
  };
  /// The record interpolated at t (the first one before it: constant initial history).
  Record at(Nanoseconds t) const;

  SensorParams p_;
  bool column_sensor_;
  bool pass_through_;
  /// The angle sensor's reading of a measurement (gain and offset; the latency is the caller's).
  SteeringMeasurement reported(SteeringMeasurement m) const;

  Nanoseconds pose_latency_, steering_latency_, yaw_rate_latency_, ay_latency_, keep_;
  std::deque<Record> history_;
};

}  // namespace lane_keeping
