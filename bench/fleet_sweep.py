#!/usr/bin/python3
"""lk_fleet sweep's throughput (issue 49; docs/fleet.md): the same grid of closed-loop runs swept in-process (the
Python module lane_keeping, no process and no CSV per point) and with one lk_simulate per point
(LK_FLEET_SWEEP_ENGINE=process), one after the other in one run, on a LocalCluster; then a check that the two
sweeps' figures agree to the last digit. Prints a table; asserts nothing else.

    /usr/bin/python3 bench/fleet_sweep.py [--points 1000] [--duration 20] [--workers 2]

The grid: tracker.k_psi x tracker.k_y x tau2 (both actuator delays) around the paper's Fig 6 point
(config/scenarios/fig6.yaml, brush tires), every point stable; 1,000 points = 10 x 10 x 10.
"""
import argparse
import csv
import json
import glob
import os
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
BIN = os.environ.get("LK_BIN_DIR", os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping"))
FLEET = ["/usr/bin/python3", os.path.join(REPO, "scripts", "lk_fleet.py")]
CONFIG = os.path.join(REPO, "config", "scenarios", "fig6.yaml")
TAU2 = "delays.desired_steering_to_actuator+delays.steering_angle_to_actuator"
FIGURES = ("rows", "t_end", "diverged", "bounded", "max_abs_e_y", "rms_e_y", "late_rms_e_y", "max_abs_delta",
           "max_abs_torque")


def grid(points):
    """Three axes of n values each, n^3 >= points (the extra points of the last axis are not used)."""
    n = 1
    while n ** 3 < points:
        n += 1
    k_psi = ",".join(f"{0.4 + 0.1 * i:.3g}" for i in range(n))
    k_y = ",".join(f"{0.01 * (i + 1):.3g}" for i in range(n))
    tau2 = ",".join(f"{1e-4 * (i + 1):.3g}" for i in range(max(1, -(-points // (n * n)))))
    return ["--grid", f"tracker.k_psi={k_psi}", "--grid", f"tracker.k_y={k_y}", "--grid", f"{TAU2}={tau2}"]


def sweep(engine, out, args):
    env = dict(os.environ, LK_FLEET_SWEEP_ENGINE=engine)
    command = FLEET + ["sweep", "--config", CONFIG, "--set", f"simulation.duration={args.duration:g}",
                       *grid(args.points), "--out", out, "--workers", str(args.workers), "--lk-bin", BIN,
                       "--progress-interval", "60"]
    start = time.monotonic()
    proc = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        sys.exit(f"{engine} sweep failed ({proc.returncode}):\n{proc.stderr}")
    results = []
    for path in glob.glob(os.path.join(out, "results", "*.json")):
        with open(path) as f:
            results.append(json.load(f))
    engines = {r.get("engine") for r in results}
    if engines != {engine}:
        sys.exit(f"asked for the {engine} engine, the results name {engines}")
    # The span: the first task's start to the last task's end (without the cluster's start-up).
    span = max(r["finished_at"] for r in results) - min(r["finished_at"] - r["wall_seconds"] for r in results)
    per_task = sum(r["wall_seconds"] for r in results) / len(results)
    return {"points": len(results), "wall": wall, "span": span, "per_task": per_task}


def figures(out):
    with open(os.path.join(out, "sweep.csv")) as f:
        return {r["task_id"]: tuple(r[k] for k in FIGURES) for r in csv.DictReader(f)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=1000)
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]
    print(f"lk_fleet sweep: {args.points} points of {args.duration:g} s runs (Fig 6, brush tires), "
          f"{args.workers} workers, load average {load} before")
    with tempfile.TemporaryDirectory(prefix="lk_sweep_bench_") as tmp:
        rows = {}
        for engine in ("in-process", "process"):
            rows[engine] = sweep(engine, os.path.join(tmp, engine), args)
        same = figures(os.path.join(tmp, "in-process")) == figures(os.path.join(tmp, "process"))
    print(f"{'engine':<12} {'points':>7} {'wall s':>8} {'points/s':>9} {'span s':>8} {'points/s (span)':>16} "
          f"{'s per task':>11}")
    for engine, r in rows.items():
        print(f"{engine:<12} {r['points']:>7} {r['wall']:>8.1f} {r['points'] / r['wall']:>9.2f} {r['span']:>8.1f} "
              f"{r['points'] / r['span']:>16.2f} {r['per_task']:>11.4f}")
    print(f"speed-up in-process / process: {rows['process']['wall'] / rows['in-process']['wall']:.2f}x wall, "
          f"{rows['process']['span'] / rows['in-process']['span']:.2f}x span")
    print("the two sweeps' figures (sweep.csv, every point):", "identical" if same else "DIFFER")


if __name__ == "__main__":
    main()
