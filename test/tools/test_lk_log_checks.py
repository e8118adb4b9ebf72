"""lk_log_checks --yaw-gain (scripts/lk_log_checks.py): the steady-state yaw gain G = r / (V delta / l) on
synthetic logs whose gain is known (G = 1 / (1 + K V^2 / l), K = 0.003 rad s^2/m, the speed swinging 15-19.5
m/s): noise on the steering angle biases least squares low and its reverse high, the estimators that do not
suffer from it (Deming with the measured noise, instrumental variables, the band-averaged H1 and H2) recover
K; in a closed lane-keeping loop that steers against a yaw disturbance, least squares is low again and H1..H2
still bracket G. Then the helpers on closed forms, the RAV4 minute's figures quoted in docs/real_car.md, and
bad input. Run: /usr/bin/python3 -m unittest discover -s test/tools."""
import contextlib
import io
import math
import os
import sys
import unittest

import numpy as np
from scipy import signal

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "scripts"))
import lk_log_checks  # noqa: E402

FS = 100.0
WHEELBASE, STEER_RATIO, K_TRUE, BIAS = 2.65, 16.88, 0.003, -0.007


def band_noise(rng, n, band, rms, kind="band"):
    """Filtered white noise with its start-up transient dropped."""
    sos = signal.butter(2, band, btype=kind, fs=FS, output="sos")
    u = signal.sosfilt(sos, rng.standard_normal(n + 3000))[3000:]
    return u * rms / u.std()


def synthetic_log(seed, loop=None):
    """Two minutes at 100 Hz. The driver's steering-wheel angle: band-limited 0.05-0.6 Hz, 1 deg rms. The
    yaw rate: G(V) V delta / l exactly, read with a bias of -0.007 rad/s and white noise (30 % of its sd); a
    second gyro with its own noise; a heading psi = the integrated true yaw rate plus a 0.89 deg mount.
    loop=None: the wheel angle is read with white noise of half its sd (errors in variables).
    loop=(k_psi, k_y): a lane-keeping loop steers against a yaw disturbance (0.002 rad/s rms, below 0.2 Hz)
    from the heading and lateral errors; the wheel angle is read exactly."""
    rng = np.random.default_rng(seed)
    n = int(120 * FS)
    t = np.arange(n) / FS
    v = 17.0 + 2.5 * np.sin(2 * math.pi * t / 80.0)
    gain = 1.0 / (1.0 + K_TRUE * v * v / WHEELBASE)
    wheel = band_noise(rng, n, (0.05, 0.6), math.radians(1.0))
    to_yaw = gain * v / (STEER_RATIO * WHEELBASE)  # r per steering-wheel radian
    if loop is None:
        steer = wheel
        r_true = to_yaw * wheel
        steer_read = wheel + rng.standard_normal(n) * 0.5 * wheel.std()
    else:
        k_psi, k_y = loop
        disturbance = band_noise(rng, n, 0.2, 0.002, kind="low")
        steer = np.zeros(n)
        r_true = np.zeros(n)
        psi_err = y_err = correction = 0.0
        for i in range(n):
            steer[i] = wheel[i] - correction
            r_true[i] = to_yaw[i] * steer[i] + disturbance[i]
            psi_err += (r_true[i] - to_yaw[i] * wheel[i]) / FS  # the road turns as the driver's wheel says
            y_err += v[i] * psi_err / FS
            correction = STEER_RATIO * WHEELBASE / v[i] * (k_psi * psi_err + k_y * y_err)
        steer_read = steer
    noise_r = 0.3 * r_true.std()
    log = {"t": t, "v": v, "steering_wheel_angle": steer_read,
           "yaw_rate": r_true + BIAS + rng.standard_normal(n) * noise_r,
           "yaw_rate_imu": r_true + rng.standard_normal(n) * noise_r,
           "psi": np.cumsum(r_true) / FS + math.radians(0.89) + rng.standard_normal(n) * 1e-4}
    x_true = v * steer / (STEER_RATIO * WHEELBASE)
    return log, x_true, gain


def pooled(gain, x, band=None):
    """The gain a slope estimator should find: the per-sample gains weighted by the regressor's power."""
    if band is not None:
        w = np.abs(lk_log_checks._band_analytic(x, band, FS)) ** 2
    else:
        w = (x - x.mean()) ** 2
    return float(np.sum(gain * w) / np.sum(w))


class ErrorsInVariables(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.log, cls.x_true, cls.gain = synthetic_log(3)
        cls.res = lk_log_checks.yaw_gain(cls.log, WHEELBASE, STEER_RATIO, draws=100, gyro_column="yaw_rate_imu")
        cls.rows = cls.res["groups"][0]["rows"]

    def test_noise_on_the_wheel_angle_biases_least_squares_low_and_its_reverse_high(self):
        g = pooled(self.gain, self.x_true)  # 0.739
        # Noise of a quarter of the signal's variance: least squares reads G / 1.25.
        self.assertLess(self.rows["ols"]["G"], 0.85 * g)
        self.assertLess(self.rows["ols"]["hi"], g)
        self.assertGreater(self.rows["reverse"]["G"], 1.05 * g)
        self.assertGreater(self.rows["ols"]["K"], 1.5 * K_TRUE)
        # The sensors' noise variances alone (Deming) do not tell it: here they do, as the noise is white.
        self.assertAlmostEqual(self.res["noise"]["fourth_difference"][1] / self.res["var_x"], 0.2, delta=0.03)

    def test_the_unbiased_estimators_recover_the_gain_and_the_understeer_gradient(self):
        # Tolerances that hold for seeds 3-12 (two minutes of data: a few per cent of random error).
        g_broad = pooled(self.gain, self.x_true)
        g_band = pooled(self.gain, self.x_true, (0.1, 0.5))
        for name in ("deming_fourth_difference", "iv_delayed", "iv_heading_rate", "iv_gyro"):
            self.assertAlmostEqual(self.rows[name]["G"], g_broad, delta=0.05 * g_broad, msg=name)
        for name in ("h1", "h2"):
            self.assertAlmostEqual(self.rows[name]["G"], g_band, delta=0.05 * g_band, msg=name)
        for name in ("deming_fourth_difference", "iv_delayed", "iv_heading_rate", "iv_gyro", "h1", "h2"):
            e = self.rows[name]
            self.assertAlmostEqual(e["K"], K_TRUE, delta=0.2 * K_TRUE, msg=name)
            self.assertTrue(e["lo"] <= e["G"] <= e["hi"], msg=name)
            self.assertTrue(e["K_lo"] <= e["K"] <= e["K_hi"], msg=name)

    def test_h1_and_h2_bracket_the_gain(self):
        g_band = pooled(self.gain, self.x_true, (0.1, 0.5))
        self.assertLessEqual(self.rows["h1"]["G"], self.rows["h2"]["G"])
        self.assertLess(self.rows["h1"]["lo"], g_band)
        self.assertGreater(self.rows["h2"]["hi"], g_band)

    def test_the_yaw_rate_bias_and_the_mount_are_told_apart(self):
        # The heading's constant 0.89 deg mount does not enter the rate bias.
        b, se, count = self.res["bias_refs"]["heading psi"]
        self.assertAlmostEqual(b, BIAS, delta=max(3 * se, 1e-4))
        self.assertEqual(count, 12)
        self.assertAlmostEqual(self.res["bias"], b)
        # The gyro has no bias of its own here.
        self.assertAlmostEqual(self.res["bias_gyro"][0], BIAS, delta=2e-4)
        self.assertAlmostEqual(self.res["gyro_bias_refs"]["heading psi"][0], 0.0, delta=2e-4)


class ClosedLoop(unittest.TestCase):
    def test_steering_against_a_disturbance_biases_least_squares_and_h1_h2_still_bracket(self):
        log, x_true, gain = synthetic_log(3, loop=(1.0, 0.1))
        res = lk_log_checks.yaw_gain(log, WHEELBASE, STEER_RATIO, draws=100, gyro_column="yaw_rate_imu")
        rows = res["groups"][0]["rows"]
        g = pooled(gain, x_true)
        g_band = pooled(gain, x_true, (0.1, 0.5))
        # The wheel angle is read exactly, yet least squares is low (7-13 % over seeds 3-12): the
        # correction moves no net yaw.
        self.assertLess(rows["ols"]["G"], 0.95 * g)
        self.assertLess(res["noise"]["fourth_difference"][1] / res["var_x"], 1e-3)
        # Deming with the sensors' noise cannot see it (it stays at least squares).
        self.assertAlmostEqual(rows["deming_fourth_difference"]["G"], rows["ols"]["G"], delta=0.01)
        # H1..H2 hold the gain between their bootstrap ends (the points themselves may pass it by a few %).
        self.assertLess(rows["h1"]["G"], rows["h2"]["G"])
        self.assertLess(rows["h1"]["lo"], g_band)
        self.assertGreater(rows["h2"]["hi"], g_band)
        self.assertLess(rows["h1"]["G"], g_band)  # steering against the disturbance: H1 low (seeds 3-12)


class Helpers(unittest.TestCase):
    def test_held_level_step_of_a_quantised_held_resampled_signal(self):
        # A 0.244 deg/s bus step, held at 25 Hz, linearly resampled to 100 Hz (as lk_import does).
        step = math.radians(0.244)
        t_bus = np.arange(0, 60, 0.04)
        bus = step * np.round(0.004 * np.sin(2 * math.pi * 0.2 * t_bus) / step)
        t = np.arange(0, 59.9, 0.01)
        self.assertAlmostEqual(lk_log_checks.held_level_step(np.interp(t, t_bus, bus)), step, places=9)
        self.assertTrue(math.isnan(lk_log_checks.held_level_step(np.linspace(0.0, 1.0, 50))))

    def test_fourth_differences_measure_white_noise_on_a_smooth_signal(self):
        rng = np.random.default_rng(5)
        t = np.arange(0, 60, 0.01)
        x = np.sin(2 * math.pi * 0.2 * t) + 0.01 * rng.standard_normal(len(t))
        self.assertAlmostEqual(lk_log_checks.fourth_difference_variance(x), 1e-4, delta=5e-6)

    def test_deming_between_least_squares_and_its_reverse(self):
        rng = np.random.default_rng(6)
        x = rng.standard_normal(2000)
        y = 0.7 * x + 0.3 * rng.standard_normal(2000)
        ols = np.cov(x, y)[0, 1] / np.var(x, ddof=1)
        rev = np.var(y, ddof=1) / np.cov(x, y)[0, 1]
        self.assertAlmostEqual(lk_log_checks.deming_slope(x, y, 1e9), ols, places=6)
        self.assertAlmostEqual(lk_log_checks.deming_slope(x, y, 1e-9), rev, places=6)
        self.assertTrue(ols < lk_log_checks.deming_slope(x, y, 1.0) < rev)

    def test_openpilots_rav4_calibration(self):
        # opendbc: m = 1791.6 kg, l = 2.65 m, l_r = 0.56 l (CG 0.44 l behind the front axle),
        # C_f, C_r = 121.6, 151.0 kN/rad: K = m / l (l_r / C_f - l_f / C_r).
        K = lk_log_checks.reference_understeer(1791.6, 2.65, 1.484, 121.6e3, 151.0e3)
        self.assertAlmostEqual(K, 1791.6 / 2.65 * (1.484 / 121.6e3 - 1.166 / 151.0e3), places=12)
        self.assertAlmostEqual(K, 0.00303, places=5)
        self.assertAlmostEqual(lk_log_checks.gain_at(K, 16.7, 2.65), 0.758, places=3)
        h0 = lk_log_checks.single_track_yaw_response(0.0, 16.7, 1791.6, 2951, 2.65, 1.484, 121.6e3, 151.0e3)
        self.assertAlmostEqual(h0.real, lk_log_checks.gain_at(K, 16.7, 2.65), places=9)
        self.assertAlmostEqual(h0.imag, 0.0, places=12)
        # A weighted mean of one speed is the plain formula, inverted.
        v = np.full(10, 16.7)
        self.assertAlmostEqual(lk_log_checks.understeer_from_gain(0.758, v, np.ones(10), 2.65),
                               (1 / 0.758 - 1) * 2.65 / 16.7 ** 2, places=9)

    def test_circular_blocks_draw_every_sample_alike(self):
        rng = np.random.default_rng(7)
        counts = np.zeros(100)
        for _ in range(2000):
            np.add.at(counts, lk_log_checks.circular_blocks(100, 10, rng), 1)
        self.assertLess(counts.max() / counts.min(), 1.2)  # the ends as often as the middle


class TheRav4Minute(unittest.TestCase):
    """The figures docs/real_car.md quotes (point estimates; the intervals need the default 1000 draws)."""

    @classmethod
    def setUpClass(cls):
        d = lk_log_checks.read(os.path.join(REPO, "data", "comma2k19", "rav4_segment40.csv"))
        cls.res = lk_log_checks.yaw_gain(d, 2.65, 16.88, draws=10, gyro_column="yaw_rate_imu",
                                         accel_bins=[(-0.3, 0.3)])

    def test_the_figure_first_published_and_the_bias(self):
        self.assertAlmostEqual(self.res["ols_raw"][0], 0.639, places=3)
        self.assertAlmostEqual(self.res["ols_raw"][1], -0.0064, places=4)
        self.assertAlmostEqual(self.res["bias"], -0.00713, places=5)
        self.assertAlmostEqual(self.res["bias_refs"]["course from x, y"][0], -0.00715, places=5)
        self.assertAlmostEqual(math.degrees(self.res["offset"]), -0.16, places=2)
        self.assertAlmostEqual(self.res["steps"][0], math.radians(0.244), places=6)
        self.assertAlmostEqual(self.res["steps"][1], math.radians(0.1), places=6)

    def test_openpilots_understeer_lies_between_h2_and_h1(self):
        K = lk_log_checks.reference_understeer(1791.6, 2.65, 1.484, 121.6e3, 151.0e3)
        rows = self.res["groups"][0]["rows"]
        self.assertAlmostEqual(rows["h1"]["G"], 0.675, places=3)
        self.assertAlmostEqual(rows["h2"]["G"], 0.734, places=3)
        self.assertTrue(rows["h2"]["K"] < K < rows["h1"]["K"])
        steady = self.res["groups"][1]["rows"]
        self.assertAlmostEqual(steady["h1"]["G"], 0.716, places=3)
        self.assertAlmostEqual(steady["h2"]["G"], 0.745, places=3)


class BadInput(unittest.TestCase):
    def test_a_missing_column_is_named(self):
        log, _, _ = synthetic_log(3)
        del log["steering_wheel_angle"]
        with self.assertRaises(ValueError) as e:
            lk_log_checks.yaw_gain(log, WHEELBASE, STEER_RATIO, draws=5)
        self.assertIn("steering_wheel_angle", str(e.exception))

    def test_a_band_beyond_nyquist_is_refused(self):
        log, _, _ = synthetic_log(3)
        with self.assertRaises(ValueError) as e:
            lk_log_checks.yaw_gain(log, WHEELBASE, STEER_RATIO, band=(0.1, 60.0), draws=5)
        self.assertIn("Nyquist frequency 50 Hz", str(e.exception))

    def test_a_reference_without_mass_is_refused(self):
        path = os.path.join(REPO, "data", "comma2k19", "rav4_segment40.csv")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as e:
            lk_log_checks.main([path, "--wheelbase", "2.65", "--steer-ratio", "16.88", "--yaw-gain",
                                "--reference-stiffness", "121.6e3:151.0e3"])
        self.assertEqual(e.exception.code, 2)
        self.assertIn("--mass", err.getvalue())
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit):
            lk_log_checks.main([path, "--wheelbase", "2.65", "--steer-ratio", "16.88", "--yaw-gain",
                                "--band", "0.5:0.1"])
        self.assertIn("--band", err.getvalue())


if __name__ == "__main__":
    unittest.main()
