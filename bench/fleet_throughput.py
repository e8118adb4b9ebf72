#!/usr/bin/python3
"""lk_fleet's figures (docs/fleet.md): throughput with 1 and 2 workers on identical short logs, the same logs
diagnosed one after another without Dask, and the scheduler's own cost per task (no-op tasks on a
LocalCluster against calling the function directly).

    /usr/bin/python3 bench/fleet_throughput.py [LOGS] [SECONDS_PER_LOG]     (default 8 logs of 10 s at 100 Hz)
"""
import os
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
BIN = os.environ.get("LK_BIN_DIR", os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping"))
FLEET = ["/usr/bin/python3", os.path.join(REPO, "scripts", "lk_fleet.py")]
CONFIG = os.path.join(REPO, "config", "default.yaml")


def noop(x):
    return x


def scheduler_overhead(tasks=400):
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        client.gather(client.map(noop, range(20), pure=False))  # warm up
        start = time.perf_counter()
        client.gather(client.map(noop, range(tasks), pure=False))
        through_dask = (time.perf_counter() - start) / tasks
    start = time.perf_counter()
    for i in range(tasks):
        noop(i)
    direct = (time.perf_counter() - start) / tasks
    return through_dask, direct


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
    with tempfile.TemporaryDirectory() as tmp:
        logs = os.path.join(tmp, "logs")
        os.makedirs(logs)
        for i in range(count):  # identical runs but for the noise-free start offset: the same work per log
            subprocess.run([os.path.join(BIN, "lk_simulate"), "--out", os.path.join(logs, "run%02d.csv" % i),
                            "--quiet", "--set", "simulation.duration=%g" % seconds, "--set",
                            "simulation.log_rate=100", "--set", "disturbance.lateral_force=400"], check=True)
        start = time.perf_counter()
        for i in range(count):
            subprocess.run([os.path.join(BIN, "lk_gap"), "--config", CONFIG, "--log",
                            os.path.join(logs, "run%02d.csv" % i), "--report", os.path.join(tmp, "direct%d" % i),
                            "--quiet", "--no-plots", "--threads", "1"], check=True, stdout=subprocess.DEVNULL)
        direct = time.perf_counter() - start
        print("%d logs of %g s at 100 Hz, all 11 candidates, one thread per lk_gap" % (count, seconds))
        print("%-34s %9s %11s" % ("", "wall [s]", "logs/min"))
        print("%-34s %9.1f %11.1f" % ("one after another, no Dask", direct, 60.0 * count / direct))
        for workers in (1, 2):
            out = os.path.join(tmp, "fleet%d" % workers)
            start = time.perf_counter()
            subprocess.run(FLEET + ["gap", "--config", CONFIG, "--logs", os.path.join(logs, "*.csv"), "--out", out,
                                    "--workers", str(workers), "--lk-gap-args", "--no-plots --threads 1"],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            wall = time.perf_counter() - start
            print("%-34s %9.1f %11.1f" % ("lk_fleet, LocalCluster, %d worker%s" % (workers, "s" * (workers > 1)),
                                          wall, 60.0 * count / wall))
    through_dask, direct_call = scheduler_overhead()
    print("scheduler cost per task: %.2f ms through a LocalCluster (2 workers), %.4f ms direct"
          % (1e3 * through_dask, 1e3 * direct_call))


if __name__ == "__main__":
    main()
