#include "lane_keeping/common/resources.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace lane_keeping {

double physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

std::string formatBytes(double bytes) {
  char text[48];
  if (bytes >= 1e12) std::snprintf(text, sizeof(text), "%.3g TB", bytes / 1e12);
  else if (bytes >= 1e9) std::snprintf(text, sizeof(text), "%.3g GB", bytes / 1e9);
  else if (bytes >= 1e6) std::snprintf(text, sizeof(text), "%.3g MB", bytes / 1e6);
  else std::snprintf(text, sizeof(text), "%.3g kB", bytes / 1e3);
  return text;
}

std::string formatDuration(double seconds) {
  char text[64];
  if (!std::isfinite(seconds) || seconds > 3.15e9) return "more than a century";
  if (seconds >= 2 * 86400.0) std::snprintf(text, sizeof(text), "%.3g days", seconds / 86400.0);
  else if (seconds >= 3600.0) std::snprintf(text, sizeof(text), "%.0f h %.0f min", std::floor(seconds / 3600.0),
                                            std::fmod(seconds, 3600.0) / 60.0);
  else if (seconds >= 60.0) std::snprintf(text, sizeof(text), "%.0f min", seconds / 60.0);
  else std::snprintf(text, sizeof(text), "%.2g s", seconds);
  return text;
}

}  // namespace lane_keeping
