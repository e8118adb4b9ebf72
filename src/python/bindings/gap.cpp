// diagnose: lk_gap in-process. The nominal configuration, each run's log (a file, or a table handed over
// from a pandas DataFrame: gapLogFromTable applies readCsvLog's rules), its scenario and log mapping are
// read as lk_gap reads them; diagnoseGap runs without the GIL; the report is gapReportJson's text, the
// very report.json lk_gap writes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "config_input.h"
#include "lane_keeping/common/errors.h"
#include "lane_keeping/gap/diagnosis.h"
#include "lane_keeping/gap/evaluation/config_change.h"
#include "lane_keeping/gap/log/gap_log.h"
#include "lane_keeping/gap/log/gap_run.h"
#include "lane_keeping/gap/log/log_reader.h"
#include "lane_keeping/gap/report/gap_report.h"

namespace py = pybind11;

namespace lane_keeping {
namespace python {
namespace {

/// A table of the Python side: (source, column names, 2-D float64 array rows x columns).
LogTable tableOf(py::handle table) {
  const py::tuple t = table.cast<py::tuple>();
  LogTable out;
  out.source = t[0].cast<std::string>();
  out.columns = t[1].cast<std::vector<std::string>>();
  const auto values = t[2].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  if (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != out.columns.size()) {
    throw InputError(out.source + ": the values must be a table of " + std::to_string(out.columns.size()) + " columns");
  }
  const std::size_t rows = static_cast<std::size_t>(values.shape(0));
  out.values.assign(out.columns.size(), std::vector<double>(rows));
  const auto v = values.unchecked<2>();
  for (std::size_t c = 0; c < out.columns.size(); ++c) {
    for (std::size_t r = 0; r < rows; ++r) out.values[c][r] = v(r, c);
  }
  return out;
}

/// One run as the Python side describes it: {"log": ("file", path) | ("table", source, names, values),
/// "scenario": layers or None, "log_map": layers or None}; as lk_gap's --log/--holdout, --scenario,
/// --log-map: the log's mapping is its own log_map's, else its scenario's log: section, else the nominal's.
GapRun runOf(py::handle item, const FlatParams& nominal_params, const LogMapping& shared_mapping) {
  const py::dict run = item.cast<py::dict>();
  LogMapping mapping = shared_mapping;
  const py::object scenario = run["scenario"], log_map = run["log_map"], log = run["log"];
  if (!scenario.is_none()) {
    const LogMapping m = logMappingOf(scenario);
    if (!m.source.empty()) mapping = m;
  }
  if (!log_map.is_none()) {
    mapping = logMappingOf(log_map);
    if (mapping.source.empty()) throw ConfigError("log_map: it has no log: section");
  }
  const py::tuple source = log.cast<py::tuple>();
  GapLog gap_log = source[0].cast<std::string>() == "file" ? readLog(source[1].cast<std::string>(), mapping)
                                                           : gapLogFromTable(tableOf(source[1]), mapping);
  if (scenario.is_none()) return gapRun(std::move(gap_log), nominal_params, FlatParams{}, "");
  const std::string origin = run["scenario_source"].cast<std::string>();
  return gapRun(std::move(gap_log), nominal_params, flatParamsOf(scenario), origin);
}

py::dict artifactsDict(const DiagnosisArtifacts& a) {
  py::dict d;
  d["residual_t"] = a.residual_t;
  d["residual"] = a.residual;
  d["spectrum_f"] = a.spectrum_f;
  d["spectrum"] = a.spectrum;
  d["overlay_t"] = a.overlay_t;
  d["overlay"] = a.overlay;
  return d;
}

/// The nominal configuration and the runs, read as lk_gap reads --config/--set, --log and --holdout.
struct GapInputs {
  SimConfig nominal;
  std::vector<GapRun> training, heldout;
};

GapInputs gapInputs(py::handle nominal_layers, py::sequence training_runs, py::sequence heldout_runs) {
  FlatParams nominal_params = flatParamsOf(nominal_layers);
  const LogMapping shared_mapping = logMappingOf(nominal_layers);
  nominal_params.erasePrefix("log.");
  GapInputs in;
  in.nominal = simConfigFromFlat(nominal_params);
  for (const auto& run : training_runs) in.training.push_back(runOf(run, nominal_params, shared_mapping));
  for (const auto& run : heldout_runs) in.heldout.push_back(runOf(run, nominal_params, shared_mapping));
  return in;
}

/// How far `change` ("key=value" texts) takes the closed loop toward the logs, as diagnose measures a verdict's
/// (closedLoopHowFar): report.json's how_far object for that change, as its text.
std::string howFar(py::handle nominal_layers, py::sequence training_runs, py::sequence heldout_runs,
                   const std::vector<std::string>& change, int threads) {
  if (threads < 1 || threads > 256) throw ConfigError("threads must be between 1 and 256");
  if (change.empty()) throw ConfigError("change: no key=value given (the change whose closed loop is measured)");
  const GapInputs in = gapInputs(nominal_layers, training_runs, heldout_runs);
  const ConfigChange with = assignmentsChange(change);
  (void)changed(in.nominal, with);  // a bad key or value: the reader's error naming it, before any replay
  DiagnosisOptions options;
  options.threads = threads;
  py::gil_scoped_release release;
  return closedLoopGapJson(closedLoopHowFar(in.training, in.heldout, with, options));
}

py::tuple diagnose(py::handle nominal_layers, py::sequence training_runs, py::sequence heldout_runs, py::dict options_in,
                   py::object progress) {
  DiagnosisOptions options;
  options.threads = options_in["threads"].cast<int>();
  options.noise_reference_draws = options_in["noise_reference_draws"].cast<int>();
  options.coarse_fit_stride = options_in["coarse_fit_stride"].cast<std::size_t>();
  options.effects = options_in["effects"].cast<std::vector<std::string>>();
  options.two_folds = options_in["two_folds"].cast<bool>();
  if (options_in.contains("every_fold")) options.every_fold = options_in["every_fold"].cast<bool>();
  if (options_in.contains("max_side_force")) {
    options.max_side_force = options_in["max_side_force"].cast<double>();
    if (!(options.max_side_force >= 0.0 && options.max_side_force <= 10.0)) {
      throw ConfigError("max_side_force must be between 0 and 10 (g)");
    }
  }
  if (options_in.contains("measured_corrections")) {
    options.correct_measured_sensor_errors = options_in["measured_corrections"].cast<bool>();
  }
  if (options_in.contains("targeted_test")) options.targeted_delay_test = options_in["targeted_test"].cast<bool>();
  options.leader_forms = options_in["leader_forms"].cast<bool>();
  if (options_in.contains("closed_loop_placement")) {
    options.closed_loop_placement = options_in["closed_loop_placement"].cast<bool>();
  }
  if (options.noise_reference_draws < 0 || options.noise_reference_draws > 100) {
    throw ConfigError("noise_reference_draws must be between 0 and 100");
  }
  if (options.coarse_fit_stride < 1) throw ConfigError("coarse_fit_stride must be at least 1");
  const GapInputs in = gapInputs(nominal_layers, training_runs, heldout_runs);
  for (const auto& effect : options.effects) {
    bool known = false;
    for (const auto& name : candidateEffectNames()) known = known || name == effect;
    if (!known) throw ConfigError("effects: '" + effect + "' is not a candidate effect");
  }
  if (!progress.is_none()) {
    // Called from the diagnosis' worker threads: each call takes the GIL for the Python callable.
    options.progress = [progress](const std::string& message) {
      py::gil_scoped_acquire acquire;
      progress(message);
    };
  }
  DiagnosisArtifacts artifacts;
  std::string report_json;
  {
    py::gil_scoped_release release;
    const GapReport report = diagnoseGap(in.nominal, in.training, in.heldout, options, &artifacts);
    report_json = gapReportJson(report);
  }
  return py::make_tuple(report_json, artifactsDict(artifacts));
}

}  // namespace

void bindGap(py::module_& m) {
  m.def("diagnose", &diagnose, py::arg("nominal_layers"), py::arg("training"), py::arg("heldout"), py::arg("options"),
        py::arg("progress") = py::none(), "lk_gap in-process: (report.json text, the plots' series).");
  m.def("candidate_effects", [] { return candidateEffectNames(); }, "The candidate effects' names, as report.json names them.");
  m.def("how_far", &howFar, py::arg("nominal_layers"), py::arg("training"), py::arg("heldout"), py::arg("change"),
        py::arg("threads"), "The closed loop with a change against the logs, as diagnose measures a verdict's how far (how_far's JSON).");
}

}  // namespace python
}  // namespace lane_keeping
