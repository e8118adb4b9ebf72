#include "lane_keeping/sim/oscillation.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include <unsupported/Eigen/FFT>

namespace lane_keeping {

std::string OscillationEstimate::trend(double steady_rate) const {
  if (!valid) return "none";
  if (growth_rate > steady_rate) return "grows";
  if (growth_rate < -steady_rate) return "decays";
  return "steady";
}

namespace {

/// Least-squares slope of y over x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() < 2) return 0.0;
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= x.size();
  my /= y.size();
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += (x[i] - mx) * (y[i] - my);
    den += (x[i] - mx) * (x[i] - mx);
  }
  return den > 0.0 ? num / den : 0.0;
}

double spectralPeakFrequency(const std::vector<double>& d, double dt) {
  const std::size_t n = d.size();
  std::vector<double> windowed(n);
  for (std::size_t i = 0; i < n; ++i) {
    windowed[i] = d[i] * (0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n - 1)));
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, windowed);
  const std::size_t half = n / 2;
  std::size_t peak = 1;
  double peak_mag = 0.0;
  for (std::size_t k = 1; k < half; ++k) {
    const double mag = std::abs(spectrum[k]);
    if (mag > peak_mag) {
      peak_mag = mag;
      peak = k;
    }
  }
  double bin = static_cast<double>(peak);
  if (peak > 1 && peak + 1 < half) {
    const double a = std::log(std::abs(spectrum[peak - 1]) + 1e-300);
    const double b = std::log(peak_mag + 1e-300);
    const double c = std::log(std::abs(spectrum[peak + 1]) + 1e-300);
    const double curvature = a - 2.0 * b + c;
    if (curvature < 0.0) bin += 0.5 * (a - c) / curvature;
  }
  return bin / (dt * static_cast<double>(n));
}

}  // namespace

OscillationEstimate analyzeOscillation(const std::vector<double>& values, double dt) {
  OscillationEstimate estimate;
  const std::size_t n = values.size();
  if (n < 16 || !(dt > 0.0)) return estimate;

  // The channels analysed here (e_y, delta - delta_des) settle to zero, so the signal is used as is:
  // removing a trend would distort the envelope of a decaying or growing response.
  const std::vector<double>& d = values;
  double energy = 0.0;
  for (double v : d) energy += v * v;
  if (!(energy > 0.0) || !std::isfinite(energy)) return estimate;
  estimate.valid = true;

  // Zero crossings (linear interpolation) and the peak of each half-cycle between them.
  std::vector<double> crossings;
  std::vector<std::size_t> crossing_index;
  for (std::size_t i = 1; i < n; ++i) {
    if ((d[i - 1] < 0.0 && d[i] >= 0.0) || (d[i - 1] > 0.0 && d[i] <= 0.0)) {
      const double frac = d[i - 1] / (d[i - 1] - d[i]);
      crossings.push_back(dt * (static_cast<double>(i - 1) + frac));
      crossing_index.push_back(i);
    }
  }
  bool regular = false;
  if (crossings.size() >= 3) {
    std::vector<double> halves;
    for (std::size_t i = 1; i < crossings.size(); ++i) halves.push_back(crossings[i] - crossings[i - 1]);
    double mean = 0.0;
    for (double h : halves) mean += h;
    mean /= halves.size();
    double var = 0.0;
    for (double h : halves) var += (h - mean) * (h - mean);
    const double cv = std::sqrt(var / halves.size()) / mean;
    if (cv < 0.5) {
      regular = true;
      estimate.frequency_hz = 1.0 / (2.0 * mean);
      estimate.cycles = static_cast<int>((crossings.size() - 1) / 2);
      std::vector<double> peak_times, peak_logs;
      for (std::size_t k = 1; k < crossing_index.size(); ++k) {
        std::size_t best = crossing_index[k - 1];
        for (std::size_t i = crossing_index[k - 1]; i < crossing_index[k]; ++i) {
          if (std::fabs(d[i]) > std::fabs(d[best])) best = i;
        }
        if (d[best] != 0.0) {
          peak_times.push_back(dt * static_cast<double>(best));
          peak_logs.push_back(std::log(std::fabs(d[best])));
        }
      }
      estimate.growth_rate = slope(peak_times, peak_logs);
      if (!peak_logs.empty()) {
        estimate.rms_first = std::exp(peak_logs.front()) / std::sqrt(2.0);
        estimate.rms_last = std::exp(peak_logs.back()) / std::sqrt(2.0);
      }
    }
  }
  if (!regular) {
    estimate.frequency_hz = spectralPeakFrequency(d, dt);
    estimate.cycles = static_cast<int>(estimate.frequency_hz * dt * n);
    // RMS over four equal windows.
    std::vector<double> times, logs;
    const std::size_t window = n / 4;
    for (std::size_t start = 0; start + window <= n; start += window) {
      double sum = 0.0;
      for (std::size_t i = start; i < start + window; ++i) sum += d[i] * d[i];
      const double rms = std::sqrt(sum / window);
      if (times.empty()) estimate.rms_first = rms;
      estimate.rms_last = rms;
      if (rms > 0.0) {
        times.push_back(dt * (start + 0.5 * window));
        logs.push_back(std::log(rms));
      }
    }
    estimate.growth_rate = slope(times, logs);
  }
  estimate.regular = regular;
  return estimate;
}

}  // namespace lane_keeping
