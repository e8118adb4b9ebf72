"""lk_import (scripts/lk_import.py): the DBC decoding on frames of the comma2k19 example segment, decoded by
hand from the DBC's start bit, length, byte order, sign, factor and offset; the geodesy on closed forms; the
AiM CSV import on a synthetic right-hand circle whose course crosses +-180 deg (units, signs found by the
checks, the export's interpolation across the wrap repaired, the cut) and on the committed Fuji excerpt.
Run: /usr/bin/python3 -m unittest discover -s test/tools (the gap tests run it: RealCar.ImporterUnitTests)."""
import io
import math
import os
import sys
import tempfile
import unittest

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "scripts"))
import lk_import  # noqa: E402

DBC = lk_import.read_dbc([lk_import.DEFAULT_DBC])


def decode(address, signal, hex_frame):
    return DBC[address][1][signal].decode(bytes.fromhex(hex_frame))


class DecodesKnownFrames(unittest.TestCase):
    def test_kinematics_0x24(self):
        # 01 fe 01 d5 41 f9 80 bb: YAW_RATE 1|10@0+ -> (0x01 & 3) << 8 | 0xfe = 510 -> 510 * 0.244 - 125;
        # ACCEL_Y 33|10@0+ -> (0x41 & 3) << 8 | 0xf9 = 505 -> 505 * 0.03589 - 18.375.
        self.assertAlmostEqual(decode(0x24, "YAW_RATE", "01fe01d541f980bb"), 510 * 0.244 - 125, places=9)
        self.assertAlmostEqual(decode(0x24, "ACCEL_Y", "01fe01d541f980bb"), 505 * 0.03589 - 18.375, places=9)

    def test_steer_torque_sensor_0x260(self):
        # 08 ff fb 00 00 00 18 84: DRIVER 15|16@0- -> 0xfffb = -5; EPS 47|16@0- -> 0x0018 = 24;
        # STEER_ANGLE 31|16 -> 0; INITIALIZING bit 3 of byte 0 -> 1; OVERRIDE bit 0 -> 0.
        frame = "08fffb0000001884"
        self.assertEqual(decode(0x260, "STEER_TORQUE_DRIVER", frame), -5)
        self.assertEqual(decode(0x260, "STEER_TORQUE_EPS", frame), 24)
        self.assertEqual(decode(0x260, "STEER_ANGLE", frame), 0)
        self.assertEqual(decode(0x260, "STEER_ANGLE_INITIALIZING", frame), 1)
        self.assertEqual(decode(0x260, "STEER_OVERRIDE", frame), 0)

    def test_steering_lka_0x2e4(self):
        # cd ff f6 00 ad: REQUEST bit 0 -> 1; TORQUE_CMD 15|16@0- -> 0xfff6 = -10; COUNTER 6|6@0+ -> bits 6..1
        # of 0xcd = 0b100110 = 38.
        frame = "cdfff600ad"
        self.assertEqual(decode(0x2E4, "STEER_REQUEST", frame), 1)
        self.assertEqual(decode(0x2E4, "STEER_TORQUE_CMD", frame), -10)
        self.assertEqual(decode(0x2E4, "COUNTER", frame), 38)

    def test_little_endian_and_bounds(self):
        sig = lk_import.Signal("S", 4, 8, False, True, 0.5, 1.0)  # bits 4..11, Intel, signed
        self.assertEqual(sig.raw(bytes([0xF0, 0x0F])), -1)        # 0xFF
        self.assertEqual(sig.decode(bytes([0x70, 0x00])), 0.5 * 7 + 1.0)
        with self.assertRaises(lk_import.InputError):
            lk_import.Signal("S", 60, 8, False, False, 1, 0).raw(bytes(8))


class Geodesy(unittest.TestCase):
    def test_geodetic_of_a_point_on_the_equator_and_the_pole(self):
        lat, lon = lk_import.ecef_to_geodetic((lk_import.WGS84_A, 0.0, 0.0))
        self.assertAlmostEqual(lat, 0.0, places=12)
        self.assertAlmostEqual(lon, 0.0, places=12)
        b = lk_import.WGS84_A * (1.0 - lk_import.WGS84_F)
        lat, _ = lk_import.ecef_to_geodetic((1e-3, 0.0, b + 100.0))
        self.assertAlmostEqual(lat, math.pi / 2, places=9)

    def test_enu_rows_are_orthonormal_and_up_is_radial_on_the_equator(self):
        R = lk_import.enu_rotation(0.3, -1.2)
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
        np.testing.assert_allclose(lk_import.enu_rotation(0.0, 0.0)[2], [1.0, 0.0, 0.0], atol=1e-12)

    def test_quaternion_of_a_quarter_turn_about_z(self):
        q = np.array([math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4)])
        np.testing.assert_allclose(lk_import.quaternion_matrix(q) @ [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], atol=1e-12)


class BadInput(unittest.TestCase):
    def test_a_missing_segment_is_a_clear_error(self):
        with self.assertRaises(lk_import.InputError) as e:
            lk_import.import_comma2k19("/nonexistent/segment", [lk_import.DEFAULT_DBC], 100.0, report=lambda *_: None)
        self.assertIn("comma2k19 segment directory", str(e.exception))
        self.assertEqual(lk_import.main(["comma2k19", "/nonexistent/segment", "--out", "/tmp/never.csv"]), 4)


def aim_csv(rows, names=("Time", "GPS Speed", "GPS Heading", "GPS Latitude", "GPS Longitude", "steering",
                          "InlineAcc", "LateralAcc", "YawRate"),
            units=("s", "km/h", "deg", "deg", "deg", "deg", "g", "g", "deg/s")):
    head = ['"Format","AiM CSV File"', '"Vehicle","TEST"', '"Sample Rate","20"', "",
            ",".join('"%s"' % n for n in names), ",".join('"%s"' % u for u in units), ""]
    return "\n".join(head + [",".join('"%s"' % v for v in r) for r in rows]) + "\n"


def right_circle(v=20.0, radius=100.0, course0=170.0, n=200, dt=0.05, glitch=True, glitch_weight=None):
    """AiM rows of a car on a right-hand circle (AiM signs: yaw rate, steering and LateralAcc positive to the
    right), the course starting at course0 [deg clockwise from north] so that it crosses 180 deg; with
    glitch, the sample after the crossing holds what an export interpolating across the wrap gives."""
    lat0, lon0 = math.radians(35.0), math.radians(139.0)
    rm, rn = 6.35643e6, 6.38517e6  # WGS84 meridian and prime-vertical radii of curvature at 35 N
    rows, e, nn = [], 0.0, 0.0
    for k in range(n):
        t = 100.0 + k * dt
        course = course0 + math.degrees(v / radius * k * dt)
        wrapped = (course + 180.0) % 360.0 - 180.0
        rows.append(["%.3f" % t, "%.4f" % (3.6 * v), "%.4f" % wrapped,
                     "%.8f" % math.degrees(lat0 + nn / rm),
                     "%.8f" % math.degrees(lon0 + e / (rn * math.cos(lat0))),
                     "30.0", "0.00", "%.2f" % (v * v / radius / lk_import.G), "%.1f" % math.degrees(v / radius)])
        c = math.radians(course)
        e += v * dt * math.sin(c + 0.5 * v / radius * dt)
        nn += v * dt * math.cos(c + 0.5 * v / radius * dt)
    if glitch:
        k = next(i for i in range(1, n) if float(rows[i][2]) < 0.0)
        if glitch_weight is None:
            rows[k][2] = "%.4f" % (0.5 * (float(rows[k - 1][2]) + 0.0))  # half way to 0: across the wrap
        else:  # a little of the way from the sample before to the sample after, the long way round
            before, after = float(rows[k - 1][2]), float(rows[k + 1][2])
            rows[k][2] = "%.4f" % ((1.0 - glitch_weight) * before + glitch_weight * after)
    return rows


class AimImport(unittest.TestCase):
    def run_import(self, text, **kw):
        with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
            f.write(text)
        self.addCleanup(os.unlink, f.name)
        lines = []
        columns, out = lk_import.import_aim(f.name, report=lines.append, **kw)
        return columns, out, "\n".join(lines)

    def test_units_signs_and_frame_on_a_right_hand_circle(self):
        columns, out, report = self.run_import(aim_csv(right_circle()))
        self.assertEqual(columns[:7], ["t", "x", "y", "psi", "yaw_rate", "v", "ay"])
        np.testing.assert_allclose(out["v"], 20.0, atol=1e-3)
        # Found flipped, not assumed: a right turn has a negative yaw rate, ay and steering in the schema.
        self.assertIn("flipped", report)
        np.testing.assert_allclose(out["yaw_rate"], -0.2, atol=math.radians(0.05))
        np.testing.assert_allclose(out["ay"], -4.0, atol=0.05)
        np.testing.assert_allclose(out["steering_wheel_angle"], -math.radians(30.0), atol=1e-9)
        # psi: counter-clockwise, continuous across +-180 deg, 0 at the start, along x; the glitch repaired.
        self.assertIn("replaced by its neighbours' mean", report)
        self.assertLess(np.max(np.abs(np.diff(out["psi"]))), 0.02)
        np.testing.assert_allclose(np.gradient(out["psi"], out["t"])[1:-1], -0.2, atol=0.005)
        self.assertEqual(out["psi"][0], 0.0)
        self.assertAlmostEqual(out["t"][0], 0.0)
        self.assertGreater(out["x"][1], 0.9)
        self.assertLess(abs(out["y"][1]), 0.05)
        # The positions lie on the circle: radius 100 m about (0, -100) in the local frame (a right turn).
        np.testing.assert_allclose(np.hypot(out["x"], out["y"] + 100.0), 100.0, atol=0.1)

    def test_an_interpolation_a_little_way_across_the_wrap_is_repaired_too(self):
        # Fuji lap 6's course: 179.07, 171.01, -178.86 (2 % of the way round the long arc, 9 deg off).
        _, out, report = self.run_import(aim_csv(right_circle(glitch_weight=0.025)))
        self.assertIn("replaced by its neighbours' mean", report)
        self.assertLess(np.max(np.abs(np.diff(out["psi"]))), 0.02)
        # Without a glitch nothing is replaced, though the course crosses the wrap.
        _, _, clean = self.run_import(aim_csv(right_circle(glitch=False)))
        self.assertNotIn("replaced", clean)

    def test_a_channel_that_is_not_finite_is_refused_naming_it(self):
        rows = right_circle(glitch=False)
        rows[50][2] = "nan"  # the course
        with self.assertRaisesRegex(lk_import.InputError, r'channel "GPS Heading" is not a finite number at Time 102.5'):
            self.run_import(aim_csv(rows))
        # Outside the cut it does not matter.
        _, out, _ = self.run_import(aim_csv(rows), start=103.0)
        self.assertTrue(np.all(np.isfinite(out["psi"])))

    def test_the_cut_restarts_time_at_zero(self):
        _, out, _ = self.run_import(aim_csv(right_circle(glitch=False)), start=102.0, end=104.0)
        self.assertEqual(len(out["t"]), 41)
        self.assertAlmostEqual(out["t"][-1], 2.0, places=6)

    def test_the_committed_excerpt_imports_with_its_checks(self):
        excerpt = os.path.join(REPO, "data", "aim_super_fj", "fuji_t1_excerpt.aim.csv")
        lines = []
        columns, out = lk_import.import_aim(excerpt, report=lines.append)
        report = "\n".join(lines)
        self.assertEqual(len(out["t"]), 748)
        self.assertEqual(report.count("flipped"), 3)  # AiM's yaw rate, LateralAcc and steering: right positive
        self.assertIn("course sample 598: 89.4416 deg replaced", report)
        # Sign checks strong: |r| > 0.9 for the yaw rate against the course rate.
        self.assertRegex(report, r"YawRate\) vs d\(psi\)/dt.* r   = -0\.9[0-9]{2}")

    def test_bad_input_is_a_clear_error(self):
        with self.assertRaises(lk_import.InputError) as e:
            self.run_import("t,v\n0,1\n")
        self.assertIn("not an AiM CSV export", str(e.exception))
        names = ("Time", "GPS Speed", "GPS Heading", "GPS Latitude", "GPS Longitude", "steering", "InlineAcc",
                 "LateralAcc", "YawRateX")
        with self.assertRaises(lk_import.InputError) as e:
            self.run_import(aim_csv(right_circle(), names=names))
        self.assertIn('no channel "YawRate"', str(e.exception))
        units = ("s", "m/s", "deg", "deg", "deg", "deg", "g", "g", "deg/s")
        with self.assertRaises(lk_import.InputError) as e:
            self.run_import(aim_csv(right_circle(), units=units))
        self.assertIn('channel "GPS Speed" in "m/s", expected "km/h"', str(e.exception))
        rows = right_circle()
        rows[5][3] = "n/a"
        with self.assertRaises(lk_import.InputError) as e:
            self.run_import(aim_csv(rows))
        self.assertRegex(str(e.exception), r":13: a value that is not a number")
        self.assertEqual(lk_import.main(["aim", "/nonexistent.csv", "--out", "/tmp/never.csv"]), 4)

    def test_a_path_that_turns_back_gets_no_lane(self):
        _, out, _ = self.run_import(aim_csv(right_circle(n=400, glitch=False)))  # 4 rad: past a U-turn
        with tempfile.TemporaryDirectory() as d:
            lines = []
            lk_import.write_scenario(os.path.join(d, "s.yaml"), out, "test", report=lines.append)
            text = open(os.path.join(d, "s.yaml")).read()
        self.assertNotIn("waypoints", text)
        self.assertIn("turns back on itself", "\n".join(lines))


if __name__ == "__main__":
    unittest.main()
