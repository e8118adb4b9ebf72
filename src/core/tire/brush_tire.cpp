#include "lane_keeping/tire/brush_tire.h"

namespace lane_keeping {

BrushTire::BrushTire(double normal_load, double half_length, double stiffness, double mu, double mu0)
    : normal_load_(normal_load), a_(half_length), mu_(mu) {
  const double a = half_length, k = stiffness, fz = normal_load;
  const double a2 = a * a, a3 = a2 * a, a4 = a2 * a2, a5 = a4 * a, a6 = a3 * a3, a7 = a6 * a, a9 = a7 * a2;
  const double k2 = k * k, k3 = k2 * k, k4 = k2 * k2;
  phi1_ = 2.0 * a2 * k;                                                                           // A.1
  phi2_ = -8.0 * a4 * k2 / (3.0 * fz * mu0) + 4.0 * a4 * k2 * mu / (3.0 * fz * mu0 * mu0);       // A.2
  phi3_ = 8.0 * a6 * k3 / (9.0 * fz * fz * mu0 * mu0) - 16.0 * a6 * k3 * mu / (27.0 * fz * fz * mu0 * mu0 * mu0);  // A.3
  mu1_ = -2.0 / 3.0 * a3 * k;                                                                      // A.4
  mu2_ = 8.0 * a5 * k2 / (3.0 * fz * mu0) - 4.0 * a5 * k2 * mu / (3.0 * fz * mu0 * mu0);          // A.5
  mu3_ = -8.0 * a7 * k3 / (3.0 * fz * fz * mu0 * mu0) + 16.0 * a7 * k3 * mu / (9.0 * fz * fz * mu0 * mu0 * mu0);  // A.6
  mu4_ = 64.0 * a9 * k4 / (81.0 * fz * fz * fz * mu0 * mu0 * mu0) -
         16.0 * a9 * k4 * mu / (27.0 * fz * fz * fz * mu0 * mu0 * mu0 * mu0);                     // A.7
  // The cubic reaches mu F_z with the patch fully sliding at tan(alpha) = 3 mu0 F_z / (2 a^2 k)
  // (Pacejka's brush model with separate adhesion/sliding friction, which App. A expands).
  tan_crit_ = 3.0 * mu0 * fz / phi1_;
}

}  // namespace lane_keeping
