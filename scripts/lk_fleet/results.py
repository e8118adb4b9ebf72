"""A task's identity and its result on disk: the task id (a hash of the task's inputs), the result record
every task leaves in OUT/results/<task-id>.json, storing it without undoing a verdict, and loading it to
resume. Plus the one-line texts the progress and the reports show of a result.

Depends on storage and tool."""
import hashlib
import json
import os
import socket
import time

from .storage import write_json_atomic
from .tool import EXIT_MEANINGS, tail

RESULT_FORMAT = "lane_keeping.fleet_result"
RESULT_VERSION = 1


def file_digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def task_id(fields):
    """A stable id for a task: the hash of its inputs in canonical JSON (sorted keys)."""
    canonical = json.dumps(fields, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(canonical.encode()).hexdigest()[:16]


def format_value(value):
    """A number as it goes into a --set argument, and so into a task id (12 digits: no float noise)."""
    return f"{value:.12g}"


def result_path(out, tid):
    return os.path.join(out, "results", tid + ".json")


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


def error_result(spec, exc):
    """A task Dask gave up on (its workers kept dying, retries spent): stored as status 'error', which a
    rerun retries."""
    result = new_result(spec, None, "", "", 0.0)
    result.update(status="error", error_kind="lost (Dask gave up)", error=f"{type(exc).__name__}: {exc}",
                  host=None, pid=None)
    return result


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


def last_line(text):
    lines = text.strip().splitlines()
    return lines[-1] if lines else ""


def error_text(result):
    """One line for tables: what the exit code means and the tool's last line of stderr."""
    return f"{result['error_kind']}: {last_line(result['error'])}" if result["status"] != "ok" else ""
