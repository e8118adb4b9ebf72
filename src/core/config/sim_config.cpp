#include "lane_keeping/config/sim_config.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {

void SimConfig::visit(ParamVisitor& v) {
  vehicle.visit(v, "vehicle.");
  steering.visit(v, "steering.");
  disturbance.visit(v, "disturbance.");
  tire_front.visit(v, "tire.front.");
  tire_rear.visit(v, "tire.rear.");
  path.visit(v, "path.");
  tracker.visit(v, "tracker.");
  actuator.visit(v, "actuator.");
  delays.visit(v, "delays.");
  sensors.visit(v, "sensors.");
  simulation.visit(v, "simulation.");
}

namespace {

/// RK4's stability interval on the negative real axis is about [-2.785, 0]. The transport term of
/// the distributed LuGre model (Deur eq 22) has eigenvalues down to -V (N - 1) / L.
void checkDistributedTireStep(const TireParams& tire, const std::string& prefix, double speed, double step,
                              std::vector<ConfigProblem>& problems) {
  if (tire.model != "lugre_distributed") return;
  const double rate = speed * (tire.lugre.bristles - 1) / tire.contactLength();
  const double product = rate * step;
  const double limit = 2.5;
  if (product > limit) {
    const int max_bristles = static_cast<int>(std::floor(limit * tire.contactLength() / (speed * step))) + 1;
    std::ostringstream message;
    message << "= " << tire.lugre.bristles << " with simulation.step = " << formatNumber(step)
            << " s is beyond RK4's stability limit: transport rate V (N-1)/L = " << formatNumber(rate)
            << " 1/s times the step = " << formatNumber(product) << " > " << limit << "; use at most "
            << max_bristles << " bristles or step <= " << formatNumber(limit / rate) << " s";
    problems.push_back({prefix + "lugre.bristles", "", message.str()});
  }
}

/// A lane the car cannot follow at any steering angle: its tightest bend must be no tighter than the
/// car's smallest turning radius, l / tan(delta_max) (single-track geometry, Beregi eq 1 with zero slip),
/// delta_max being the steering angle at which a run stops as diverged. `sinusoid.wavelength: 1e-9` was
/// accepted and ended as "spinning out". The sinusoid's curvature reaches A (2 pi / wavelength)^2 (more
/// during its fade-in); the quintic lane change's 10/sqrt(3) offset / length^2.
/// Three significant digits, for figures derived in a message (a radius, a bound).
std::string shortNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

void checkLaneAgainstCar(const PathParams& path, const VehicleParams& vehicle, const DivergenceLimits& limits,
                         std::vector<ConfigProblem>& problems) {
  const double max_curvature = std::tan(limits.max_steering_angle) / vehicle.wheelbase;
  if (!std::isfinite(max_curvature) || !(max_curvature > 0.0)) return;  // the ranges are reported elsewhere
  const std::string car = "the car turns no tighter than a radius of vehicle.wheelbase / tan(simulation.divergence."
                          "max_steering_angle) = " + shortNumber(1.0 / max_curvature) + " m";
  if (path.type == "sinusoid" && path.sinusoid_wavelength > 0.0 && path.sinusoid_amplitude != 0.0) {
    const double k = 2.0 * M_PI / path.sinusoid_wavelength;
    const double curvature = std::fabs(path.sinusoid_amplitude) * k * k;
    if (curvature > max_curvature) {
      const double shortest = 2.0 * M_PI * std::sqrt(std::fabs(path.sinusoid_amplitude) / max_curvature);
      problems.push_back({"path.sinusoid.wavelength", "",
                          "= " + formatNumber(path.sinusoid_wavelength) + " m with path.sinusoid.amplitude = " +
                              formatNumber(path.sinusoid_amplitude) + " m bends the lane to a radius of " +
                              shortNumber(1.0 / curvature) + " m; " + car + ": the wavelength must be at least " +
                              shortNumber(shortest) + " m for this amplitude"});
    }
  }
  if (path.type == "lane_change" && path.lane_change_length > 0.0 && path.lane_change_offset != 0.0) {
    const double curvature = 10.0 / std::sqrt(3.0) * std::fabs(path.lane_change_offset) /
                             (path.lane_change_length * path.lane_change_length);
    if (curvature > max_curvature) {
      const double shortest = std::sqrt(10.0 / std::sqrt(3.0) * std::fabs(path.lane_change_offset) / max_curvature);
      problems.push_back({"path.lane_change.length", "",
                          "= " + formatNumber(path.lane_change_length) + " m with path.lane_change.offset = " +
                              formatNumber(path.lane_change_offset) + " m bends the lane to a radius of " +
                              shortNumber(1.0 / curvature) + " m; " + car + ": the length must be at least " +
                              shortNumber(shortest) + " m for this offset"});
    }
  }
}

}  // namespace

std::vector<ConfigProblem> SimConfig::problems() const {
  SimConfig copy = *this;  // visit() takes non-const references
  RangeChecker checker;
  copy.visit(checker);
  std::vector<ConfigProblem> problems = checker.problems();
  vehicle.validate("vehicle.", problems);
  tire_front.validate("tire.front.", problems);
  tire_rear.validate("tire.rear.", problems);
  path.validate("path.", problems);
  simulation.validate("simulation.", problems);
  if (steering.friction_model == "lugre" && steering.breakaway_friction > 0.0 && steering.coulomb_friction <= 0.0) {
    problems.push_back({"steering.coulomb_friction", "",
                        "must be > 0 N m with steering.friction_model = lugre and a breakaway friction "
                        "(g of Deur eq 6 must stay positive)"});
  }
  if (steering.columnSensor() && !steering.compliant()) {
    problems.push_back({"steering.angle_sensor", "",
                        "= column needs a compliant column (steering.column_stiffness > 0): with a rigid one the "
                        "motor side is the road wheel"});
  }
  checkLaneAgainstCar(path, vehicle, simulation.divergence, problems);
  checkDistributedTireStep(tire_front, "tire.front.", vehicle.fastestSpeed(), simulation.step, problems);
  checkDistributedTireStep(tire_rear, "tire.rear.", vehicle.fastestSpeed(), simulation.step, problems);
  return problems;
}

void SimConfig::validate(const FlatParams* source) const {
  std::vector<ConfigProblem> found = problems();
  if (found.empty()) return;
  if (source != nullptr) {
    for (auto& problem : found) {
      if (problem.location.empty()) problem.location = source->locationOf(problem.key);
    }
  }
  throw ConfigError(found);
}

void SimConfig::print(std::ostream& out, bool with_docs) const {
  SimConfig copy = *this;
  ParamPrinter printer(out, with_docs);
  copy.visit(printer);
}

SimConfig simConfigFromFlat(const FlatParams& source, MissingKeys missing) {
  SimConfig config;
  FlatParamReader reader(source);
  config.visit(reader);
  std::vector<ConfigProblem> problems = reader.problems();
  if (missing == MissingKeys::kRefuse && !reader.absentKeys().empty()) {
    // Name each missing key with the value it would otherwise have taken, so the user sees what the
    // tree lacks (a key deleted from the server, a launch that loaded only its own overlay).
    SimConfig defaults;
    ParamCatalog catalog;
    defaults.visit(catalog);
    for (const std::string& key : reader.absentKeys()) {
      std::string default_text;
      for (const ParamCatalog::Row& row : catalog.rows()) {
        if (row.key == key) default_text = row.value + (row.unit.empty() ? "" : " " + row.unit);
      }
      problems.push_back(ConfigProblem{key, "", "is missing (its default would be " + default_text +
                                                    "); a partial configuration is refused, not completed silently"});
    }
  }
  const auto unknown = reader.unknownKeyProblems();
  problems.insert(problems.end(), unknown.begin(), unknown.end());
  if (!problems.empty()) throw ConfigError(problems);
  config.validate(&source);
  return config;
}

SimConfig loadSimConfig(const std::vector<std::string>& files, const std::vector<std::string>& assignments) {
  FlatParams source;
  for (const auto& file : files) source.overlayFile(file);
  for (const auto& assignment : assignments) source.overlayAssignment(assignment);
  return loadSimConfig(std::move(source));
}

SimConfig loadSimConfig(FlatParams source) {
  // A `log:` section says how a log's columns map to the gap diagnosis's schema (gap/log/log_mapping.h): it
  // belongs to the files a vehicle's logs are read with, not to the simulation, which ignores it.
  source.erasePrefix("log.");
  return simConfigFromFlat(source);
}

}  // namespace lane_keeping
