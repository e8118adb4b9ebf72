"""diagnose: lk_gap in-process; how_far: the closed loop with a change of one's own (docs/python_api.md)."""

import json
import os
from collections.abc import Mapping

from . import _lane_keeping
from ._inputs import config_layers, log_source


def candidate_effects():
    """The candidate effects, as report.json names them."""
    return list(_lane_keeping.candidate_effects())


def _run(item, name):
    """One run: a log (path, DataFrame, dict of columns), or {"log": ..., "scenario": ..., "log_map": ...}
    (lk_gap's --log with --scenario and --log-map)."""
    if isinstance(item, Mapping) and "log" in item:
        unknown = set(item) - {"log", "scenario", "log_map"}
        if unknown:
            raise ValueError(f"{name}: unknown entries {sorted(unknown)} (log, scenario, log_map)")
        scenario, log_map = item.get("scenario"), item.get("log_map")
        log = item["log"]
    else:
        scenario = log_map = None
        log = item
    scenario_source = ""
    if scenario is not None:
        scenario_source = os.fspath(scenario) if isinstance(scenario, (str, os.PathLike)) else f"{name} scenario"
    return {"log": log_source(log, name),
            "scenario": None if scenario is None else config_layers(scenario),
            "scenario_source": scenario_source,
            "log_map": None if log_map is None else config_layers(log_map)}


def _runs(items, name):
    if items is None:
        return []
    if isinstance(items, (str, os.PathLike, Mapping)) or hasattr(items, "to_numpy"):
        items = [items]
    return [_run(item, f"{name}[{i}]") for i, item in enumerate(items)]


def _assignments(change):
    """A change as "key=value" texts: a dict of dotted keys and values, or "key=value" texts."""
    if isinstance(change, Mapping):
        out = []
        for key, value in change.items():
            if isinstance(value, Mapping):
                raise TypeError(f"change: {key}: give dotted keys ({key}.name: value), not a nested dict")
            text = ("true" if value else "false") if isinstance(value, bool) else str(value)
            out.append(f"{key}={text}")
        return out
    if isinstance(change, str):
        return [change]
    out = list(change)
    for assignment in out:
        if not isinstance(assignment, str):
            raise TypeError(f"change: expected a dict or 'key=value' texts, found {assignment!r}")
    return out


def how_far(nominal, logs, holdout=None, *, change, overrides=None, threads=2):
    """How far a change of the configuration takes the closed loop toward the logs — the third question, asked of
    a change of one's own (a fitted effect, a value from a test bench) — measured as diagnose() measures its
    verdict's (report["how_far"]): the closed-loop replays of the held-out runs (of the training runs where
    none is held out) with each run's configuration and with `change`, gross and net of the logs' noise.

    nominal, logs, holdout, overrides: as diagnose() takes them
    change:  {"tire.front.lateral_stiffness": 1.8e6, ...} or ["key=value", ...] (as lk_gap --set takes them)

    Returns report.json's how_far object for the change as a dict ("before", "after", "shrink", "noise_floor",
    "net_before", "net_after", "net_shrink"; None where not run, and "not_run" saying why). Raises ConfigError
    naming a bad key or value, InputError for a bad log.
    """
    return json.loads(_lane_keeping.how_far(config_layers(nominal, overrides), _runs(logs, "logs"),
                                            _runs(holdout, "holdout"), _assignments(change), int(threads)))


def diagnose(nominal, logs, holdout=None, *, overrides=None, effects=None, threads=2, noise_reference_draws=19,
             coarse_fit_stride=3, two_folds=True, every_fold=False, leader_forms=True, measured_corrections=True,
             targeted_test=True, max_side_force=0.1, closed_loop_placement=True, progress=None, series=False):
    """The sim-to-real gap diagnosis, as `lk_gap --config NOMINAL --log ... [--holdout ...] --report DIR`.

    nominal:  the nominal configuration (as simulate() takes it; a `log:` section maps every log's columns)
    logs:     the training runs: each a CSV or bag path, a pandas DataFrame (the CSV's columns) or a dict of
              columns, or {"log": ..., "scenario": ..., "log_map": ...} with the run's own scenario (per-run
              settings: a path, YAML text or dict) and log mapping
    holdout:  held-out runs, the same forms; None: blocks of the training logs are held out
    overrides: applied to the nominal last (lk_gap --set)
    effects:  restrict the candidates (lk_gap --effects); threads, noise_reference_draws, coarse_fit_stride:
              lk_gap's options of those names
    two_folds: hold each side out in turn where the held-out side alone misses the gap (False: lk_gap --one-fold);
               with three runs or more, each run in turn
    every_fold: hold every run (or side) out in turn even where the held-out side alone detects the gap
                (lk_gap --every-fold); report["folds"] lists each
    leader_forms: fit the LuGre, soft or contact-length form of the leader and of further effects
                  (False: lk_gap --candidate-forms-only)
    measured_corrections: correct the gyro's scale and drift that the input checks measure against psi and ay / V
                          before the fits, and name them (False: lk_gap --no-measured-corrections, reported only)
    targeted_test: where the replays' test sees no gap, test the actuation delay's fit against the same fit on
                   the noise-only draws (False: lk_gap --no-targeted-test)
    max_side_force: the largest steady side force [g of the car's weight] a candidate may fit and still be the
                    cause (lk_gap --max-side-force; 0 lifts the bound)
    closed_loop_placement: place one named effect by the training runs' closed loop, among the values its replays
                           cannot tell apart, where its closed loop closes clearly less than its replays
                           (False: lk_gap --no-closed-loop-placement; the placed values in the effect's "params",
                           the replays' own in its "replay_params")
    progress: a callable given each progress message (lk_gap prints them on stderr)
    series:   also return the plots' series (residuals.csv, spectrum.csv, overlay.csv) as DataFrames

    Returns report.json as a dict (with series=True: (report, series)). Raises ConfigError and InputError
    with lk_gap's messages (a DataFrame's rows are named "DataFrame logs[i] row N", counting from 0).
    """
    options = {"threads": int(threads), "noise_reference_draws": int(noise_reference_draws),
               "coarse_fit_stride": int(coarse_fit_stride), "effects": list(effects or []),
               "two_folds": bool(two_folds), "every_fold": bool(every_fold), "leader_forms": bool(leader_forms),
               "measured_corrections": bool(measured_corrections), "targeted_test": bool(targeted_test),
               "max_side_force": float(max_side_force), "closed_loop_placement": bool(closed_loop_placement)}
    text, artifacts = _lane_keeping.diagnose(config_layers(nominal, overrides), _runs(logs, "logs"),
                                             _runs(holdout, "holdout"), options, progress)
    report = json.loads(text)
    if not series:
        return report
    import pandas as pd
    subsystems = ["tracker", "actuator", "steering", "chassis"]
    overlay = ["y_real", "y_nominal", "y_corrected", "yaw_rate_real", "yaw_rate_nominal", "yaw_rate_corrected",
               "delta_real", "delta_nominal", "delta_corrected"]

    def frame(first, x, columns, data):
        table = {first: x}
        for c in columns:
            values = data.get(c, [])
            table[c] = list(values) + [float("nan")] * (len(x) - len(values))
        return pd.DataFrame(table)

    return report, {
        "residuals": frame("t", artifacts["residual_t"], subsystems, artifacts["residual"]),
        "spectrum": frame("f", artifacts["spectrum_f"], subsystems, artifacts["spectrum"]),
        "overlay": frame("t", artifacts["overlay_t"], overlay, artifacts["overlay"]),
    }
