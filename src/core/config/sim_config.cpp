#include "lane_keeping/config/sim_config.h"

#include <cmath>
#include <sstream>

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
  // A `log:` section says how a log's columns map to the gap diagnosis's schema (gap/log/log_mapping.h): it
  // belongs to the files a vehicle's logs are read with, not to the simulation, which ignores it.
  source.erasePrefix("log.");
  return simConfigFromFlat(source);
}

}  // namespace lane_keeping
