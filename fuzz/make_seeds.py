#!/usr/bin/python3
"""Writes the seed corpora fuzz/corpus/<target>/ from the repository's own files (run from anywhere with
Debian's python3; the bags need the messages of a catkin build: PYTHONPATH=build/ws/devel/lib/python3/dist-packages).

  sim_config  config/default.yaml, every scenario and vehicle file; default + a scenario overlay + --set lines
  csv_log     the first rows of the RAV4 log (data/comma2k19) with and without its log mapping; a small log in
              the schema's columns with a BOM, quotes, empty cells and NaN; time in ms through a mapping
  bag_log     two small bags of the suite's topics (as test/ros/bag_log_reader_test.cpp writes them):
              with torque commands, uncompressed; without, bz2-compressed chunks
  path        waypoint lists of config/scenarios/waypoints.yaml and the RAV4 scenario, as raw doubles and as
              points files (header, comments, ';' and whitespace separators, a UTF-8 BOM); the lane change and
              sinusoid of config/scenarios, a tight and an impossible one (wavelength 1e-9)
  options     the tools' numeric option values, good and bad (abc, 5x, +-5, 1e999, nan), and --change texts
  log_mapping the RAV4 mapping, a mapping onto a car's own column names with time in ms, one mapping a column
              twice, a nominal configuration with a log: section
  gap_report  report.json, written by lk_gap on a benchmark log (checked in as is), and one with only the required keys
Each seed stays below 50 kB.
"""
import json
import math
import os
import struct
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORPUS = os.path.join(ROOT, "fuzz", "corpus")


def out(target, name, data):
    os.makedirs(os.path.join(CORPUS, target), exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    assert len(data) < 50000, (target, name, len(data))
    with open(os.path.join(CORPUS, target, name), "wb") as f:
        f.write(data)


def read(rel):
    with open(os.path.join(ROOT, rel), "rb") as f:
        return f.read().decode()


def sim_config():
    files = ["config/default.yaml"] + ["config/scenarios/" + n for n in sorted(os.listdir(os.path.join(ROOT, "config/scenarios")))]
    files += ["config/vehicles/rav4_2018.yaml"]
    for rel in files:
        out("sim_config", os.path.basename(rel), read(rel))
    out("sim_config", "default_fig6_set",
        read("config/default.yaml") + "#--overlay\n" + read("config/scenarios/fig6.yaml") +
        "#--set\ntracker.k_y=0.15\npath.waypoints=[[0, 0], [10, 1]]\nvehicle.speed=20\n")
    out("sim_config", "lane_change_set",
        read("config/scenarios/lane_change.yaml") + "#--set\ntire.front.model=lugre_distributed\nsimulation.duration=1e9\n")


def csv_log():
    lines = read("data/comma2k19/rav4_segment40.csv").splitlines()
    head = "\n".join(lines[:31]) + "\n"
    mapping = read("config/vehicles/rav4_2018.yaml")
    log_section = mapping[mapping.index("log:"):]
    out("csv_log", "rav4_head.csv", head)
    out("csv_log", "rav4_head_mapped", log_section + "#--csv\n" + head)
    cols = ["t", "x", "y", "psi", "yaw_rate", "v", "ay", "delta", "delta_rate", "delta_des", "torque"]
    rows = []
    for i in range(25):
        t = 0.01 * i
        rows.append([t, 15 * t, 0.5 * math.sin(t), 0.01 * t, 0.01, 15.0, 0.2, 0.002 * t, 0.002, 0.001 * t, 3.0])
    body = "\n".join(",".join("%.17g" % v for v in r) for r in rows)
    out("csv_log", "schema.csv", ",".join(cols) + "\n" + body + "\n")
    messy = ["\ufeff" + ",".join('"%s"' % c for c in cols)]
    for i, r in enumerate(rows):
        cells = ["%.6g" % v for v in r]
        if i == 3:
            cells[4] = ""
        if i == 7:
            cells[9] = "nan"
        if i == 9:
            cells[2] = "-inf"
        messy.append(" , ".join(cells))
    out("csv_log", "schema_messy.csv", "\r\n".join(messy) + "\r\n\r\n")
    ms = ["stamp_ms,x,y,psi,yaw_rate,v,wheel"] + [
        "%d,%g,%g,%g,%g,%g,%g" % (10 * i, r[1], r[2], r[3], r[4], r[5], r[7] * 15) for i, r in enumerate(rows)]
    out("csv_log", "time_ms_mapped",
        "log:\n  time: {column: stamp_ms, unit: ms}\n  columns:\n    delta: {column: wheel, scale: 0.0667, offset: 0}\n"
        "    torque: {column: x, unscaled: true}\n#--csv\n" + "\n".join(ms) + "\n")


def bag_log():
    import rospy
    import rosbag
    from lane_keeping.msg import (DesiredSteering, DesiredSteeringArray, SteeringTorque, SteeringTorqueArray,
                                  VehicleState, VehicleStateArray)

    def write(name, with_torque, compression):
        path = os.path.join(CORPUS, "bag_log", name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with rosbag.Bag(path, "w", compression=compression) as bag:
            for k in range(0, 40, 10):
                states = VehicleStateArray()
                for i in range(k, k + 10):
                    s = VehicleState()
                    s.header.stamp = rospy.Time.from_sec(i * 1e-3)
                    s.x, s.y, s.yaw_rate, s.delta, s.speed, s.steering_torque = 15 * i * 1e-3, 0.5, 0.01, 2e-6 * i, 15.0, 3.0
                    states.samples.append(s)
                receipt = rospy.Duration(1.0)
                bag.write("/car/vehicle_state", states, states.samples[0].header.stamp + receipt)
                desired = DesiredSteeringArray()
                d = DesiredSteering()
                d.header.stamp = rospy.Time.from_sec(k * 1e-3)
                d.delta_des = 1e-6 * k
                desired.samples.append(d)
                if k == 30:  # the last desired sample after the last state: the states stay inside it
                    d2 = DesiredSteering()
                    d2.header.stamp = rospy.Time.from_sec(0.05)
                    desired.samples.append(d2)
                bag.write("/car/desired_steering", desired, d.header.stamp + receipt)
                if with_torque:
                    torque = SteeringTorqueArray()
                    t = SteeringTorque()
                    t.header.stamp = d.header.stamp
                    t.torque = 7.0
                    torque.samples.append(t)
                    bag.write("/car/steering_torque", torque, t.header.stamp + receipt)
        assert os.path.getsize(path) < 50000, path

    write("suite_torque.bag", True, "none")
    write("suite_bz2.bag", False, "bz2")


def path():
    import yaml
    lists = {
        "waypoints": yaml.safe_load(read("config/scenarios/waypoints.yaml"))["path"]["waypoints"],
        "rav4": yaml.safe_load(read("data/comma2k19/rav4_segment40.yaml"))["path"]["waypoints"][:40],
        "two": [[0.0, 0.0], [1.0, 1.0]],
        "collinear": [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]],
    }
    for name, points in lists.items():
        out("path", name + ".bin", b"\x00" + b"".join(struct.pack("<dd", x, y) for x, y in points))
        out("path", name + ".csv", b"\x01" + ("x,y\n# a lane\n" + "\n".join("%r,%r" % (x, y) for x, y in points) + "\n").encode())
    out("path", "separators.csv", b"\x01" + b"0 0\n10;0.5\n20\t1\n  30 , 1.5\r\n")
    out("path", "bom.csv", b"\x01" + b"\xef\xbb\xbfx,y\n0,0\n10,0.5\n20,1\n")
    # Lane shapes: first byte 2 (lane change: start, length, offset) or 3 (sinusoid: amplitude, wavelength,
    # start), then three doubles.
    shapes = {"lane_change": (2, (30.0, 60.0, 3.5)), "lane_change_tight": (2, (0.0, 5.0, 3.5)),
              "sinusoid": (3, (1.0, 150.0, 30.0)), "sinusoid_tight": (3, (1.0, 7.0, 0.0)),
              "sinusoid_1e-9": (3, (1.0, 1e-9, 30.0))}
    for name, (mode, values) in shapes.items():
        out("path", name + ".bin", bytes([mode]) + b"".join(struct.pack("<d", v) for v in values))


def options():
    # One value per line, its first byte picking the option (options_fuzz.cpp: 5 number options, 6 whole
    # number options, then --change).
    lines = ["\x00" + v for v in ["4", "0.5", "1e-3", "abc", "5x", "", "+-5", "1e999", "nan", "inf", " 7"]]
    lines += ["\x05" + v for v in ["12", "1e3", "2.5", "0", "256", "257", "-1", "0x10", "+3"]]
    lines += ["\x06" + v for v in ["19", "5", "18", "1000", "1001"]]
    lines += ["\x0b" + v for v in ["10:steering.coulomb_friction=3", "0:tracker.k_y=0.15", "1e9:a=b", "-1:a=b",
                                     "5:a b=1", "5:=1", "5:a=", "nan:a=1", " 2.5 : delays.hold = zoh "]]
    out("options", "values", "\n".join(lines) + "\n")
    out("options", "changes", "\x0b10:steering.coulomb_friction=3\n\x0b10:steering.coulomb_friction=3\n")


def log_mapping():
    mapping = read("config/vehicles/rav4_2018.yaml")
    out("log_mapping", "rav4.yaml", mapping[mapping.index("log:"):])
    out("log_mapping", "own_names.yaml",
        "log:\n  time: {column: stamp_ms, unit: ms}\n  columns:\n    x: {column: east}\n    y: {column: north}\n"
        "    psi: {column: heading}\n    yaw_rate: {column: yaw}\n    v: {column: speed}\n"
        "    delta: {column: wheel, scale: 0.0667, offset: 0}\n    delta_des: {column: wheel_des, scale: 0.0667}\n"
        "    torque: {column: eps, unscaled: true}\n")
    out("log_mapping", "twice.yaml", "log:\n  columns:\n    delta: {column: x}\n    y: {column: x}\n")
    out("log_mapping", "scales.yaml",
        "log:\n  time: {column: t, unit: us}\n  columns:\n    delta: {column: delta, scale: 1e-300}\n"
        "    torque: {column: torque, scale: -1e308, offset: 1e308}\n")
    out("log_mapping", "nominal_with_log.yaml", read("config/scenarios/fig6.yaml") +
        "log:\n  columns:\n    yaw_rate: {column: yaw_rate, scale: 0.0174533}\n")


def gap_report():
    minimal = {
        "where": {"subsystem": "steering", "subsystems": [{"name": "steering", "nrmse": 0.5}], "windows": [],
                  "bands": [{"f0": 0.0, "f1": 1.0, "share": 1.0}]},
        "ranking": [{"effect": "tire_lag", "params": {"tau": 0.1}, "heldout_gap_before": 1.0, "heldout_gap_after": None,
                     "shrink": 0.5}],
        "verdict": {"effect": "unexplained", "confidence": 0.0, "gap_before": 1, "gap_after": 1, "shrink": 0},
        "detection": {"draws": 19, "heldout": {"value": 1.0, "detected": True}},
    }
    out("gap_report", "minimal.json", json.dumps(minimal, indent=1))


if __name__ == "__main__":
    for name in sys.argv[1:] or ["sim_config", "csv_log", "bag_log", "path", "gap_report", "options", "log_mapping"]:
        globals()[name]()
