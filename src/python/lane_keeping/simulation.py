"""simulate and simulate_many: lk_simulate in-process (docs/python_api.md)."""

import os
from collections.abc import Mapping

from . import _lane_keeping
from ._inputs import change_texts, config_layers

LOG_COLUMNS = tuple(_lane_keeping.LOG_COLUMNS)


class Run:
    """One closed-loop run.

    log:      the log, the columns of `lk_simulate --out` (LOG_COLUMNS) with the same numbers: a pandas
              DataFrame, a dict of numpy arrays (as_frame=False), or None (log=False)
    summary:  the run summary (lk_simulate's, as a dict): offsets, settling, peaks, and each mode's
              oscillation ("lateral": e_y, "steering": delta - delta_des) with its growth rate [1/s]
    status:   "completed" or "diverged" (then `message` says why; lk_simulate exits 3)
    text:     the summary as lk_simulate prints it
    changes:  the runtime changes that took effect, each a dict (t, key, old_value, new_value, ...)
    plant_steps, end_time [s]

    `log, summary = lk.simulate(...)` unpacks the first two.
    """

    __slots__ = ("log", "summary", "status", "message", "text", "changes", "plant_steps", "end_time")

    def __init__(self, result, as_frame):
        self.log = _log_of(result, as_frame)
        self.summary = result["summary"]
        self.status = result["status"]
        self.message = result["message"]
        self.text = result["summary_text"]
        self.changes = result["changes"]
        self.plant_steps = result["plant_steps"]
        self.end_time = result["end_time"]

    @property
    def diverged(self):
        return self.status == "diverged"

    def __iter__(self):
        return iter((self.log, self.summary))

    def __repr__(self):
        rows = "no log" if self.log is None else f"{len(self.log['t'])} rows"
        return f"<lane_keeping.Run {self.summary['scenario']!r}: {self.status} {self.end_time:g} s, {rows}>"


def _log_of(result, as_frame):
    values = result["values"]
    if values is None:
        return None
    if as_frame:
        import pandas as pd
        return pd.DataFrame(values, columns=list(LOG_COLUMNS), copy=False)
    return {name: values[:, i] for i, name in enumerate(LOG_COLUMNS)}


def simulate(config=None, changes=None, *, overrides=None, log=True, as_frame=True, out=None):
    """One closed-loop run, as `lk_simulate --config ... --set ... --change ... --out run.csv`.

    config:    a path to a YAML file, YAML text, a nested dict of the configuration schema (dotted keys
               allowed), or a list of these overlaid in order on the paper's defaults; None: the defaults
    changes:   runtime changes: "T:key=value" texts, (T, key, value) tuples or {T: {key: value}}
    overrides: {"key": value} or ["key=value", ...], applied last (lk_simulate --set)
    log:       False: keep only the summary (faster for sweeps)
    as_frame:  the log as a pandas DataFrame (True) or a dict of numpy arrays (False)
    out:       a path: also write the log there as CSV, by lk_simulate --out's own writer

    Returns a Run (`log, summary = simulate(...)`). A diverged run is a result, not an error (status
    "diverged"). Raises ConfigError naming every bad key (the message lk_simulate prints), ScheduleError
    when the delays leave the lockstep schedule no lookahead.
    """
    result = _lane_keeping.simulate(config_layers(config, overrides), change_texts(changes), bool(log),
                                    "" if out is None else os.fspath(out))
    return Run(result, as_frame)


def _is_one_config(configs):
    return configs is None or isinstance(configs, (str, os.PathLike, Mapping))


def simulate_many(configs, changes=None, *, overrides=None, threads=None, log=True, as_frame=True):
    """A batch of runs in one call, on `threads` threads (default: every core) without the GIL.

    configs:   a list of configurations (each as simulate() takes it; a tuple is one configuration's
               layers), or one configuration that every override is applied to
    overrides: None, or a list (one per run) of {"key": value} or ["key=value", ...]: with one
               configuration, the batch is one run per override (a sweep)
    changes:   runtime changes applied to every run

    Returns the Runs in the order given; each equals simulate() of its configuration, whatever the number
    of threads (every run has its own objects; the core shares only immutable data). A bad configuration
    raises ConfigError naming it (configs[i]) before any run starts.
    """
    if _is_one_config(configs):
        if overrides is None:
            configs = [configs]
        else:
            configs = [configs] * len(overrides)
    else:
        configs = list(configs)
    if overrides is None:
        overrides = [None] * len(configs)
    overrides = list(overrides)
    if len(overrides) != len(configs):
        raise ValueError(f"simulate_many: {len(configs)} configurations but {len(overrides)} overrides")
    layer_lists = [config_layers(c, o) for c, o in zip(configs, overrides)]
    texts = change_texts(changes)
    threads = (os.cpu_count() or 1) if threads is None else int(threads)
    if threads < 1:
        raise ValueError("simulate_many: threads must be at least 1")
    results = _lane_keeping.simulate_many(layer_lists, [texts] * len(layer_lists), threads, bool(log))
    return [Run(result, as_frame) for result in results]


def effective_config(config=None, *, overrides=None, docs=False):
    """The effective configuration as YAML text (`lk_simulate --print-config`); `docs`: with each key's
    unit and meaning."""
    return _lane_keeping.effective_config(config_layers(config, overrides), bool(docs))
