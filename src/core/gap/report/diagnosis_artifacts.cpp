#include "lane_keeping/gap/report/diagnosis_artifacts.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

void writeDiagnosisArtifacts(const std::string& dir, const DiagnosisArtifacts& artifacts) {
  auto write = [&](const std::string& name, const std::string& first, const std::vector<double>& x,
                   const std::vector<std::string>& columns, const std::map<std::string, std::vector<double>>& data) {
    std::ofstream out(dir + "/" + name);
    if (!out) throw InputError(dir + "/" + name + ": cannot write");
    out << first;
    for (const auto& c : columns) out << "," << c;
    out << "\n";
    char buffer[40];
    for (std::size_t i = 0; i < x.size(); ++i) {
      std::snprintf(buffer, sizeof(buffer), "%.10g", x[i]);
      out << buffer;
      for (const auto& c : columns) {
        const auto it = data.find(c);
        const double value = (it != data.end() && i < it->second.size()) ? it->second[i] : kNaN;
        if (std::isfinite(value)) {
          std::snprintf(buffer, sizeof(buffer), "%.10g", value);
          out << "," << buffer;
        } else {
          out << ",nan";
        }
      }
      out << "\n";
    }
  };
  write("residuals.csv", "t", artifacts.residual_t, {"tracker", "actuator", "steering", "chassis"}, artifacts.residual);
  write("spectrum.csv", "f", artifacts.spectrum_f, {"tracker", "actuator", "steering", "chassis"}, artifacts.spectrum);
  write("overlay.csv", "t", artifacts.overlay_t,
        {"y_real", "y_nominal", "y_corrected", "yaw_rate_real", "yaw_rate_nominal", "yaw_rate_corrected", "delta_real",
         "delta_nominal", "delta_corrected"},
        artifacts.overlay);
}

}  // namespace lane_keeping
