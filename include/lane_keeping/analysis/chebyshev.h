#pragma once
/// Chebyshev points and the spectral differentiation matrix (Trefethen, "Spectral Methods in
/// MATLAB", SIAM 2000, Program 11 `cheb.m`): x_j = cos(pi j / N), j = 0..N, so x_0 = 1 and x_N = -1,
/// and (D u)_i = p'(x_i) for the degree-N interpolant p of u. Diagonal by the negative-sum trick
/// (rows of D sum to zero exactly), which Trefethen recommends for accuracy.
#include <Eigen/Core>

namespace lane_keeping {

struct ChebyshevGrid {
  Eigen::VectorXd nodes;          ///< x_j, descending from 1 to -1
  Eigen::MatrixXd differentiation;  ///< D, (N+1) x (N+1)
};

/// Throws std::invalid_argument for degree < 1.
ChebyshevGrid chebyshevGrid(int degree);

}  // namespace lane_keeping
