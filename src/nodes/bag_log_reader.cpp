#include "bag_log_reader.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <lane_keeping/DesiredSteeringArray.h>
#include <lane_keeping/SteeringTorqueArray.h>
#include <lane_keeping/VehicleStateArray.h>

#include "conversions.h"
#include "lane_keeping/common/errors.h"
#include "topic_names.h"

namespace lane_keeping {
namespace {

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Linear interpolation in a time-sorted (stamp, value) series; false outside it.
bool interpolate(const std::vector<std::pair<Nanoseconds, double>>& series, Nanoseconds t, std::size_t* cursor,
                 double* value) {
  if (series.empty() || t < series.front().first || t > series.back().first) return false;
  std::size_t i = std::min(*cursor, series.size() - 1);
  while (i > 0 && series[i].first > t) --i;
  while (i + 1 < series.size() && series[i + 1].first <= t) ++i;
  *cursor = i;
  if (series[i].first == t || i + 1 == series.size()) {
    *value = series[i].second;
    return true;
  }
  const double w = static_cast<double>(t - series[i].first) / static_cast<double>(series[i + 1].first - series[i].first);
  *value = series[i].second + w * (series[i + 1].second - series[i].second);
  return true;
}

}  // namespace

GapLog readBagLog(const std::string& path, double max_rate) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw InputError(path + ": cannot open bag: " + e.what());
  }
  // Topics of the suite, by suffix (any namespace) and type.
  std::string state_topic, desired_topic, torque_topic;
  std::ostringstream available;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo* c : all.getConnections()) {
    available << "\n    " << c->topic << " (" << c->datatype << ")";
    if (endsWith(c->topic, std::string("/") + topics::kVehicleState) && c->datatype == "lane_keeping/VehicleStateArray") {
      state_topic = c->topic;
    }
    if (endsWith(c->topic, std::string("/") + topics::kDesiredSteering) &&
        c->datatype == "lane_keeping/DesiredSteeringArray") {
      desired_topic = c->topic;
    }
    if (endsWith(c->topic, std::string("/") + topics::kSteeringTorque) && c->datatype == "lane_keeping/SteeringTorqueArray") {
      torque_topic = c->topic;
    }
  }
  auto missing = [&](const char* what, const char* type) {
    return InputError(path + ": the bag has no " + what + " topic (lane_keeping/" + type + "); it holds:" + available.str());
  };
  if (state_topic.empty()) throw missing(topics::kVehicleState, "VehicleStateArray");
  if (desired_topic.empty()) throw missing(topics::kDesiredSteering, "DesiredSteeringArray");

  std::vector<std::pair<Nanoseconds, VehicleStateSample>> states;
  std::vector<std::pair<Nanoseconds, double>> desired, torque;
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{state_topic, desired_topic, torque_topic}));
  for (const rosbag::MessageInstance& m : view) {
    if (m.getTopic() == state_topic) {
      if (auto msg = m.instantiate<lane_keeping::VehicleStateArray>()) {
        for (const auto& s : msg->samples) states.emplace_back(toNanoseconds(s.header.stamp), fromVehicleStateMsg(s));
      }
    } else if (m.getTopic() == desired_topic) {
      if (auto msg = m.instantiate<lane_keeping::DesiredSteeringArray>()) {
        for (const auto& s : msg->samples) desired.emplace_back(toNanoseconds(s.header.stamp), s.delta_des);
      }
    } else if (m.getTopic() == torque_topic) {
      if (auto msg = m.instantiate<lane_keeping::SteeringTorqueArray>()) {
        for (const auto& s : msg->samples) torque.emplace_back(toNanoseconds(s.header.stamp), s.torque);
      }
    }
  }
  bag.close();
  auto byStamp = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::stable_sort(states.begin(), states.end(), byStamp);
  std::stable_sort(desired.begin(), desired.end(), byStamp);
  std::stable_sort(torque.begin(), torque.end(), byStamp);
  if (states.empty()) throw InputError(path + ": topic " + state_topic + " holds no samples");
  if (desired.empty()) throw InputError(path + ": topic " + desired_topic + " holds no samples");

  GapLog log;
  log.source = path;
  const Nanoseconds period = max_rate > 0.0 ? static_cast<Nanoseconds>(std::llround(1e9 / max_rate)) : 0;
  Nanoseconds last_kept = -1;
  std::size_t desired_cursor = 0, torque_cursor = 0, outside = 0, non_finite = 0;
  for (const auto& [stamp, s] : states) {
    if (last_kept >= 0 && (stamp <= last_kept || stamp - last_kept < period)) continue;
    ++log.rows_read;
    double delta_des = 0.0, command = s.torque;
    const bool have_desired = interpolate(desired, stamp, &desired_cursor, &delta_des);
    const bool have_torque = torque.empty() || interpolate(torque, stamp, &torque_cursor, &command);
    if (!have_desired || !have_torque) {
      ++outside;
      ++log.rows_skipped;
      continue;
    }
    const double values[] = {s.x, s.y, s.psi, s.sigma2, s.delta, s.sigma3, s.speed, s.lateral_acceleration, delta_des, command};
    if (!std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); })) {
      ++non_finite;
      ++log.rows_skipped;
      continue;
    }
    last_kept = stamp;
    log.t.push_back(nanosecondsToSeconds(stamp));
    log.x.push_back(s.x);
    log.y.push_back(s.y);
    log.psi.push_back(s.psi);
    log.yaw_rate.push_back(s.sigma2);
    log.delta.push_back(s.delta);
    log.delta_rate.push_back(s.sigma3);
    log.v.push_back(s.speed);
    log.ay.push_back(s.lateral_acceleration);
    log.delta_des.push_back(delta_des);
    log.torque.push_back(command);
  }
  if (torque.empty()) {
    log.notes.push_back("topic " + std::string(topics::kSteeringTorque) +
                        " not recorded: the torque column is the torque acting on the wheel (vehicle_state), which "
                        "equals the command unless delays.torque_to_plant > 0");
  }
  if (outside > 0) log.notes.push_back(std::to_string(outside) + " samples outside the recorded desired steering/torque skipped");
  if (non_finite > 0) log.notes.push_back(std::to_string(non_finite) + " samples holding NaN/Inf skipped");
  if (log.size() < 10) throw InputError(path + ": fewer than 10 usable samples in the bag");
  return log;
}

}  // namespace lane_keeping
