"""The gap command's tasks: one lk_gap per log. On the client, the logs the --logs globs match, their
scenarios (--scenarios), the lk_gap arguments and one task spec per log; on a worker, gap_task runs lk_gap
into an attempt folder, publishes the report and stores the result with the fleet's summary of report.json.

Depends on messages, storage, tool and results. gap_task runs on the Dask workers (shipped by value: see
cluster)."""
import fnmatch
import glob
import json
import os
import shlex
import shutil
import tempfile

from .messages import UsageError
from .results import file_digest, new_result, store_result, task_id
from .storage import publish_dir
from .tool import ToolKilled, run_tool

LOG_SUFFIXES = (".csv", ".bag")
# Arguments lk_fleet gives lk_gap itself; --extra-args may not repeat them.
GAP_OWNED_ARGS = ("--config", "--log", "--scenario", "--report", "--holdout", "--log-map")


def summarize_gap_report(report):
    """The fleet's view of one report.json: the verdict, its fitted parameters (from the ranking entry
    of the verdict's effect and form; an unexplained verdict has none), where, how far."""
    verdict = report.get("verdict", {})
    effect, form = verdict.get("effect", ""), verdict.get("form", "")
    chosen = next((entry for entry in report.get("ranking", [])
                   if entry.get("effect") == effect and entry.get("form", "") == form), {})
    how_far = report.get("how_far", {})
    heldout = report.get("detection", {}).get("heldout", {})
    return {
        "effect": effect,
        "form": form,
        "confidence": verdict.get("confidence"),
        "shrink": verdict.get("shrink"),
        "gap_before": verdict.get("gap_before"),
        "gap_after": verdict.get("gap_after"),
        "how_far_shrink": how_far.get("shrink"),
        "where": report.get("where", {}).get("subsystem", ""),
        "detected": heldout.get("detected"),
        "p_value": heldout.get("p_value"),
        "params": chosen.get("params", {}),
        "param_sigma": chosen.get("param_sigma", {}),
        "config_overlay": chosen.get("config", {}),
        "reason": verdict.get("reason", ""),
        "stage_seconds": {s["stage"]: s["seconds"] for s in report.get("wall_seconds", [])},
    }


def gap_task(spec):
    """Worker side: lk_gap on one log, the report under OUT/reports/<task-id>, the result stored."""
    out, tid = spec["out"], spec["task_id"]
    reports = os.path.join(out, "reports")
    os.makedirs(reports, exist_ok=True)
    attempt = tempfile.mkdtemp(prefix=f".{tid}.", dir=reports)
    try:
        code, stdout, stderr, wall = run_tool(spec["argv"] + ["--report", attempt], spec["timeout"])
    except ToolKilled:
        shutil.rmtree(attempt, ignore_errors=True)  # half a report; the retry makes its own
        raise
    result = new_result(spec, code, stdout, stderr, wall)
    if result["status"] == "ok":
        try:
            with open(os.path.join(attempt, "report.json")) as f:
                result["summary"] = summarize_gap_report(json.load(f))
            result["report_dir"] = publish_dir(attempt, os.path.join(reports, tid))
        except (OSError, ValueError) as exc:
            result.update(status="failed", error_kind="unreadable report",
                          error=f"lk_gap exited 0 but its report.json is unreadable: {exc}")
    if result["status"] != "ok":
        shutil.rmtree(attempt, ignore_errors=True)
    return store_result(out, result)


def expand_logs(patterns, out=None):
    """Log files matched by the --logs globs (recursive '**'), .csv and .bag only, without duplicates.
    Files under `out` (the fleet's own reports: their residuals.csv and overlay.csv) are not logs; a
    symbolic link to nothing is refused by name rather than dropped."""
    out_real = os.path.realpath(out) if out else None
    logs = []
    for pattern in patterns:
        matches = []
        for p in glob.glob(os.path.expanduser(pattern), recursive=True):
            if not p.endswith(LOG_SUFFIXES):
                continue
            if os.path.islink(p) and not os.path.exists(p):
                raise UsageError("--logs", f"'{p}' is a symbolic link to '{os.readlink(p)}', which does not exist")
            real = os.path.realpath(p)
            if out_real and (real == out_real or real.startswith(out_real + os.sep)):
                continue
            if os.path.isfile(p):
                matches.append(os.path.abspath(p))
        if not matches:
            raise UsageError("--logs", f"no log matched '{pattern}' (.csv and .bag files are logs; files under --out "
                                       "are the fleet's own)")
        logs.extend(matches)
    return sorted(set(logs))


def read_scenario_map(path):
    """--scenarios MAP.yaml: 'log glob or name: scenario file' lines, first match wins; scenario paths
    are relative to the map file. (PyYAML comes with dask.)"""
    import yaml
    try:
        with open(path) as f:
            mapping = yaml.safe_load(f) or {}
    except (OSError, yaml.YAMLError) as exc:
        raise UsageError("--scenarios", f"cannot read '{path}': {exc}")
    if not isinstance(mapping, dict):
        raise UsageError("--scenarios", f"'{path}' must map log globs to scenario files")
    base = os.path.dirname(os.path.abspath(path))
    entries = []
    for pattern, scenario in mapping.items():
        scenario = os.path.join(base, str(scenario))
        if not os.path.isfile(scenario):
            raise UsageError("--scenarios", f"'{path}': scenario '{scenario}' for '{pattern}' does not exist")
        entries.append((str(pattern), scenario))
    return entries


def scenario_for(log, entries):
    """The scenario of a log: the first map entry whose glob matches its path (absolute or relative to
    the working directory) or its file name."""
    names = (log, os.path.relpath(log), os.path.basename(log))
    for pattern, scenario in entries:
        if any(fnmatch.fnmatch(name, pattern) for name in names):
            return scenario
    return None


def gap_tool_args(args):
    """The lk_gap arguments shared by every log: --extra-args, with the fleet's defaults (one thread per
    task: Dask runs the tasks in parallel; no per-log plots unless asked)."""
    try:
        extra = shlex.split(args.extra_args)
    except ValueError as exc:
        raise UsageError("--extra-args", str(exc))
    owned = [a for a in extra if a.split("=")[0] in GAP_OWNED_ARGS]
    if owned:
        raise UsageError("--extra-args", f"{', '.join(owned)} is set by lk_fleet per log")
    if "--threads" not in extra:
        extra += ["--threads", "1"]
    if not args.per_log_plots and "--no-plots" not in extra:
        extra.append("--no-plots")
    if "--quiet" not in extra:
        extra.append("--quiet")
    return extra


def gap_specs(args, lk_gap):
    """One task per log; the task id hashes the log's path, the nominal and scenario contents and the
    tool's arguments."""
    logs = expand_logs(args.logs, args.out)
    entries = read_scenario_map(args.scenarios) if args.scenarios else []
    tool_args = gap_tool_args(args)
    config = os.path.abspath(args.config)
    config_digest = file_digest(config)
    specs = []
    for log in logs:
        scenario = scenario_for(log, entries)
        inputs = {"tool": "lk_gap", "log": log, "config": config, "scenario": scenario, "args": tool_args}
        tid = task_id({**inputs, "config": config_digest,
                       "scenario": [scenario, file_digest(scenario)] if scenario else None})
        argv = [lk_gap, "--config", config, "--log", log] + (["--scenario", scenario] if scenario else []) + tool_args
        specs.append({"kind": "gap", "task_id": tid, "inputs": inputs, "argv": argv, "out": args.out,
                      "timeout": args.task_timeout, "size": os.path.getsize(log)})
    return specs
