// Fuzz target: the CSV log reader of the gap diagnosis, readCsvLog (gap/log/gap_log.h), without and with a
// log mapping (gap/log/log_mapping.h), as lk_gap --log FILE.csv [--log-map MAP.yaml] reads them.
// Feeds: the input as a CSV file; if it holds a line "#--csv", what comes before it is a YAML file whose
// `log:` section is read by readLogMapping, and the rest is the CSV, read both plain and through the
// mapping. Asserts: either an InputError/ConfigError naming the file, or a GapLog that keeps the reader's
// contract: at least 10 rows, t finite and strictly increasing, every present column as long as t and
// finite, no value beyond 1e9 (the loosest limit the reader documents); anything else is a finding.
#include <cmath>

#include "fuzz_support.h"
#include "log_contract.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/log_mapping.h"

using namespace lane_keeping;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> parts = fuzz::splitAt(input, "#--csv\n", 2);
  const std::string csv = fuzz::writeFile("log.csv", parts.back());
  fuzz::expectResultOrSuiteError([&] { fuzz::checkLogContract(readCsvLog(csv)); }, csv);
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
  if (mapped) fuzz::expectResultOrSuiteError([&] { fuzz::checkLogContract(readCsvLog(csv, mapping)); }, csv);
  return 0;
}
