// Fuzz target: the CSV log reader of the gap diagnosis, readCsvLog (gap/log/gap_log.h), without and with a
// log mapping (gap/log/log_mapping.h), as lk_gap --log FILE.csv [--log-map MAP.yaml] reads them.
// Feeds: the input as a CSV file; if it holds a line "#--csv", what comes before it is a YAML file whose
// `log:` section is read by readLogMapping, and the rest is the CSV, read both plain and through the
// mapping. Asserts: either an InputError/ConfigError naming the file, or a GapLog that keeps the reader's
// contract: at least 10 rows, t finite and strictly increasing, every present column as long as t and
// finite, no value beyond 1e9 (the loosest limit the reader documents); anything else is a finding.
#include <cmath>

#include "fuzz_support.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"

using namespace lane_keeping;

namespace {

void checkContract(const GapLog& log) {
  if (log.size() < 10) fuzz::finding("a log with " + std::to_string(log.size()) + " rows was accepted");
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (!std::isfinite(log.t[i])) fuzz::finding("non-finite t accepted");
    if (i > 0 && !(log.t[i] > log.t[i - 1])) fuzz::finding("t not strictly increasing at row " + std::to_string(i));
  }
  const std::vector<double>* columns[] = {&log.x,  &log.y,     &log.psi,       &log.yaw_rate,  &log.delta,
                                          &log.delta_des, &log.torque, &log.v, &log.ay, &log.delta_rate};
  for (const std::vector<double>* column : columns) {
    if (column->empty()) continue;
    if (column->size() != log.size()) fuzz::finding("a column's length differs from t's");
    for (double v : *column) {
      if (!std::isfinite(v) || std::fabs(v) > 1e9) fuzz::finding("value " + std::to_string(v) + " accepted");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> parts = fuzz::splitAt(input, "#--csv\n", 2);
  const std::string csv = fuzz::writeFile("log.csv", parts.back());
  fuzz::expectResultOrSuiteError([&] { checkContract(readCsvLog(csv)); }, csv);
  if (parts.size() == 1) return 0;
  const std::string map_file = fuzz::writeFile("map.yaml", parts[0]);
  LogMapping mapping;
  bool mapped = false;
  fuzz::expectResultOrSuiteError(
      [&] {
        mapping = readLogMapping(map_file);
        mapped = true;
      },
      map_file);
  if (mapped) fuzz::expectResultOrSuiteError([&] { checkContract(readCsvLog(csv, mapping)); }, csv);
  return 0;
}
