#include "lane_keeping/analysis/stability_budget.h"

#include <cmath>

#include <Eigen/SVD>

namespace lane_keeping {

SpectrumCost spectrumCost(const LinearDelaySystem& system, int degree, double rank_tolerance) {
  // The order as collocationMatrix (dde_spectrum.cpp) builds it: the states, then per delay term its rank
  // times the degree.
  double order = system.size();
  for (const auto& term : system.delayed) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(term.matrix);
    const Eigen::VectorXd& s = svd.singularValues();
    int r = 0;
    while (r < s.size() && s[r] > rank_tolerance * s[0] && s[r] > 0.0) ++r;
    order += static_cast<double>(degree) * r;
  }
  SpectrumCost cost;
  cost.order = order > 2e9 ? 2000000000 : static_cast<int>(order);
  cost.bytes = kCopies * 8.0 * order * order;
  cost.seconds = kSecondsPerOrderCubed * order * order * order;
  return cost;
}

}  // namespace lane_keeping
