#include "lane_keeping/common/time.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lane_keeping {

Nanoseconds secondsToNanoseconds(double seconds) {
  if (!std::isfinite(seconds) || std::fabs(seconds) > 9.2e9) {
    throw std::invalid_argument("time value " + std::to_string(seconds) + " s is not a finite time");
  }
  return static_cast<Nanoseconds>(std::llround(seconds * 1e9));
}

Nanoseconds periodFromRate(double rate_hz) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw std::invalid_argument("rate " + std::to_string(rate_hz) + " Hz must be a positive number");
  }
  const Nanoseconds period = secondsToNanoseconds(1.0 / rate_hz);
  if (period <= 0) throw std::invalid_argument("rate " + std::to_string(rate_hz) + " Hz exceeds 1 GHz");
  return period;
}

std::string formatSeconds(double seconds) {
  char buffer[64];
  const double a = std::fabs(seconds);
  if (a != 0.0 && a < 1e-3) {
    std::snprintf(buffer, sizeof(buffer), "%.6g ms", seconds * 1e3);
  } else {
    std::snprintf(buffer, sizeof(buffer), "%.6g s", seconds);
  }
  return buffer;
}

}  // namespace lane_keeping
