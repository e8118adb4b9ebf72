#include "lane_keeping/gap/evaluation/config_change.h"

#include <sstream>
#include <utility>

#include "lane_keeping/config/flat_params.h"

namespace lane_keeping {

ConfigChange assignmentsChange(std::vector<std::string> assignments) {
  return [assignments = std::move(assignments)](SimConfig& config) {
    // Through the same reader the tools use: the printed configuration, then the assignments.
    std::ostringstream yaml;
    config.print(yaml);
    FlatParams flat;
    flat.overlayText(yaml.str(), "configuration under test");
    for (const auto& assignment : assignments) flat.overlayAssignment(assignment);
    config = simConfigFromFlat(flat);
  };
}

SimConfig changed(const SimConfig& base, const ConfigChange& change) {
  SimConfig out = base;
  if (change) change(out);
  return out;
}

}  // namespace lane_keeping
