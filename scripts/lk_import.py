#!/usr/bin/python3
"""lk_import: a public real-car dataset's segment -> the suite's log CSV (docs/real_car.md).

    /usr/bin/python3 scripts/lk_import.py comma2k19 SEGMENT_DIR --out run.csv [--scenario-out run.yaml]
                                          [--rate 100] [--dbc FILE ...]

comma2k19 (commaai/comma2k19, MIT licence): a segment directory holds numpy arrays, `processed_log/<group>/
<signal>/{t,value}` and `global_pose/frame_*`. From them:
  * the raw CAN frames (`processed_log/CAN/raw_can/{t,address,src,data}`) decoded with the car's DBC
    (commaai/opendbc, the Toyota files; data/comma2k19/toyota_rav4_subset.dbc holds the messages used):
    0x24 KINEMATICS (yaw rate, lateral acceleration), 0x260 STEER_TORQUE_SENSOR (driver and EPS torque),
    0x2E4 STEERING_LKA (the torque command openpilot sent and its request flag);
  * the steering-wheel angle and speed comma already decoded (`processed_log/CAN/{steering_angle,speed}`);
  * the GNSS/INS pose (`global_pose/frame_positions`, ECEF, 20 Hz; `frame_orientations`, the quaternion of
    the device frame in ECEF): converted to a local horizontal frame at the first position (east-north,
    turned so that x lies along the first heading; psi counter-clockwise from x, the suite's conventions)
    and the device's forward axis to a heading;
all resampled (linear interpolation, psi unwrapped) to one time base from the latest start to the earliest
end. Sign checks — yaw rate against the heading's derivative, lateral acceleration against speed x yaw rate —
are printed with their correlations; a CAN signal whose correlation is negative is flipped and the flip is
printed (the DBC marks YAW_RATE "verify").

Columns written: t, x, y, psi, yaw_rate, v, ay (the suite's schema, SI units, psi and angles in rad),
steering_wheel_angle [rad] (not the road wheel's: the vehicle file's `log:` mapping divides by the steer
ratio), torque (the STEERING_LKA command while requested, else 0; bus counts, units unknown: map it
`unscaled`), torque_eps, torque_driver (counts), steer_request, yaw_rate_imu [rad/s] (the phone's gyro about
the vertical, for comparison). No delta_des and no lane: openpilot's desired angle is not on the bus.
Exit status: 0 ok, 2 bad arguments, 4 bad input data (a clear message naming the file).
"""
import argparse
import math
import os
import re
import sys

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_DBC = os.path.join(REPO, "data", "comma2k19", "toyota_rav4_subset.dbc")


class InputError(Exception):
    """Bad input data (exit status 4)."""


# ---- DBC ---------------------------------------------------------------------------------------------

class Signal:
    def __init__(self, name, start, length, big_endian, signed, factor, offset):
        self.name, self.start, self.length = name, start, length
        self.big_endian, self.signed, self.factor, self.offset = big_endian, signed, factor, offset

    def raw(self, data):
        """The signal's raw integer from the frame bytes (DBC bit numbering: bit i is bit i % 8 of byte i // 8)."""
        if self.big_endian:
            # Motorola: `start` is the most significant bit; walk towards less significant bits, which
            # continue at bit 7 of the next byte after bit 0 of a byte.
            value, bit = 0, self.start
            for _ in range(self.length):
                byte, pos = divmod(bit, 8)
                if byte >= len(data):
                    raise InputError("signal %s reaches beyond a %d-byte frame" % (self.name, len(data)))
                value = (value << 1) | ((data[byte] >> pos) & 1)
                bit = bit - 1 if pos > 0 else (byte + 1) * 8 + 7
        else:
            value = 0
            for i in range(self.length):
                byte, pos = divmod(self.start + i, 8)
                if byte >= len(data):
                    raise InputError("signal %s reaches beyond a %d-byte frame" % (self.name, len(data)))
                value |= ((data[byte] >> pos) & 1) << i
        if self.signed and value & (1 << (self.length - 1)):
            value -= 1 << self.length
        return value

    def decode(self, data):
        return self.raw(data) * self.factor + self.offset


_BO = re.compile(r"^BO_\s+(\d+)\s+(\w+)\s*:")
_SG = re.compile(r"^\s*SG_\s+(\w+)\s*:\s*(\d+)\|(\d+)@([01])([+-])\s*\(([^,]+),([^)]+)\)")


def read_dbc(paths):
    """address -> (message name, {signal name: Signal}) from DBC files (BO_ and SG_ lines)."""
    messages = {}
    for path in paths:
        try:
            lines = open(path, encoding="utf-8", errors="replace").read().splitlines()
        except OSError as e:
            raise InputError("%s: cannot read the DBC file (%s)" % (path, e.strerror))
        current = None
        for number, line in enumerate(lines, 1):
            m = _BO.match(line)
            if m:
                current = int(m.group(1))
                messages[current] = (m.group(2), {})
                continue
            m = _SG.match(line)
            if m:
                if current is None:
                    raise InputError("%s:%d: a signal before any message" % (path, number))
                name, start, length, order, sign, factor, offset = m.groups()
                messages[current][1][name] = Signal(name, int(start), int(length), order == "0", sign == "-",
                                                    float(factor), float(offset))
            elif not line.startswith(" SG_"):
                current = current if line.strip() else None
    return messages


def decode_signal(frames, messages, address, signal, src=None):
    """(times, values) of one signal over the frames of `address` (on bus `src` if given)."""
    if address not in messages or signal not in messages[address][1]:
        raise InputError("the DBC holds no signal %s in message 0x%X" % (signal, address))
    sig = messages[address][1][signal]
    t, addresses, sources, data = frames
    mask = addresses == address
    if src is not None:
        mask &= sources == src
    if not mask.any():
        raise InputError("no CAN frame with address 0x%X%s in the segment" % (address, "" if src is None else " on bus %d" % src))
    return t[mask], np.array([sig.decode(bytes(d)) for d in data[mask]])


# ---- geodesy -----------------------------------------------------------------------------------------

WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563


def ecef_to_geodetic(p):
    """(lat, lon) [rad] of an ECEF point (Bowring's iteration, converges to < 1e-12 rad in a few steps)."""
    x, y, z = p
    e2 = WGS84_F * (2.0 - WGS84_F)
    lon = math.atan2(y, x)
    r = math.hypot(x, y)
    lat = math.atan2(z, r * (1.0 - e2))
    for _ in range(10):
        n = WGS84_A / math.sqrt(1.0 - e2 * math.sin(lat) ** 2)
        h = r / math.cos(lat) - n
        lat = math.atan2(z, r * (1.0 - e2 * n / (n + h)))
    return lat, lon


def enu_rotation(lat, lon):
    """Rows: the east, north and up unit vectors in ECEF at (lat, lon)."""
    sl, cl, so, co = math.sin(lat), math.cos(lat), math.sin(lon), math.cos(lon)
    return np.array([[-so, co, 0.0], [-sl * co, -sl * so, cl], [cl * co, cl * so, sl]])


def quaternion_matrix(q):
    """Rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


# ---- comma2k19 ---------------------------------------------------------------------------------------

def load(segment, *parts):
    path = os.path.join(segment, *parts)
    if not os.path.isfile(path):
        raise InputError("%s: missing (is %s a comma2k19 segment directory?)" % (path, segment))
    try:
        return np.load(path, allow_pickle=False)
    except (ValueError, OSError) as e:
        raise InputError("%s: not a numpy array (%s)" % (path, e))


def correlation(a, b):
    a, b = a - a.mean(), b - b.mean()
    d = math.sqrt(float((a * a).sum() * (b * b).sum()))
    return float((a * b).sum()) / d if d > 0 else 0.0


def import_comma2k19(segment, dbc_paths, rate, report=print):
    messages = read_dbc(dbc_paths)
    can = "processed_log/CAN"
    frames = (load(segment, can, "raw_can", "t"), load(segment, can, "raw_can", "address"),
              load(segment, can, "raw_can", "src"), load(segment, can, "raw_can", "data"))
    series = {}
    series["yaw_rate_can"] = decode_signal(frames, messages, 0x24, "YAW_RATE", 0)
    series["ay_can"] = decode_signal(frames, messages, 0x24, "ACCEL_Y", 0)
    series["torque_eps"] = decode_signal(frames, messages, 0x260, "STEER_TORQUE_EPS", 0)
    series["torque_driver"] = decode_signal(frames, messages, 0x260, "STEER_TORQUE_DRIVER", 0)
    series["torque_cmd"] = decode_signal(frames, messages, 0x2E4, "STEER_TORQUE_CMD")
    series["steer_request"] = decode_signal(frames, messages, 0x2E4, "STEER_REQUEST")
    series["steering_wheel_angle"] = (load(segment, can, "steering_angle", "t"),
                                      np.radians(load(segment, can, "steering_angle", "value").reshape(-1)))
    series["v"] = (load(segment, can, "speed", "t"), load(segment, can, "speed", "value").reshape(-1))
    gyro_t, gyro = load(segment, "processed_log/IMU/gyro", "t"), load(segment, "processed_log/IMU/gyro", "value")

    pose_t = load(segment, "global_pose", "frame_times")
    positions = load(segment, "global_pose", "frame_positions")
    orientations = load(segment, "global_pose", "frame_orientations")
    if len(pose_t) < 10 or positions.shape != (len(pose_t), 3) or orientations.shape != (len(pose_t), 4):
        raise InputError("%s: global_pose arrays of unexpected shapes %s, %s for %d times" %
                         (segment, positions.shape, orientations.shape, len(pose_t)))
    lat, lon = ecef_to_geodetic(positions[0])
    R = enu_rotation(lat, lon)
    enu = (positions - positions[0]) @ R.T
    forward = np.array([R @ quaternion_matrix(q) @ np.array([1.0, 0.0, 0.0]) for q in orientations])
    heading = np.unwrap(np.arctan2(forward[:, 1], forward[:, 0]))
    # The local frame's x axis along the first heading (east-north turned by it): the lane the car drives
    # is then a function y(x), as the suite's waypoint lanes are.
    turn = heading[0]
    c, s_ = math.cos(turn), math.sin(turn)
    enu = np.column_stack([c * enu[:, 0] + s_ * enu[:, 1], -s_ * enu[:, 0] + c * enu[:, 1], enu[:, 2]])
    heading = heading - turn
    report("local frame: origin at %.6f N %.6f E, x axis %.2f deg north of east (the first heading)"
           % (math.degrees(lat), math.degrees(lon), math.degrees(turn)))
    # The vertical of the device in ENU: the phone's gyro about it is a yaw rate (device z points down).
    up_in_device = np.array([quaternion_matrix(q).T @ R[2] for q in orientations])

    t0 = max(pose_t[0], gyro_t[0], *(s[0][0] for s in series.values()))
    t1 = min(pose_t[-1], gyro_t[-1], *(s[0][-1] for s in series.values()))
    if not t1 - t0 > 1.0:
        raise InputError("%s: the signals overlap for %.3f s only" % (segment, t1 - t0))
    t = np.arange(t0, t1, 1.0 / rate)
    out = {"t": t - t0}
    out["x"] = np.interp(t, pose_t, enu[:, 0])
    out["y"] = np.interp(t, pose_t, enu[:, 1])
    out["psi"] = np.interp(t, pose_t, heading)
    for name, (ts, vs) in series.items():
        out[name] = np.interp(t, ts, vs)
    up = np.array([np.interp(t, pose_t, up_in_device[:, k]) for k in range(3)])
    g = np.array([np.interp(t, gyro_t, gyro[:, k]) for k in range(3)])
    out["yaw_rate_imu"] = (g * up).sum(axis=0)  # the rotation rate about the local vertical

    # Sign checks (the DBC's YAW_RATE says "verify"): against the pose and the kinematics.
    psi_rate = np.gradient(out["psi"], out["t"])
    checks = []
    c = correlation(out["yaw_rate_can"], psi_rate)
    yaw_sign = 1.0 if c >= 0 else -1.0
    checks.append(("yaw_rate (CAN 0x24) vs d(psi)/dt of the GNSS/INS heading", c, yaw_sign))
    c_imu = correlation(out["yaw_rate_imu"], psi_rate)
    checks.append(("yaw_rate_imu (phone gyro) vs d(psi)/dt", c_imu, 1.0 if c_imu >= 0 else -1.0))
    out["yaw_rate"] = yaw_sign * np.radians(out["yaw_rate_can"])
    out["yaw_rate_imu"] *= 1.0 if c_imu >= 0 else -1.0
    c = correlation(out["ay_can"], out["v"] * out["yaw_rate"])
    ay_sign = 1.0 if c >= 0 else -1.0
    checks.append(("ay (CAN 0x24) vs v * yaw_rate", c, ay_sign))
    out["ay"] = ay_sign * out["ay_can"]
    course = np.unwrap(np.arctan2(np.gradient(out["y"], out["t"]), np.gradient(out["x"], out["t"])))
    moving = out["v"] > 3.0
    slip = np.degrees(out["psi"][moving] - course[moving])
    report("sign checks (correlation; sign applied):")
    for what, corr, sign in checks:
        report("  %-58s r = %+.3f  sign %+d" % (what, corr, int(sign)))
    report("  heading - course over ground (a body slip and a mounting offset): mean %+.2f deg, sd %.2f deg"
           % (slip.mean(), slip.std()) if moving.any() else "  heading vs course: the car does not move")
    requested = out["steer_request"] > 0.5
    out["torque"] = np.where(requested, out["torque_cmd"], 0.0)
    out["steer_request"] = requested.astype(float)
    report("openpilot steering engaged %.0f %% of the time; speed %.1f-%.1f m/s; %d rows at %g Hz over %.1f s"
           % (100.0 * requested.mean(), out["v"].min(), out["v"].max(), len(t), rate, t1 - t0))
    columns = ["t", "x", "y", "psi", "yaw_rate", "v", "ay", "steering_wheel_angle", "torque", "torque_eps",
               "torque_driver", "steer_request", "yaw_rate_imu"]
    return columns, out


def write_scenario(path, out, source):
    """A scenario for lk_gap (docs/gap.md, --scenario): the driven path as the lane (waypoints every 5 m of
    x, the trajectory smoothed over 1 s), the duration and the mean speed. The log holds no lane: the driven
    path stands in for it, so that the nominal closed loop (the noise-only draws) drives where the car drove."""
    t, x, y = out["t"], out["x"], out["y"]
    k = max(1, int(round(1.0 / (t[1] - t[0]))))
    kernel = np.ones(k) / k
    xs = np.convolve(x, kernel, mode="same")[k:-k]
    ys = np.convolve(y, kernel, mode="same")[k:-k]
    points = []
    for target in np.arange(math.ceil(xs.min() / 5.0) * 5.0, xs.max(), 5.0):
        i = int(np.argmin(np.abs(xs - target)))
        if not points or xs[i] > points[-1][0] + 1.0:
            points.append((float(xs[i]), float(ys[i])))
    if len(points) < 4:
        raise InputError("%s: the car moves too little along x for a waypoint lane" % source)
    # Straight continuations before and after, so that the lane covers the whole run.
    (x0, y0), (x1, y1) = points[0], points[1]
    points.insert(0, (x0 - 50.0, y0 - 50.0 * (y1 - y0) / (x1 - x0)))
    (xa, ya), (xb, yb) = points[-2], points[-1]
    points.append((xb + 50.0, yb + 50.0 * (yb - ya) / (xb - xa)))
    try:
        with open(path, "w") as f:
            f.write("# lk_import: the run's own settings for lk_gap --scenario (%s)\n" % source)
            f.write("simulation:\n  name: %s\n  duration: %.2f\n  log_rate: %g\n" %
                    (os.path.splitext(os.path.basename(path))[0], t[-1], round(1.0 / (t[1] - t[0]))))
            f.write("vehicle:\n  speed: %.2f\n" % float(np.mean(out["v"])))
            f.write("path:\n  type: waypoints\n  waypoints: [%s]\n" %
                    ", ".join("[%.2f, %.3f]" % p for p in points))
    except OSError as e:
        raise InputError("%s: cannot write (%s)" % (path, e.strerror))


def write_csv(path, columns, out):
    table = np.column_stack([out[c] for c in columns])
    try:
        with open(path, "w") as f:
            f.write(",".join(columns) + "\n")
            np.savetxt(f, table, delimiter=",", fmt="%.7g")
    except OSError as e:
        raise InputError("%s: cannot write (%s)" % (path, e.strerror))


def main(argv):
    parser = argparse.ArgumentParser(prog="lk_import", description=__doc__.split("\n")[0])
    parser.add_argument("dataset", choices=["comma2k19"])
    parser.add_argument("segment", help="the segment directory (holds processed_log/ and global_pose/)")
    parser.add_argument("--out", required=True, help="the CSV to write")
    parser.add_argument("--rate", type=float, default=100.0, help="sampling rate of the written log [Hz]")
    parser.add_argument("--scenario-out", help="also write the run's scenario (the driven path as the lane) for lk_gap")
    parser.add_argument("--dbc", action="append", help="DBC file(s) (default: %s)" % os.path.relpath(DEFAULT_DBC, REPO))
    args = parser.parse_args(argv)
    if not (args.rate > 0.0 and math.isfinite(args.rate)):
        parser.error("--rate must be a positive number of Hz, not %s" % args.rate)
    try:
        columns, out = import_comma2k19(args.segment, args.dbc or [DEFAULT_DBC], args.rate)
        write_csv(args.out, columns, out)
        if args.scenario_out:
            write_scenario(args.scenario_out, out, args.segment)
            print("wrote %s" % args.scenario_out)
    except InputError as e:
        print("lk_import: %s" % e, file=sys.stderr)
        return 4
    print("wrote %s" % args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
