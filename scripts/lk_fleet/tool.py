"""Launching lane_keeping's C++ tools (lk_gap, lk_simulate): on a worker, one run per task, dying with the
worker, a signal raised as ToolKilled so that Dask retries; on the client, the checks before any task runs
(the tool exists, the configuration loads). And what the tools' exit codes mean.

Depends on messages."""
import os
import shutil
import subprocess
import time

from .messages import UsageError

# A failed task keeps the end of the tool's stderr: its error, short enough for the reports.
STDERR_TAIL_LINES = 20
STDERR_TAIL_CHARS = 4000
# What the tools' exit codes mean (lk_gap.cpp, lk_simulate.cpp), for the reports.
EXIT_MEANINGS = {
    "lk_gap": {1: "error", 2: "bad arguments or configuration", 3: "configuration error", 4: "bad input data"},
    "lk_simulate": {1: "error", 2: "bad configuration", 3: "diverged"},
}


class ToolKilled(RuntimeError):
    """The tool died from a signal (worker shutdown, OOM killer): raised so that Dask retries the task."""


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
