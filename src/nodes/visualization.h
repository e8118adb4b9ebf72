#pragma once
/// What a user looks at in rviz: tf (map -> base_link -> front_wheel rotated by delta, rear_wheel),
/// nav_msgs/Odometry, the errors e_y and e_psi, the lane centre (nav_msgs/Path) and boundaries, and
/// markers for the car body, the wheels, the tire force vectors, the driven trail and a text label.
/// Geometry for display only: the values come from the plant's state and the core path.
#include <string>
#include <vector>

#include <geometry_msgs/Point.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/control/path.h"
#include "lane_keeping/common/time.h"
#include "lane_keeping/sim/signals.h"

namespace lane_keeping {

struct VisualizationOptions {
  double rate = 50.0;          ///< [Hz] of simulated time; 0 = off
  double trail_spacing = 0.1;  ///< [s] of simulated time between trail points
  double force_scale = 200.0;  ///< [N per m] of arrow length
};

class LaneVisualizer {
 public:
  LaneVisualizer(ros::NodeHandle& nh, const SimConfig& config, const Path& path, const VisualizationOptions& options);

  /// The lane centre and boundaries (latched), from x0 - 20 m to the distance the run covers.
  void publishLane();
  /// True if a frame is due at t (the visualisation rate, in simulated time).
  bool due(Nanoseconds t) const { return period_ > 0 && t >= next_; }
  /// tf, odometry, errors and markers of the state at t.
  void publish(Nanoseconds t, const VehicleStateSample& state);

 private:
  ros::NodeHandle nh_;
  const SimConfig& config_;
  const Path& path_;
  VisualizationOptions options_;
  Nanoseconds period_ = 0, next_ = 0, trail_period_ = 0, next_trail_ = 0;
  std::vector<geometry_msgs::Point> trail_;
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher odometry_pub_, errors_pub_, markers_pub_, lane_center_pub_, lane_markers_pub_;
};

}  // namespace lane_keeping
