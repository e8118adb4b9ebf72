// Fuzz target: the log mapping (gap/log/log_mapping.h), a `log:` section as lk_gap reads it from the
// nominal configuration, a scenario or a --log-map file, applied by readCsvLog (gap/log/gap_log.h) to
// logs that are themselves valid. csv_log_fuzz.cpp feeds the CSV and the mapping together, so most of its
// inputs end in the CSV reader; here the CSV is fixed and the input is the mapping file alone, so the
// fuzzer explores what a mapping can say: columns renamed, mapped twice or onto missing columns, time
// units, scales (0, huge, denormal, negative), offsets, unscaled columns.
// Feeds: the input as a YAML file; its `log:` section is read by readLogMapping and applied to two fixed
// logs: one in the schema's columns (t in s) and one in a car's own names (stamp_ms, east, north,
// heading, yaw, speed, wheel, wheel_des, eps). The same file is also read as a configuration
// (loadSimConfig), which must leave the `log:` section to the log reader.
// Asserts: readLogMapping returns a mapping or throws a ConfigError naming the file; each readCsvLog returns
// a log that keeps the reader's contract (at least 10 rows, t finite and strictly increasing, every present
// column as long as t, finite, within 1e9) or throws an error naming the CSV file or the mapping file;
// loadSimConfig refuses no `log.*` key of a mapping readLogMapping accepted.
#include <cmath>
#include <cstdio>
#include <string>

#include <yaml-cpp/yaml.h>

#include "fuzz_support.h"
#include "log_contract.h"
#include "lane_keeping/config/sim_config.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"

using namespace lane_keeping;

namespace {

/// 40 rows of a lane change at 15 m/s, 100 Hz, in the schema's columns (`schema`) or a car's own names
/// with time in ms and the steering-wheel angle (`own`).
std::string fixedLog(bool own) {
  std::string text = own ? "stamp_ms,east,north,heading,yaw,speed,wheel,wheel_des,eps\n"
                         : "t,x,y,psi,yaw_rate,v,ay,delta,delta_rate,delta_des,torque\n";
  char row[256];
  for (int i = 0; i < 40; ++i) {
    const double t = 0.01 * i, y = 0.5 * std::sin(t), psi = 0.03 * std::cos(t), r = -0.03 * std::sin(t);
    const double delta = 0.002 * std::cos(2 * t), delta_des = 0.0021 * std::cos(2 * t);
    if (own) {
      std::snprintf(row, sizeof(row), "%d,%.9g,%.9g,%.9g,%.9g,15,%.9g,%.9g,%d\n", 10 * i, 15 * t, y, psi, r,
                    15.0 * delta, 15.0 * delta_des, 300 + i);
    } else {
      std::snprintf(row, sizeof(row), "%.9g,%.9g,%.9g,%.9g,%.9g,15,%.9g,%.9g,%.9g,%.9g,%.9g\n", t, 15 * t, y, psi, r,
                    15.0 * r, delta, -0.004 * std::sin(2 * t), delta_des, 3.0 + 0.1 * i);
    }
    text += row;
  }
  return text;
}

/// readCsvLog's errors name the log or, for a mapping that does not fit it, the mapping's file.
void readThrough(const std::string& csv, const LogMapping& mapping, const std::string& map_file) {
  try {
    fuzz::checkLogContract(readCsvLog(csv, mapping));
  } catch (const LaneKeepingError& e) {
    const std::string message = e.what();
    if (message.find(csv) == std::string::npos && message.find(map_file) == std::string::npos) {
      fuzz::finding("a mapped log's error names neither the log nor the mapping: " + message);
    }
  } catch (const std::exception& e) {
    fuzz::finding(std::string("an exception that is not the suite's: ") + e.what());
  }
}

/// Whether the file's "log." keys can come only from a top-level log: section (no top-level key spelled
/// "log.something"); false for a file yaml-cpp cannot read.
bool logSectionOnly(const std::string& path) {
  try {
    const YAML::Node root = YAML::LoadFile(path);
    if (!root.IsMap()) return true;
    for (const auto& item : root) {
      if (!item.first.IsScalar()) continue;
      if (item.first.Scalar().rfind("log.", 0) == 0) return false;
    }
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string schema = fuzz::writeFile("schema.csv", fixedLog(false));
  static const std::string own = fuzz::writeFile("own.csv", fixedLog(true));
  const std::string map_file = fuzz::writeFile("map.yaml", std::string(reinterpret_cast<const char*>(data), size));
  LogMapping mapping;
  bool mapped = false;
  fuzz::expectResultOrSuiteError(
      [&] {
        mapping = readLogMapping(map_file);
        mapped = true;
      },
      map_file);
  if (mapped) {
    readThrough(schema, mapping, map_file);
    readThrough(own, mapping, map_file);
  }
  // The same file as a configuration (lk_gap --config with a log: section): the keys of a mapping the
  // mapping's reader accepts are the mapping's, never a configuration problem. (A log: section both
  // readers refuse, e.g. a key that is not a name, may be named by either. A top-level key spelled with
  // dots, "log.columns.x: ...", flattens to a "log." key too but is no log: section: the mapping's reader
  // never reads it, and the configuration's may refuse it; found by this target, fuzz/regressions/log_mapping.)
  const bool only_a_log_section = logSectionOnly(map_file);
  try {
    loadSimConfig({map_file}, {});
  } catch (const ConfigError& e) {
    for (const ConfigProblem& p : e.problems()) {
      if (mapped && only_a_log_section && p.key.rfind("log.", 0) == 0) {
        fuzz::finding("loadSimConfig refused the log: key " + p.key);
      }
    }
  } catch (const LaneKeepingError&) {
  } catch (const std::exception& e) {
    fuzz::finding(std::string("loadSimConfig: an exception that is not the suite's: ") + e.what());
  }
  return 0;
}
