"""lk_import (scripts/lk_import.py): the DBC decoding on frames of the comma2k19 example segment, decoded by
hand from the DBC's start bit, length, byte order, sign, factor and offset; the geodesy on closed forms.
Run: /usr/bin/python3 -m unittest discover -s test/tools (the gap tests run it: RealCar.ImporterUnitTests)."""
import math
import os
import sys
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


if __name__ == "__main__":
    unittest.main()
