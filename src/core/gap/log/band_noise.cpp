#include "lane_keeping/gap/log/band_noise.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include <unsupported/Eigen/FFT>

#include "lane_keeping/common/median.h"

namespace lane_keeping {
namespace {

/// Per bin of the upper half band, its cells (one per segment), or nothing where there are fewer than
/// kBandMinimumSegments segments.
std::vector<std::vector<double>> upperBandCells(const std::vector<double>& values,
                                                const std::vector<std::pair<std::size_t, std::size_t>>& stretches) {
  constexpr std::size_t n = kBandSegment;
  std::vector<double> window(n), gain(n / 2 + 1, 0.0);
  double window_power = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n - 1));
    window_power += window[i] * window[i];
  }
  const std::size_t first_bin = n / 4, end_bin = n / 2;  // [1/4, 1/2) cycles per sample; Nyquist's bin is real
  for (std::size_t k = first_bin; k < end_bin; ++k) {
    gain[k] = std::pow(2.0 * std::sin(M_PI * static_cast<double>(k) / static_cast<double>(n)), 8);
  }
  std::vector<std::pair<std::size_t, std::size_t>> parts = stretches;
  if (parts.empty()) parts.emplace_back(0, values.size());
  Eigen::FFT<double> fft;
  std::vector<std::vector<double>> cells(end_bin - first_bin);  // per bin, one cell per segment
  std::vector<double> chunk(n);
  std::vector<std::complex<double>> spectrum;
  for (const auto& [begin, end] : parts) {
    if (end > values.size() || end < begin + n + 4) continue;
    std::vector<double> d4;  // fourth differences within the stretch
    d4.reserve(end - begin - 4);
    for (std::size_t i = begin + 2; i + 2 < end; ++i) {
      d4.push_back(values[i - 2] - 4.0 * values[i - 1] + 6.0 * values[i] - 4.0 * values[i + 1] + values[i + 2]);
    }
    for (std::size_t start = 0; start + n <= d4.size(); start += n / 2) {
      for (std::size_t i = 0; i < n; ++i) chunk[i] = d4[start + i] * window[i];
      fft.fwd(spectrum, chunk);
      for (std::size_t k = first_bin; k < end_bin; ++k) {
        cells[k - first_bin].push_back(std::norm(spectrum[k]) / window_power / gain[k]);
      }
    }
  }
  if (cells[0].size() < kBandMinimumSegments) return {};
  return cells;
}

}  // namespace

UpperBand upperBand(const std::vector<double>& values, const std::vector<std::pair<std::size_t, std::size_t>>& stretches) {
  UpperBand out;
  for (std::vector<double>& bin : upperBandCells(values, stretches)) {
    double sum = 0.0;
    for (double c : bin) sum += c;
    out.mean.push_back(sum / static_cast<double>(bin.size()));
    out.median.push_back(median(std::move(bin)));
  }
  return out;
}

double upperBandFrequency(std::size_t bin, double rate) {
  return (static_cast<double>(kBandSegment / 4 + bin) / static_cast<double>(kBandSegment)) * rate;
}

std::optional<double> upperBandNoise(const std::vector<double>& values,
                                     const std::vector<std::pair<std::size_t, std::size_t>>& stretches) {
  UpperBand band = upperBand(values, stretches);
  if (band.median.empty()) return std::nullopt;
  const double level = median(band.median);
  if (!std::isfinite(level)) return std::nullopt;
  return std::sqrt(level / std::log(2.0));  // an exponential variable's median is ln 2 of its mean
}

}  // namespace lane_keeping
