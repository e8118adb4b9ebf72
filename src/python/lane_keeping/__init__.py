"""lane_keeping: the lane-keeping loop, its stability analysis and the sim-to-real gap diagnosis in Python.

    import lane_keeping as lk
    log, summary = lk.simulate("config/scenarios/fig6.yaml")          # the log as a pandas DataFrame
    runs = lk.simulate_many(["fig6.yaml"] * 8, overrides=[{"tracker.k_y": k} for k in ks], threads=2)
    report = lk.diagnose("nominal.yaml", ["run.csv"])                   # report.json as a dict
    critical = lk.critical_delay("config/scenarios/fig9.yaml")         # lk_stability critical
    chart = lk.stability_chart("fig6.yaml", x=("tracker.k_psi", 0, 2.5, 50), y=("tracker.k_y", 0, 0.3, 50))

A thin layer over the C++ core (the extension module lane_keeping._lane_keeping, built by the catkin
package with pybind11): the same code the command-line tools and the ROS nodes run, so the results are
theirs to the bit. docs/python_api.md describes every function.

This file also runs inside the package that catkin generates in devel space beside the message (msg,
srv) and dynamic_reconfigure (cfg) modules; the API is imported on first use, so that `import
lane_keeping.msg` (the rostests, dynamic_reconfigure's client) stays as light as it was.
"""

# Imported without the relay (a process spawned by multiprocessing inherits the relay's sys.path entry for this
# folder, ahead of the devel space: Dask's workers do), the package still finds its other half, the extension and
# the message modules in the devel space's lane_keeping folder on sys.path.
__path__ = __import__("pkgutil").extend_path(__path__, __name__)

_API = {
    "simulate": "simulation",
    "simulate_many": "simulation",
    "effective_config": "simulation",
    "Run": "simulation",
    "LOG_COLUMNS": "simulation",
    "diagnose": "gap",
    "candidate_effects": "gap",
    "how_far": "gap",
    "critical_delay": "stability",
    "rightmost_roots": "stability",
    "stability_boundary": "stability",
    "stability_chart": "stability",
    "LaneKeepingError": "_lane_keeping",
    "ConfigError": "_lane_keeping",
    "InputError": "_lane_keeping",
    "ModelError": "_lane_keeping",
    "ScheduleError": "_lane_keeping",
}


def __getattr__(name):
    module = _API.get(name)
    if module is None:
        raise AttributeError(f"module 'lane_keeping' has no attribute '{name}'")
    import importlib
    value = getattr(importlib.import_module("lane_keeping." + module), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(list(globals()) + list(_API))
