#pragma once
/// One configuration change during a run, as a user writes it: "T:key=value" — from simulated time
/// T [s] on, `key` has `value` (e.g. "10:steering.coulomb_friction=3": kingpin friction on at 10 s).
/// `lk_simulate --change`, the nodes' `~changes` parameter and the record of a dynamic_reconfigure
/// request (msg/ParameterChange.msg) all use this form. Parsing checks only the form; the value is
/// read and checked by the configuration's reader when the change is scheduled
/// (sim/change_schedule.h), by the same rules as a YAML file.
#include <string>

namespace lane_keeping {

struct TimedChange {
  double t = 0.0;     ///< [s] simulated time from which the new value holds (>= 0)
  std::string key;    ///< full dotted configuration key, e.g. "steering.coulomb_friction"
  std::string value;  ///< the new value as YAML text ("3", "lugre")

  /// "key=value", as --set takes it.
  std::string assignment() const { return key + "=" + value; }
  /// "T:key=value" (T printed so that it reads back to the same double).
  std::string text() const;
};

/// The largest T accepted [s] (about 31.7 years; stamps are int64 nanoseconds).
constexpr double kMaxChangeTime = 1e9;

/// Parses "T:key=value" (spaces around the parts are ignored). Throws ConfigError naming the change
/// and the bad part: the time (not a number, negative, beyond kMaxChangeTime), a missing key or value.
TimedChange parseTimedChange(const std::string& text);

}  // namespace lane_keeping
