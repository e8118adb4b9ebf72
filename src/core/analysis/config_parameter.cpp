#include "lane_keeping/analysis/config_parameter.h"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {
namespace {

constexpr const char* kTau2 = "tau2";

/// Finds one numeric key; optionally writes it.
class NumberAccess : public ParamVisitor {
 public:
  NumberAccess(std::string key, std::optional<double> write) : key_(std::move(key)), write_(write) {}

  void number(const std::string& key, double& value, const char* unit, const Range&, const char* doc) override {
    if (key != key_) return;
    if (write_) value = *write_;
    hit(value, unit, doc);
  }
  void optionalNumber(const std::string& key, std::optional<double>& value, const char* unit, const Range&,
                      const char* doc) override {
    if (key != key_) return;
    if (write_) value = *write_;
    hit(value.value_or(std::numeric_limits<double>::quiet_NaN()), unit, doc);
  }
  void integer(const std::string& key, int& value, const Range&, const char* doc) override {
    if (key != key_) return;
    if (write_) {
      if (*write_ != std::round(*write_)) {
        throw ConfigError(key_ + " = " + std::to_string(*write_) + " must be a whole number");
      }
      value = static_cast<int>(*write_);
    }
    hit(value, "", doc);
  }
  void flag(const std::string& key, bool&, const char*) override { notNumeric(key); }
  void choice(const std::string& key, std::string&, const std::vector<std::string>&, const char*) override {
    notNumeric(key);
  }
  void points(const std::string& key, PointList&, const char*, const char*) override { notNumeric(key); }

  bool found() const { return found_; }
  double value() const { return value_; }
  const std::string& unit() const { return unit_; }
  const std::string& doc() const { return doc_; }

 private:
  void hit(double value, const char* unit, const char* doc) {
    found_ = true;
    value_ = value;
    unit_ = unit;
    doc_ = doc;
  }
  void notNumeric(const std::string& key) const {
    if (key == key_) throw ConfigError(key_ + " is not a numeric parameter (it cannot be a chart axis)");
  }

  std::string key_;
  std::optional<double> write_;
  bool found_ = false;
  double value_ = 0.0;
  std::string unit_, doc_;
};

[[noreturn]] void unknownKey(const std::string& key) {
  throw ConfigError(key + " is not a numeric configuration key; use a dotted key such as tracker.k_psi, "
                          "tracker.k_y, actuator.p, delays.pose_to_tracker, vehicle.steering_inertia "
                          "(lk_simulate --print-config lists them all), or tau2 for both actuator delays");
}

NumberAccess access(SimConfig& config, const std::string& key, std::optional<double> write) {
  NumberAccess visitor(key, write);
  config.visit(visitor);
  if (!visitor.found()) unknownKey(key);
  return visitor;
}

}  // namespace

void setConfigNumber(SimConfig& config, const std::string& key, double value) {
  if (!std::isfinite(value)) throw ConfigError(key + " = " + std::to_string(value) + " must be a finite number");
  if (key == kTau2) {
    config.delays.desired_steering_to_actuator = value;
    config.delays.steering_angle_to_actuator = value;
    return;
  }
  access(config, key, value);
}

double configNumber(const SimConfig& config, const std::string& key) {
  if (key == kTau2) {
    if (config.delays.desired_steering_to_actuator != config.delays.steering_angle_to_actuator) {
      throw ConfigError("tau2 is ambiguous: delays.desired_steering_to_actuator (" +
                        std::to_string(config.delays.desired_steering_to_actuator) +
                        " s) differs from delays.steering_angle_to_actuator (" +
                        std::to_string(config.delays.steering_angle_to_actuator) + " s)");
    }
    return config.delays.steering_angle_to_actuator;
  }
  SimConfig copy = config;
  return access(copy, key, std::nullopt).value();
}

ConfigParameterInfo configParameterInfo(const std::string& key) {
  if (key == kTau2) {
    return {key, "s", "tau2: both actuator input delays (delays.desired_steering_to_actuator and "
                      "delays.steering_angle_to_actuator), Beregi eq 12"};
  }
  SimConfig config;
  const NumberAccess visitor = access(config, key, std::nullopt);
  return {key, visitor.unit(), visitor.doc()};
}

}  // namespace lane_keeping
