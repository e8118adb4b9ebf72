#include "lane_keeping/gap/evaluation/sensor_character.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace lane_keeping {
namespace {

constexpr std::size_t kMinimumSamples = 50;

/// The most common length of the runs of equal consecutive values, if it is at least 2 and at least 60 %
/// of the runs (of at least 10) have it; else 1.
int holdOf(const std::vector<double>& v) {
  std::map<int, int> lengths;
  int runs = 0, length = 1;
  for (std::size_t i = 1; i <= v.size(); ++i) {
    if (i < v.size() && v[i] == v[i - 1]) {
      ++length;
      continue;
    }
    // The first and last runs may be cut by the log's ends: not counted.
    if (i - length > 0 && i < v.size()) {
      ++lengths[length];
      ++runs;
    }
    length = 1;
  }
  if (runs < 10) return 1;
  const auto mode = std::max_element(lengths.begin(), lengths.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  return mode->first >= 2 && mode->second >= 0.6 * runs ? mode->first : 1;
}

/// AR(1) correlation from the lag-one autocorrelation r of second differences (inverting
/// r = -(4 - 3 rho + rho^2) / (2 (3 - rho)), monotone on rho in [-1, 1], r in [-1, -1/2]).
double correlationFromSecondDifferences(double r) {
  r = std::clamp(r, -1.0, -0.5);
  const double b = 3.0 + 2.0 * r, c = 4.0 + 6.0 * r;
  return 0.5 * (b - std::sqrt(std::max(0.0, b * b - 4.0 * c)));
}

}  // namespace

ChannelCharacter estimateCharacter(const std::vector<double>& values, double white_sigma) {
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
  // Level and colour from the second differences of the readings.
  double var2 = 0.0, cov2 = 0.0;
  std::size_t n2 = 0;
  double previous = 0.0;
  for (std::size_t i = 1; i + 1 < readings.size(); ++i) {
    const double d = readings[i - 1] - 2.0 * readings[i] + readings[i + 1];
    var2 += d * d;
    if (i > 1) cov2 += d * previous;
    previous = d;
    ++n2;
  }
  if (n2 < kMinimumSamples || !(var2 > 0.0)) return c;
  // Colour only on a bus's channels (quantised or held): on a continuous one the second differences
  // cannot tell coloured noise from the signal's own fast content (a steering loop ringing at 120 Hz in
  // a 1 kHz log reads as a lag-one correlation of 0.7), and the suite's own logs would get noise they
  // do not have.
  const double rho = std::clamp(correlationFromSecondDifferences(cov2 / var2), -0.9, 0.9);
  if ((c.quantum > 0.0 || c.hold > 1) && std::fabs(rho) >= 0.3) c.ar = rho;
  if (c.ar != 0.0 || c.quantum > 0.0 || c.hold > 1) {
    double level2 = (var2 / static_cast<double>(n2)) / (6.0 - 8.0 * c.ar + 2.0 * c.ar * c.ar);
    if (c.quantum > 0.0) level2 = std::max(0.0, level2 - c.quantum * c.quantum / 12.0);
    c.sigma = std::sqrt(level2);
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
