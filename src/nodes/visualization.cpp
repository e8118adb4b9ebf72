#include "visualization.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <visualization_msgs/MarkerArray.h>

#include "conversions.h"
#include "lane_keeping/TrackingErrors.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

// Drawing sizes [m] (display only; the single-track model has no width).
constexpr double kBodyOverhang = 0.7;   // beyond each axle
constexpr double kBodyWidth = 1.75;
constexpr double kBodyHeight = 0.4;      // flat, so that the wheels and arrows above it show from the top
constexpr double kTrackWidth = 1.5;     // wheels drawn at +-kTrackWidth/2
constexpr double kWheelDiameter = 0.64;  // wheels drawn as boxes: diameter x width x width
constexpr double kWheelWidth = 0.22;
constexpr double kLaneLineWidth = 0.15;
constexpr double kTrailWidth = 0.12;
constexpr std::size_t kMaxLanePoints = 5000;

std_msgs::ColorRGBA color(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

geometry_msgs::Point point(double x, double y, double z = 0.0) {
  geometry_msgs::Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  return p;
}

visualization_msgs::Marker marker(const std::string& frame, const std::string& ns, int id, int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;  // stamp 0 + frame_locked: drawn at the latest transform of its frame
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.frame_locked = true;
  return m;
}

geometry_msgs::TransformStamped transform(const ros::Time& stamp, const std::string& parent, const std::string& child,
                                          double x, double y, double yaw) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.translation.y = y;
  t.transform.rotation = yawToQuaternion(yaw);
  return t;
}

}  // namespace

LaneVisualizer::LaneVisualizer(ros::NodeHandle& nh, const SimConfig& config, const Path& path,
                               const VisualizationOptions& options)
    : nh_(nh), config_(config), path_(path), options_(options) {
  if (options_.rate > 0) period_ = periodFromRate(options_.rate);
  if (options_.trail_spacing > 0) trail_period_ = secondsToNanoseconds(options_.trail_spacing);
  odometry_pub_ = nh_.advertise<nav_msgs::Odometry>(topics::kOdometry, 10);
  errors_pub_ = nh_.advertise<TrackingErrors>(topics::kTrackingErrors, 10);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>(topics::kVehicleMarkers, 10);
  lane_center_pub_ = nh_.advertise<nav_msgs::Path>(topics::kLaneCenter, 1, true);
  lane_markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>(topics::kLaneMarkers, 1, true);
}

void LaneVisualizer::publishLane() {
  const double x0 = config_.simulation.initial.x - 20.0;
  const double x1 = config_.simulation.initial.x + config_.vehicle.fastestSpeed() * config_.simulation.duration + 50.0;
  const double spacing = std::max(0.5, (x1 - x0) / kMaxLanePoints);
  nav_msgs::Path center;
  center.header.frame_id = frames::kMap;
  visualization_msgs::Marker left = marker(frames::kMap, "lane_boundaries", 0, visualization_msgs::Marker::LINE_STRIP);
  visualization_msgs::Marker right = marker(frames::kMap, "lane_boundaries", 1, visualization_msgs::Marker::LINE_STRIP);
  left.scale.x = right.scale.x = kLaneLineWidth;
  left.color = right.color = color(1.0f, 0.85f, 0.0f);
  const double half_width = 0.5 * config_.path.lane_width;
  for (double x = x0; x <= x1; x += spacing) {
    double y = 0.0, slope = 0.0, second = 0.0;
    path_.evaluate(x, &y, &slope, &second);
    const double heading = std::atan(slope);
    geometry_msgs::PoseStamped pose;
    pose.header.frame_id = frames::kMap;
    pose.pose.position = point(x, y);
    pose.pose.orientation = yawToQuaternion(heading);
    center.poses.push_back(pose);
    // Normal to the left: (-sin, cos) of the heading.
    const double nx = -std::sin(heading), ny = std::cos(heading);
    left.points.push_back(point(x + half_width * nx, y + half_width * ny, 0.01));
    right.points.push_back(point(x - half_width * nx, y - half_width * ny, 0.01));
  }
  lane_center_pub_.publish(center);
  visualization_msgs::MarkerArray lane;
  lane.markers.push_back(left);
  lane.markers.push_back(right);
  lane_markers_pub_.publish(lane);
}

void LaneVisualizer::publish(Nanoseconds t, const VehicleStateSample& s) {
  while (next_ <= t) next_ += period_;
  const ros::Time stamp = toRosTime(t);
  const double l = config_.vehicle.wheelbase, d = config_.vehicle.cg_to_rear_axle, b = l - d;

  // tf: map -> base_link (G), base_link -> front_wheel (F, rotated by delta), base_link -> rear_wheel (R).
  std::vector<geometry_msgs::TransformStamped> transforms;
  transforms.push_back(transform(stamp, frames::kMap, frames::kBaseLink, s.x, s.y, s.psi));
  transforms.push_back(transform(stamp, frames::kBaseLink, frames::kFrontWheel, b, 0.0, s.delta));
  transforms.push_back(transform(stamp, frames::kBaseLink, frames::kRearWheel, -d, 0.0, 0.0));
  tf_.sendTransform(transforms);

  // Odometry: pose in map, twist in base_link.
  nav_msgs::Odometry odometry;
  odometry.header.stamp = stamp;
  odometry.header.frame_id = frames::kMap;
  odometry.child_frame_id = frames::kBaseLink;
  odometry.pose.pose.position = point(s.x, s.y);
  odometry.pose.pose.orientation = yawToQuaternion(s.psi);
  const double c = std::cos(s.psi), sn = std::sin(s.psi);
  odometry.twist.twist.linear.x = c * s.x_dot + sn * s.y_dot;
  odometry.twist.twist.linear.y = -sn * s.x_dot + c * s.y_dot;
  odometry.twist.twist.angular.z = s.sigma2;
  odometry_pub_.publish(odometry);

  const PathErrors errors = path_.errors(s.x, s.y, s.psi, s.x_dot, s.y_dot, s.sigma2);
  errors_pub_.publish(toTrackingErrorsMsg(t, errors));

  if (trail_period_ > 0 && t >= next_trail_) {
    trail_.push_back(point(s.x, s.y, 0.02));
    while (next_trail_ <= t) next_trail_ += trail_period_;
  }
  if (markers_pub_.getNumSubscribers() == 0) return;

  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker body = marker(frames::kBaseLink, "body", 0, visualization_msgs::Marker::CUBE);
  body.pose.position = point(b - 0.5 * l, 0.0, 0.5 * kBodyHeight);
  body.scale.x = l + 2.0 * kBodyOverhang;
  body.scale.y = kBodyWidth;
  body.scale.z = kBodyHeight;
  body.color = color(0.15f, 0.35f, 0.95f, 0.9f);
  markers.markers.push_back(body);

  int id = 0;
  for (const char* frame : {frames::kFrontWheel, frames::kRearWheel}) {
    for (double side : {-0.5 * kTrackWidth, 0.5 * kTrackWidth}) {
      visualization_msgs::Marker wheel = marker(frame, "wheels", id++, visualization_msgs::Marker::CUBE);
      wheel.pose.position = point(0.0, side, kBodyHeight + 0.5 * kWheelWidth);  // drawn above the body
      // A box of diameter x width x width: from the top it reads as a tyre.
      wheel.scale.x = kWheelDiameter;
      wheel.scale.y = kWheelWidth;
      wheel.scale.z = kWheelWidth;
      wheel.color = color(0.08f, 0.08f, 0.08f);
      markers.markers.push_back(wheel);
    }
  }

  // Lateral tire forces, along each wheel's y axis (left positive), from the axle centre.
  const double forces[2] = {s.force_front, s.force_rear};
  const char* force_frames[2] = {frames::kFrontWheel, frames::kRearWheel};
  for (int i = 0; i < 2; ++i) {
    visualization_msgs::Marker arrow = marker(force_frames[i], "tire_forces", i, visualization_msgs::Marker::ARROW);
    arrow.points.push_back(point(0.0, 0.0, 1.0));
    arrow.points.push_back(point(0.0, forces[i] / options_.force_scale, 1.0));
    arrow.scale.x = 0.12;  // shaft diameter
    arrow.scale.y = 0.3;   // head diameter
    arrow.scale.z = 0.3;   // head length
    arrow.color = i == 0 ? color(1.0f, 0.1f, 0.1f) : color(1.0f, 0.5f, 0.0f);
    markers.markers.push_back(arrow);
  }

  if (trail_.size() >= 2) {
    visualization_msgs::Marker trail = marker(frames::kMap, "trail", 0, visualization_msgs::Marker::LINE_STRIP);
    trail.points = trail_;
    trail.points.push_back(point(s.x, s.y, 0.02));
    trail.scale.x = kTrailWidth;
    trail.color = color(0.9f, 0.3f, 0.9f);
    markers.markers.push_back(trail);
  }

  visualization_msgs::Marker label = marker(frames::kBaseLink, "label", 0, visualization_msgs::Marker::TEXT_VIEW_FACING);
  char text[160];
  std::snprintf(text, sizeof(text), "t=%.2fs  e_y=%+.3fm  e_psi=%+.2fdeg  delta=%+.2fdeg",
                nanosecondsToSeconds(t), errors.lateral, errors.heading * 180.0 / M_PI, s.delta * 180.0 / M_PI);
  label.text = text;
  label.pose.position = point(8.0, 3.0, 2.0);
  label.scale.z = 0.5;
  label.color = color(1.0f, 1.0f, 1.0f);
  markers.markers.push_back(label);
  markers_pub_.publish(markers);
}

}  // namespace lane_keeping
