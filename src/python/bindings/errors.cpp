#include "errors.h"

#include <exception>

#include "lane_keeping/common/errors.h"

namespace py = pybind11;

namespace lane_keeping {
namespace python {
namespace {

// Owned for the life of the interpreter (never decremented: the translator may run until the end).
PyObject* g_base = nullptr;
PyObject* g_config = nullptr;
PyObject* g_input = nullptr;
PyObject* g_model = nullptr;
PyObject* g_schedule = nullptr;

PyObject* newClass(py::module_& m, const char* name, PyObject* first, PyObject* second, const char* doc) {
  const std::string qualified = std::string("lane_keeping.") + name;
  py::tuple bases = second ? py::make_tuple(py::handle(first), py::handle(second)) : py::make_tuple(py::handle(first));
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module holds one reference; g_* keep the one from creation
  return type;
}

void raise(PyObject* type, const std::exception& e) { PyErr_SetString(type, e.what()); }

void raiseConfigError(const ConfigError& e) {
  py::list problems;
  for (const ConfigProblem& p : e.problems()) {
    py::dict problem;
    problem["key"] = p.key;
    problem["location"] = p.location;
    problem["message"] = p.message;
    problems.append(problem);
  }
  py::object instance = py::reinterpret_borrow<py::object>(g_config)(py::str(e.what()));
  instance.attr("problems") = problems;
  PyErr_SetObject(g_config, instance.ptr());
}

}  // namespace

void bindErrors(py::module_& m) {
  g_base = newClass(m, "LaneKeepingError", PyExc_Exception, nullptr, "Base of every error the lane_keeping core raises on purpose.");
  g_config = newClass(m, "ConfigError", g_base, PyExc_ValueError,
                      "Invalid configuration. The message lists every problem, each naming the key, where it came "
                      "from and why; .problems holds them as dicts with 'key', 'location' and 'message'.");
  g_input = newClass(m, "InputError", g_base, PyExc_ValueError,
                     "Bad input data (a log file or table): names the file or table, the line or row and the column.");
  g_model = newClass(m, "ModelError", g_base, PyExc_RuntimeError,
                     "A model evaluation produced a non-finite value or left its domain.");
  g_schedule = newClass(m, "ScheduleError", g_base, PyExc_RuntimeError,
                        "The lockstep schedule cannot advance: the loop's delays give no lookahead.");
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const ConfigError& e) {
      raiseConfigError(e);
    } catch (const InputError& e) {
      raise(g_input, e);
    } catch (const ModelError& e) {
      raise(g_model, e);
    } catch (const ScheduleError& e) {
      raise(g_schedule, e);
    } catch (const LaneKeepingError& e) {
      raise(g_base, e);
    }
  });
}

}  // namespace python
}  // namespace lane_keeping
