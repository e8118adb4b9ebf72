// simulate and simulate_many: the closed loop of lk_simulate (ClosedLoop, summarizeRun), its log as one
// float64 array whose columns are logColumns() in order, filled by logValues(): the very values
// lk_simulate --out prints with %.17g, so a log and its CSV agree to the bit.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <sstream>

#include "bindings.h"
#include "config_input.h"
#include "lane_keeping/common/parallel_for.h"
#include "lane_keeping/sim/closed_loop.h"
#include "lane_keeping/sim/run_summary.h"

namespace py = pybind11;

namespace lane_keeping {
namespace python {
namespace {

/// One run, made without the GIL: the configuration and changes are read under it first.
struct Job {
  SimConfig config;
  std::optional<ClosedLoop> loop;  ///< validated, its changes scheduled (ConfigError, ScheduleError) under the GIL
  RunResult result;
  RunSummary summary;
};

void run(Job& job) {
  job.result = job.loop->run();
  job.summary = summarizeRun(job.config, job.result);
}

py::dict oscillationDict(const OscillationEstimate& o) {
  py::dict d;
  d["valid"] = o.valid;
  d["frequency_hz"] = o.frequency_hz;
  d["growth_rate"] = o.growth_rate;
  d["rms_first"] = o.rms_first;
  d["rms_last"] = o.rms_last;
  d["cycles"] = o.cycles;
  d["regular"] = o.regular;
  d["trend"] = o.trend();
  return d;
}

py::dict summaryDict(const RunSummary& s) {
  py::dict d;
  d["scenario"] = s.scenario;
  d["diverged"] = s.diverged;
  d["stop_message"] = s.stop_message;
  d["duration"] = s.duration;
  d["final_lateral_offset"] = s.final_lateral_offset;
  d["peak_lateral_offset"] = s.peak_lateral_offset;
  d["peak_lateral_offset_time"] = s.peak_lateral_offset_time;
  d["settling_time"] = s.settling_time >= 0.0 ? py::object(py::float_(s.settling_time)) : py::object(py::none());
  d["settling_band"] = s.settling_band;
  d["peak_steering_angle"] = s.peak_steering_angle;
  d["peak_torque"] = s.peak_torque;
  d["peak_lateral_acceleration"] = s.peak_lateral_acceleration;
  d["peak_slip_angle"] = s.peak_slip_angle;
  d["left_lane"] = s.left_lane;
  d["lateral"] = oscillationDict(s.lateral);
  d["steering"] = oscillationDict(s.steering);
  d["changes"] = s.changes;
  return d;
}

py::array_t<double> logArray(const std::vector<LogRow>& rows) {
  py::array_t<double> values({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(kLogColumnCount)});
  double* out = values.mutable_data();
  for (const LogRow& row : rows) {
    logValues(row, out);
    out += kLogColumnCount;
  }
  return values;
}

py::dict resultDict(const Job& job, bool with_log) {
  py::dict d;
  d["status"] = job.result.diverged() ? "diverged" : "completed";
  d["message"] = job.result.message;
  d["end_time"] = job.result.end_time;
  d["plant_steps"] = job.result.plant_steps;
  d["rows"] = job.result.rows.size();
  d["columns"] = logColumns();
  d["values"] = with_log ? py::object(logArray(job.result.rows)) : py::object(py::none());
  d["summary"] = summaryDict(job.summary);
  d["summary_text"] = formatSummary(job.summary);
  std::vector<ScheduledChange> changes = job.result.changes;
  sortForSummary(changes);
  py::list change_list;
  for (const ScheduledChange& c : changes) {
    py::dict change;
    change["t"] = nanosecondsToSeconds(c.stamp);
    change["key"] = c.key;
    change["old_value"] = c.old_value;
    change["new_value"] = c.new_value;
    change["argument"] = c.argument();
    change["description"] = c.describe();
    change_list.append(change);
  }
  d["changes"] = change_list;
  return d;
}

Job jobOf(py::handle layers, py::handle changes) {
  Job job;
  job.config = simConfigOf(layers);
  job.loop.emplace(job.config, timedChangesOf(changes));
  return job;
}

py::dict simulate(py::handle layers, py::handle changes, bool with_log, const std::string& csv_path) {
  Job job = jobOf(layers, changes);
  {
    py::gil_scoped_release release;
    run(job);
    if (!csv_path.empty()) writeLogCsv(csv_path, job.result.rows);  // lk_simulate --out's writer
  }
  return resultDict(job, with_log);
}

py::list simulateMany(py::sequence layer_lists, py::sequence change_lists, int threads, bool with_log) {
  if (change_lists.size() != layer_lists.size()) throw std::invalid_argument("simulate_many: one change list per configuration");
  std::vector<Job> jobs;
  jobs.reserve(layer_lists.size());
  for (std::size_t i = 0; i < layer_lists.size(); ++i) {
    try {
      jobs.push_back(jobOf(layer_lists[i], change_lists[i]));
    } catch (const ConfigError& e) {
      // Which configuration of the batch is wrong, then the core's own list of problems.
      const std::string where = "configs[" + std::to_string(i) + "]";
      std::vector<ConfigProblem> problems = e.problems();
      if (problems.empty()) throw ConfigError(where + ": " + e.what());
      for (ConfigProblem& p : problems) p.location = where + (p.location.empty() ? "" : " " + p.location);
      throw ConfigError(problems);
    } catch (const ScheduleError& e) {
      throw ScheduleError("configs[" + std::to_string(i) + "]: " + e.what());
    }
  }
  {
    py::gil_scoped_release release;
    // Each run owns its configuration, loop and result; the core shares only immutable data between
    // runs (a lane's points, the path cache behind its mutex), so the runs are independent.
    parallelFor(jobs.size(), threads, [&](std::size_t i) { run(jobs[i]); });
  }
  py::list results;
  for (const Job& job : jobs) results.append(resultDict(job, with_log));
  return results;
}

std::string effectiveConfig(py::handle layers, bool with_docs) {
  std::ostringstream out;
  simConfigOf(layers).print(out, with_docs);
  return out.str();
}

}  // namespace

void bindSimulation(py::module_& m) {
  m.def("simulate", &simulate, py::arg("layers"), py::arg("changes"), py::arg("with_log") = true,
        py::arg("csv_path") = std::string(),
        "One closed-loop run (lk_simulate): a dict with the log's columns and values, the summary and the changes; "
        "with csv_path, the log written there as lk_simulate --out writes it.");
  m.def("simulate_many", &simulateMany, py::arg("layer_lists"), py::arg("change_lists"), py::arg("threads") = 1,
        py::arg("with_log") = true, "Runs on `threads` threads without the GIL; results in the order given.");
  m.def("effective_config", &effectiveConfig, py::arg("layers"), py::arg("with_docs") = false,
        "The effective configuration as YAML (lk_simulate --print-config).");
  m.attr("LOG_COLUMNS") = logColumns();
}

}  // namespace python
}  // namespace lane_keeping
