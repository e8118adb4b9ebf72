#include "lane_keeping/gap/log/window_weights.h"

#include <Eigen/Dense>

namespace lane_keeping {

std::vector<double> quadraticWeights(const std::vector<double>& s, double scale, int order) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  for (double sk : s) {
    const Eigen::Vector3d basis(1.0, sk, sk * sk);
    A += basis * basis.transpose();
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt = A.ldlt();
  Eigen::Vector3d pick = Eigen::Vector3d::Zero();
  pick[order] = order == 0 ? 1.0 : (order == 1 ? 1.0 / scale : 2.0 / (scale * scale));
  const Eigen::Vector3d row = ldlt.solve(pick);  // A is symmetric: e^T A^-1 basis = (A^-1 e)^T basis
  std::vector<double> w(s.size());
  for (std::size_t k = 0; k < s.size(); ++k) w[k] = row[0] + row[1] * s[k] + row[2] * s[k] * s[k];
  return w;
}

void UniformWindowWeights::select(double h, int order) {
  auto it = bases_.begin();
  while (it != bases_.end() && !(it->h == h && it->order == order)) ++it;
  if (it == bases_.end()) {
    bases_.push_front(Base{h, order, {}, 0});
  } else if (it != bases_.begin()) {
    bases_.splice(bases_.begin(), bases_, it);
  }
  // The least recently used go first; the selected one stays whatever it holds.
  std::size_t held = doublesHeld();
  while (held > capacity_ && bases_.size() > 1) {
    held -= bases_.back().doubles;
    bases_.pop_back();
  }
}

const std::vector<double>& UniformWindowWeights::weights(std::size_t before, std::size_t after) {
  Base& base = bases_.front();
  const auto key = std::make_pair(before, after);
  if (const auto it = base.shapes.find(key); it != base.shapes.end()) return it->second;
  // The expressions smoothedDerivative solved each window with: i - a = before, b - i = after, the
  // offsets (j - i) h / scale for j = a .. b (integers, exact in a double).
  const double scale = static_cast<double>(before + after) * base.h;
  std::vector<double> s;
  s.reserve(before + after + 1);
  for (std::size_t k = 0; k <= before + after; ++k) {
    s.push_back((static_cast<double>(k) - static_cast<double>(before)) * base.h / scale);
  }
  base.doubles += s.size();
  return base.shapes.emplace(key, quadraticWeights(s, scale, base.order)).first->second;
}

std::size_t UniformWindowWeights::doublesHeld() const {
  std::size_t held = 0;
  for (const Base& base : bases_) held += base.doubles;
  return held;
}

UniformWindowWeights& windowWeightsOfThisThread() {
  thread_local UniformWindowWeights weights(std::size_t{4} << 20);
  return weights;
}

}  // namespace lane_keeping
