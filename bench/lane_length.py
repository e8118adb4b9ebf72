#!/usr/bin/python3
"""Lanes of real length: lk_simulate (whole process, 20 s of the sinusoid scenario's loop) on a straight lane
and on waypoint lanes of 10, 1,000 and 100,000 points (the same gentle S, sampled ever more densely: maps
give thousands of points per kilometre), inline in the YAML and, for 100,000, in a CSV file beside it; and the
cost of 100 s of driving alone (a 120 s run minus a 20 s run: the lane queries without the start-up). Side by side
in one run, median of 7 (docs/benchmarks.md, "Lanes of real length"). Given several builds' lk_simulate (before and after a change),
runs them alternately and prints a table for each.

    /usr/bin/python3 bench/lane_length.py [LK_SIMULATE ...]   (default: build/ws/devel/lib/lane_keeping/lk_simulate)
"""
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BINS = sys.argv[1:] or [os.path.join(REPO, "build/ws/devel/lib/lane_keeping/lk_simulate")]


def lane_points(points):
    xs = [-50.0 + 600.0 * i / (points - 1) for i in range(points)]
    return [(x, 1.5 * math.sin(2 * math.pi * x / 300.0)) for x in xs]


def lane_yaml(points, csv=None):
    """The lane inline in the YAML, or (csv given) in a CSV file beside it (path.waypoints: FILE)."""
    if points == 0:
        return "path:\n  type: straight\n"
    if csv:
        with open(csv, "w") as f:
            f.write("x,y\n" + "".join("%.4f,%.5f\n" % p for p in lane_points(points)))
        return "path:\n  type: waypoints\n  waypoints: %s\n" % os.path.basename(csv)
    pts = ", ".join("[%.4f, %.5f]" % p for p in lane_points(points))
    return "path:\n  type: waypoints\n  waypoints: [%s]\n" % pts


def run(binary, config, duration):
    start = time.perf_counter()
    subprocess.run([binary, "--config", config, "--set", "simulation.duration=%g" % duration, "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def main():
    with tempfile.TemporaryDirectory() as tmp:
        configs = {}
        for n, csv in ((0, False), (10, False), (1000, False), (100000, False), (100000, True)):
            name = "%d waypoints%s" % (n, " (CSV file)" if csv else " (YAML)") if n else "straight"
            path = os.path.join(tmp, "lane_%d%s.yaml" % (n, "_csv" if csv else ""))
            with open(path, "w") as f:
                f.write(lane_yaml(n, os.path.join(tmp, "lane_%d.csv" % n) if csv else None))
            configs[name] = path
        # 20 s runs (the figure, start-up included: reading the lane, building the spline) and 120 s
        # runs: their difference is the cost of 100 s of driving alone, i.e. of the lane queries.
        times = {(b, n, d): [] for b in BINS for n in configs for d in (20, 120)}
        for _ in range(7):  # interleaved: the machine's speed drifts
            for n, path in configs.items():
                for d in (20, 120):
                    for b in BINS:
                        times[(b, n, d)].append(run(b, path, d))
        med = {k: statistics.median(v) for k, v in times.items()}
        for b in BINS:
            if len(BINS) > 1:
                print("\n" + b)
            base20 = med[(b, "straight", 20)]
            base_drive = med[(b, "straight", 120)] - base20
            print("%-30s %12s %8s %16s %8s" % ("lane", "20 s run [s]", "ratio", "100 s driving [s]", "ratio"))
            for name in configs:
                drive = med[(b, name, 120)] - med[(b, name, 20)]
                print("%-30s %12.3f %8.2f %16.3f %8.2f" % (name, med[(b, name, 20)], med[(b, name, 20)] / base20,
                                                              drive, drive / base_drive))


if __name__ == "__main__":
    main()
