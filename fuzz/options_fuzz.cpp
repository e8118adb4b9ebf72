// Fuzz target: the tools' numeric options and runtime changes, as every tool reads them: numberOption and
// wholeNumberOption (common/command_line.h; lk_gap --threads, --noise-reference-draws, --coarse-fit-stride,
// --time-budget, lk_stability --degree, --n, --tau2-max, lk_gap_benchmark --log-rate, ...) and
// parseTimedChange (config/timed_change.h; lk_simulate --change T:key=value, a node's ~changes).
// Feeds: each line of the input is one value; its first byte picks the reader and the range (ranges of the
// tools' own options), the rest is the text. Asserts: a UsageError (ConfigError for a change) naming the
// option (the change), or a result that is what the text says: a finite number within the range that
// strtod reads from the whole text (a whole number for wholeNumberOption); a change whose time is finite,
// in [0, kMaxChangeTime], whose key has no blank, whose value is not empty, and whose text() reads back to
// the same change.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "fuzz_support.h"
#include "lane_keeping/common/command_line.h"
#include "lane_keeping/config/timed_change.h"

using namespace lane_keeping;

namespace {

struct Limits {
  const char* option;
  double min, max;
};

// The tools' options and their ranges (as lk_gap, lk_stability and lk_gap_benchmark give them), and a few
// extremes.
constexpr Limits kNumbers[] = {{"--time-budget", 0.0, 1e4},    {"--tau2-max", 1e-6, 10.0},
                               {"--log-rate", 1.0, 1e5},       {"--from", -1e300, 1e300},
                               {"--to", -1.7976931348623157e308, 1.7976931348623157e308}};
constexpr Limits kWholes[] = {{"--threads", 1, 256},         {"--noise-reference-draws", 0, 1000},
                              {"--coarse-fit-stride", 1, 1000}, {"--degree", 2, 400},
                              {"--n", 2, 2000},               {"--count", 1, 1000}};

/// strtod of the whole text ("+5" included), or false.
bool strtodWhole(const std::string& text, double* value) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && text.find('\0') == std::string::npos;
}

void number(const Limits& limits, const std::string& text) {
  double value = 0.0;
  bool accepted = false;
  fuzz::expectResultOrSuiteError([&] {
    try {
      value = numberOption(limits.option, text, limits.min, limits.max);
      accepted = true;
    } catch (const UsageError& e) {
      if (std::string(e.what()).find(limits.option) == std::string::npos) fuzz::finding("an option error without the option");
      throw;
    }
  }, "");
  if (!accepted) return;
  double expected = 0.0;
  if (!strtodWhole(text, &expected)) fuzz::finding("numberOption accepted '" + text + "', which is not a whole number text");
  if (!std::isfinite(value) || value < limits.min || value > limits.max) fuzz::finding("numberOption out of its range");
  if (value != expected && !(std::fabs(value) < 1e-300 && std::fabs(expected) < 1e-300)) {
    fuzz::finding("numberOption read '" + text + "' as " + std::to_string(value));
  }
}

void whole(const Limits& limits, const std::string& text) {
  long long value = 0;
  bool accepted = false;
  fuzz::expectResultOrSuiteError([&] {
    try {
      value = wholeNumberOption(limits.option, text, static_cast<long long>(limits.min),
                                static_cast<long long>(limits.max));
      accepted = true;
    } catch (const UsageError& e) {
      if (std::string(e.what()).find(limits.option) == std::string::npos) fuzz::finding("an option error without the option");
      throw;
    }
  }, "");
  if (!accepted) return;
  double expected = 0.0;
  if (!strtodWhole(text, &expected) || expected != static_cast<double>(value)) {
    fuzz::finding("wholeNumberOption read '" + text + "' as " + std::to_string(value));
  }
  if (value < static_cast<long long>(limits.min) || value > static_cast<long long>(limits.max)) {
    fuzz::finding("wholeNumberOption out of its range");
  }
}

void change(const std::string& text) {
  TimedChange c;
  bool accepted = false;
  fuzz::expectResultOrSuiteError([&] {
    c = parseTimedChange(text);
    accepted = true;
  }, "");
  if (!accepted) return;
  if (!std::isfinite(c.t) || c.t < 0.0 || c.t > kMaxChangeTime) fuzz::finding("a change time out of range");
  if (c.key.empty() || c.key.find_first_of(" \t") != std::string::npos) fuzz::finding("a change key '" + c.key + "'");
  if (c.value.empty()) fuzz::finding("a change without a value");
  const TimedChange again = parseTimedChange(c.text());
  if (again.t != c.t || again.key != c.key || again.value != c.value) {
    fuzz::finding("a change's text() does not read back: '" + c.text() + "'");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::istringstream lines(input);
  int count = 0;
  for (std::string line; std::getline(lines, line) && count < 16; ++count) {
    if (line.empty()) continue;
    const auto selector = static_cast<unsigned char>(line[0]);
    const std::string text = line.substr(1);
    constexpr std::size_t numbers = sizeof(kNumbers) / sizeof(kNumbers[0]);
    constexpr std::size_t wholes = sizeof(kWholes) / sizeof(kWholes[0]);
    const std::size_t pick = selector % (numbers + wholes + 1);
    if (pick < numbers) number(kNumbers[pick], text);
    else if (pick < numbers + wholes) whole(kWholes[pick - numbers], text);
    else change(text);
  }
  return 0;
}
