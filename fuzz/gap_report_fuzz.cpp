// Fuzz target: the gap report reader, readGapReportJson (gap/report/gap_report.h), as lk_gap_benchmark's scorer
// reads report.json files back. Feeds: the input as report.json. Asserts: a GapReport, or an InputError
// naming the file; any other exception (nlohmann::json's type_error, out_of_range, ...), crash, hang or
// sanitizer report is a finding.
#include "fuzz_support.h"
#include "lane_keeping/gap/report/gap_report.h"

using namespace lane_keeping;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::writeFile("report.json", std::string(reinterpret_cast<const char*>(data), size));
  fuzz::expectResultOrSuiteError([&] { (void)readGapReportJson(path); }, path);
  return 0;
}
