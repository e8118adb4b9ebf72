#pragma once
/// What every harness in fuzz/ shares: the fuzz input written to a file (the parsers read files), the
/// input split into parts at separator lines, and the rule that decides a finding. A parser given any
/// bytes must either return a result that keeps its documented contract or throw one of the suite's
/// error types (common/errors.h) whose message names the file; any other exception, a crash, a hang or a
/// sanitizer report is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "lane_keeping/common/errors.h"

namespace lane_keeping {
namespace fuzz {

/// A private scratch folder per process (-fork and -jobs run several), created once.
inline const std::string& scratchDir() {
  static const std::string dir = [] {
    const char* base = std::getenv("TMPDIR");
    std::string d = std::string(base && *base ? base : "/tmp") + "/lk_fuzz_" + std::to_string(::getpid());
    std::error_code ec;  // no shell: a TMPDIR with a quote in it is a name like any other
    std::filesystem::create_directories(d, ec);
    if (ec) std::abort();
    return d;
  }();
  return dir;
}

/// Writes `bytes` to scratchDir()/name (replacing it) and returns the path.
inline std::string writeFile(const std::string& name, const std::string& bytes) {
  const std::string path = scratchDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) std::abort();
  return path;
}

/// `input` cut at each occurrence of `separator` (a whole line, e.g. "#--overlay\n"): part 0 is what comes
/// before the first one. At most `max_parts` parts; the last keeps any further separators.
inline std::vector<std::string> splitAt(const std::string& input, const std::string& separator, std::size_t max_parts) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (parts.size() + 1 < max_parts) {
    const std::size_t at = input.find(separator, start);
    if (at == std::string::npos) break;
    parts.push_back(input.substr(start, at - start));
    start = at + separator.size();
  }
  parts.push_back(input.substr(start));
  return parts;
}

/// A finding: prints what broke the contract and aborts (libFuzzer saves the input as crash-*).
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "\n== lane_keeping fuzz finding: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

/// A clean rejection: one of the suite's errors, whose message names `file` (when `file` is not empty).
inline void expectNamesFile(const LaneKeepingError& error, const std::string& file) {
  const std::string message = error.what();
  if (message.empty()) finding("an error without a message");
  if (!file.empty() && message.find(file) == std::string::npos) {
    finding("the error does not name the file " + file + ": " + message);
  }
}

/// Runs `parse`; a LaneKeepingError naming `file` is a clean rejection, any other exception a finding.
template <typename Parse>
void expectResultOrSuiteError(const Parse& parse, const std::string& file) {
  try {
    parse();
  } catch (const LaneKeepingError& error) {
    expectNamesFile(error, file);
  } catch (const std::exception& error) {
    finding(std::string("an exception that is not the suite's: ") + typeid(error).name() + ": " + error.what());
  } catch (...) {
    finding("an exception that is not a std::exception");
  }
}

}  // namespace fuzz
}  // namespace lane_keeping
