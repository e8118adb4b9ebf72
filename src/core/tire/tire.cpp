#include "lane_keeping/tire/tire.h"

#include <algorithm>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {

Tire::Tire(std::string name, Model model, double normal_load, double relaxation_length)
    : name_(std::move(name)),
      model_(std::move(model)),
      normal_load_(normal_load),
      relaxation_length_(relaxation_length),
      inv_relaxation_length_(relaxation_length > 0.0 ? 1.0 / relaxation_length : 0.0),
      model_states_(modelStateSize()) {}

namespace {
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace

int Tire::modelStateSize() const {
  return std::visit(Overloaded{[](const LugreDistributedTire& m) { return m.stateSize(); },
                               [](const auto& m) { return static_cast<int>(std::decay_t<decltype(m)>::kStateSize); }},
                    model_);
}

TireForces<double> Tire::steadyState(const ContactKinematics<double>& kinematics) const {
  return std::visit(Overloaded{[&](const LugreLumpedTire& m) { return m.steadyState(kinematics); },
                               [&](const LugreDistributedTire& m) { return m.steadyState(kinematics); },
                               [&](const auto& m) {
                                 return m.evaluate(kinematics, static_cast<const double*>(nullptr), static_cast<double*>(nullptr));
                               }},
                    model_);
}

void Tire::steadyStateVector(const ContactKinematics<double>& kinematics, double* state) const {
  std::visit(Overloaded{[&](const LugreLumpedTire& m) { m.steadyState(kinematics, state); },
                        [&](const LugreDistributedTire& m) {
                          std::vector<double> z;
                          m.steadyState(kinematics, &z);
                          std::copy(z.begin(), z.end(), state);
                        },
                        [&](const auto&) {}},
             model_);
  if (relaxation_length_ > 0.0) {
    const TireForces<double> forces = steadyState(kinematics);
    state[model_states_] = forces.lateral_force;
    state[model_states_ + 1] = forces.aligning_moment;
  }
}

double Tire::contactHalfLength() const {
  return std::visit(Overloaded{[](const BrushTire& m) { return m.halfLength(); },
                               [](const LugreLumpedTire& m) { return 0.5 * m.coefficients().contact_length; },
                               [](const LugreDistributedTire& m) { return 0.5 * m.coefficients().contact_length; },
                               [](const MagicFormulaTire&) { return 0.0; }},
                    model_);
}

namespace {
/// Deur eq 27a (uniform) / 32a (trapezoid): K_y = L sigma0y K_v / 2.
double lugreCorneringStiffness(const LugreCoefficients& c, const ContactPressure& p) {
  return 0.5 * c.contact_length * c.sigma0y * p.kv();
}
/// Deur eq 27b (uniform) / 32b (trapezoid).
double lugreAligningStiffness(const LugreCoefficients& c, const ContactPressure& p) {
  const double L = c.contact_length, rl = p.leftMargin(), rr = p.rightMargin();
  if (p.isUniform()) return L * L * c.sigma0y / 12.0;
  return L * L * c.sigma0y / 6.0 * (rr * rr * rr + rl * rl - rl * rl * rl) / (1.0 + rr - rl);
}
}  // namespace

double Tire::corneringStiffness() const {
  return std::visit(
      Overloaded{[](const BrushTire& m) { return m.corneringStiffness(); },
                 [](const LugreLumpedTire& m) { return lugreCorneringStiffness(m.coefficients(), m.pressure()); },
                 [](const LugreDistributedTire& m) { return lugreCorneringStiffness(m.coefficients(), m.pressure()); },
                 [](const MagicFormulaTire& m) { return m.corneringStiffness(); }},
      model_);
}

double Tire::aligningStiffness() const {
  return std::visit(
      Overloaded{[](const BrushTire& m) { return m.aligningStiffness(); },
                 [](const LugreLumpedTire& m) { return lugreAligningStiffness(m.coefficients(), m.pressure()); },
                 [](const LugreDistributedTire& m) { return lugreAligningStiffness(m.coefficients(), m.pressure()); },
                 [](const MagicFormulaTire& m) { return m.aligningStiffness(); }},
      model_);
}

Tire createTire(const TireParams& params, double normal_load) {
  const SlidingFriction friction(normal_load, params.mu, params.mu0, params.lugre.stribeck_velocity,
                                 params.lugre.stribeck_exponent);
  const LugreCoefficients coefficients{params.contactLength(), params.sigma0x(), params.sigma0y(), params.lugre.sigma1,
                                       params.lugre.sigma2};
  const ContactPressure pressure =
      params.lugre.pressure == "trapezoidal"
          ? ContactPressure::trapezoidal(params.lugre.pressure_left_margin, params.lugre.pressure_right_margin)
          : ContactPressure::uniform();
  if (params.model == "brush") {
    return Tire(params.model,
                BrushTire(normal_load, params.contact_half_length, params.lateral_stiffness, params.mu, params.mu0),
                normal_load, params.relaxation_length);
  }
  if (params.model == "lugre_lumped") {
    const double kappa_constant = params.lugre.kappa == "constant" ? params.lugre.kappa_constant : 0.0;
    return Tire(params.model, LugreLumpedTire(coefficients, friction, pressure, kappa_constant, params.lugre.lambda2),
                normal_load, params.relaxation_length);
  }
  if (params.model == "lugre_distributed") {
    return Tire(params.model,
                LugreDistributedTire(coefficients, friction, pressure, params.lugre.bristles, params.lugre.turn_slip),
                normal_load, params.relaxation_length);
  }
  if (params.model == "magic_formula") {
    return Tire(params.model, MagicFormulaTire(params.magic_formula, normal_load, params.mu), normal_load,
                params.relaxation_length);
  }
  throw ConfigError("tire model '" + params.model + "' is unknown; allowed: brush, lugre_lumped, "
                    "lugre_distributed, magic_formula");
}

}  // namespace lane_keeping
