"""lk_fleet (scripts/lk_fleet.py, the package scripts/lk_fleet/) on Dask, end to end with the real tools: a
LocalCluster over short logs and a bad one; a dask-scheduler with two dask-workers, one SIGKILLed while it holds
a task; a run killed midway and resumed; a 2 x 2 stability sweep, in-process and with one lk_simulate per point;
bad arguments. Run from the repository root:
    /usr/bin/python3 -m pytest -q test/tools/test_lk_fleet_cluster.py
LK_BIN_DIR names the folder of lk_simulate and lk_gap (default: build/ws/devel/lib/lane_keeping)."""
import csv
import glob
import json
import math
import os
import signal
import subprocess
import sys
import time

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
BIN = os.path.abspath(os.environ.get("LK_BIN_DIR", os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping")))
PY = "/usr/bin/python3"  # Debian's: dask, distributed, matplotlib
FLEET = [PY, os.path.join(REPO, "scripts", "lk_fleet.py")]
CONFIG = os.path.join(REPO, "config", "default.yaml")
# Three candidates, enough to tell the test logs apart (the fleet is under test, not the diagnosis).
EFFECTS = "--effects steering_friction,sensing_delay,actuation_delay"
# Where only the bookkeeping matters: no noise-only null (fast; fewer than 19 draws are refused, since no
# gap could be detected with them).
FAST = EFFECTS + " --noise-reference-draws 0"

# tornado, under the Client the cluster fixture uses to wait for its workers.
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")

sys.path.insert(0, os.path.join(REPO, "scripts"))
from lk_fleet.results import result_path, task_id  # noqa: E402
from lk_fleet.sweep import parse_grid  # noqa: E402


def simulate(path, *sets):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    argv = [os.path.join(BIN, "lk_simulate"), "--config", CONFIG, "--set", "simulation.duration=6", "--out", path,
            "--quiet"]
    for s in sets:
        argv += ["--set", s]
    subprocess.run(argv, check=True)


def fleet(*args, timeout=240, env=None):
    return subprocess.run(FLEET + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          timeout=timeout, env=None if env is None else dict(os.environ, **env))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def verdicts(rows):
    return [(r["task_id"], r["status"], r["effect"], r["error"]) for r in rows]


def result_files(out):
    return sorted(glob.glob(os.path.join(out, "results", "*.json")))


def counting_bin(folder, delay):
    """A tool folder whose lk_gap appends 'worker-pid args' to calls.log, sleeps, then runs the real one: it
    counts invocations, names the worker that ran each, and holds tasks long enough for a kill to land."""
    os.makedirs(folder)
    calls = os.path.join(folder, "calls.log")
    with open(os.path.join(folder, "lk_gap"), "w") as f:
        f.write(f'#!/bin/sh\necho "$PPID $*" >> {calls}\nsleep {delay}\nexec {BIN}/lk_gap "$@"\n')
    os.chmod(os.path.join(folder, "lk_gap"), 0o755)
    os.symlink(os.path.join(BIN, "lk_simulate"), os.path.join(folder, "lk_simulate"))
    return folder, calls


def calls_made(calls):
    """[(worker pid, task id)] per lk_gap invocation; the task id is in the --report attempt folder."""
    if not os.path.exists(calls):
        return []
    made = []
    with open(calls) as f:
        for line in f:
            pid, *argv = line.split()
            report = os.path.basename(argv[argv.index("--report") + 1])
            made.append((int(pid), report.split(".")[1]))  # .<task-id>.<random>
    return made


def wait_for(predicate, timeout, what):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.1)
    pytest.fail(f"timed out waiting for {what}")


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """Four 6 s logs (no effect, Coulomb friction 3 and 1.5 N m, 30 ms more sensing delay) and one that is
    not a log."""
    root = str(tmp_path_factory.mktemp("logs"))
    simulate(os.path.join(root, "nominal.csv"))
    simulate(os.path.join(root, "friction", "coulomb3.csv"), "steering.coulomb_friction=3")
    simulate(os.path.join(root, "friction", "coulomb1.5.csv"), "steering.coulomb_friction=1.5")
    simulate(os.path.join(root, "late_pose.csv"), "delays.pose_to_tracker=0.23")
    with open(os.path.join(root, "friction", "garbage.csv"), "w") as f:
        f.write("t,x,y,psi,yaw_rate,delta,delta_des,torque\n0,0,0,0,0,0,0,0\n0.001,zero,0,0,0,0,0,0\n")
    return root


GOOD = ["coulomb1.5.csv", "coulomb3.csv", "late_pose.csv", "nominal.csv"]


def test_local_cluster_diagnoses_each_log_once_and_reports_the_bad_one(logs, tmp_path):
    out = str(tmp_path / "fleet")
    run = fleet("gap", "--config", CONFIG, "--logs", os.path.join(logs, "**", "*.csv"), "--out", out,
                "--workers", "2", "--lk-bin", BIN, "--extra-args", EFFECTS)
    assert run.returncode == 0, run.stderr
    rows = read_csv(os.path.join(out, "fleet.csv"))
    by_name = {os.path.basename(r["log"]): r for r in rows}
    assert len(rows) == 5 and sorted(by_name) == sorted(GOOD + ["garbage.csv"])
    # The verdicts, with the fitted magnitudes of what each log was made with.
    assert by_name["nominal.csv"]["effect"] == "unexplained"
    for name, coulomb in (("coulomb3.csv", 3.0), ("coulomb1.5.csv", 1.5)):
        assert by_name[name]["effect"] == "steering_friction"
        assert float(by_name[name]["steering_friction.coulomb"]) == pytest.approx(coulomb, rel=0.1)
        assert float(by_name[name]["shrink"]) > 0.8
    assert by_name["late_pose.csv"]["effect"] == "sensing_delay"
    assert float(by_name["late_pose.csv"]["sensing_delay.extra_delay"]) == pytest.approx(0.03, abs=0.005)
    assert all(float(by_name[n]["wall_seconds"]) > 0 for n in GOOD)
    # The bad log: failed with lk_gap's exit code and its message (file and line), the others unharmed.
    bad = by_name["garbage.csv"]
    assert (bad["status"], bad["exit_code"], bad["effect"]) == ("failed", "4", "")
    assert "bad input data (exit 4)" in bad["error"] and "garbage.csv:3" in bad["error"]
    assert "failed: " + os.path.join(logs, "friction", "garbage.csv") in run.stderr
    # One result per task, named by its id; the reports of the good logs beside them.
    assert [os.path.basename(p)[:-5] for p in result_files(out)] == sorted(r["task_id"] for r in rows)
    for r in rows:
        if r["status"] == "ok":
            with open(os.path.join(out, "reports", r["task_id"], "report.json")) as f:
                assert json.load(f)["verdict"]["effect"] == r["effect"]
    with open(os.path.join(out, "fleet.md")) as f:
        md = f.read()
    assert "5 logs: 4 diagnosed, 1 failed." in md
    assert "| steering_friction | 2 |" in md and "| sensing_delay | 1 |" in md and "| unexplained | 1 |" in md
    assert "## Unexplained (1)" in md and "garbage.csv:3" in md
    for plot in ("steering_friction.coulomb", "steering_friction.viscous", "sensing_delay.extra_delay"):
        with open(os.path.join(out, "plots", plot + ".png"), "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    # --retry-failed runs the failed log again (and only it): a fixed file would now be diagnosed.
    again = fleet("gap", "--config", CONFIG, "--logs", os.path.join(logs, "**", "*.csv"), "--out", out,
                  "--workers", "1", "--lk-bin", BIN, "--extra-args", EFFECTS, "--retry-failed")
    assert again.returncode == 0, again.stderr
    assert "5 tasks: 1 to diagnose, 4 done before (skipped)" in again.stderr
    assert verdicts(read_csv(os.path.join(out, "fleet.csv"))) == verdicts(rows)


@pytest.fixture
def dask_cluster(tmp_path):
    """A dask-scheduler and two dask-workers (no nanny: the killed process is the one running the task, and
    nothing restarts it) on 127.0.0.1."""
    scheduler_file = str(tmp_path / "scheduler.json")
    procs = [subprocess.Popen(["/usr/bin/dask-scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", scheduler_file], stderr=subprocess.DEVNULL)]
    try:
        wait_for(lambda: os.path.exists(scheduler_file) and os.path.getsize(scheduler_file), 60, "the scheduler")
        with open(scheduler_file) as f:
            address = json.load(f)["address"]
        for i in range(2):
            procs.append(subprocess.Popen(["/usr/bin/dask-worker", address, "--nthreads", "1", "--no-nanny",
                                           "--no-dashboard", "--name", f"w{i}"], stderr=subprocess.DEVNULL))
        from distributed import Client
        with Client(address, timeout=30) as client:
            client.wait_for_workers(2, timeout=60)
        yield address, procs[1:]
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_a_worker_killed_mid_task_loses_nothing(logs, tmp_path, dask_cluster):
    address, workers = dask_cluster
    victim, survivor = workers
    tool_bin, calls = counting_bin(str(tmp_path / "bin"), delay=2)
    out = str(tmp_path / "fleet")
    run = subprocess.Popen(FLEET + ["gap", "--config", CONFIG, "--logs", os.path.join(logs, "*.csv"),
                                    "--logs", os.path.join(logs, "friction", "c*.csv"), "--out", out,
                                    "--scheduler", address, "--lk-bin", tool_bin, "--extra-args", FAST],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        # Kill the victim while its lk_gap is in the wrapper's sleep: its task has started, not finished.
        killed = wait_for(lambda: [t for pid, t in calls_made(calls) if pid == victim.pid], 120,
                          "a task on the victim worker")[0]
        assert not os.path.exists(result_path(out, killed))
        victim.send_signal(signal.SIGKILL)
        stdout, stderr = run.communicate(timeout=240)
    finally:
        if run.poll() is None:
            run.kill()
    assert run.returncode == 0, stderr
    rows = read_csv(os.path.join(out, "fleet.csv"))
    assert sorted(os.path.basename(r["log"]) for r in rows) == GOOD
    assert all(r["status"] == "ok" and r["effect"] for r in rows)
    assert len(result_files(out)) == 4
    # The killed task ran again, on the survivor, and its result is the survivor's.
    made = calls_made(calls)
    assert (survivor.pid, killed) in made
    with open(result_path(out, killed)) as f:
        assert json.load(f)["pid"] == survivor.pid
    # Every task ran to its result once, plus the one rerun: 4 + 1 invocations (the victim started no other).
    assert len(made) == 5 and sorted({t for _, t in made}) == sorted(r["task_id"] for r in rows)
    # Nothing half-written: no attempt folder or temporary file left behind.
    assert not glob.glob(os.path.join(out, "reports", ".*")) and not glob.glob(os.path.join(out, "results", ".*"))


def test_a_killed_run_resumes_without_redoing_finished_tasks(logs, tmp_path):
    tool_bin, calls = counting_bin(str(tmp_path / "bin"), delay=1)
    out = str(tmp_path / "fleet")
    command = FLEET + ["gap", "--config", CONFIG, "--logs", os.path.join(logs, "**", "c*.csv"),
                       "--logs", os.path.join(logs, "*.csv"), "--out", out, "--workers", "1",
                       "--lk-bin", tool_bin, "--extra-args", FAST]
    first = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for(lambda: len(result_files(out)) >= 2, 180, "two results")
    finally:
        first.send_signal(signal.SIGKILL)  # no clean-up at all: a crash, a lost SSH session
        first.wait(timeout=30)
    time.sleep(1.0)  # the LocalCluster's workers notice their parent is gone and exit
    done = {p: os.stat(p).st_mtime_ns for p in result_files(out)}
    assert 2 <= len(done) < 4, "the kill came too late to test a resume"
    for path in done:  # atomic writes: every stored result is whole
        with open(path) as f:
            assert json.load(f)["status"] == "ok"
    calls_before = len(calls_made(calls))

    second = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=240)
    assert second.returncode == 0, second.stderr
    assert f"4 tasks: {4 - len(done)} to diagnose, {len(done)} done before (skipped)" in second.stderr
    # lk_gap ran only for the tasks without a result, and the stored results were not touched.
    rerun = calls_made(calls)[calls_before:]
    assert len(rerun) == 4 - len(done)
    assert not {t for _, t in rerun} & {os.path.basename(p)[:-5] for p in done}
    assert all(os.stat(p).st_mtime_ns == mtime for p, mtime in done.items())
    rows = read_csv(os.path.join(out, "fleet.csv"))
    assert sorted(os.path.basename(r["log"]) for r in rows) == GOOD and all(r["status"] == "ok" for r in rows)


def test_a_two_by_two_sweep(tmp_path):
    out = str(tmp_path / "sweep")
    tau2 = "delays.desired_steering_to_actuator+delays.steering_angle_to_actuator"
    args = ["sweep", "--config", CONFIG, "--set", "simulation.duration=2", "--grid", "tracker.k_psi=0.4:0.8:0.4",
            "--grid", f"{tau2}=0.0001,0.0025", "--out", out, "--workers", "2", "--lk-bin", BIN]
    run = fleet(*args)
    assert run.returncode == 0, run.stderr
    rows = read_csv(os.path.join(out, "sweep.csv"))
    assert sorted((float(r["tracker.k_psi"]), float(r[tau2])) for r in rows) == [
        (0.4, 0.0001), (0.4, 0.0025), (0.8, 0.0001), (0.8, 0.0025)]
    for r in rows:
        if float(r[tau2]) < 1e-3:  # below the critical 1.76 ms: the 2 s run completes, the error decays
            assert (r["status"], r["exit_code"], r["bounded"], r["rows"]) == ("ok", "0", "True", "2001")
            assert float(r["t_end"]) == pytest.approx(2.0)
            assert float(r["max_abs_e_y"]) == pytest.approx(1.0, abs=1e-6)  # the initial 1 m offset
            assert float(r["late_rms_e_y"]) < 0.9 and float(r["max_abs_delta"]) < 0.05
        else:  # above it: the steering oscillation grows until lk_simulate stops the run (exit 3)
            assert (r["status"], r["exit_code"], r["diverged"], r["bounded"]) == ("ok", "3", "True", "False")
            assert float(r["t_end"]) < 0.5 and float(r["max_abs_delta"]) > 1.0
    # The tracker holds the heading error near -(k_y / k_psi) e_y, so the offset closes at about
    # V k_y / k_psi (0.375 1/s at k_psi = 0.4, half that at 0.8): over the last quarter (1.5-2 s), after the
    # 0.2 s pose delay, |e_y| is near exp(-rate (1.75 - 0.2)).
    for r in rows:
        if r["bounded"] == "True":
            rate = 15 * 0.01 / float(r["tracker.k_psi"])
            assert float(r["late_rms_e_y"]) == pytest.approx(math.exp(-rate * 1.55), rel=0.15)
    with open(os.path.join(out, "sweep.png"), "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    # The points ran in the workers' own processes (the Python module lane_keeping), with no log written.
    engines = set()
    for path in result_files(out):
        with open(path) as f:
            engines.add(json.load(f)["engine"])
    assert engines == {"in-process"} and not os.path.exists(os.path.join(out, "runs"))
    again = fleet(*args)
    assert again.returncode == 0 and "4 tasks: 0 to simulate, 4 done before (skipped)" in again.stderr
    # One lk_simulate per point (the engine where the module is not built) gives every figure to the last digit.
    processes = str(tmp_path / "processes")
    run = fleet(*[processes if a == out else a for a in args], "--keep-logs", env={"LK_FLEET_SWEEP_ENGINE": "process"})
    assert run.returncode == 0, run.stderr
    figures = ("status", "exit_code", "rows", "t_end", "diverged", "bounded", "max_abs_e_y", "rms_e_y", "late_rms_e_y",
               "max_abs_delta", "max_abs_torque")
    by_task = {r["task_id"]: [r[k] for k in figures] for r in rows}
    assert {r["task_id"]: [r[k] for k in figures] for r in read_csv(os.path.join(processes, "sweep.csv"))} == by_task
    for path in result_files(processes):
        with open(path) as f:
            assert json.load(f)["engine"] == "process"
    assert len(glob.glob(os.path.join(processes, "runs", "*.csv"))) == 4


@pytest.mark.parametrize("args, argument, words", [
    (["gap", "--logs", "/nonexistent/**/*.csv"], "--logs", "no log matched"),
    (["sweep", "--grid", "tracker.k_psi=1:0:0.5"], "--grid", "does not lead from 1 to 0"),
    (["sweep", "--grid", "tracker.nosuch=0:1:0.5"], "--grid", "tracker.nosuch is not a known parameter"),
    (["sweep", "--monte-carlo", "5", "--vary", "vehicle.mass=normal(1100,-1)"], "--vary", "sigma must be positive"),
    (["sweep", "--grid", "tracker.k_psi=0:1:0.5", "--scheduler", "nowhere"], "--scheduler", "not an address"),
])
def test_bad_arguments_name_the_argument_and_exit_2(tmp_path, args, argument, words):
    run = fleet(*args, "--config", CONFIG, "--out", str(tmp_path / "out"), "--lk-bin", BIN, timeout=60)
    assert run.returncode == 2
    assert f"argument {argument}: " in run.stderr and words in run.stderr


def test_extra_args_may_not_set_what_the_fleet_sets_per_log(logs, tmp_path):
    run = fleet("gap", "--config", CONFIG, "--logs", os.path.join(logs, "nominal.csv"), "--out", str(tmp_path),
                "--lk-bin", BIN, "--extra-args", "--report /tmp/elsewhere", timeout=60)
    assert run.returncode == 2 and "argument --extra-args: --report is set by lk_fleet per log" in run.stderr
    assert not result_files(str(tmp_path))


def test_grids_and_task_ids():
    assert parse_grid("a.b=0:0.3:0.1") == ("a.b", [0.0, 0.1, 0.2, 0.3])  # stop included, no drift
    assert parse_grid("a.b=1,2.5") == ("a.b", [1.0, 2.5])
    assert task_id({"x": 1, "y": [2]}) == task_id({"y": [2], "x": 1})
    assert task_id({"x": 1}) != task_id({"x": 2})
