#include "lane_keeping/config/timed_change.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "lane_keeping/common/errors.h"
#include "lane_keeping/config/param_readers.h"

namespace lane_keeping {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

[[noreturn]] void refuse(const std::string& text, const std::string& key, const std::string& why) {
  throw ConfigError(std::vector<ConfigProblem>{{key, "change '" + text + "'", why}});
}

}  // namespace

std::string TimedChange::text() const { return formatNumber(t) + ":" + key + "=" + value; }

TimedChange parseTimedChange(const std::string& text) {
  const std::string kForm = "expected T:key=value with T in seconds, e.g. 10:steering.coulomb_friction=3";
  const auto colon = text.find(':');
  if (colon == std::string::npos) refuse(text, "", "has no ':' after the time; " + kForm);
  TimedChange change;
  const std::string time_text = trim(text.substr(0, colon));
  if (time_text.empty()) refuse(text, "", "has no time before ':'; " + kForm);
  char* end = nullptr;
  errno = 0;
  const double t = std::strtod(time_text.c_str(), &end);
  if (end == time_text.c_str() || *end != '\0') {
    refuse(text, "", "time '" + time_text + "' is not a number of seconds; " + kForm);
  }
  if (!std::isfinite(t) || (errno == ERANGE && std::fabs(t) > 1.0)) {
    refuse(text, "", "time '" + time_text + "' is not a finite number of seconds");
  }
  // A subnormal time (0x1p-1074, or 4.94066e-324 which strtod reads with ERANGE) in any spelling: refused
  // alike, so that a change's text() reads back as itself (found by fuzz/options_fuzz.cpp).
  if (t != 0.0 && (errno == ERANGE || std::fpclassify(t) == FP_SUBNORMAL)) {
    refuse(text, "", "time '" + time_text + "' is too small to represent (below 2.2e-308 s); write 0 for the start");
  }
  if (t < 0.0) refuse(text, "", "time " + formatNumber(t) + " s is before the start of the run; must be >= 0 s");
  if (t > kMaxChangeTime) {
    refuse(text, "", "time " + formatNumber(t) + " s is beyond " + formatNumber(kMaxChangeTime) + " s");
  }
  change.t = t;
  const std::string assignment = text.substr(colon + 1);
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) refuse(text, trim(assignment), "has no '=' after the key; " + kForm);
  change.key = trim(assignment.substr(0, eq));
  change.value = trim(assignment.substr(eq + 1));
  if (change.key.empty()) refuse(text, "", "has no key between ':' and '='; " + kForm);
  if (change.key.find_first_of(" \t") != std::string::npos) {
    refuse(text, change.key, "is not a key (a dotted name without spaces, e.g. tracker.k_psi)");
  }
  if (change.value.empty()) refuse(text, change.key, "has no value after '='");
  return change;
}

}  // namespace lane_keeping
