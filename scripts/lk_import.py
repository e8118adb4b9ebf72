#!/usr/bin/python3
"""lk_import: a public real-car dataset's segment -> the suite's log CSV (docs/real_car.md).

    /usr/bin/python3 scripts/lk_import.py comma2k19 SEGMENT_DIR --out run.csv [--scenario-out run.yaml]
                                          [--rate 100] [--dbc FILE ...]
    /usr/bin/python3 scripts/lk_import.py aim EXPORT.csv --out run.csv [--scenario-out run.yaml]
                                          [--start S] [--end S]

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
aim (an AiM data logger's "AiM CSV File" export, RaceStudio's format; data/aim_super_fj/ holds one): a header
block of "key","value" rows, a blank row, the channel names, their units, a blank row, then samples on one time
base. Read: Time [s], GPS Speed [km/h], GPS Heading [deg, clockwise from north: the GNSS course over ground, not
where the car points], GPS Latitude/Longitude [deg], steering [deg at the steering wheel], LateralAcc and
InlineAcc [g], YawRate [deg/s]; optional --start/--end cut [s of the log's own Time]. The position goes to the
local frame as for comma2k19 (x along the first course); psi is the course (the body slip is not removed: the
log has no heading sensor), unwrapped, with single-sample spikes of an export that interpolated the course
across +-180 deg replaced by their neighbours' mean (each repair printed). AiM's signs (yaw rate and steering
positive to the right, LateralAcc positive to the right) are found, not assumed: yaw rate against d(psi)/dt,
ay against v * yaw rate, the steering-wheel angle against the yaw rate; a negative correlation flips the
channel and says so. Columns written: t, x, y, psi, yaw_rate, v, ay (schema, SI), steering_wheel_angle [rad,
positive left] (the vehicle file's `log:` mapping divides by the steer ratio), ax [m/s^2], course_raw_deg (the
export's heading as logged, for checking). Time restarts at 0 at the cut's first sample.
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


# ---- AiM CSV export ------------------------------------------------------------------------------------

G = 9.80665  # standard gravity [m/s^2]: AiM logs accelerations in g
AIM_CHANNELS = {  # schema use: (AiM channel name, unit it must carry)
    "time": ("Time", "s"), "speed": ("GPS Speed", "km/h"), "course": ("GPS Heading", "deg"),
    "lat": ("GPS Latitude", "deg"), "lon": ("GPS Longitude", "deg"), "steering": ("steering", "deg"),
    "ay": ("LateralAcc", "g"), "ax": ("InlineAcc", "g"), "yaw_rate": ("YawRate", "deg/s"),
}


def read_aim_csv(path):
    """(metadata {key: [values]}, {channel name: (unit, float array)}) of an "AiM CSV File" export."""
    import csv
    try:
        with open(path, newline="", encoding="utf-8-sig", errors="replace") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InputError("%s: cannot read (%s)" % (path, e.strerror))
    if not rows or rows[0][:2] != ["Format", "AiM CSV File"]:
        raise InputError('%s:1: not an AiM CSV export (the first row must be "Format","AiM CSV File")' % path)
    meta, i = {}, 0
    while i < len(rows) and any(c.strip() for c in rows[i]):
        meta[rows[i][0]] = rows[i][1:]
        i += 1
    while i < len(rows) and not any(c.strip() for c in rows[i]):
        i += 1
    if i + 1 >= len(rows):
        raise InputError("%s: no channel-name and unit rows after the header block" % path)
    names, units, first = rows[i], rows[i + 1], i + 2
    if len(units) != len(names):
        raise InputError("%s:%d: %d units for %d channels" % (path, i + 2, len(units), len(names)))
    data = []
    for number, row in enumerate(rows[first:], first + 1):
        if not any(c.strip() for c in row):
            continue
        if len(row) != len(names):
            raise InputError("%s:%d: %d values for %d channels" % (path, number, len(row), len(names)))
        try:
            data.append([float(c) for c in row])
        except ValueError:
            raise InputError("%s:%d: a value that is not a number (%s)" % (path, number, ",".join(row)[:80]))
    if len(data) < 10:
        raise InputError("%s: %d samples; at least 10 are needed" % (path, len(data)))
    table = np.array(data)
    return meta, {name: (unit.strip(), table[:, k]) for k, (name, unit) in enumerate(zip(names, units))}


def sign_agreement(a, b):
    """(r, how): the correlation of a and b, or, where it is weak (|r| < 0.3: a steady corner has almost no
    variation to correlate), the uncentred cosine sum(a b) / sqrt(sum a^2 sum b^2), whose sign still holds."""
    varies = all(x.std() > 1e-6 * (np.abs(x).max() + 1e-300) for x in (a, b))
    r = correlation(a, b) if varies else 0.0
    if abs(r) >= 0.3:
        return r, "r"
    d = math.sqrt(float((a * a).sum() * (b * b).sum()))
    return (float((a * b).sum()) / d if d > 0 else 0.0), "cos"


def repair_course_spikes(course_deg, report):
    """Unwrapped course [deg]. A sample that differs from both neighbours by more than 30 deg while they agree
    within 30 deg is an export's interpolation across +-180 (e.g. 178.4, 89.4, -179.5): it takes their mean.
    So is a sample whose neighbours, as exported, lie on either side of +-180 and which lies between them the
    long way round, however little it differs from them (179.07, 171.01, -178.86: no course on the short arc
    between the neighbours takes such a value)."""
    raw = np.asarray(course_deg, dtype=float)
    c = np.degrees(np.unwrap(np.radians(raw)))
    for k in range(1, len(c) - 1):
        before, after = c[k] - c[k - 1], c[k + 1] - c[k]
        across = abs(raw[k + 1] - raw[k - 1]) > 180.0 and min(raw[k - 1], raw[k + 1]) < raw[k] < max(raw[k - 1], raw[k + 1])
        if across or (abs(before) > 30.0 and abs(after) > 30.0 and abs(c[k + 1] - c[k - 1]) < 30.0):
            report("  course sample %d: %.4f deg replaced by its neighbours' mean (an interpolation across "
                   "+-180 deg)" % (k, course_deg[k]))
            c[k] = 0.5 * (c[k - 1] + c[k + 1])
            c[k + 1:] -= 360.0 * round((c[k + 1] - c[k]) / 360.0)
    return np.degrees(np.unwrap(np.radians(c)))


def geodetic_to_ecef(lat, lon, h=0.0):
    """ECEF [m] of geodetic (lat, lon) [rad] at height h [m] on WGS84."""
    e2 = WGS84_F * (2.0 - WGS84_F)
    n = WGS84_A / np.sqrt(1.0 - e2 * np.sin(lat) ** 2)
    return np.column_stack([(n + h) * np.cos(lat) * np.cos(lon), (n + h) * np.cos(lat) * np.sin(lon),
                            (n * (1.0 - e2) + h) * np.sin(lat)])


def import_aim(path, start=None, end=None, report=print):
    meta, channels = read_aim_csv(path)
    ch = {}
    for key, (name, unit) in AIM_CHANNELS.items():
        if name not in channels:
            raise InputError('%s: no channel "%s" (has: %s)' % (path, name, ", ".join(sorted(channels))))
        if channels[name][0] != unit:
            raise InputError('%s: channel "%s" in "%s", expected "%s"' % (path, name, channels[name][0], unit))
        ch[key] = channels[name][1]
    t = ch["time"]
    if not np.all(np.diff(t) > 0):
        raise InputError("%s: Time is not strictly increasing" % path)
    keep = np.ones(len(t), bool)
    if start is not None:
        keep &= t >= start - 1e-9
    if end is not None:
        keep &= t <= end + 1e-9
    if keep.sum() < 10:
        raise InputError("%s: %d samples between --start %s and --end %s" % (path, keep.sum(), start, end))
    ch = {k: v[keep] for k, v in ch.items()}
    # A channel the conversion reads must be finite: one NaN course would make every later psi NaN (unwrapped).
    for key, (name, _) in AIM_CHANNELS.items():
        bad = np.flatnonzero(~np.isfinite(ch[key]))
        if bad.size:
            raise InputError('%s: channel "%s" is not a finite number at Time %s (%d samples); cut the log around it '
                             "with --start / --end" % (path, name, ch["time"][bad[0]], bad.size))
    out = {"t": ch["time"] - ch["time"][0]}
    report("%s: %s, %s, %s; %d samples at %.1f Hz, log time %.3f-%.3f s" % (
        path, (meta.get("Vehicle") or ["?"])[0], (meta.get("Session") or ["?"])[0],
        (meta.get("Date") or ["?"])[0], len(out["t"]), 1.0 / np.median(np.diff(out["t"])), ch["time"][0],
        ch["time"][-1]))
    lat, lon = np.radians(ch["lat"]), np.radians(ch["lon"])
    R = enu_rotation(lat[0], lon[0])
    enu = (geodetic_to_ecef(lat, lon) - geodetic_to_ecef(lat[:1], lon[:1])) @ R.T
    course = np.radians(90.0 - repair_course_spikes(ch["course"], report))  # east-north, counter-clockwise
    turn = course[0]
    c, s_ = math.cos(turn), math.sin(turn)
    out["x"] = c * enu[:, 0] + s_ * enu[:, 1]
    out["y"] = -s_ * enu[:, 0] + c * enu[:, 1]
    out["psi"] = course - turn
    report("local frame: origin at %.6f N %.6f E, x axis %.2f deg north of east (the first course)"
           % (ch["lat"][0], ch["lon"][0], math.degrees(turn)))
    out["v"] = ch["speed"] / 3.6
    psi_rate = np.gradient(out["psi"], out["t"])
    checks = []
    r = np.radians(ch["yaw_rate"])
    corr = sign_agreement(r, psi_rate)
    out["yaw_rate"] = r if corr[0] >= 0 else -r
    checks.append(("yaw_rate (YawRate) vs d(psi)/dt of the GNSS course", corr))
    ay = ch["ay"] * G
    corr = sign_agreement(ay, out["v"] * out["yaw_rate"])
    out["ay"] = ay if corr[0] >= 0 else -ay
    checks.append(("ay (LateralAcc) vs v * yaw_rate", corr))
    sw = np.radians(ch["steering"])
    corr = sign_agreement(sw, out["yaw_rate"])
    out["steering_wheel_angle"] = sw if corr[0] >= 0 else -sw
    checks.append(("steering wheel angle vs yaw_rate", corr))
    out["ax"] = ch["ax"] * G
    out["course_raw_deg"] = ch["course"]
    report("sign checks (correlation r, or cos where r is weak; a negative one flips the channel):")
    for what, (corr, how) in checks:
        report("  %-58s %-3s = %+.3f  %s" % (what, how, corr, "as logged" if corr >= 0 else "flipped"))
    step = np.hypot(np.diff(out["x"]), np.diff(out["y"])) / np.diff(out["t"])
    mid_v = 0.5 * (out["v"][1:] + out["v"][:-1])
    report("  speed from positions - GPS speed: mean %+.3f m/s, sd %.3f m/s" % ((step - mid_v).mean(),
                                                                                 (step - mid_v).std()))
    report("speed %.1f-%.1f m/s; |ay| up to %.1f m/s^2; %d rows over %.2f s" % (
        out["v"].min(), out["v"].max(), abs(out["ay"]).max(), len(out["t"]), out["t"][-1]))
    columns = ["t", "x", "y", "psi", "yaw_rate", "v", "ay", "steering_wheel_angle", "ax", "course_raw_deg"]
    return columns, out


def write_scenario(path, out, source, report=print):
    """A scenario for lk_gap (docs/gap.md, --scenario): the driven path as the lane (waypoints every 5 m of
    x, the trajectory smoothed over 1 s), the duration and the mean speed. The log holds no lane: the driven
    path stands in for it, so that the nominal closed loop (the noise-only draws) drives where the car drove.
    The suite's waypoint lanes are functions y(x) (x strictly increasing): a path that turns back on itself
    (a hairpin) cannot be one, and then the scenario holds no lane (said on the report line) and the
    closed-loop draws run on the vehicle file's path."""
    t, x, y = out["t"], out["x"], out["y"]
    k = max(1, int(round(1.0 / (t[1] - t[0]))))
    kernel = np.ones(k) / k
    xs = np.convolve(x, kernel, mode="same")[k:-k]
    ys = np.convolve(y, kernel, mode="same")[k:-k]
    turned_back = float(np.max(np.maximum.accumulate(xs) - xs)) if len(xs) else 0.0
    points = []
    if turned_back <= 1.0:
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
    else:
        report("%s: the driven path turns back on itself (x falls %.0f m below its running maximum): a "
               "waypoint lane y(x) cannot hold it, so the scenario has no lane" % (path, turned_back))
    try:
        with open(path, "w") as f:
            f.write("# lk_import: the run's own settings for lk_gap --scenario (%s)\n" % source)
            f.write("simulation:\n  name: %s\n  duration: %.2f\n  log_rate: %g\n" %
                    (os.path.splitext(os.path.basename(path))[0], t[-1], round(1.0 / (t[1] - t[0]))))
            f.write("vehicle:\n  speed: %.2f\n" % float(np.mean(out["v"])))
            if points:
                f.write("path:\n  type: waypoints\n  waypoints: [%s]\n" %
                        ", ".join("[%.2f, %.3f]" % p for p in points))
            else:
                f.write("# no path: the driven path turns back (x not increasing); see the report line of lk_import\n")
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
    parser.add_argument("dataset", choices=["comma2k19", "aim"])
    parser.add_argument("segment", help="comma2k19: the segment directory (holds processed_log/ and global_pose/); "
                                        "aim: the AiM CSV export")
    parser.add_argument("--out", required=True, help="the CSV to write")
    parser.add_argument("--rate", type=float, default=100.0, help="comma2k19: sampling rate of the written log [Hz]")
    parser.add_argument("--scenario-out", help="also write the run's scenario (the driven path as the lane) for lk_gap")
    parser.add_argument("--dbc", action="append", help="comma2k19: DBC file(s) (default: %s)" % os.path.relpath(DEFAULT_DBC, REPO))
    parser.add_argument("--start", type=float, help="aim: first sample to keep [s of the log's Time]")
    parser.add_argument("--end", type=float, help="aim: last sample to keep [s of the log's Time]")
    args = parser.parse_args(argv)
    if not (args.rate > 0.0 and math.isfinite(args.rate)):
        parser.error("--rate must be a positive number of Hz, not %s" % args.rate)
    if args.start is not None and args.end is not None and not args.end > args.start:
        parser.error("--end (%s) must be after --start (%s)" % (args.end, args.start))
    try:
        if args.dataset == "comma2k19":
            columns, out = import_comma2k19(args.segment, args.dbc or [DEFAULT_DBC], args.rate)
        else:
            columns, out = import_aim(args.segment, args.start, args.end)
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
