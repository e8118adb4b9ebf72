#include "lane_keeping/analysis/chebyshev.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lane_keeping {

ChebyshevGrid chebyshevGrid(int degree) {
  if (degree < 1) throw std::invalid_argument("chebyshevGrid: degree " + std::to_string(degree) + " must be >= 1");
  const int n = degree;
  ChebyshevGrid grid;
  grid.nodes.resize(n + 1);
  // sin form of cos(pi j / n): exact symmetry about 0 (Trefethen's chebfun convention).
  for (int j = 0; j <= n; ++j) grid.nodes[j] = std::sin(M_PI * (n - 2.0 * j) / (2.0 * n));
  Eigen::VectorXd c(n + 1);
  for (int j = 0; j <= n; ++j) c[j] = ((j == 0 || j == n) ? 2.0 : 1.0) * ((j % 2 == 0) ? 1.0 : -1.0);
  Eigen::MatrixXd& d = grid.differentiation;
  d.setZero(n + 1, n + 1);
  for (int i = 0; i <= n; ++i) {
    double row_sum = 0.0;
    for (int j = 0; j <= n; ++j) {
      if (i == j) continue;
      d(i, j) = (c[i] / c[j]) / (grid.nodes[i] - grid.nodes[j]);
      row_sum += d(i, j);
    }
    d(i, i) = -row_sum;
  }
  return grid;
}

}  // namespace lane_keeping
