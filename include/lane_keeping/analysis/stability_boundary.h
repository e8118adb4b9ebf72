#pragma once
/// Where a one-parameter family of delay systems loses stability (a stability boundary of Beregi
/// §3: a real root through 0, D~(0) = 0, or a complex pair through +-i omega, D(i omega) = 0):
/// scan the spectral abscissa, bisect the first sign change with full spectra (so the crossing
/// root is the rightmost one), then pin Re lambda = 0 by secant steps on the Newton-continued
/// crossing root, to ~1e-12 relative in the parameter.
#include <functional>
#include <string>

#include "lane_keeping/analysis/closed_loop_linearization.h"
#include "lane_keeping/analysis/dde_spectrum.h"
#include "lane_keeping/analysis/linear_delay_system.h"

namespace lane_keeping {

/// The delay system at parameter value s.
using SystemFamily = std::function<LinearDelaySystem(double)>;

struct ScanOptions {
  double start = 1e-5;    ///< first parameter value
  double end = 0.05;      ///< last parameter value
  int steps = 300;        ///< scan intervals between start and end
  bool geometric = true;  ///< geometric spacing (start, end > 0) or uniform
  SpectrumOptions spectrum;
};

struct Crossing {
  bool found = false;
  double parameter = 0.0;     ///< where the rightmost root reaches Re = 0
  Complex root;               ///< the crossing root, Re ~ 0, Im >= 0 (i omega; 0 for a real root)
  double abscissa_start = 0.0;  ///< spectral abscissa at the scan start
  int spectra = 0;            ///< collocation spectra computed
  std::string reason;         ///< why none was found
  double frequencyHz() const;
  double angularFrequency() const { return root.imag(); }
};

/// First loss of stability along the scan. If the start is already unstable, found = false and
/// `reason` says so.
Crossing findFirstCrossing(const SystemFamily& family, const ScanOptions& options);

/// The crossing between `stable` and `unstable` (spectral abscissa < 0 at one, >= 0 at the other).
Crossing refineCrossing(const SystemFamily& family, double stable, double unstable, const SpectrumOptions& spectrum);

/// The family obtained by setting config key `key` (config_parameter.h; "tau2" moves both actuator
/// delays) to s and linearising the loop (linearizeClosedLoop).
SystemFamily configFamily(const SimConfig& config, const std::string& key, const LinearizationOptions& options = {});

}  // namespace lane_keeping
