#include "lane_keeping/analysis/dde_spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "lane_keeping/analysis/chebyshev.h"

namespace lane_keeping {

double CharacteristicRoot::frequencyHz() const { return std::fabs(value.imag()) / (2.0 * M_PI); }

double Spectrum::abscissa() const {
  double a = -std::numeric_limits<double>::infinity();
  for (const auto& r : roots) a = std::max(a, r.value.real());
  return a;
}

int Spectrum::unstableCount(double tolerance) const {
  int count = 0;
  for (const auto& r : roots) {
    if (r.value.real() > tolerance) count += r.value.imag() > 0.0 ? 2 : 1;
  }
  return count;
}

Eigen::MatrixXd collocationMatrix(const LinearDelaySystem& system, int degree, double rank_tolerance,
                                  std::vector<int>* ranks) {
  const int n = system.size();
  const ChebyshevGrid grid = chebyshevGrid(degree);
  const int m = degree;
  // Low-rank factors A_j = B_j C_j from the SVD.
  struct Block {
    double tau;
    Eigen::MatrixXd b, c;
  };
  std::vector<Block> blocks;
  int dimension = n;
  if (ranks) ranks->clear();
  for (const auto& term : system.delayed) {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(term.matrix, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& s = svd.singularValues();
    int r = 0;
    while (r < s.size() && s[r] > rank_tolerance * s[0] && s[r] > 0.0) ++r;
    if (ranks) ranks->push_back(r);
    if (r == 0) continue;
    blocks.push_back({term.delay, svd.matrixU().leftCols(r) * s.head(r).asDiagonal(), svd.matrixV().leftCols(r).transpose()});
    dimension += m * r;
  }
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(dimension, dimension);
  g.topLeftCorner(n, n) = system.a0;
  int offset = n;
  for (const auto& block : blocks) {
    const int r = static_cast<int>(block.c.rows());
    // theta = tau (x - 1) / 2: node 0 is theta = 0 (w = C x), node M is theta = -tau.
    const double scale = 2.0 / block.tau;
    // Unknowns: w at nodes 1..M, node k at columns offset + (k - 1) r.
    g.block(0, offset + (m - 1) * r, n, r) += block.b;
    for (int k = 1; k <= m; ++k) {
      const int row = offset + (k - 1) * r;
      g.block(row, 0, r, n) += (scale * grid.differentiation(k, 0)) * block.c;
      for (int l = 1; l <= m; ++l) {
        g.block(row, offset + (l - 1) * r, r, r).diagonal().array() += scale * grid.differentiation(k, l);
      }
    }
    offset += m * r;
  }
  return g;
}

bool refineRoot(const LinearDelaySystem& system, Complex* lambda, int max_iterations, double tolerance,
                int* iterations) {
  Complex x = *lambda;
  for (int it = 1; it <= max_iterations; ++it) {
    const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(system.characteristicMatrix(x));
    const Complex trace = lu.solve(system.characteristicMatrixDerivative(x)).trace();
    if (!std::isfinite(trace.real()) || !std::isfinite(trace.imag()) || std::abs(trace) == 0.0) {
      // Delta(x) numerically singular: x is a root to working precision.
      if (iterations) *iterations = it;
      *lambda = x;
      return true;
    }
    const Complex step = 1.0 / trace;
    x -= step;
    if (!std::isfinite(x.real()) || !std::isfinite(x.imag())) return false;
    if (std::abs(step) <= tolerance * std::max(1.0, std::abs(x))) {
      if (iterations) *iterations = it;
      *lambda = x;
      return true;
    }
  }
  return false;
}

double relativeResidual(const LinearDelaySystem& system, Complex lambda) {
  Eigen::JacobiSVD<Eigen::MatrixXcd> svd(system.characteristicMatrix(lambda));
  return svd.singularValues().minCoeff() / (std::abs(lambda) + system.coefficientNorm());
}

Spectrum computeSpectrum(const LinearDelaySystem& system, const SpectrumOptions& options) {
  if (options.degree < 2) {
    throw std::invalid_argument("computeSpectrum: degree " + std::to_string(options.degree) + " must be >= 2");
  }
  if (system.size() == 0) throw std::invalid_argument("computeSpectrum: empty system");
  if (options.seeds < 1) throw std::invalid_argument("computeSpectrum: seeds must be >= 1");
  Spectrum spectrum;
  const Eigen::MatrixXd g = collocationMatrix(system, options.degree, options.rank_tolerance, &spectrum.ranks);
  spectrum.dimension = static_cast<int>(g.rows());
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(g, false);
  std::vector<Complex> eigenvalues;
  for (int i = 0; i < solver.eigenvalues().size(); ++i) {
    const Complex e = solver.eigenvalues()[i];
    if (e.imag() >= 0.0) eigenvalues.push_back(e);
  }
  std::sort(eigenvalues.begin(), eigenvalues.end(), [](Complex l, Complex r) { return l.real() > r.real(); });
  if (static_cast<int>(eigenvalues.size()) > options.seeds) eigenvalues.resize(options.seeds);

  auto same = [](Complex a, Complex b) { return std::abs(a - b) <= 1e-7 * std::max(1.0, std::abs(a)); };
  for (const Complex seed : eigenvalues) {
    CharacteristicRoot root;
    root.discretised = seed;
    root.value = seed;
    root.refined = refineRoot(system, &root.value, options.newton_iterations, options.newton_tolerance,
                              &root.newton_iterations);
    if (!root.refined) root.value = seed;
    if (root.value.imag() < 0.0) root.value = std::conj(root.value);
    if (std::fabs(root.value.imag()) <= 1e-9 * std::max(1.0, std::abs(root.value))) root.value.imag(0.0);
    bool duplicate = false;
    for (const auto& existing : spectrum.roots) duplicate = duplicate || same(existing.value, root.value);
    if (!duplicate) spectrum.roots.push_back(root);
  }
  std::sort(spectrum.roots.begin(), spectrum.roots.end(),
            [](const CharacteristicRoot& l, const CharacteristicRoot& r) { return l.value.real() > r.value.real(); });
  return spectrum;
}

}  // namespace lane_keeping
