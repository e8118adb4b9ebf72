"""The sweep command's tasks: one closed-loop run per point of a grid (--grid) and of Monte-Carlo draws
(--monte-carlo, --vary). On the client, the points (drawn from --seed, so that a rerun makes the same task ids),
one task spec per point and the configuration checks; on a worker, sweep_task runs the point and stores the
run's stability figures.

A point runs in the worker's own process through the Python module lane_keeping (docs/python_api.md): no
process and no CSV per point, the same core code as lk_simulate and the same numbers. Where the module is not
built (or LK_FLEET_SWEEP_ENGINE=process), each point runs one lk_simulate and is summarised from its CSV, as
before; the two give the same figures, and a task's id does not depend on the engine, so either resumes the
other's sweep.

Depends on messages, storage, tool and results. sweep_task runs on the Dask workers (shipped by value: see
cluster)."""
import csv
import itertools
import math
import os
import re
import sys
import tempfile
import time

from .messages import UsageError
from .results import file_digest, format_value, new_result, store_result, task_id
from .storage import write_bytes_atomic
from .tool import check_config, run_tool

# lk_simulate exits 3 when the run diverged: a result of the sweep, not a failure.
SIMULATE_DIVERGED = 3
# Columns of the lk_simulate log a sweep point is summarised from.
SWEEP_COLUMNS = ("t", "e_y", "delta", "torque")
SWEEP_METRICS = ("max_abs_e_y", "rms_e_y", "late_rms_e_y", "max_abs_delta", "max_abs_torque")
# "in-process" (the default where the module is built) or "process" (one lk_simulate per point).
ENGINE_VARIABLE = "LK_FLEET_SWEEP_ENGINE"


def summarize_columns(t, e_y, delta, torque, diverged):
    """Stability figures of one closed-loop log: peaks and RMS of the lateral error, steering angle and
    torque, over the whole run and its last quarter (decay or not), and whether it stayed bounded."""
    import numpy as np
    finite = bool(all(np.isfinite(c).all() for c in (t, e_y, delta, torque)))
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


def summarize_run_csv(path, diverged):
    """summarize_columns of an lk_simulate log file."""
    import numpy as np
    with open(path, newline="") as f:
        header = next(csv.reader(f))
    missing = [c for c in SWEEP_COLUMNS if c not in header]
    if missing:
        raise ValueError(f"{path}: no column {', '.join(missing)} (found {', '.join(header)})")
    columns = [header.index(c) for c in SWEEP_COLUMNS]
    data = np.loadtxt(path, delimiter=",", skiprows=1, usecols=columns, ndmin=2)
    return summarize_columns(*(data[:, i] for i in range(len(SWEEP_COLUMNS))), diverged)


def module_path(lk_bin):
    """The devel space's Python folder beside the tools' folder (DEVEL/lib/lane_keeping ->
    DEVEL/lib/python3/dist-packages), where the build puts the package lane_keeping."""
    return os.path.join(os.path.dirname(os.path.abspath(lk_bin)), "python3", "dist-packages")


def import_lane_keeping(python_path):
    """The module lane_keeping, from the environment (setup.bash) or else from `python_path`."""
    try:
        import lane_keeping
        lane_keeping.simulate  # the API, not only the message modules of an older build
        return lane_keeping
    except (ImportError, AttributeError):
        pass
    for name in [n for n in sys.modules if n == "lane_keeping" or n.startswith("lane_keeping.")]:
        del sys.modules[name]
    if python_path not in sys.path:
        sys.path.insert(0, python_path)
    import lane_keeping
    lane_keeping.simulate
    return lane_keeping


def sweep_engine(lk_bin):
    """The engine of this sweep: in-process when the module imports here, else one process per point."""
    if os.environ.get(ENGINE_VARIABLE, "in-process") == "process":
        return "process"
    try:
        import_lane_keeping(module_path(lk_bin))
        return "in-process"
    except (ImportError, AttributeError, OSError):
        return "process"


def run_in_process(spec):
    """One point through the module: (exit code as lk_simulate's, error text, summary or None)."""
    lk = import_lane_keeping(spec["python_path"])
    keep = os.path.join(spec["out"], "runs", spec["task_id"] + ".csv") if spec["keep_logs"] else None
    try:
        if keep is not None:
            os.makedirs(os.path.dirname(keep), exist_ok=True)
            partial = f"{keep}.{os.getpid()}.tmp"
            run = lk.simulate(spec["inputs"]["config"], overrides=spec["inputs"]["sets"], as_frame=False, out=partial)
            os.replace(partial, keep)  # atomic, as write_bytes_atomic
        else:
            run = lk.simulate(spec["inputs"]["config"], overrides=spec["inputs"]["sets"], as_frame=False)
    except lk.ConfigError as exc:
        return 2, f"lk_simulate: {exc}", None  # what lk_simulate prints and its exit status
    except lk.LaneKeepingError as exc:
        return 1, f"lk_simulate: {exc}", None
    code = SIMULATE_DIVERGED if run.diverged else 0
    summary = summarize_columns(*(run.log[c] for c in SWEEP_COLUMNS), diverged=run.diverged)
    return code, "", summary


def sweep_task(spec):
    """Worker side: the closed loop at one point, summarised; the log itself is kept only if asked."""
    out, tid = spec["out"], spec["task_id"]
    if spec.get("engine") == "in-process":
        start = time.monotonic()
        code, error, summary = run_in_process(spec)
        result = new_result(spec, code, "", error, time.monotonic() - start, ok_codes=(0, SIMULATE_DIVERGED))
        result["engine"] = "in-process"
        if summary is not None:
            result["summary"] = summary
        return store_result(out, result)
    with tempfile.TemporaryDirectory(prefix="lk_fleet_") as tmp:
        log = os.path.join(tmp, "run.csv")
        code, stdout, stderr, wall = run_tool(spec["argv"] + ["--out", log, "--quiet"], spec["timeout"])
        result = new_result(spec, code, stdout, stderr, wall, ok_codes=(0, SIMULATE_DIVERGED))
        result["engine"] = "process"
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
    lk_bin = os.path.dirname(lk_simulate)
    engine = sweep_engine(lk_bin)
    specs = []
    for point, draw in sweep_points(axes, laws, args.monte_carlo or 0, args.seed):
        # A key 'a+b' sets both keys to the value (e.g. the two actuator delays that make tau2).
        sets = list(args.set) + [f"{k}={format_value(v)}" for keys, v in point.items() for k in keys.split("+")]
        inputs = {"tool": "lk_simulate", "config": config, "sets": sets, "point": point, "draw": draw}
        tid = task_id({**inputs, "config": config_digest})
        argv = [lk_simulate, "--config", config] + [a for s in sets for a in ("--set", s)]
        # argv: the lk_simulate command of the point (what the process engine runs; by hand, the same run).
        specs.append({"kind": "sweep", "task_id": tid, "inputs": inputs, "argv": argv, "out": args.out,
                      "timeout": args.task_timeout, "keep_logs": args.keep_logs, "engine": engine,
                      "python_path": module_path(lk_bin)})
    return specs, axes, laws


def check_sweep_arguments(lk_simulate, args, specs):
    check_config(lk_simulate, args.config, [], "--config")
    check_config(lk_simulate, args.config, args.set, "--set")
    first = specs[0]["inputs"]["sets"]
    check_config(lk_simulate, args.config, first, "--grid" if args.grid else "--vary")
