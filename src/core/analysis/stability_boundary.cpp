#include "lane_keeping/analysis/stability_boundary.h"

#include <cmath>
#include <sstream>

#include "lane_keeping/analysis/config_parameter.h"

namespace lane_keeping {

double Crossing::frequencyHz() const { return std::fabs(root.imag()) / (2.0 * M_PI); }

namespace {

double scanValue(const ScanOptions& o, int i) {
  const double u = static_cast<double>(i) / o.steps;
  return o.geometric ? o.start * std::pow(o.end / o.start, u) : o.start + (o.end - o.start) * u;
}

}  // namespace

Crossing findFirstCrossing(const SystemFamily& family, const ScanOptions& options) {
  if (options.steps < 1 || !(options.end != options.start) || (options.geometric && !(options.start > 0.0 && options.end > 0.0))) {
    throw std::invalid_argument("findFirstCrossing: need steps >= 1, start != end, and start, end > 0 for a geometric scan");
  }
  Crossing out;
  double previous = options.start;
  for (int i = 0; i <= options.steps; ++i) {
    const double s = scanValue(options, i);
    const Spectrum spectrum = computeSpectrum(family(s), options.spectrum);
    ++out.spectra;
    const double a = spectrum.abscissa();
    if (i == 0) {
      out.abscissa_start = a;
      if (a >= 0.0) {
        std::ostringstream why;
        why << "unstable already at the scan start " << s << " (rightmost root " << spectrum.roots.front().value.real()
            << (spectrum.roots.front().value.imag() >= 0 ? " + " : " - ") << std::fabs(spectrum.roots.front().value.imag())
            << "i 1/s)";
        out.reason = why.str();
        return out;
      }
    } else if (a >= 0.0) {
      Crossing refined = refineCrossing(family, previous, s, options.spectrum);
      refined.abscissa_start = out.abscissa_start;
      refined.spectra += out.spectra;
      return refined;
    }
    previous = s;
  }
  std::ostringstream why;
  why << "stable over the whole scan [" << options.start << ", " << options.end << "]";
  out.reason = why.str();
  return out;
}

Crossing refineCrossing(const SystemFamily& family, double stable, double unstable, const SpectrumOptions& spectrum_options) {
  Crossing out;
  double a = stable, b = unstable;
  Complex root_b;
  // Bisection on the sign of the spectral abscissa until the bracket is ~1e-7 relative: the rightmost
  // root at b is then the one that crossed.
  auto rightmost = [&](double s, Complex* root) {
    const Spectrum spectrum = computeSpectrum(family(s), spectrum_options);
    ++out.spectra;
    *root = spectrum.roots.front().value;
    return spectrum.abscissa();
  };
  if (rightmost(b, &root_b) < 0.0) throw std::invalid_argument("refineCrossing: the 'unstable' end is stable");
  for (int i = 0; i < 200 && std::fabs(b - a) > 1e-7 * std::max(std::fabs(a), std::fabs(b)); ++i) {
    const double mid = 0.5 * (a + b);
    Complex root_mid;
    if (rightmost(mid, &root_mid) >= 0.0) {
      b = mid;
      root_b = root_mid;
    } else {
      a = mid;
    }
  }
  // Secant on Re lambda(s) of the continued root.
  Complex root_a = root_b;
  const bool ok_a = refineRoot(family(a), &root_a);
  double s0 = a, s1 = b;
  double f0 = ok_a ? root_a.real() : -1.0;
  double f1 = root_b.real();
  Complex root = root_b;
  if (ok_a && f0 < 0.0) {
    for (int i = 0; i < 30; ++i) {
      if (f1 == f0) break;
      const double s2 = s1 - f1 * (s1 - s0) / (f1 - f0);
      Complex r = root;
      if (!refineRoot(family(s2), &r)) break;
      s0 = s1;
      f0 = f1;
      s1 = s2;
      f1 = r.real();
      root = r;
      if (std::fabs(s1 - s0) <= 1e-13 * std::fabs(s1) || std::fabs(f1) < 1e-12) break;
    }
  }
  out.found = true;
  out.parameter = s1;
  out.root = root.imag() < 0.0 ? std::conj(root) : root;
  return out;
}

SystemFamily configFamily(const SimConfig& config, const std::string& key, const LinearizationOptions& options) {
  configParameterInfo(key);  // throws for an unknown key now rather than inside the scan
  return [config, key, options](double s) {
    SimConfig c = config;
    setConfigNumber(c, key, s);
    return linearizeClosedLoop(c, options).dde;
  };
}

}  // namespace lane_keeping
