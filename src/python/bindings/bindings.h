#pragma once
// The parts of the extension module lane_keeping._lane_keeping (module.cpp), one file per area of the
// core it wraps. Thin by rule: they read Python objects into the core's types, call the core, and hand
// its results back; no physics, control law or diagnosis step lives here.
#include <pybind11/pybind11.h>

namespace lane_keeping {
namespace python {

void bindSimulation(pybind11::module_& m);  // simulation.cpp: simulate, simulate_many, effective_config
void bindGap(pybind11::module_& m);         // gap.cpp: diagnose
void bindStability(pybind11::module_& m);   // stability.cpp: critical delay, roots, boundary, chart

}  // namespace python
}  // namespace lane_keeping
