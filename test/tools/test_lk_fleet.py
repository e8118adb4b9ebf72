"""lk_fleet (scripts/lk_fleet.py, the package scripts/lk_fleet/) on Dask: a LocalCluster over short logs with a
bad one among them, resume after a finished and after an interrupted run, and a real dask-scheduler with two
dask-workers of which one is killed mid-run. Run: /usr/bin/python3 -m pytest -q test/tools/test_lk_fleet.py (CI
runs it through catkin's run_tests; LK_BIN_DIR names the folder of lk_simulate and lk_gap)."""
import csv
import glob
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
BIN = os.environ.get("LK_BIN_DIR", os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping"))
FLEET = [sys.executable if sys.executable.startswith("/usr/bin/") else "/usr/bin/python3",
         os.path.join(REPO, "scripts", "lk_fleet.py")]
# A small diagnosis: two candidates (the fleet machinery is under test, not the diagnosis).
GAP_ARGS = "--no-plots --effects lateral_disturbance,pose_bias --threads 1"


def simulate(path, *sets):
    cmd = [os.path.join(BIN, "lk_simulate"), "--out", path, "--quiet", "--set", "simulation.duration=6",
           "--set", "simulation.log_rate=100"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def fleet(out, logs_glob, *extra, lk_bin=BIN, wait=True):
    cmd = FLEET + ["gap", "--config", os.path.join(REPO, "config", "default.yaml"), "--logs", logs_glob,
                   "--out", out, "--lk-bin", lk_bin, "--lk-gap-args", GAP_ARGS] + list(extra)
    if not wait:
        # Started as a user's foreground command is, with SIGINT at its default: a test runner started in
        # the background by a shell without job control (`cmd &`) ignores SIGINT, its children inherit
        # that, and a Ctrl-C sent to the fleet was then lost (the run finished every task, three times).
        return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)


def fleet_rows(out):
    with open(os.path.join(out, "fleet.csv")) as f:
        return list(csv.DictReader(f))


def slow_lk_gap(folder, seconds):
    """An lk_gap that first sleeps, so that a worker can be killed while its task runs."""
    path = os.path.join(folder, "lk_gap")
    with open(path, "w") as f:
        f.write("#!/bin/sh\nsleep %g\nexec %s \"$@\"\n" % (seconds, os.path.join(BIN, "lk_gap")))
    os.chmod(path, 0o755)
    return folder


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Fleet(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.logs = os.path.join(cls.tmp.name, "logs")
        os.makedirs(os.path.join(cls.logs, "day2"))
        simulate(os.path.join(cls.logs, "a.csv"))
        simulate(os.path.join(cls.logs, "b.csv"), "disturbance.lateral_force=400")
        simulate(os.path.join(cls.logs, "day2", "c.csv"), "simulation.initial.y=-0.5")
        with open(os.path.join(cls.logs, "day2", "bad.csv"), "w") as f:
            f.write("t,x,y\n0,1\n")  # a ragged row: lk_gap's error names the line

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_local_cluster_diagnoses_every_log_once_and_reports_the_bad_one(self):
        out = os.path.join(self.tmp.name, "local")
        run = fleet(out, os.path.join(self.logs, "**", "*.csv"), "--workers", "2")
        self.assertEqual(run.returncode, 0, run.stderr)
        rows = fleet_rows(out)
        self.assertEqual(sorted(os.path.basename(r["log"]) for r in rows), ["a.csv", "b.csv", "bad.csv", "c.csv"])
        by_name = {os.path.basename(r["log"]): r for r in rows}
        self.assertEqual(by_name["bad.csv"]["status"], "failed")
        self.assertIn("bad input data (exit 4)", by_name["bad.csv"]["error"])
        self.assertIn("bad.csv:2", by_name["bad.csv"]["error"])
        for name in ("a.csv", "b.csv", "c.csv"):
            self.assertEqual(by_name[name]["status"], "ok", by_name[name])
            self.assertIn(by_name[name]["effect"], ("unexplained", "lateral_disturbance", "pose_bias"))
        # 400 N of crosswind the nominal lacks: found, with its force.
        self.assertEqual(by_name["b.csv"]["effect"], "lateral_disturbance")
        self.assertAlmostEqual(float(by_name["b.csv"]["lateral_disturbance.force"]), 400.0, delta=80.0)
        self.assertEqual(len(glob.glob(os.path.join(out, "results", "*.json"))), 4)
        with open(os.path.join(out, "fleet.md")) as f:
            md = f.read()
        self.assertIn("4 logs: 3 diagnosed, 1 failed.", md)
        self.assertTrue(glob.glob(os.path.join(out, "plots", "lateral_disturbance.force.png")))

        # Resume: the same command again diagnoses nothing and leaves every result as it was.
        stamps = {p: os.stat(p).st_mtime_ns for p in glob.glob(os.path.join(out, "results", "*.json"))}
        again = fleet(out, os.path.join(self.logs, "**", "*.csv"), "--workers", "1")
        self.assertEqual(again.returncode, 0, again.stderr)
        self.assertIn("0 to diagnose, 4 done before", again.stderr)
        self.assertEqual(stamps, {p: os.stat(p).st_mtime_ns for p in glob.glob(os.path.join(out, "results", "*.json"))})

    def test_an_interrupted_run_resumes_where_it_stopped(self):
        # Ctrl-C as soon as the first result is written. The shutdown races the worker's task in flight (and,
        # on a loaded machine, its start-up and the test's polling): a run that still finished every task
        # tests nothing, so it is tried again in a fresh folder, up to three times.
        slow = slow_lk_gap(tempfile.mkdtemp(dir=self.tmp.name), 2.0)
        attempts = []
        for attempt in range(3):
            out = os.path.join(self.tmp.name, "interrupted-%d" % attempt)
            proc = fleet(out, os.path.join(self.logs, "**", "*.csv"), "--workers", "1", lk_bin=slow, wait=False)
            deadline = time.time() + 300
            while time.time() < deadline and not glob.glob(os.path.join(out, "results", "*.json")):
                time.sleep(0.05)
            proc.send_signal(signal.SIGINT)  # as a user's Ctrl-C
            _, stderr = proc.communicate(timeout=120)
            done_before = len(glob.glob(os.path.join(out, "results", "*.json")))
            attempts.append((done_before, proc.returncode, stderr))
            self.assertGreaterEqual(done_before, 1)
            if done_before < 4:
                break
        self.assertLess(done_before, 4, "the interruption came too late to test anything, %d times: %s" %
                        (len(attempts), attempts))
        self.assertEqual(proc.returncode, 130, stderr)
        self.assertIn("interrupted: the results written so far are kept", stderr)
        run = fleet(out, os.path.join(self.logs, "**", "*.csv"), "--workers", "2")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("%d to diagnose, %d done before" % (4 - done_before, done_before), run.stderr)
        self.assertEqual(len(fleet_rows(out)), 4)

    def test_a_killed_worker_loses_nothing(self):
        out = os.path.join(self.tmp.name, "cluster")
        slow = slow_lk_gap(tempfile.mkdtemp(dir=self.tmp.name), 3.0)
        port = free_port()
        address = "tcp://127.0.0.1:%d" % port
        procs = [subprocess.Popen(["/usr/bin/dask-scheduler", "--host", "127.0.0.1", "--port", str(port),
                                   "--dashboard-address", ":0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
        try:
            time.sleep(2.0)
            for _ in range(2):
                procs.append(subprocess.Popen(["/usr/bin/dask-worker", address, "--nthreads", "1", "--nworkers", "1",
                                               "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            time.sleep(3.0)
            run = fleet(out, os.path.join(self.logs, "**", "*.csv"), "--scheduler", address, lk_bin=slow, wait=False)
            time.sleep(4.0)  # both workers are inside a task (3 s of sleep, then lk_gap)
            procs[1].send_signal(signal.SIGKILL)
            stdout, stderr = run.communicate(timeout=600)
            self.assertEqual(run.returncode, 0, stderr)
        finally:
            for p in procs:
                if p.poll() is None:
                    p.terminate()
            for p in procs:
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    p.kill()
        rows = fleet_rows(out)
        self.assertEqual(sorted(os.path.basename(r["log"]) for r in rows), ["a.csv", "b.csv", "bad.csv", "c.csv"])
        self.assertEqual(sum(r["status"] == "ok" for r in rows), 3)
        self.assertEqual(len(glob.glob(os.path.join(out, "results", "*.json"))), 4)

    def test_its_own_reports_are_not_logs_and_a_dangling_link_is_named(self):
        # --out inside --logs: the fleet's reports (residuals.csv, overlay.csv) were diagnosed as logs on the
        # next run; a symbolic link to a missing log was dropped without a word.
        root = os.path.join(self.tmp.name, "runs")
        os.makedirs(os.path.join(root, "fleet", "reports", "old"))
        simulate(os.path.join(root, "a.csv"))
        with open(os.path.join(root, "fleet", "reports", "old", "residuals.csv"), "w") as f:
            f.write("t,tracker,actuator,steering,chassis\n0,1,1,1,1\n")
        run = fleet(os.path.join(root, "fleet"), os.path.join(root, "**", "*.csv"))
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual([os.path.basename(r["log"]) for r in fleet_rows(os.path.join(root, "fleet"))], ["a.csv"])
        os.symlink(os.path.join(root, "gone.csv"), os.path.join(root, "b.csv"))
        run = fleet(os.path.join(root, "fleet2"), os.path.join(root, "*.csv"))
        self.assertEqual(run.returncode, 2)
        self.assertIn("b.csv' is a symbolic link to", run.stderr)
        self.assertIn("which does not exist", run.stderr)

    def test_bad_arguments_name_the_argument(self):
        run = fleet(os.path.join(self.tmp.name, "none"), os.path.join(self.logs, "*.nothing"))
        self.assertEqual(run.returncode, 2)
        self.assertIn("--logs", run.stderr)
        self.assertIn("no log matched", run.stderr)


if __name__ == "__main__":
    unittest.main()
