#include "lane_keeping/analysis/equation_readings.h"

#include <variant>

#include <Eigen/Dense>

#include "lane_keeping/analysis/config_parameter.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/sim/model_factory.h"

namespace lane_keeping {

std::vector<EquationReading> candidateReadings() {
  auto make = [](const char* name, const char* description) {
    EquationReading e;
    e.name = name;
    e.description = description;
    return e;
  };
  std::vector<EquationReading> r;
  r.push_back(make("printed", "eqs 3-5, 8, 12 as printed (the default)"));
  EquationReading e = make("no_front_leading_point", "eq 8 front at the contact centre: no a (sigma2 + sigma3) term");
  e.front_leading_point = false;
  r.push_back(e);
  e = make("no_aligning_moment_in_f3", "f3 = M_S: the front aligning moment does not act on the steering");
  e.aligning_moment_in_f3 = 0.0;
  r.push_back(e);
  e = make("aligning_moment_sign_in_f3", "f3 = M_S - M_F: aligning moment on the steering with the opposite sign");
  e.aligning_moment_in_f3 = -1.0;
  r.push_back(e);
  e = make("decoupled_steering_inertia", "sigma3' = f3 / J_F: the J_F couplings of eq 3 dropped");
  e.steering_inertia_coupled = false;
  r.push_back(e);
  e = make("kd_on_measured_rate_only", "eq 12 with -k_d delta' (no k_d delta_des')");
  e.derivative_on_desired_rate = false;
  r.push_back(e);
  e = make("no_steering_mass", "m_F = 0 in eqs 4-5");
  e.overrides = {{"vehicle.steering_mass", 0.0}};
  r.push_back(e);
  e = make("sign_in_f3_and_decoupled_inertia", "f3 = M_S - M_F and sigma3' = f3 / J_F");
  e.aligning_moment_in_f3 = -1.0;
  e.steering_inertia_coupled = false;
  r.push_back(e);
  e = make("no_leading_point_no_aligning_moment_in_f3", "contact-centre slip and f3 = M_S");
  e.front_leading_point = false;
  e.aligning_moment_in_f3 = 0.0;
  r.push_back(e);
  return r;
}

PlantLinearization applyReading(const PlantLinearization& plant, const SingleTrackModel& model,
                                const EquationReading& reading) {
  const SteeringParams& st = model.steering();
  if (st.stateSize() != 0 || st.hasFriction() || st.torque_limit > 0.0 || st.dead_band > 0.0) {
    throw ConfigError("equation readings assume Beregi's rigid, frictionless steering (f3 = M_F + M_S): reset "
                      "steering.* to its defaults");
  }
  if (!reading.front_leading_point && !std::holds_alternative<BrushTire>(model.frontTire().model())) {
    throw ConfigError("the leading-point reading needs tire.front.model = brush (eq 8 is the brush's slip angle)");
  }
  PlantLinearization out = plant;
  // Generalised forces of eq 3 (rows sigma1..3), per unit state and per unit M_S.
  Eigen::MatrixXd f = plant.mass * plant.a.middleRows(kSigma1, 3);
  Eigen::Vector3d f_u = plant.mass * plant.b.segment(kSigma1, 3);
  if (!reading.front_leading_point) {
    // At straight-line motion the brush forces depend on sigma3 only through a (sigma2 + sigma3)
    // of eq 8, so that column is the whole term; remove it from sigma3 and from sigma2.
    f.col(kSigma2) -= f.col(kSigma3);
    f.col(kSigma3).setZero();
  }
  f.row(2) *= reading.aligning_moment_in_f3;  // d f3 / d state = d M_F / d state (rigid steering)
  Eigen::Matrix3d mass = plant.mass;
  if (!reading.steering_inertia_coupled) {
    const double jf = mass(2, 2);
    mass(1, 1) -= jf;
    mass(1, 2) = mass(2, 1) = 0.0;
  }
  const Eigen::Matrix3d inverse = mass.inverse();
  out.a.middleRows(kSigma1, 3) = inverse * f;
  out.b.segment(kSigma1, 3) = inverse * f_u;
  out.mass = mass;
  return out;
}

EquationReading readingByName(const std::string& name) {
  std::string known;
  for (const auto& r : candidateReadings()) {
    if (r.name == name) return r;
    known += (known.empty() ? "" : ", ") + r.name;
  }
  throw ConfigError("unknown equation reading '" + name + "'; known: " + known);
}

namespace {

struct ReadingSetup {
  SimConfig config;
  PlantLinearization plant;
  LinearizationOptions options;
};

ReadingSetup setUp(const SimConfig& config, const EquationReading& reading) {
  ReadingSetup s{config, {}, {}};
  for (const auto& [key, value] : reading.overrides) setConfigNumber(s.config, key, value);
  s.config.validate();
  const SingleTrackModel model = createVehicleModel(s.config);
  s.plant = applyReading(linearizePlant(model), model, reading);
  s.options.derivative_on_desired_rate = reading.derivative_on_desired_rate;
  return s;
}

}  // namespace

LinearDelaySystem linearizeUnderReading(const SimConfig& config, const EquationReading& reading) {
  const ReadingSetup s = setUp(config, reading);
  return assembleClosedLoop(s.config, s.plant, s.options).dde;
}

SystemFamily readingFamily(const SimConfig& config, const EquationReading& reading) {
  const ReadingSetup s = setUp(config, reading);
  return [c = s.config, plant = s.plant, options = s.options](double tau2) {
    SimConfig at = c;
    setConfigNumber(at, "tau2", tau2);
    return assembleClosedLoop(at, plant, options).dde;
  };
}

}  // namespace lane_keeping
