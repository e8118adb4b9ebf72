#!/usr/bin/python3
"""lk_fleet: run lane_keeping's command-line tools over many inputs on Dask.

  lk_fleet gap   --config nominal.yaml --logs 'DIR/**/*.csv' --out DIR [--scenarios MAP.yaml] ...
  lk_fleet sweep --config base.yaml --grid key=start:stop:step [--grid ...]
                 [--monte-carlo N --vary 'key=normal(mu,sigma)' ...] --out DIR ...

Thin by design: each task launches one C++ tool (lk_gap per log, lk_simulate per sweep point) with
subprocess; Dask only places the tasks. Every task's result is written atomically to
OUT/results/<task-id>.json, the task id being a hash of the task's inputs, so a rerun of the same
command skips what is done and the reports count each task once. Design and measured figures:
docs/fleet.md. Exit status: 0 every task has a result (a log the tool refused is a result: the report
lists it as failed), 1 a task Dask gave up on (its workers kept dying), 2 bad arguments, 130 interrupted
(the results written so far are kept; a rerun resumes).
"""
import argparse
import csv
import fnmatch
import glob
import hashlib
import io
import itertools
import json
import logging
import math
import os
import re
import shlex
import shutil
import socket
import subprocess
import sys
import tempfile
import time

RESULT_FORMAT = "lane_keeping.fleet_result"
RESULT_VERSION = 1
DEFAULT_LK_BIN = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                              "build", "ws", "devel", "lib", "lane_keeping")
LOG_SUFFIXES = (".csv", ".bag")
STDERR_TAIL_LINES = 20
STDERR_TAIL_CHARS = 4000
# lk_simulate exits 3 when the run diverged: a result of the sweep, not a failure.
SIMULATE_DIVERGED = 3
# Columns of the lk_simulate log a sweep point is summarised from.
SWEEP_COLUMNS = ("t", "e_y", "delta", "torque")
SWEEP_METRICS = ("max_abs_e_y", "rms_e_y", "late_rms_e_y", "max_abs_delta", "max_abs_torque")
# What the tools' exit codes mean (lk_gap.cpp, lk_simulate.cpp), for the reports.
EXIT_MEANINGS = {
    "lk_gap": {1: "error", 2: "bad arguments or configuration", 3: "configuration error", 4: "bad input data"},
    "lk_simulate": {1: "error", 2: "bad configuration", 3: "diverged"},
}
# Arguments lk_fleet gives lk_gap itself; --extra-args may not repeat them.
GAP_OWNED_ARGS = ("--config", "--log", "--scenario", "--report", "--holdout", "--log-map")


class UsageError(Exception):
    """Bad command-line input: reported as 'argument NAME: message', exit status 2."""

    def __init__(self, argument, message):
        super().__init__(f"argument {argument}: {message}")


class ToolKilled(RuntimeError):
    """The tool died from a signal (worker shutdown, OOM killer): raised so that Dask retries the task."""


# ----------------------------------------------------------------------------------------------------
# Task identity and atomic storage


def file_digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def task_id(fields):
    """A stable id for a task: the hash of its inputs in canonical JSON (sorted keys)."""
    canonical = json.dumps(fields, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()[:16]


def write_bytes_atomic(path, data):
    """Write, fsync and rename in the same directory: a reader (or a rerun after a crash) sees the old
    file or the complete new one, never a torn one."""
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".tmp-" + os.path.basename(path) + ".", dir=directory)
    try:
        os.fchmod(fd, 0o644)  # mkstemp makes 0600; the results are for everyone who reads the report
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    # The rename itself is durable only once the directory entry is on disk.
    dir_fd = os.open(directory, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def write_json_atomic(path, obj):
    write_bytes_atomic(path, (json.dumps(obj, indent=1, sort_keys=True) + "\n").encode())


def result_path(out, tid):
    return os.path.join(out, "results", tid + ".json")


def store_result(out, result):
    """Store a task's result, unless it would replace a good one with a failure: a second attempt of a
    task (a worker thought dead that was not) must not undo the first's verdict."""
    path = result_path(out, result["task_id"])
    if result["status"] != "ok" and load_result(out, result["task_id"]) is not None:
        with open(path) as f:
            stored = json.load(f)
        if stored["status"] == "ok":
            return stored
    write_json_atomic(path, result)
    return result


def load_result(out, tid):
    """The stored result of a task, or None when it must (re)run: absent, unreadable, or an
    infrastructure error (status 'error', e.g. a task whose workers kept dying) rather than a verdict or
    a failure of the tool on its input."""
    try:
        with open(result_path(out, tid)) as f:
            result = json.load(f)
    except (OSError, ValueError):
        return None
    if result.get("format") != RESULT_FORMAT or result.get("status") not in ("ok", "failed"):
        return None
    return result


# ----------------------------------------------------------------------------------------------------
# Running one tool (on a worker)


def die_with_worker(argv):
    """The command, run so that it gets SIGKILL when the worker that launched it dies: a SIGKILLed worker
    must leave no orphan computing a task that Dask has already given to another worker. util-linux's
    setpriv sets the parent-death signal and execs the tool (+10 ms a task here); a preexec_fn calling
    prctl would do the same but forces fork() of the whole worker instead of vfork() (+50 ms a task)."""
    setpriv = shutil.which("setpriv")
    return [setpriv, "--pdeathsig", "KILL", "--"] + argv if setpriv else argv


def tail(text, lines=STDERR_TAIL_LINES, chars=STDERR_TAIL_CHARS):
    return "\n".join(text.strip().splitlines()[-lines:])[-chars:]


def run_tool(argv, timeout):
    """Run a tool; returns (exit code or None on timeout, stdout, stderr, wall seconds). A tool killed by
    a signal raises ToolKilled: that is the machine's doing, not the input's, and worth a retry."""
    start = time.monotonic()
    try:
        proc = subprocess.run(die_with_worker(argv), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              errors="replace", timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        stderr = exc.stderr.decode(errors="replace") if isinstance(exc.stderr, bytes) else (exc.stderr or "")
        return None, "", stderr + f"\nlk_fleet: timed out after {timeout} s", time.monotonic() - start
    if proc.returncode < 0:
        raise ToolKilled(f"{os.path.basename(argv[0])} killed by signal {-proc.returncode}: {tail(proc.stderr)}")
    return proc.returncode, proc.stdout, proc.stderr, time.monotonic() - start


def new_result(spec, code, stdout, stderr, wall, ok_codes=(0,)):
    """The fields every task result carries; status 'failed' for a nonzero exit (bad input, bad
    configuration, timeout): a result like any other, recorded and not retried."""
    ok = code in ok_codes
    tool = spec["inputs"]["tool"]
    meaning = "timed out" if code is None else EXIT_MEANINGS[tool].get(code, "error")
    return {
        "format": RESULT_FORMAT,
        "version": RESULT_VERSION,
        "task_id": spec["task_id"],
        "kind": spec["kind"],
        "inputs": spec["inputs"],
        "argv": spec["argv"],
        "status": "ok" if ok else "failed",
        "exit_code": code,
        "error_kind": "" if ok else f"{meaning} (exit {code})",
        "error": "" if ok else tail(stderr) or tail(stdout),
        "wall_seconds": wall,
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "finished_at": time.time(),
    }


def publish_dir(attempt_dir, final_dir):
    """Move an attempt's output to its final name. Each attempt writes to its own directory, so a retry
    never mixes files with an earlier attempt; a stale earlier copy is replaced."""
    if os.path.exists(final_dir):
        trash = tempfile.mkdtemp(prefix=".old-", dir=os.path.dirname(final_dir))
        os.rename(final_dir, os.path.join(trash, "x"))
        shutil.rmtree(trash, ignore_errors=True)
    os.rename(attempt_dir, final_dir)
    return final_dir


# ----------------------------------------------------------------------------------------------------
# gap: one lk_gap per log


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


# ----------------------------------------------------------------------------------------------------
# sweep: one lk_simulate per point


def summarize_run_csv(path, diverged):
    """Stability figures of one closed-loop log: peaks and RMS of the lateral error, steering angle and
    torque, over the whole run and its last quarter (decay or not), and whether it stayed bounded."""
    import numpy as np
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    missing = [c for c in SWEEP_COLUMNS if c not in header]
    if missing:
        raise ValueError(f"{path}: no column {', '.join(missing)} (found {', '.join(header)})")
    columns = [header.index(c) for c in SWEEP_COLUMNS]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=columns, ndmin=2)
    t, e_y, delta, torque = (data[:, i] for i in range(len(SWEEP_COLUMNS)))
    finite = bool(np.isfinite(data).all())
    late = e_y[len(e_y) * 3 // 4:]

    def peak(x):
        return float(np.max(np.abs(x))) if len(x) else float("nan")

    def rms(x):
        return float(np.sqrt(np.mean(np.square(x)))) if len(x) else float("nan")

    return {
        "rows": int(len(t)),
        "t_end": float(t[-1]) if len(t) else 0.0,
        "diverged": diverged,
        "finite": finite,
        "bounded": finite and not diverged,
        "max_abs_e_y": peak(e_y),
        "rms_e_y": rms(e_y),
        "late_rms_e_y": rms(late),
        "max_abs_delta": peak(delta),
        "max_abs_torque": peak(torque),
    }


def sweep_task(spec):
    """Worker side: lk_simulate at one point, summarised; the log itself is kept only if asked."""
    out, tid = spec["out"], spec["task_id"]
    with tempfile.TemporaryDirectory(prefix="lk_fleet_") as tmp:
        log = os.path.join(tmp, "run.csv")
        code, stdout, stderr, wall = run_tool(spec["argv"] + ["--out", log, "--quiet"], spec["timeout"])
        result = new_result(spec, code, stdout, stderr, wall, ok_codes=(0, SIMULATE_DIVERGED))
        if result["status"] == "ok":
            try:
                result["summary"] = summarize_run_csv(log, diverged=code == SIMULATE_DIVERGED)
                if spec["keep_logs"]:
                    with open(log, "rb") as f:
                        write_bytes_atomic(os.path.join(out, "runs", tid + ".csv"), f.read())
            except (OSError, ValueError) as exc:
                result.update(status="failed", error_kind="unreadable log", error=f"cannot summarise the log: {exc}")
    return store_result(out, result)


def parse_grid(text):
    """--grid key=start:stop:step (stop included) or key=v1,v2,...: the axis's key and values."""
    key, sep, spec = text.partition("=")
    if not sep or not key:
        raise UsageError("--grid", f"'{text}': expected key=start:stop:step or key=v1,v2,...")
    if ":" in spec and spec.count(":") != 2:
        raise UsageError("--grid", f"'{text}': expected key=start:stop:step")
    try:
        if ":" in spec:
            start, stop, step = (float(x) for x in spec.split(":"))
            if step == 0 or (stop - start) * step < 0:
                raise UsageError("--grid", f"'{text}': step {step:g} does not lead from {start:g} to {stop:g}")
            # Inclusive stop, robust to rounding: 0:0.3:0.1 has four points.
            count = int(math.floor((stop - start) / step + 1e-9)) + 1
            values = [float(f"{start + i * step:.12g}") for i in range(count)]
        else:
            values = [float(x) for x in spec.split(",")]
    except ValueError:
        raise UsageError("--grid", f"'{text}': the values must be numbers")
    return key, values


VARY_PATTERN = re.compile(r"^([\w.]+)=(normal|uniform)\(\s*([^,()]+)\s*,\s*([^,()]+)\s*\)$")


def parse_vary(text):
    """--vary key=normal(mu,sigma) or key=uniform(a,b): (key, law, first, second)."""
    match = VARY_PATTERN.match(text.replace(" ", ""))
    if not match:
        raise UsageError("--vary", f"'{text}': expected key=normal(mu,sigma) or key=uniform(a,b)")
    key, law = match.group(1), match.group(2)
    try:
        first, second = float(match.group(3)), float(match.group(4))
    except ValueError:
        raise UsageError("--vary", f"'{text}': the law's parameters must be numbers")
    if law == "normal" and not second > 0:
        raise UsageError("--vary", f"'{text}': sigma must be positive")
    if law == "uniform" and not second > first:
        raise UsageError("--vary", f"'{text}': uniform(a,b) needs a < b")
    return key, law, first, second


def sweep_points(axes, laws, draws, seed):
    """The sweep's points: the grid's product, each with `draws` Monte-Carlo draws of the varied keys.
    The draws are made here, from the seed, so that a rerun makes the same points (and task ids)."""
    import numpy as np
    rng = np.random.default_rng(seed)
    grid = list(itertools.product(*[[(key, v) for v in values] for key, values in axes])) or [()]
    points = []
    for cell in grid:
        for draw in range(draws if laws else 1):
            point = dict(cell)
            for key, law, first, second in laws:
                value = rng.normal(first, second) if law == "normal" else rng.uniform(first, second)
                point[key] = float(f"{value:.12g}")
            points.append((point, draw if laws else None))
    return points


def format_value(value):
    return f"{value:.12g}"


def sweep_specs(args, lk_simulate):
    axes = [parse_grid(g) for g in args.grid]
    laws = [parse_vary(v) for v in args.vary]
    if args.monte_carlo is not None and args.monte_carlo < 1:
        raise UsageError("--monte-carlo", "must be at least 1")
    if not axes and not args.monte_carlo:
        raise UsageError("--grid", "give at least one --grid axis, or --monte-carlo N with --vary")
    if bool(args.monte_carlo) != bool(laws):
        raise UsageError("--monte-carlo" if laws else "--vary",
                         "--monte-carlo N and --vary key=law(...) go together")
    keys = [k for k, _ in axes] + [k for k, *_ in laws]
    repeated = sorted({k for k in keys if keys.count(k) > 1})
    if repeated:
        raise UsageError("--grid", f"key {', '.join(repeated)} is swept twice")
    config = os.path.abspath(args.config)
    config_digest = file_digest(config)
    specs = []
    for point, draw in sweep_points(axes, laws, args.monte_carlo or 0, args.seed):
        # A key 'a+b' sets both keys to the value (e.g. the two actuator delays that make tau2).
        sets = list(args.set) + [f"{k}={format_value(v)}" for keys, v in point.items() for k in keys.split("+")]
        inputs = {"tool": "lk_simulate", "config": config, "sets": sets, "point": point, "draw": draw}
        tid = task_id({**inputs, "config": config_digest})
        argv = [lk_simulate, "--config", config] + [a for s in sets for a in ("--set", s)]
        specs.append({"kind": "sweep", "task_id": tid, "inputs": inputs, "argv": argv, "out": args.out,
                      "timeout": args.task_timeout, "keep_logs": args.keep_logs})
    return specs, axes, laws


# ----------------------------------------------------------------------------------------------------
# Checks before any task runs: a mistake in the arguments is one clear message, not N failed tasks


def find_tool(lk_bin, name):
    path = os.path.join(os.path.abspath(lk_bin), name)
    if not os.access(path, os.X_OK):
        raise UsageError("--lk-bin", f"no executable {name} in '{lk_bin}' (build the project, or set LK_BIN_DIR)")
    return path


def check_config(lk_simulate, config, sets, argument):
    """Load the configuration (and overrides) as the tools will: lk_simulate --print-config."""
    argv = [lk_simulate, "--config", config] + [a for s in sets for a in ("--set", s)] + ["--print-config"]
    proc = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise UsageError(argument, tail(proc.stderr) or f"lk_simulate exited {proc.returncode}")


def check_sweep_arguments(lk_simulate, args, specs):
    check_config(lk_simulate, args.config, [], "--config")
    check_config(lk_simulate, args.config, args.set, "--set")
    first = specs[0]["inputs"]["sets"]
    check_config(lk_simulate, args.config, first, "--grid" if args.grid else "--vary")


# ----------------------------------------------------------------------------------------------------
# Dask


def open_client(args):
    """An embedded LocalCluster (processes, one thread each: the tools are single-threaded and CPU
    bound), or the scheduler given by --scheduler."""
    from distributed import Client, LocalCluster
    if args.scheduler:
        try:
            return Client(args.scheduler, timeout=args.connect_timeout), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise UsageError("--scheduler", f"cannot connect to '{args.scheduler}': {exc}")
    # A random dashboard port: the default 8787 may be taken by another cluster on the machine.
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.ERROR)
    return Client(cluster), cluster


class Progress:
    """Done / running / failed counts, rate and time left, on stderr: a redrawn bar on a terminal, a plain
    line every `interval` seconds otherwise (CI logs, files)."""

    def __init__(self, total, skipped, stream=sys.stderr, interval=5.0):
        self.total, self.skipped, self.stream = total, skipped, stream
        self.tty = stream.isatty()
        self.interval = 0.5 if self.tty else interval
        self.start = time.monotonic()
        self.last = -math.inf
        self.width = 0
        self.shown = ""

    def line(self, done, failed, running):
        ran = done - self.skipped
        elapsed = time.monotonic() - self.start
        rate = ran / elapsed * 60 if elapsed > 0 else 0.0
        left = self.total - done
        eta = duration(left / (rate / 60)) if ran and left else ("0 s" if not left else "?")
        counts = (f"{done}/{self.total} done ({self.skipped} skipped), {running} running, {failed} failed, "
                  f"{rate:.1f}/min, {eta} left")
        if not self.tty:
            return f"[lk_fleet] {counts}"
        filled = int(30 * done / self.total) if self.total else 30
        return f"[{'#' * filled}{'.' * (30 - filled)}] {counts}"

    def update(self, done, failed, running, force=False):
        now = time.monotonic()
        if not force and now - self.last < self.interval:
            return
        self.last = now
        text = self.line(done, failed, running())
        if text == self.shown:
            return
        self.shown = text
        if self.tty:
            self.stream.write("\r" + text.ljust(self.width))
            self.width = len(text)
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def note(self, text):
        """A line (a failed task) printed above the bar."""
        if self.tty and self.width:
            self.stream.write("\r" + " " * self.width + "\r")
            self.width = 0
        self.stream.write(text + "\n")
        self.stream.flush()
        self.last, self.shown = -math.inf, ""

    def finish(self, done, failed):
        self.update(done, failed, lambda: 0, force=True)
        if self.tty:
            self.stream.write("\n")


def duration(seconds):
    """'42 s', '7 min 05 s', '3 h 12 min'."""
    seconds = int(round(seconds))
    if seconds < 60:
        return f"{seconds} s"
    if seconds < 3600:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"


def error_result(spec, exc):
    """A task Dask gave up on (its workers kept dying, retries spent): stored as status 'error', which a
    rerun retries."""
    result = new_result(spec, None, "", "", 0.0)
    result.update(status="error", error_kind="lost (Dask gave up)", error=f"{type(exc).__name__}: {exc}",
                  host=None, pid=None)
    return result


def collect(future, spec):
    """The result of a finished future; stored here too in case the worker could not write it (an --out
    directory the worker does not share)."""
    if future.status == "finished":
        result = future.result()
    else:
        exc = future.exception() if future.status == "error" else RuntimeError(f"task {future.status}")
        result = error_result(spec, exc)
    if result["status"] == "error" or not os.path.exists(result_path(spec["out"], spec["task_id"])):
        result = store_result(spec["out"], result)
    return result


def remove_stale_attempts(out, tids):
    """Report folders of attempts whose worker died mid-task (.<task-id>.<random>). Removed by the client
    once every task has finished, when no attempt of these tasks can still be writing."""
    for tid in tids:
        for folder in glob.glob(os.path.join(out, "reports", f".{tid}.*")):
            shutil.rmtree(folder, ignore_errors=True)


def running_count(client, keys):
    """Tasks of ours the scheduler has placed on workers, capped by the threads: a worker may hold one
    queued task beside the one it runs."""
    def count():
        try:
            processing = client.processing()
            threads = sum(client.nthreads().values())
        except Exception:  # progress is best effort; a slow scheduler must not stop the run
            return 0
        return min(threads, sum(1 for tasks in processing.values() for k in tasks if k in keys))
    return count


def run_tasks(args, fn, specs, skipped, total):
    """Submit the tasks not done yet and gather their results as they finish, keyed by task id."""
    from distributed import as_completed
    results = {}
    failed = sum(1 for r in skipped.values() if r["status"] != "ok")
    progress = Progress(total, len(skipped), interval=args.progress_interval)
    client, cluster = open_client(args)
    futures = {}
    try:
        for spec in specs:
            key = f"lk_fleet-{spec['kind']}-{spec['task_id']}"
            futures[client.submit(fn, spec, key=key, retries=args.retries, pure=False)] = spec
        running = running_count(client, {f.key for f in futures})
        pending = as_completed(futures)
        while not pending.is_empty():
            batch = pending.next_batch(block=False)
            for future in batch:
                spec = futures[future]
                result = collect(future, spec)
                results[spec["task_id"]] = result
                if result["status"] != "ok":
                    failed += 1
                    progress.note(f"[lk_fleet] {result['status']}: {describe(spec)}: {error_text(result)}")
                future.release()
            progress.update(len(skipped) + len(results), failed, running)
            if not batch:
                time.sleep(0.1)
        progress.finish(len(skipped) + len(results), failed)
    except KeyboardInterrupt:
        # Ctrl-C: cancel what has not finished, so that no queued task starts while the cluster shuts
        # down (a worker went on through its queue meanwhile: on a loaded machine an interrupted run had
        # finished every task). What is written stays; the same command resumes.
        try:
            client.cancel([f for f in futures if not f.done()], force=True)
        except Exception:  # best effort: the interrupt must not become another error
            pass
        raise
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return results


def status(text):
    """Messages and progress go to stderr: stdout stays free for a caller's pipe."""
    print(f"[lk_fleet] {text}", file=sys.stderr, flush=True)


def describe(spec):
    inputs = spec["inputs"]
    return inputs.get("log") or " ".join(f"{k}={format_value(v)}" for k, v in inputs["point"].items())


def last_line(text):
    lines = text.strip().splitlines()
    return lines[-1] if lines else ""


def execute(args, fn, specs):
    """Resume, then run: tasks with a stored result are skipped; the rest run on Dask. Returns every
    task's result in the order of `specs`, each task once."""
    unique = list({spec["task_id"]: spec for spec in specs}.values())
    skipped = {}
    for spec in unique:
        stored = load_result(args.out, spec["task_id"])
        if stored is not None and not (args.retry_failed and stored["status"] == "failed"):
            skipped[spec["task_id"]] = stored
    todo = [spec for spec in unique if spec["task_id"] not in skipped]
    # Longest first: a big log started last would set the run's tail alone.
    todo.sort(key=lambda spec: -spec.get("size", 0))
    where = args.scheduler or f"a LocalCluster of {args.workers} workers"
    verb = "diagnose" if args.command == "gap" else "simulate"
    status(f"{len(unique)} tasks: {len(todo)} to {verb}, {len(skipped)} done before (skipped)"
           + (f"; running on {where}" if todo else ""))
    results = dict(skipped)
    if todo:
        results.update(run_tasks(args, fn, todo, skipped, len(unique)))
        remove_stale_attempts(args.out, [spec["task_id"] for spec in todo])
    return [results[spec["task_id"]] for spec in unique], len(skipped), len(todo)


# ----------------------------------------------------------------------------------------------------
# Reports


def write_text_atomic(path, text):
    write_bytes_atomic(path, text.encode())


def csv_text(header, rows):
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=header, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    return buffer.getvalue()


def error_text(result):
    """One line for tables: what the exit code means and the tool's last line of stderr."""
    return f"{result['error_kind']}: {last_line(result['error'])}" if result["status"] != "ok" else ""


def gap_rows(results):
    """One flat row per log; the verdict's fitted parameters as columns 'effect.parameter'."""
    rows = []
    for r in sorted(results, key=lambda r: r["inputs"]["log"]):
        s = r.get("summary", {})
        row = {"task_id": r["task_id"], "log": r["inputs"]["log"], "scenario": r["inputs"]["scenario"] or "",
               "status": r["status"], "exit_code": r["exit_code"], "effect": s.get("effect", ""),
               "form": s.get("form", ""), "confidence": s.get("confidence", ""), "where": s.get("where", ""),
               "shrink": s.get("shrink", ""), "how_far_shrink": s.get("how_far_shrink", ""),
               "gap_before": s.get("gap_before", ""), "gap_after": s.get("gap_after", ""),
               "wall_seconds": round(r["wall_seconds"], 3), "error": error_text(r)}
        for name, value in s.get("params", {}).items():
            row[f"{s['effect']}.{name}"] = value
        rows.append(row)
    return rows


def parameter_values(results):
    """{'effect.parameter': [values]} over the logs whose verdict is that effect."""
    values = {}
    for r in results:
        s = r.get("summary", {})
        for name, value in s.get("params", {}).items():
            values.setdefault(f"{s['effect']}.{name}", []).append(value)
    return values


def plot_parameters(out, values):
    """One histogram per fitted parameter of the verdicts, OUT/plots/<effect>.<parameter>.png
    (matplotlib, Agg: no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    os.makedirs(os.path.join(out, "plots"), exist_ok=True)
    files = []
    for label, xs in sorted(values.items()):
        fig, ax = plt.subplots(figsize=(5, 3.2))
        ax.hist(xs, bins=max(5, min(30, len(xs) // 3)), color="#4878a8", edgecolor="white")
        ax.plot(xs, np.zeros(len(xs)), "|", color="black", markersize=12)  # each log, under the bars
        ax.set_xlabel(label)
        ax.set_ylabel("logs")
        ax.set_title(f"{label}: {len(xs)} log{'s' if len(xs) > 1 else ''}, median {np.median(xs):.4g}")
        fig.tight_layout()
        filename = os.path.join("plots", re.sub(r"[^\w.-]+", "_", label) + ".png")
        fig.savefig(os.path.join(out, filename), dpi=110)
        plt.close(fig)
        files.append(filename)
    return files


def markdown_counts(results):
    ok = [r for r in results if r["status"] == "ok"]
    effects = {}
    for r in ok:
        effects[r["summary"]["effect"]] = effects.get(r["summary"]["effect"], 0) + 1
    lines = ["## Verdicts", "", "| effect | logs |", "|---|---|"]
    lines += [f"| {effect} | {n} |" for effect, n in sorted(effects.items(), key=lambda kv: (-kv[1], kv[0]))]
    return lines


def markdown_unexplained(results):
    unexplained = [r for r in results if r["status"] == "ok" and r["summary"]["effect"] == "unexplained"]
    lines = [f"## Unexplained ({len(unexplained)})", ""]
    lines += [f"- `{r['inputs']['log']}` (where: {r['summary']['where']}): {r['summary']['reason']}"
              for r in unexplained] or ["None."]
    return lines


def markdown_failed(results):
    bad = [r for r in results if r["status"] != "ok"]
    lines = [f"## Failed ({len(bad)})", ""]
    for r in bad:
        lines += [f"- `{r['inputs']['log']}`: {r['error_kind']}", "", "  ```",
                  *["  " + line for line in r["error"].splitlines()], "  ```"]
    return lines + ([] if bad else ["None."])


def markdown_every_log(results):
    lines = ["## Every log", "", "| log | status | effect | confidence | parameters | shrink | where | wall s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in sorted(results, key=lambda r: r["inputs"]["log"]):
        s = r.get("summary", {})
        params = ", ".join(f"{k} = {v:.4g}" for k, v in s.get("params", {}).items())
        lines.append(f"| `{r['inputs']['log']}` | {r['status']} | {s.get('effect', '')} | "
                     f"{fmt(s.get('confidence'))} | {params} | {fmt(s.get('shrink'))} | {s.get('where', '')} | "
                     f"{r['wall_seconds']:.1f} |")
    return lines


def fleet_markdown(results, plots, command, ran, skipped):
    ok = sum(1 for r in results if r["status"] == "ok")
    lines = ["# Fleet gap report", "", f"`{command}`", "",
             f"{len(results)} logs: {ok} diagnosed, {len(results) - ok} failed.",
             f"{ran} diagnosed by this run, {skipped} by earlier runs (resumed).", ""]
    lines += markdown_counts(results) + [""]
    lines += ["## Fitted parameters", ""] + ([f"![{p}]({p})" for p in plots] or ["No verdict fitted a parameter."])
    lines += [""] + markdown_unexplained(results) + [""] + markdown_failed(results) + [""]
    lines += markdown_every_log(results)
    return "\n".join(lines) + "\n"


def fmt(value):
    return f"{value:.3f}" if isinstance(value, (int, float)) else ""


def write_fleet_report(out, results, command, ran, skipped):
    rows = gap_rows(results)
    base = ["task_id", "log", "scenario", "status", "exit_code", "effect", "form", "confidence", "where",
            "shrink", "how_far_shrink", "gap_before", "gap_after", "wall_seconds", "error"]
    params = sorted({k for row in rows for k in row if k not in base})
    write_text_atomic(os.path.join(out, "fleet.csv"), csv_text(base + params, rows))
    plots = plot_parameters(out, parameter_values(results))
    write_text_atomic(os.path.join(out, "fleet.md"), fleet_markdown(results, plots, command, ran, skipped))


def sweep_rows(results, keys):
    rows = []
    for r in results:
        s = r.get("summary", {})
        row = {"task_id": r["task_id"], "draw": "" if r["inputs"]["draw"] is None else r["inputs"]["draw"],
               "status": r["status"], "exit_code": r["exit_code"], "wall_seconds": round(r["wall_seconds"], 4),
               "error": error_text(r)}
        row.update({k: r["inputs"]["point"][k] for k in keys})
        row.update({k: s.get(k, "") for k in ("diverged", "finite", "bounded", "t_end", "rows") + SWEEP_METRICS})
        rows.append(row)
    return rows


def plot_sweep(path, rows, axes, laws, metric):
    """A colour map for two grid axes, a line for one, a histogram of the metric for Monte-Carlo draws.
    Unbounded points (diverged or non-finite) are marked: their metric is where the run stopped."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    ok = [r for r in rows if r["status"] == "ok"]
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    if laws:
        # Unbounded runs stopped early: their figure is not comparable; the title counts them.
        values = [r[metric] for r in ok if r["bounded"]]
        ax.hist(values, bins=max(5, min(40, len(values) // 4)), color="#4878a8")
        ax.set_xlabel(metric)
        ax.set_ylabel("bounded runs")
        ax.set_title(f"{len(ok)} draws, {len(ok) - len(values)} diverged ({', '.join(k for k, *_ in laws)})",
                     fontsize=10)
    elif len(axes) == 1:
        key = axes[0][0]
        ok.sort(key=lambda r: r[key])
        ax.plot([r[key] for r in ok], [r[metric] for r in ok], "o-", color="#4878a8", label=metric)
        unbounded = [r for r in ok if not r["bounded"]]
        if unbounded:
            ax.plot([r[key] for r in unbounded], [r[metric] for r in unbounded], "x", color="red",
                    markersize=10, label="diverged / not finite (where the run stopped)")
        ax.set_xlabel(axis_label(key))
        ax.set_ylabel(metric)
        ax.legend()
    elif len(axes) == 2:
        (kx, xs), (ky, ys) = axes
        # Unbounded runs stopped early: their figure is not comparable, the cell stays grey.
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in ok:
            if r["bounded"]:
                grid[ys.index(r[ky]), xs.index(r[kx])] = r[metric]
        cmap = matplotlib.colormaps["viridis"].copy()
        cmap.set_bad("#d0d0d0")
        mesh = ax.pcolormesh(cell_edges(xs), cell_edges(ys), np.ma.masked_invalid(grid), shading="flat",
                             cmap=cmap, norm=colour_norm(grid))
        fig.colorbar(mesh, ax=ax, label=metric)
        unbounded = [r for r in ok if not r["bounded"]]
        ax.plot([r[kx] for r in unbounded], [r[ky] for r in unbounded], "x", color="red", markersize=10,
                label="diverged / not finite")
        if unbounded:
            ax.legend(loc="upper right")
        ax.set_xlabel(axis_label(kx))
        ax.set_ylabel(axis_label(ky))
    else:
        plt.close(fig)
        return False
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def axis_label(key):
    """'a.b.c+a.b.d' (keys set together) reads 'c = d'."""
    return " = ".join(k.split(".")[-1] for k in key.split("+")) if "+" in key else key


def colour_norm(grid):
    """A log colour scale when the values span decades (a diverged corner next to decaying runs)."""
    from matplotlib.colors import LogNorm
    import numpy as np
    positive = grid[np.isfinite(grid) & (grid > 0)]
    if len(positive) and positive.size == np.isfinite(grid).sum() and positive.max() > 100 * positive.min():
        return LogNorm(positive.min(), positive.max())
    return None


def cell_edges(values):
    """Cell boundaries around grid values (midpoints; half a step beyond the ends)."""
    if len(values) == 1:
        return [values[0] - 0.5, values[0] + 0.5]
    mids = [(a + b) / 2 for a, b in zip(values, values[1:])]
    return [2 * values[0] - mids[0]] + mids + [2 * values[-1] - mids[-1]]


def write_sweep_report(out, results, axes, laws, metric):
    keys = [k for k, _ in axes] + [k for k, *_ in laws]
    rows = sweep_rows(results, keys)
    header = ["task_id"] + keys + ["draw", "status", "exit_code", "diverged", "finite", "bounded", "t_end",
                                   "rows", *SWEEP_METRICS, "wall_seconds", "error"]
    write_text_atomic(os.path.join(out, "sweep.csv"), csv_text(header, rows))
    if not plot_sweep(os.path.join(out, "sweep.png"), rows, axes, laws, metric):
        status(f"no plot for {len(axes)} grid axes (one or two, or Monte-Carlo draws)")


# ----------------------------------------------------------------------------------------------------
# Command line


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def build_parser():
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--config", required=True, help="the nominal (gap) or base (sweep) configuration YAML")
    common.add_argument("--out", required=True, help="output directory (results/, reports, plots)")
    common.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786; "
                                            "default: an embedded LocalCluster")
    common.add_argument("--workers", type=positive_int, default=os.cpu_count() or 1,
                        help="LocalCluster worker processes (default: the CPU count)")
    common.add_argument("--lk-bin", default=os.environ.get("LK_BIN_DIR", DEFAULT_LK_BIN),
                        help="directory of the lane_keeping tools (default: $LK_BIN_DIR or the build tree)")
    common.add_argument("--retries", type=int, default=2,
                        help="reruns of a task whose worker or tool died (default 2)")
    common.add_argument("--task-timeout", type=float, default=None, help="seconds before a task is failed")
    common.add_argument("--retry-failed", action="store_true",
                        help="run again the tasks whose tool failed before (a fixed log, a fixed tool)")
    common.add_argument("--progress-interval", type=float, default=5.0,
                        help="seconds between progress lines when stdout is not a terminal")
    common.add_argument("--connect-timeout", type=float, default=10.0,
                        help="seconds to wait for the --scheduler (default 10)")
    parser = argparse.ArgumentParser(prog="lk_fleet", description=__doc__.split("\n\n")[0])
    commands = parser.add_subparsers(dest="command", required=True)
    gap = commands.add_parser("gap", parents=[common], help="lk_gap on every log, and a fleet report")
    gap.add_argument("--logs", action="append", required=True,
                     help="glob of logs (.csv, .bag; '**' recurses); repeatable")
    gap.add_argument("--scenarios", help="YAML map: log glob or name -> scenario file")
    gap.add_argument("--extra-args", "--lk-gap-args", dest="extra_args", default="",
                     help="more lk_gap arguments, e.g. '--effects a,b --noise-reference-draws 19'")
    gap.add_argument("--per-log-plots", action="store_true", help="let lk_gap draw each log's plots")
    sweep = commands.add_parser("sweep", parents=[common], help="lk_simulate over a grid or Monte-Carlo draws")
    sweep.add_argument("--grid", action="append", default=[],
                       help="key=start:stop:step or key=v1,v2,...; key a+b sets both keys")
    sweep.add_argument("--monte-carlo", type=int, metavar="N", help="draws per grid point")
    sweep.add_argument("--vary", action="append", default=[], help="key=normal(mu,sigma) or key=uniform(a,b)")
    sweep.add_argument("--seed", type=int, default=0, help="seed of the Monte-Carlo draws")
    sweep.add_argument("--set", action="append", default=[], help="fixed override key=value, e.g. "
                                                                  "simulation.duration=5")
    sweep.add_argument("--metric", default="late_rms_e_y", choices=SWEEP_METRICS,
                       help="the plotted figure (default: RMS lateral error over the last quarter of the run)")
    sweep.add_argument("--keep-logs", action="store_true", help="keep each point's CSV under OUT/runs/")
    return parser


def check_common(args):
    if not os.path.isfile(args.config):
        raise UsageError("--config", f"'{args.config}' is not a file")
    if args.scheduler and not re.match(r"^(tcp|tls|inproc|ucx)://[^/]+$|^[\w.-]+:\d+$", args.scheduler):
        raise UsageError("--scheduler", f"'{args.scheduler}' is not an address like tcp://host:port")
    if args.retries < 0:
        raise UsageError("--retries", "must not be negative")
    args.out = os.path.abspath(args.out)
    os.makedirs(os.path.join(args.out, "results"), exist_ok=True)


def command_gap(args):
    lk_gap = find_tool(args.lk_bin, "lk_gap")
    specs = gap_specs(args, lk_gap)
    if os.access(os.path.join(args.lk_bin, "lk_simulate"), os.X_OK):
        check_config(find_tool(args.lk_bin, "lk_simulate"), args.config, [], "--config")
    results, skipped, ran = execute(args, gap_task, specs)
    write_fleet_report(args.out, results, " ".join(shlex.quote(a) for a in sys.argv), ran, skipped)
    return summary_line("gap", results, os.path.join(args.out, "fleet.md"))


def command_sweep(args):
    lk_simulate = find_tool(args.lk_bin, "lk_simulate")
    specs, axes, laws = sweep_specs(args, lk_simulate)
    check_sweep_arguments(lk_simulate, args, specs)
    results, _, _ = execute(args, sweep_task, specs)
    write_sweep_report(args.out, results, axes, laws, args.metric)
    return summary_line("sweep", results, os.path.join(args.out, "sweep.csv"))


def summary_line(command, results, report):
    failed = sum(1 for r in results if r["status"] == "failed")
    lost = sum(1 for r in results if r["status"] == "error")
    status(f"{command}: {len(results) - failed - lost} ok, {failed} failed, {lost} lost; report: {report}")
    return 1 if lost else 0


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        check_common(args)
        return command_gap(args) if args.command == "gap" else command_sweep(args)
    except UsageError as exc:
        parser.error(f"{args.command}: {exc}")  # prints usage and exits 2
    except KeyboardInterrupt:
        status("interrupted: the results written so far are kept; the same command resumes")
        return 130


if __name__ == "__main__":
    sys.exit(main())
