#pragma once
// The core's typed exceptions (lane_keeping/common/errors.h) as Python exception classes:
//   LaneKeepingError(Exception)
//   ConfigError(LaneKeepingError, ValueError)   .problems: [{"key", "location", "message"}, ...]
//   InputError(LaneKeepingError, ValueError)
//   ModelError(LaneKeepingError, RuntimeError)
//   ScheduleError(LaneKeepingError, RuntimeError)
// The message is the core's own (the text lk_simulate, lk_gap and lk_stability print after their name).
#include <pybind11/pybind11.h>

namespace lane_keeping {
namespace python {

/// Creates the classes in `m` and registers the translation of the C++ exceptions.
void bindErrors(pybind11::module_& m);

}  // namespace python
}  // namespace lane_keeping
