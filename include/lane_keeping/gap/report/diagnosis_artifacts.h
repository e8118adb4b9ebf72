#pragma once
/// The series a diagnosis leaves for its plots (scripts/gap_report_plots.py): residuals per subsystem,
/// their spectra, and the closed-loop overlays of the real, nominal and corrected runs.
#include <map>
#include <string>
#include <vector>

namespace lane_keeping {

/// Series for the plots (scripts/gap_report_plots.py formats).
struct DiagnosisArtifacts {
  std::vector<double> residual_t;
  std::map<std::string, std::vector<double>> residual;  ///< per subsystem, NaN where not replayed
  std::vector<double> spectrum_f;
  std::map<std::string, std::vector<double>> spectrum;
  std::vector<double> overlay_t;
  std::map<std::string, std::vector<double>> overlay;  ///< y_real, y_nominal, y_corrected, yaw_rate_*, delta_*
};

/// residuals.csv, spectrum.csv, overlay.csv in `dir`.
void writeDiagnosisArtifacts(const std::string& dir, const DiagnosisArtifacts& artifacts);

}  // namespace lane_keeping
