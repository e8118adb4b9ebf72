#include "lane_keeping/gap/log/angle_unwrap.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace lane_keeping {

std::size_t unwrapAngle(std::vector<double>* angles) {
  constexpr double kTwoPi = 2.0 * M_PI;
  std::vector<double>& a = *angles;
  std::size_t wraps = 0;
  double shift = 0.0;  // added to every sample from the last wrap on
  double previous_raw = a.empty() ? 0.0 : a.front();
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double raw = a[i];
    const double step = raw - previous_raw;
    previous_raw = raw;
    if (std::fabs(std::fabs(step) - kTwoPi) < 0.5 * M_PI) {
      shift -= step > 0.0 ? kTwoPi : -kTwoPi;
      ++wraps;
    }
    a[i] = raw + shift;
  }
  return wraps;
}

void unwrapHeading(GapLog* log) {
  if (log->psi.empty()) return;
  std::vector<double> psi = log->psi;
  // The first wrap's time, for the note: the first sample whose unwrapped value moved.
  const std::size_t wraps = unwrapAngle(&psi);
  if (wraps == 0) return;
  double first = log->t.empty() ? 0.0 : log->t.front();
  for (std::size_t i = 0; i < psi.size() && i < log->t.size(); ++i) {
    if (psi[i] != log->psi[i]) {
      first = log->t[i] - log->t.front();
      break;
    }
  }
  log->psi = std::move(psi);
  char text[160];
  std::snprintf(text, sizeof text,
                "psi unwrapped: %zu wrap%s at +-pi removed (the first %.3g s after the log's start); the heading "
                "is continuous from there on",
                wraps, wraps == 1 ? "" : "s", first);
  log->notes.push_back(text);
}

}  // namespace lane_keeping
