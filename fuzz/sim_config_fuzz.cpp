// Fuzz target: the YAML configuration reader with validation, loadSimConfig(files, assignments)
// (config/sim_config.h), as lk_simulate --config BASE --config OVERLAY --set k=v ... calls it.
// Feeds: the input cut at a line "#--set" into YAML and assignments, the YAML cut at a line "#--overlay"
// into a base file and a scenario overlay (written to files), each non-empty line after "#--set" one
// `--set key=value` (at most 4). Asserts: a valid SimConfig that prints, or a lane_keeping error
// (ConfigError, ...); any other exception, crash, hang or sanitizer report is a finding.
#include <sstream>

#include "fuzz_support.h"
#include "lane_keeping/config/sim_config.h"

using namespace lane_keeping;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> yaml_and_sets = fuzz::splitAt(input, "#--set\n", 2);
  const std::vector<std::string> yaml = fuzz::splitAt(yaml_and_sets[0], "#--overlay\n", 2);
  std::vector<std::string> files{fuzz::writeFile("base.yaml", yaml[0])};
  if (yaml.size() > 1) files.push_back(fuzz::writeFile("overlay.yaml", yaml[1]));
  std::vector<std::string> assignments;
  if (yaml_and_sets.size() > 1) {
    std::istringstream lines(yaml_and_sets[1]);
    for (std::string line; std::getline(lines, line) && assignments.size() < 4;) {
      if (!line.empty()) assignments.push_back(line);
    }
  }
  fuzz::expectResultOrSuiteError(
      [&] {
        const SimConfig config = loadSimConfig(files, assignments);
        std::ostringstream printed;
        config.print(printed, true);
        if (printed.str().empty()) fuzz::finding("a valid configuration printed nothing");
      },
      "");
  return 0;
}
