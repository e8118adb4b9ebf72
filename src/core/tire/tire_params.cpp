#include "lane_keeping/tire/tire_params.h"

#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {

const std::vector<std::string>& TireParams::modelNames() {
  static const std::vector<std::string> names{"brush", "lugre_lumped", "lugre_distributed", "magic_formula"};
  return names;
}

void TireParams::visit(ParamVisitor& v, const std::string& prefix) {
  v.choice(prefix + "model", model, modelNames(),
           "tire model of this axle: brush (Beregi eqs 6-7), lugre_lumped (Deur eqs 33-57), "
           "lugre_distributed (Deur eq 22), magic_formula (Velenis Table 1, steady state)");
  v.number(prefix + "contact_half_length", contact_half_length, "m", Range::positive(),
           "a, half-length of the contact patch (Beregi Table 1)");
  v.number(prefix + "lateral_stiffness", lateral_stiffness, "N/m^2", Range::positive(),
           "k, lateral tread stiffness per unit length (Beregi Table 1)");
  v.number(prefix + "mu", mu, "", Range::positive(), "sliding friction coefficient (brush mu, LuGre mu_k)");
  v.number(prefix + "mu0", mu0, "", Range::positive(), "adhesion friction coefficient (brush mu0, LuGre mu_s)");
  v.number(prefix + "relaxation_length", relaxation_length, "m", Range::nonNegative(),
           "first-order relaxation of force and moment, time constant relaxation_length / wheel speed; 0 = none");

  const std::string lp = prefix + "lugre.";
  v.optionalNumber(lp + "contact_length", lugre.contact_length, "m", Range::positive(), "L; auto = 2 a");
  v.optionalNumber(lp + "sigma0y", lugre.sigma0y, "N/m", Range::positive(),
                   "lateral bristle stiffness; auto = k L, so that L sigma0y / 2 = 2 a^2 k");
  v.optionalNumber(lp + "sigma0x", lugre.sigma0x, "N/m", Range::positive(),
                   "longitudinal bristle stiffness; auto = sigma0y (no effect in free rolling)");
  v.number(lp + "sigma1", lugre.sigma1, "N s/m", Range::nonNegative(), "bristle damping (Deur eq 18)");
  v.number(lp + "sigma2", lugre.sigma2, "N s/m", Range::nonNegative(), "viscous friction (Deur eq 18)");
  v.number(lp + "stribeck_velocity", lugre.stribeck_velocity, "m/s", Range::positive(), "v_s (Deur eq 6)");
  v.number(lp + "stribeck_exponent", lugre.stribeck_exponent, "", Range::positive(), "Stribeck exponent (Deur eq 6)");
  v.choice(lp + "pressure", lugre.pressure, {"uniform", "trapezoidal"},
           "normal pressure distribution along the patch (Deur Fig 7)");
  v.number(lp + "pressure_left_margin", lugre.pressure_left_margin, "", Range::open(0.0, 1.0),
           "r_l of the trapezoid (Deur eq 29); trapezoidal only");
  v.number(lp + "pressure_right_margin", lugre.pressure_right_margin, "", Range::open(0.0, 1.0),
           "r_r of the trapezoid (Deur eq 29); trapezoidal only");
  v.choice(lp + "kappa", lugre.kappa, {"variable", "constant"},
           "variable: steady state equal to the distributed model (Deur eq 40/43); constant: kappa_constant");
  v.number(lp + "kappa_constant", lugre.kappa_constant, "", Range::positive(), "kappa when kappa = constant (Deur §5.1)");
  v.number(lp + "lambda2", lugre.lambda2, "", Range::closed(-5.0, 5.0),
           "fixed lambda2 of Deur eq 50 (0: basic model, lambda1 = lambda)");
  v.integer(lp + "bristles", lugre.bristles, Range::closed(3, 100000),
            "N, bristles per direction of lugre_distributed (Deur eq 22)");
  v.flag(lp + "turn_slip", lugre.turn_slip,
         "lugre_distributed: slip speed varies along the patch with the wheel yaw rate (Velenis eq 64b)");

  const std::string mp = prefix + "magic_formula.";
  v.number(mp + "fy_b", magic_formula.fy_b, "1/deg", Range::positive(), "B of F_y (Velenis Table 1)");
  v.number(mp + "fy_c", magic_formula.fy_c, "", Range::positive(), "C of F_y");
  v.number(mp + "fy_d", magic_formula.fy_d, "N", Range::positive(), "D of F_y at reference_load");
  v.number(mp + "fy_e", magic_formula.fy_e, "", Range::atLeast(-100.0), "E of F_y");
  v.number(mp + "mz_b", magic_formula.mz_b, "1/deg", Range::positive(), "B of M_z");
  v.number(mp + "mz_c", magic_formula.mz_c, "", Range::positive(), "C of M_z");
  v.number(mp + "mz_d", magic_formula.mz_d, "N m", Range::any(), "D of M_z at reference_load");
  v.number(mp + "mz_e", magic_formula.mz_e, "", Range::atLeast(-100.0), "E of M_z");
  v.number(mp + "reference_load", magic_formula.reference_load, "N", Range::positive(),
           "F_z0 of Table 1; D scales with F_z / F_z0");
}

void TireParams::validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const {
  if (lugre.pressure == "trapezoidal" && lugre.pressure_left_margin >= lugre.pressure_right_margin) {
    problems.push_back({prefix + "lugre.pressure_left_margin", "",
                        "= " + formatNumber(lugre.pressure_left_margin) + ", must be smaller than " + prefix +
                            "lugre.pressure_right_margin (" + formatNumber(lugre.pressure_right_margin) + ")"});
  }
  if (mu > mu0 * 1.0000001 && model == "brush") {
    problems.push_back({prefix + "mu", "",
                        "= " + formatNumber(mu) + " exceeds " + prefix + "mu0 = " + formatNumber(mu0) +
                            ": the brush model (Beregi App. A) assumes sliding friction <= adhesion friction"});
  }
}

}  // namespace lane_keeping
