#pragma once
/// Parameters of one axle's tire (single-track model: one tire per axle carrying the axle load).
/// The LuGre defaults are derived from the brush parameters so that both models have the same
/// small-slip stiffnesses (DESIGN §3): L = 2a, sigma0y = k L  =>  K_y = L sigma0y / 2 = 2 a^2 k
/// (Deur eq 27a vs Beregi eq 9) and, for uniform pressure, K_z = L^2 sigma0y / 12 = (2/3) a^3 k
/// (Deur eq 27b vs Beregi eq 10).
#include <optional>
#include <string>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_visitor.h"

namespace lane_keeping {

struct LugreParams {
  std::optional<double> contact_length;  ///< L [m]; auto: 2 a
  std::optional<double> sigma0y;         ///< lateral bristle stiffness [N/m]; auto: k L
  std::optional<double> sigma0x;         ///< longitudinal bristle stiffness [N/m]; auto: sigma0y
  double sigma1 = 0.0;                   ///< bristle damping [N s/m] (Deur eq 18)
  double sigma2 = 0.0;                   ///< viscous friction [N s/m] (Deur eq 18)
  double stribeck_velocity = 3.5;        ///< v_s [m/s] (Deur eq 6)
  double stribeck_exponent = 0.6;        ///< delta in exp(-|v_r/v_s|^delta) (Deur eq 6)
  std::string pressure = "uniform";      ///< uniform | trapezoidal (Deur Fig 7)
  double pressure_left_margin = 0.134;   ///< r_l = zeta_l / L (Deur eq 29, App. A.2)
  double pressure_right_margin = 0.707;  ///< r_r = zeta_r / L (Deur eq 29, App. A.2)
  std::string kappa = "variable";        ///< variable (Deur eq 40/43) | constant
  double kappa_constant = 1.2;           ///< kappa when kappa = constant (Deur §5.1)
  double lambda2 = 0.0;                  ///< fixed lambda2 of Deur eq 50; lambda1 from eq 56
  int bristles = 100;                    ///< N of the distributed model (Deur eq 22)
  bool turn_slip = false;                ///< distributed only: slip speed varies along the patch with
                                         ///< the wheel yaw rate (Velenis eq 64b)
};

struct MagicFormulaParams {
  // Velenis Table 1 (from Bakker, Nyborg & Pacejka 1987): slip angle in degrees, forces in N.
  double fy_b = 0.244, fy_c = 1.5, fy_d = 1936.0, fy_e = -0.132;
  double mz_b = 0.247, mz_c = 2.56, mz_d = -15.53, mz_e = -3.92;
  double reference_load = 2000.0;  ///< F_z0 [N] at which Table 1 holds (Velenis §5.3); D scales with F_z/F_z0
};

struct TireParams {
  std::string model = "lugre_lumped";  ///< brush | lugre_lumped | lugre_distributed | magic_formula
  double contact_half_length = 0.1;    ///< a [m] (Beregi Table 1)
  double lateral_stiffness = 2.0e6;    ///< k [N/m^2], distributed lateral stiffness (Beregi Table 1)
  double mu = 1.0;                     ///< sliding friction coefficient (brush mu, LuGre mu_k)
  double mu0 = 1.0;                    ///< adhesion friction coefficient (brush mu0, LuGre mu_s)
  double relaxation_length = 0.0;      ///< [m]; > 0 adds a first-order lag of force and moment (time
                                       ///< constant relaxation_length / wheel speed); 0 = none
  LugreParams lugre;
  MagicFormulaParams magic_formula;

  static const std::vector<std::string>& modelNames();

  double contactLength() const { return lugre.contact_length.value_or(2.0 * contact_half_length); }
  double sigma0y() const { return lugre.sigma0y.value_or(lateral_stiffness * contactLength()); }
  double sigma0x() const { return lugre.sigma0x.value_or(sigma0y()); }

  void visit(ParamVisitor& v, const std::string& prefix);
  void validate(const std::string& prefix, std::vector<ConfigProblem>& problems) const;
};

}  // namespace lane_keeping
