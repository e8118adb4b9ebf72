#include "lane_keeping/gap/fit/candidate_effects.h"

#include <algorithm>
#include <sstream>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace {

void forBothTires(SimConfig& c, const std::function<void(TireParams&)>& f) {
  f(c.tire_front);
  f(c.tire_rear);
}

std::vector<CandidateEffect> buildCandidates() {
  std::vector<CandidateEffect> list;
  list.push_back({"tire_lag",
                  "the tires build up force over a relaxation length (first-order lag)",
                  {{"relaxation_length", "m", 0.3, 0.05, 5.0, true}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    forBothTires(c, [&](TireParams& t) { t.relaxation_length = p[0]; });
                  }});
  list.push_back({"sensing_delay",
                  "the pose reaches the path tracker later than configured",
                  {{"extra_delay", "s", 0.02, 0.0, 0.3, false}},
                  {"tracker"},
                  true,
                  [](const std::vector<double>& p, SimConfig& c) { c.delays.pose_to_tracker += p[0]; }});
  list.push_back({"actuation_delay",
                  "the steering torque reaches the wheel later than configured",
                  {{"extra_delay", "s", 0.001, 0.0, 0.01, false}},
                  {"steering"},
                  true,
                  [](const std::vector<double>& p, SimConfig& c) { c.delays.torque_to_plant += p[0]; }});
  list.push_back({"steering_friction",
                  "Coulomb and viscous friction in the steering",
                  // Log-spaced: friction levels span decades and the loss has narrow minima (stick-slip).
                  {{"coulomb", "N m", 1.0, 0.02, 200.0, true}, {"viscous", "N m s/rad", 0.1, 0.01, 100.0, true}},
                  {"steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.steering.friction_model = "tanh";
                    c.steering.coulomb_friction = p[0];
                    c.steering.viscous_friction = p[1];
                  }});
  list.push_back({"torque_limit",
                  "the steering actuator saturates",
                  {{"limit", "N m", 100.0, 0.5, 1e5, true}},
                  {"steering"},
                  true,
                  [](const std::vector<double>& p, SimConfig& c) { c.steering.torque_limit = p[0]; }});
  list.push_back({"road_friction",
                  "the road offers a different friction coefficient",
                  {{"scale", "", 0.8, 0.05, 3.0, true}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    forBothTires(c, [&](TireParams& t) {
                      t.mu *= p[0];
                      t.mu0 *= p[0];
                    });
                  }});
  list.push_back({"cornering_stiffness",
                  "the tires' cornering stiffness differs (front and rear scales)",
                  {{"front_scale", "", 1.0, 0.1, 10.0, true}, {"rear_scale", "", 1.0, 0.1, 10.0, true}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.tire_front.lateral_stiffness *= p[0];
                    c.tire_rear.lateral_stiffness *= p[1];
                    if (c.tire_front.lugre.sigma0y) *c.tire_front.lugre.sigma0y *= p[0];
                    if (c.tire_rear.lugre.sigma0y) *c.tire_rear.lugre.sigma0y *= p[1];
                  }});
  list.push_back({"lateral_disturbance",
                  "a steady lateral force and yaw moment on the body (crosswind, road bank)",
                  {{"force", "N", 0.0, -2e4, 2e4, false}, {"moment", "N m", 0.0, -2e4, 2e4, false}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.disturbance.lateral_force += p[0];
                    c.disturbance.yaw_moment += p[1];
                  },
                  "aerodynamic"});
  // A banked road pushes the car like a crosswind, but it is gravity: the lateral accelerometer does
  // not sense it (the logged a_y lacks F / m), which the chassis replay's a_y shows.
  list.push_back({"lateral_disturbance",
                  "a steady lateral force and yaw moment from a banked road (the accelerometer does not sense it)",
                  {{"force", "N", 0.0, -2e4, 2e4, false}, {"moment", "N m", 0.0, -2e4, 2e4, false}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.disturbance.kind = "road_bank";
                    c.disturbance.lateral_force += p[0];
                    c.disturbance.yaw_moment += p[1];
                  },
                  "road_bank"});
  list.push_back({"pose_bias",
                  "the localisation the tracker uses is offset",
                  {{"y", "m", 0.0, -3.0, 3.0, false}, {"psi", "rad", 0.0, -0.3, 0.3, false}},
                  {"tracker"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.tracker.pose_bias_y += p[0];
                    c.tracker.pose_bias_psi += p[1];
                  },
                  "tracker"});
  // The localisation the tracker uses is the one the log records: the tracker replay already sees
  // the bias (nothing to fit there); the chassis replay, started from the logged heading, integrates
  // the biased heading into y. A y bias alone is unobservable (shifted initial y, shifted output).
  list.push_back({"pose_bias",
                  "the localisation (used by the tracker and recorded in the log) is offset in heading",
                  {{"psi", "rad", 0.0, -0.3, 0.3, false}},
                  {"chassis", "steering"},  // the steering replay takes its lateral velocity from the chassis'
                  false,
                  [](const std::vector<double>& p, SimConfig& c) { c.sensors.pose_bias_psi += p[0]; },
                  "localisation"});
  list.push_back({"steering_compliance",
                  "a torsionally compliant steering column between actuator and wheel",
                  // The column's inertia is fitted too: a nominal with a rigid column has no use for
                  // (and no knowledge of) it, and a wrong one leaves a resonance the other two cannot place.
                  {{"stiffness", "N m/rad", 5000.0, 100.0, 1e6, true},
                   {"damping", "N m s/rad", 5.0, 0.1, 100.0, true},
                   {"inertia", "kg m^2", 0.02, 0.01, 0.5, true}},
                  {"steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.steering.column_stiffness = p[0];
                    c.steering.column_damping = p[1];
                    c.steering.column_inertia = p[2];
                  },
                  "wheel_sensor"});
  // The same column with the actuator's angle sensor on the motor side: the PID closes on the column
  // angle, which the log does not hold; the actuator replay reconstructs it from the logged torque
  // and road-wheel angle.
  list.push_back({"steering_compliance",
                  "a torsionally compliant steering column, the actuator sensing the motor side",
                  {{"stiffness", "N m/rad", 5000.0, 100.0, 1e6, true},
                   {"damping", "N m s/rad", 5.0, 0.1, 100.0, true},
                   {"inertia", "kg m^2", 0.02, 0.01, 0.5, true}},
                  {"steering", "actuator"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.steering.column_stiffness = p[0];
                    c.steering.column_damping = p[1];
                    c.steering.column_inertia = p[2];
                    c.steering.angle_sensor = "column";
                  },
                  "motor_sensor"});
  list.push_back({"inertia",
                  "the car's yaw inertia and mass differ",
                  {{"yaw_scale", "", 1.0, 0.2, 5.0, true}, {"mass_scale", "", 1.0, 0.5, 2.0, true}},
                  {"chassis", "steering"},
                  false,
                  [](const std::vector<double>& p, SimConfig& c) {
                    c.vehicle.yaw_inertia *= p[0];
                    c.vehicle.mass *= p[1];
                  }});
  return list;
}

/// Collects "key" -> printed value for every parameter.
class ValueCollector : public ParamVisitor {
 public:
  std::map<std::string, std::string> values;
  void number(const std::string& k, double& v, const char*, const Range&, const char*) override { values[k] = formatNumber(v); }
  void optionalNumber(const std::string& k, std::optional<double>& v, const char*, const Range&, const char*) override {
    values[k] = v ? formatNumber(*v) : "auto";
  }
  void integer(const std::string& k, int& v, const Range&, const char*) override { values[k] = std::to_string(v); }
  void flag(const std::string& k, bool& v, const char*) override { values[k] = v ? "true" : "false"; }
  void choice(const std::string& k, std::string& v, const std::vector<std::string>&, const char*) override { values[k] = v; }
  void points(const std::string& k, PointList& v, const char*, const char*) override {
    std::ostringstream out;
    for (const auto& p : v) out << "[" << formatNumber(p[0]) << "," << formatNumber(p[1]) << "]";
    values[k] = out.str();
  }
};

}  // namespace

const std::vector<CandidateEffect>& candidateEffects() {
  static const std::vector<CandidateEffect> list = buildCandidates();
  return list;
}

const CandidateEffect& candidateEffect(const std::string& name) {
  for (const auto& c : candidateEffects()) {
    if (c.name == name) return c;
  }
  throw LaneKeepingError("unknown candidate effect '" + name + "'");
}

bool effectChangesSubsystem(const std::string& effect, const std::string& subsystem) {
  candidateEffect(effect);  // throws on an unknown name
  for (const auto& e : candidateEffects()) {
    if (e.name == effect && std::find(e.subsystems.begin(), e.subsystems.end(), subsystem) != e.subsystems.end()) {
      return true;
    }
  }
  return false;
}

const std::vector<std::string>& knownLookAlikes(const std::string& effect) {
  static const std::map<std::string, std::vector<std::string>> pairs{
      {"actuation_delay", {"steering_compliance"}},
      {"steering_compliance", {"actuation_delay"}},
      {"steering_friction", {"torque_limit"}},
      {"torque_limit", {"steering_friction"}},
      {"road_friction", {"cornering_stiffness", "tire_lag"}},
      {"cornering_stiffness", {"road_friction", "inertia", "tire_lag"}},
      {"tire_lag", {"cornering_stiffness", "road_friction"}},
      {"inertia", {"cornering_stiffness"}},
      {"lateral_disturbance", {"pose_bias"}},
      {"pose_bias", {"lateral_disturbance"}},
      {"sensing_delay", {}}};
  static const std::vector<std::string> none;
  const auto it = pairs.find(effect);
  return it == pairs.end() ? none : it->second;
}

std::map<std::string, std::string> configDifference(const SimConfig& nominal, const SimConfig& changed) {
  ValueCollector a, b;
  SimConfig na = nominal, cb = changed;
  na.visit(a);
  cb.visit(b);
  std::map<std::string, std::string> diff;
  for (const auto& [key, value] : b.values) {
    if (a.values[key] != value) diff[key] = value;
  }
  return diff;
}

}  // namespace lane_keeping
