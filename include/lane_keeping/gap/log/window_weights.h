#pragma once
/// The weights of smoothedDerivative's local quadratic fits (a Savitzky-Golay filter), remembered
/// across calls on a uniform time base.
///
/// On a uniform time base a window's weights depend only on its shape (samples before and after t_i),
/// the step h and the derivative's order, not on the values, the channel or the half-width. The
/// noise-only null smooths each channel of 19 noisy copies of one reference log, all on the reference's
/// time base, and solved the same shapes for each. On a 1 kHz log a window has tens to hundreds of
/// samples a side, and each edge has a shape per sample near it, each solved over the whole window: the
/// solving was 3 % of the instructions of a diagnosis that is mostly `where` (callgrind, `lk_gap
/// --effects sensing_delay` on the independent family's none-20-bend-p750-1000Hz: 15.56 -> 15.14 G).
#include <cstddef>
#include <list>
#include <map>
#include <utility>
#include <vector>

namespace lane_keeping {

/// The least-squares fit of v = c0 + c1 s + c2 s^2 over samples at offsets s_k from t_i (scaled by
/// `scale`), as weights on the samples: the requested coefficient (order 0, 1 or 2: the value, the
/// first or the second derivative at t_i) is sum_k w_k v_k.
std::vector<double> quadraticWeights(const std::vector<double>& s, double scale, int order);

/// Window weights on uniform time bases, per (step, order), the least recently used time bases dropped
/// once the weights held exceed a capacity. Not thread-safe: one per thread (windowWeightsOfThisThread).
class UniformWindowWeights {
 public:
  explicit UniformWindowWeights(std::size_t capacity_doubles) : capacity_(capacity_doubles) {}

  /// Makes (h, order) the time base weights() answers for, dropping the least recently used others
  /// beyond the capacity (never this one).
  void select(double h, int order);

  /// The weights of the window with `before` samples before t_i and `after` after, on the selected time
  /// base: quadraticWeights over s_k = (k - before) h / scale, scale = (before + after) h, to the bit.
  /// The reference stays valid until the next select().
  const std::vector<double>& weights(std::size_t before, std::size_t after);

  std::size_t timeBases() const { return bases_.size(); }
  std::size_t doublesHeld() const;

 private:
  struct Base {
    double h;
    int order;
    std::map<std::pair<std::size_t, std::size_t>, std::vector<double>> shapes;  // (nodes stay in place)
    std::size_t doubles = 0;
  };
  std::size_t capacity_;
  std::list<Base> bases_;  ///< the selected one first
};

/// This thread's weights (4 M doubles, 32 MB, at most beyond the time base in use).
UniformWindowWeights& windowWeightsOfThisThread();

}  // namespace lane_keeping
