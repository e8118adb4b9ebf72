// The live gap monitor's sliding window: three streams kept by stamp, assembled into a GapLog on demand.
#include "lane_keeping/gap/monitor/monitor_window.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lane_keeping {
namespace {

bool finite(const MonitorStateSample& s) {
  for (double v : {s.t, s.x, s.y, s.psi, s.yaw_rate, s.delta, s.delta_rate, s.speed, s.lateral_acceleration,
                   s.torque_applied}) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

/// Linear interpolation of a stamped series at t, walking `cursor` forward (queries come in increasing
/// t). False when t lies outside the series.
bool interpolate(const std::deque<std::pair<double, double>>& series, double t, std::size_t* cursor, double* value) {
  if (series.empty() || t < series.front().first || t > series.back().first) return false;
  std::size_t& i = *cursor;
  while (i + 1 < series.size() && series[i + 1].first <= t) ++i;
  if (i + 1 >= series.size()) {
    *value = series[i].second;  // t equals the last stamp
    return true;
  }
  const auto& [t0, v0] = series[i];
  const auto& [t1, v1] = series[i + 1];
  *value = v0 + (v1 - v0) * (t - t0) / (t1 - t0);
  return true;
}

}  // namespace

MonitorWindow::MonitorWindow(double length, double sample_period, double jump_back)
    : length_(length), sample_period_(sample_period), jump_back_(jump_back) {
  if (!(sample_period > 0.0 && length > sample_period && jump_back > 0.0)) {
    throw std::invalid_argument("MonitorWindow: need 0 < sample_period < length and jump_back > 0");
  }
}

MonitorWindow::Added MonitorWindow::addState(const MonitorStateSample& sample) {
  if (!finite(sample)) {
    ++counts_.rejected;
    return Added::kRejected;
  }
  if (!states_.empty()) {
    const double last = states_.back().t;
    if (sample.t < last - jump_back_) {
      // The clock jumped backwards: what the window holds belongs to another run (or loop of a bag).
      clear();
      ++counts_.restarts;
      states_.push_back(sample);
      return Added::kRestarted;
    }
    if (!(sample.t > last)) {
      ++counts_.rejected;
      return Added::kRejected;
    }
    // Thinned to the replays' rate (a tolerance of 1e-6 of the period keeps every sample of a log at
    // exactly that rate despite rounding of the stamps).
    if (sample.t < last + sample_period_ * (1.0 - 1e-6)) return Added::kThinned;
  }
  states_.push_back(sample);
  trim();
  return Added::kAccepted;
}

namespace {
MonitorWindow::Added addScalar(std::deque<std::pair<double, double>>& series, double t, double value,
                               std::size_t* rejected) {
  if (!std::isfinite(t) || !std::isfinite(value) || (!series.empty() && !(t > series.back().first))) {
    ++*rejected;
    return MonitorWindow::Added::kRejected;
  }
  series.emplace_back(t, value);
  return MonitorWindow::Added::kAccepted;
}
}  // namespace

MonitorWindow::Added MonitorWindow::addDesired(double t, double delta_des) {
  // A desired or torque stamp far before the last one is the same clock jump the state shows: start the
  // stream again (its old samples would never bracket the new states).
  if (!desired_.empty() && t < desired_.back().first - jump_back_) desired_.clear();
  const Added added = addScalar(desired_, t, delta_des, &counts_.rejected);
  trim();
  return added;
}

MonitorWindow::Added MonitorWindow::addTorque(double t, double torque) {
  if (!torque_.empty() && t < torque_.back().first - jump_back_) torque_.clear();
  const Added added = addScalar(torque_, t, torque, &counts_.rejected);
  trim();
  return added;
}

void MonitorWindow::clear() {
  states_.clear();
  desired_.clear();
  torque_.clear();
}

double MonitorWindow::latest() const {
  return states_.empty() ? std::numeric_limits<double>::quiet_NaN() : states_.back().t;
}

double MonitorWindow::span() const { return states_.empty() ? 0.0 : states_.back().t - states_.front().t; }

void MonitorWindow::trim() {
  // Keep one window of states; the command streams a little longer, so that the oldest state kept is
  // still bracketed.
  if (states_.empty()) return;
  const double newest = std::max({states_.back().t, desired_.empty() ? -INFINITY : desired_.back().first,
                                  torque_.empty() ? -INFINITY : torque_.back().first});
  // A window ending at a stamp up to kSlack before the newest sample can still be assembled (the
  // monitor evaluates once every stream covers a boundary, so the state may run ahead of it).
  const double keep_from = newest - length_ - kSlack;
  while (states_.size() > 1 && states_.front().t < keep_from) states_.pop_front();
  const double commands_from = states_.front().t - sample_period_;
  while (desired_.size() > 2 && desired_[1].first <= commands_from) desired_.pop_front();
  while (torque_.size() > 2 && torque_[1].first <= commands_from) torque_.pop_front();
}

double MonitorWindow::coveredUntil() const {
  if (states_.empty()) return std::numeric_limits<double>::quiet_NaN();
  double covered = states_.back().t;
  if (!desired_.empty()) covered = std::min(covered, desired_.back().first);
  if (!torque_.empty()) covered = std::min(covered, torque_.back().first);
  return covered;
}

GapLog MonitorWindow::log(const std::string& source, double until) const {
  GapLog log;
  log.source = source;
  const bool with_desired = !desired_.empty(), with_torque = !torque_.empty();
  std::size_t desired_cursor = 0, torque_cursor = 0;
  counts_.uncovered = 0;
  for (const MonitorStateSample& s : states_) {
    if (s.t > until) break;
    if (s.t < until - length_) continue;
    double delta_des = 0.0, torque = s.torque_applied;
    if ((with_desired && !interpolate(desired_, s.t, &desired_cursor, &delta_des)) ||
        (with_torque && !interpolate(torque_, s.t, &torque_cursor, &torque))) {
      ++counts_.uncovered;
      continue;
    }
    log.t.push_back(s.t);
    log.x.push_back(s.x);
    log.y.push_back(s.y);
    log.psi.push_back(s.psi);
    log.yaw_rate.push_back(s.yaw_rate);
    log.delta.push_back(s.delta);
    log.delta_rate.push_back(s.delta_rate);
    log.v.push_back(s.speed);
    log.ay.push_back(s.lateral_acceleration);
    if (with_desired) log.delta_des.push_back(delta_des);
    log.torque.push_back(torque);
  }
  log.rows_read = log.t.size() + counts_.uncovered;
  if (!with_torque && !log.t.empty()) {
    log.notes.push_back("no steering torque command received: the torque column is the torque acting on the wheel "
                        "(vehicle_state), which equals the command unless delays.torque_to_plant > 0");
  }
  if (counts_.uncovered > 0) {
    log.notes.push_back(std::to_string(counts_.uncovered) +
                        " state samples outside the received desired steering / torque left out");
  }
  return log;
}

}  // namespace lane_keeping
