#include "lane_keeping/gap/evaluation/sensor_character.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace lane_keeping {
namespace {

constexpr std::size_t kMinimumSamples = 50;

/// The rows each reading is held for: the largest h (2 to 100: a 10 Hz message in a 1 kHz log) such that at least 95 % of the changes of
/// value (of at least 20) fall on one residue of the row index modulo h; else 1. A held message changes
/// only where a new one arrives, every h rows; a quantised signal's long runs of one value (a coarse
/// step over a slow signal) end anywhere. (The most common run length was used before: on a gyro held
/// two rows whose 0.00426 rad/s step is twice its noise, the rounding's own runs of 4, 6, ... rows made
/// the hold unfound on half of the no-effect logs, and those logs' noise was put at a third of its level.)
int holdOf(const std::vector<double>& v) {
  std::vector<std::size_t> changes;
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (v[i] != v[i - 1]) changes.push_back(i);
  }
  if (changes.size() < 20) return 1;
  for (std::size_t h = 100; h >= 2; --h) {
    std::vector<std::size_t> count(h, 0);
    for (std::size_t i : changes) ++count[i % h];
    if (*std::max_element(count.begin(), count.end()) >= 0.95 * static_cast<double>(changes.size())) {
      return static_cast<int>(h);
    }
  }
  return 1;
}

/// AR(1) correlation from the lag-one autocorrelation r of second differences (inverting
/// r = -(4 - 3 rho + rho^2) / (2 (3 - rho)), monotone on rho in [-1, 1], r in [-1, -1/2]).
double correlationFromSecondDifferences(double r) {
  r = std::clamp(r, -1.0, -0.5);
  const double b = 3.0 + 2.0 * r, c = 4.0 + 6.0 * r;
  return 0.5 * (b - std::sqrt(std::max(0.0, b * b - 4.0 * c)));
}

/// The second differences d of `a - b` (b empty: of a), their variance and lag-one correlation, both
/// robust: the variance a trimmed mean square (the smallest 90 % of d^2, over E[z^2 | |z| < 1.645] =
/// 0.6232 of a normal z), the correlation by Gnanadesikan and Kettenring (1972) from the trimmed
/// variances of d[i] + d[i+1] and d[i] - d[i+1]. A signal that departs from the nominal's in a few
/// transients (an initial correction rung differently) then does not count as noise; a steady one still
/// does, where the smaller of two estimates decides. (A median absolute deviation was tried first: on a
/// quantised channel whose second differences take a few multiples of the step it is coarse, and it put
/// a bus gyro's AR 0.7 at 0 and its level at half.)
struct SecondDifferences {
  double var = 0.0;          ///< per-sample variance of d
  double correlation = 0.0;  ///< lag-one correlation of d
  std::size_t n = 0;
};

double trimmedVariance(std::vector<double> v) {
  if (v.empty()) return 0.0;
  for (double& x : v) x *= x;
  const std::size_t keep = std::max<std::size_t>(1, v.size() * 9 / 10);
  std::nth_element(v.begin(), v.begin() + static_cast<long>(keep - 1), v.end());
  double sum = 0.0;
  for (std::size_t i = 0; i < keep; ++i) sum += v[i];
  return sum / static_cast<double>(keep) / 0.6232;
}

SecondDifferences secondDifferences(const std::vector<double>& a, const std::vector<double>& b) {
  auto at = [&](std::size_t i) { return b.empty() ? a[i] : a[i] - b[i]; };
  std::vector<double> d;
  for (std::size_t i = 1; i + 1 < a.size() && (b.empty() || i + 1 < b.size()); ++i) {
    d.push_back(at(i - 1) - 2.0 * at(i) + at(i + 1));
  }
  SecondDifferences s;
  s.n = d.size();
  if (d.size() < 3) return s;
  std::vector<double> sum, difference;
  for (std::size_t i = 0; i + 1 < d.size(); ++i) {
    sum.push_back(d[i] + d[i + 1]);
    difference.push_back(d[i] - d[i + 1]);
  }
  const double plus = trimmedVariance(sum), minus = trimmedVariance(difference);
  s.var = trimmedVariance(d);
  s.correlation = plus + minus > 0.0 ? (plus - minus) / (plus + minus) : 0.0;
  return s;
}

/// The level of a quantised channel's noise of correlation `ar` by simulated moments: the sigma whose
/// noise, added to `signal` and rounded onto the grid, gives second differences (of the rounded values
/// less `subtract`) of the observed trimmed variance. The closed form (the rounding as white noise of
/// q^2 / 12 per reading, independent of the noise) holds for a step well below the noise; a RAV4-like
/// gyro's 0.00426 rad/s step over 0.002 rad/s of noise is not such a case: there it put the level too low
/// and 9 of 20 no-effect bus logs were "detected". The noise is drawn once (common random numbers), so
/// the bisection is on a smooth function. (Matching the correlation too, for the colour, was tried: where
/// the rounding dominates, the second differences' correlation moves by 0.01 from AR 0 to 0.9, and the
/// choice was noise.)
double quantisedNoiseLevel(const ChannelCharacter& c, double observed_var, const std::vector<double>& signal,
                           const std::vector<double>& subtract) {
  constexpr std::size_t kMaxReadings = 20000;
  const std::size_t n = std::min(signal.size(), kMaxReadings);
  std::mt19937 rng(12345);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<double> normal(n), x(n);
  for (double& u : normal) u = unit(rng);
  auto simulatedVar = [&](double sigma) {
    const double innovation = sigma * std::sqrt(1.0 - c.ar * c.ar);
    double noise = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      noise = i == 0 ? sigma * normal[i] : c.ar * noise + innovation * normal[i];
      const double v = signal[i] + noise;
      x[i] = c.offset + c.quantum * std::round((v - c.offset) / c.quantum) - (subtract.empty() ? 0.0 : subtract[i]);
    }
    return secondDifferences(x, {}).var;
  };
  if (simulatedVar(0.0) >= observed_var) return 0.0;  // the rounding of the signal alone is as large
  double lo = 0.0, hi = std::sqrt(observed_var / (6.0 - 8.0 * c.ar + 2.0 * c.ar * c.ar)) * 2.0 + c.quantum;
  for (int k = 0; k < 24; ++k) {
    const double mid = 0.5 * (lo + hi);
    (simulatedVar(mid) < observed_var ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

ChannelCharacter estimateCharacter(const std::vector<double>& values, double white_sigma,
                                   const std::vector<double>& nominal, bool colour_where_continuous) {
  ChannelCharacter c;
  c.sigma = white_sigma;
  if (values.size() < kMinimumSamples) return c;
  c.hold = holdOf(values);
  std::vector<double> readings;
  for (std::size_t i = 0; i < values.size(); i += static_cast<std::size_t>(c.hold)) readings.push_back(values[i]);
  // The step: the smallest non-zero difference (its lowest few per cent, against outliers of rounding),
  // kept if the differences are multiples of it.
  std::vector<double> steps;
  double largest = 0.0;
  for (std::size_t i = 1; i < readings.size(); ++i) {
    const double d = std::fabs(readings[i] - readings[i - 1]);
    if (d > 0.0) steps.push_back(d);
    largest = std::max(largest, std::fabs(readings[i]));
  }
  if (steps.size() >= 20) {
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 50), sorted.end());
    const double q = sorted[sorted.size() / 50];
    std::size_t on_grid = 0;
    for (double d : steps) {
      const double k = d / q;
      if (std::fabs(k - std::round(k)) <= 0.05) ++on_grid;
    }
    // A step at the print precision of a CSV (1e-9 of the values) is no quantisation worth modelling.
    if (q > 1e-6 * largest && on_grid >= 0.9 * steps.size()) {
      c.quantum = q;
      double s = 0.0, co = 0.0;  // circular mean of the residues: the grid's offset
      for (double v : readings) {
        const double phase = 2.0 * M_PI * (v / q - std::floor(v / q));
        s += std::sin(phase);
        co += std::cos(phase);
      }
      c.offset = q * std::atan2(s, co) / (2.0 * M_PI);
    }
  }
  // Level and colour from the second differences of the readings, or of the readings less the nominal's
  // where that is the smaller: a fast signal otherwise reads as noise (see the header).
  SecondDifferences d2 = secondDifferences(readings, {});
  std::vector<double> model;
  bool less_model = false;
  if (nominal.size() == values.size()) {
    for (std::size_t i = 0; i < nominal.size(); i += static_cast<std::size_t>(c.hold)) model.push_back(nominal[i]);
    const SecondDifferences residual = secondDifferences(readings, model);
    if (residual.var > 0.0 && residual.var < d2.var) {
      d2 = residual;
      less_model = true;
    }
  }
  if (d2.n < kMinimumSamples || !(d2.var > 0.0)) return c;
  // Colour on a bus's channels (quantised or held), and on a continuous one where the caller says its fast
  // content is the noise's. On a continuous channel of the steering loop the second differences cannot
  // tell coloured noise from the loop's own fast content (its ringing at 120 Hz in a 1 kHz log reads as a
  // lag-one correlation of 0.7; less the nominal, at 100 Hz a model's miss between readings does: tried,
  // docs/gap.md); the yaw rate and lateral acceleration are the car body's, which passes nothing of that
  // (its modes lie below a few hertz), so what correlates their noise is the sensor's filter.
  // The rounding onto the grid adds white noise of q^2 / 12 per reading: 6 q^2 / 12 to the variance of
  // the second differences and -4 q^2 / 12 to their lag-one covariance. Taken out before the colour is
  // read (left in, it pulls the correlation towards white noise's -2/3: a bus gyro's AR 0.7 read as 0.3).
  const double rounding = c.quantum * c.quantum / 12.0;
  const double var = d2.var - 6.0 * rounding, cov = d2.correlation * d2.var + 4.0 * rounding;
  const double rho = var > 0.0 ? std::clamp(correlationFromSecondDifferences(cov / var), -0.9, 0.9) : 0.0;
  if ((c.quantum > 0.0 || c.hold > 1 || colour_where_continuous) && std::fabs(rho) >= 0.3) c.ar = rho;
  if (c.quantum > 0.0) {
    // The level by simulation (above), on the signal under the noise: the nominal's, or where the
    // readings alone were used, their moving average over five (off the grid, as a signal is).
    std::vector<double> signal = less_model ? model : std::vector<double>(readings.size());
    if (!less_model) {
      for (std::size_t i = 0; i < readings.size(); ++i) {
        const std::size_t a = i >= 2 ? i - 2 : 0, b = std::min(readings.size(), i + 3);
        double sum = 0.0;
        for (std::size_t j = a; j < b; ++j) sum += readings[j];
        signal[i] = sum / static_cast<double>(b - a);
      }
    }
    c.sigma = quantisedNoiseLevel(c, d2.var, signal, less_model ? model : std::vector<double>{});
  } else if (c.ar != 0.0 || c.hold > 1) {
    c.sigma = std::sqrt(d2.var / (6.0 - 8.0 * c.ar + 2.0 * c.ar * c.ar));
  }
  return c;
}

void addCharacterisedNoise(std::vector<double>& truth, const ChannelCharacter& c, std::mt19937& rng,
                           std::normal_distribution<double>& unit) {
  if (c.plain()) {
    for (double& x : truth) x += c.sigma * unit(rng);
    return;
  }
  // One unit normal per row, as the white path draws them, so that the channels after this one draw
  // the same numbers whatever this one's character.
  // The colour is between readings: the noise moves once per hold.
  const double innovation = c.sigma * std::sqrt(std::max(0.0, 1.0 - c.ar * c.ar));
  double noise = 0.0, held = 0.0;
  const int hold = std::max(1, c.hold);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const double u = unit(rng);  // (drawn on every row: see above)
    if (i % static_cast<std::size_t>(hold) == 0) {
      noise = i == 0 ? c.sigma * u : c.ar * noise + innovation * u;
      held = truth[i] + noise;
    }
    double value = held;
    if (c.quantum > 0.0) value = c.offset + c.quantum * std::round((value - c.offset) / c.quantum);
    truth[i] = value;
  }
}

}  // namespace lane_keeping
