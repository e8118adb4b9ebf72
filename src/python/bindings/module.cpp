// lane_keeping._lane_keeping: the extension module behind the Python package lane_keeping
// (src/python/lane_keeping; docs/python_api.md). The package's functions call these.
#include <pybind11/pybind11.h>

#include "bag_log_reader.h"
#include "bindings.h"
#include "errors.h"
#include "lane_keeping/gap/log/log_reader.h"

PYBIND11_MODULE(_lane_keeping, m) {
  m.doc() = "The lane_keeping core (simulation, gap diagnosis, stability analysis); use the package lane_keeping.";
  lane_keeping::python::bindErrors(m);
  lane_keeping::python::bindSimulation(m);
  lane_keeping::python::bindGap(m);
  lane_keeping::python::bindStability(m);
  // Bags of the suite's own topics, as lk_gap reads them (the core has no ROS: the ROS side registers it).
  lane_keeping::registerBagLogReader([](const std::string& path) { return lane_keeping::readBagLog(path); });
}
