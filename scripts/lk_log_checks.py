#!/usr/bin/python3
"""lk_log_checks: sensor and data checks of a real log in the suite's schema, independent of lk_gap
(docs/real_logs/super_fj_fuji.md uses them as the reference for the diagnosis's sensor-error candidates).

    /usr/bin/python3 scripts/lk_log_checks.py LOG.csv --wheelbase 2.30 --steer-ratio 12 [--straight T0:T1 ...]

Prints, each with its method and an uncertainty:
  * quantisation step and sample-and-hold of every column (the smallest non-zero step; the share of samples
    equal to the previous one and the longest run of equal samples);
  * yaw-rate bias against d(psi)/dt (the whole log and the straights), and its scale (orthogonal
    regression of yaw rate on d(psi)/dt; ay on v * yaw rate);
  * latencies by cross-correlation, refined to a fraction of a sample by a parabola through the peak:
    yaw rate against d(psi)/dt, against the steering-wheel angle, ay against v * yaw rate;
  * the steering-wheel angle on the straights (its zero offset) and the kinematic steer ratio in the
    corners (steering-wheel angle / (l yaw_rate / v), an upper bound: understeer adds to it);
  * the course from the positions against psi (what the log calls heading).
Uncertainties: standard errors with the effective number of samples n_eff = n (1 - rho1) / (1 + rho1)
(rho1 the lag-1 autocorrelation), so that 20 Hz samples of a slowly varying error are not counted as
independent.

    /usr/bin/python3 scripts/lk_log_checks.py LOG.csv --wheelbase L --steer-ratio N --yaw-gain \
        [--gyro-column yaw_rate_imu] [--band 0.1:0.5] [--speed-bins 8:17,17:20] [--accel-bins=-0.3:0.3] \
        [--reference-stiffness CF:CR --mass M --cg-to-rear-axle LR [--yaw-inertia IZ]]

prints instead the steady-state yaw gain G = r / (V delta / l) (the kinematic yaw rate's share, delta the
road-wheel angle) by estimators that bracket it when delta is noisy and the loop is closed (see yaw_gain()):
the yaw-rate bias first (the drift of the integrated yaw rate against each heading reference), then least
squares and its reverse, Deming regression with the sensors' noise variances, instrumental variables, the
band-averaged frequency responses H1 and H2, each with a circular block bootstrap interval, on the whole log and
in bins of speed and of dV/dt, and the understeer gradient K each implies; with --reference-stiffness, the K
and G a set of cornering stiffnesses gives (K = m / l (l_r / C_f - l_f / C_r)) and, with --yaw-inertia, its
single-track frequency response over the band. Used in docs/real_car.md (the RAV4 minute).
"""
import argparse
import math
import sys
import zlib

import numpy as np


def read(path):
    with open(path) as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    return {n: data[:, k] for k, n in enumerate(names)}


def mean_se(x):
    x = np.asarray(x, float)
    n = len(x)
    if n < 3:
        return float(x.mean()), float("nan"), n
    d = x - x.mean()
    rho = float((d[1:] * d[:-1]).sum() / (d * d).sum()) if (d * d).sum() > 0 else 0.0
    rho = min(max(rho, 0.0), 0.99)
    n_eff = max(2.0, n * (1 - rho) / (1 + rho))
    return float(x.mean()), float(x.std(ddof=1) / math.sqrt(n_eff)), n_eff


def lag(a, b, dt, max_lag):
    """Delay of b behind a [s] (b(t) ~ a(t - lag)): the peak of the normalised cross-correlation, refined by
    a parabola through the peak and its neighbours; also the peak's correlation."""
    a = (a - a.mean()) / a.std()
    b = (b - b.mean()) / b.std()
    n = len(a)
    ks = np.arange(-max_lag, max_lag + 1)
    c = np.array([np.mean(a[max(0, -k):n - max(0, k)] * b[max(0, k):n - max(0, -k)]) for k in ks])
    i = int(np.argmax(c))
    frac = 0.0
    if 0 < i < len(c) - 1:
        den = c[i - 1] - 2 * c[i] + c[i + 1]
        frac = 0.5 * (c[i - 1] - c[i + 1]) / den if den != 0 else 0.0
    return (ks[i] + frac) * dt, float(c[i])


def tls_slope(x, y):
    """Orthogonal (total least squares) slope of y on x, both centred: no bias from noise in x."""
    x, y = x - x.mean(), y - y.mean()
    sxx, syy, sxy = (x * x).sum(), (y * y).sum(), (x * y).sum()
    return (syy - sxx + math.sqrt((syy - sxx) ** 2 + 4 * sxy * sxy)) / (2 * sxy)


# ---------------------------------------------------------------------------------------------------------
# The steady-state yaw gain (--yaw-gain).
#
# The single-track model in steady state: r = G V delta / l with G = 1 / (1 + K V^2 / l), K the understeer
# gradient (Gillespie, Fundamentals of Vehicle Dynamics, eq. 6-13; Rajamani, Vehicle Dynamics and Control,
# section 3.5). Measuring G from a log is a regression of r on x = V delta / l, and two things bias plain least
# squares low: noise in the regressor (errors in variables: slope x var(true x) / var(x)), and the closed loop
# (the driver or controller steers against disturbances, so part of delta moves no yaw; it enters the
# regression as regressor noise does). The estimators below bracket G instead of trusting one of them.


def held_level_step(x):
    """Quantisation step of a sampled-and-held, then linearly resampled signal [its unit]: the median gap
    between neighbouring levels that it holds (samples equal to the previous one). Resampling puts in-between
    values on every change, so the raw series' smallest step says nothing; a held sample is the bus's own
    value. Levels closer than 1e-4 of their range are one level (float rounding). NaN below three levels."""
    x = np.asarray(x, float)
    levels = np.unique(x[1:][np.diff(x) == 0])
    if len(levels) < 3:
        return float("nan")
    gaps = np.diff(levels)
    gaps = gaps[gaps > 1e-4 * (levels[-1] - levels[0])]
    return float(np.median(gaps)) if len(gaps) else float("nan")


def fourth_difference_variance(x):
    """Variance of white noise on a smooth signal: mean((fourth difference)^2) / 70, the sum of the squared
    binomial weights 1, -4, 6, -4, 1 (a smooth signal's fourth difference is near zero). It undercounts the
    noise of a held signal, whose differences are mostly zero."""
    return float(np.mean(np.diff(np.asarray(x, float), 4) ** 2) / 70.0)


def rate_bias_against_heading(t, rate, heading, window):
    """Bias of a rate sensor against a heading reference [rad/s]: the slope of (integrated rate - heading)
    over time, by least squares over the whole log; a constant heading offset (a mounting angle) drops out.
    Standard error: the scatter of the same slope fitted in consecutive windows of `window` seconds (a last
    one shorter than half a window joins none), sd / sqrt(count). Returns (bias, standard error, count)."""
    t, rate, heading = (np.asarray(u, float) for u in (t, rate, heading))
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
    drift = integral - heading
    bias = float(np.polyfit(t, drift, 1)[0])
    slopes = []
    t0 = t[0]
    while t0 < t[-1]:
        s = (t >= t0) & (t < t0 + window)
        if s.sum() >= 3 and t[s][-1] - t[s][0] >= 0.5 * window:
            slopes.append(np.polyfit(t[s], drift[s], 1)[0])
        t0 += window
    se = float(np.std(slopes, ddof=1) / math.sqrt(len(slopes))) if len(slopes) >= 2 else float("nan")
    return bias, se, len(slopes)


def deming_slope(x, y, noise_ratio):
    """Slope of y = b x when both carry noise, noise_ratio = var(noise of y) / var(noise of x) (Deming
    regression: the maximum-likelihood line; Fuller, Measurement Error Models, 1987, eq. 1.3.7). ratio -> inf
    is least squares of y on x, ratio -> 0 the reverse regression, ratio 1 the orthogonal (total least
    squares) line."""
    x, y = x - x.mean(), y - y.mean()
    sxx, syy, sxy = float(np.mean(x * x)), float(np.mean(y * y)), float(np.mean(x * y))
    d = syy - noise_ratio * sxx
    return (d + math.sqrt(d * d + 4.0 * noise_ratio * sxy * sxy)) / (2.0 * sxy)


def reference_understeer(mass, wheelbase, cg_to_rear_axle, c_front, c_rear):
    """Understeer gradient of a linear single-track model [rad s^2/m]: K = m / l (l_r / C_f - l_f / C_r),
    C per axle [N/rad] (Gillespie eq. 6-15 written with axle loads m g l_r / l and m g l_f / l)."""
    l_f = wheelbase - cg_to_rear_axle
    return mass / wheelbase * (cg_to_rear_axle / c_front - l_f / c_rear)


def single_track_yaw_response(f, speed, mass, yaw_inertia, wheelbase, cg_to_rear_axle, c_front, c_rear):
    """Yaw-rate response to the road-wheel angle of the linear single-track model at frequency f [Hz],
    divided by the kinematic V / l (so that it is G at f = 0): states lateral velocity and yaw rate
    (Rajamani, Vehicle Dynamics and Control, eq. 2.31 with the axle stiffnesses C_f, C_r per axle)."""
    m, I, V, l_r = mass, yaw_inertia, speed, cg_to_rear_axle
    l_f = wheelbase - l_r
    moment = c_front * l_f - c_rear * l_r
    A = np.array([[-(c_front + c_rear) / (m * V), -V - moment / (m * V)],
                  [-moment / (I * V), -(c_front * l_f ** 2 + c_rear * l_r ** 2) / (I * V)]])
    B = np.array([c_front / m, c_front * l_f / I])
    return complex(np.linalg.solve(2j * math.pi * f * np.eye(2) - A, B)[1]) / (V / wheelbase)


def gain_at(K, speed, wheelbase):
    """Steady-state yaw gain r / (V delta / l) = 1 / (1 + K V^2 / l)."""
    return 1.0 / (1.0 + K * speed * speed / wheelbase)


def understeer_from_gain(G, speed, weight, wheelbase):
    """The K whose gains, averaged with the estimator's weights over the samples' speeds, equal G: a pooled
    slope is the weighted mean of the per-sample gains (weights: the regressor's power, (x - mean)^2 or
    |x_band|^2), so the speed at which G holds is the excitation's, not the log's mean. NaN if G <= 0."""
    from scipy.optimize import brentq
    if not (G > 0 and math.isfinite(G)):
        return float("nan")
    w = weight / weight.sum()
    f = lambda K: float(np.sum(w / (1.0 + K * speed * speed / wheelbase))) - G
    lo = -0.999 * wheelbase / float(np.max(speed)) ** 2
    hi = 1.0
    if f(lo) < 0 or f(hi) > 0:
        return float("nan")
    return brentq(f, lo, hi, xtol=1e-9)


def circular_blocks(n, block, rng):
    """Indices of a circular block bootstrap draw of n samples from 0..n-1 (Politis and Romano 1992): blocks
    of `block` consecutive samples from random starts, wrapping past the end, concatenated and cut to n.
    Unlike plain moving blocks, every sample is drawn equally often, so the log's ends are not under-weighted
    (what is resampled are per-sample products, so the wrap joins no signals)."""
    block = max(1, min(block, n))
    starts = rng.integers(0, n, size=int(math.ceil(n / block)))
    return ((starts[:, None] + np.arange(block)[None, :]) % n).ravel()[:n]


def _band_analytic(u, band, fs):
    """Band-pass (4th-order Butterworth, zero phase) and the analytic signal: mean(conj(a_x) a_r) over the
    samples is the band's integral of the cross-spectrum S_xr (Parseval), so ratios of such means are
    band-averaged frequency responses, and a bootstrap can resample them sample by sample."""
    from scipy import signal
    sos = signal.butter(2, band, btype="band", fs=fs, output="sos")
    return signal.hilbert(signal.sosfiltfilt(sos, u - u.mean()))


def yaw_gain_signals(d, wheelbase, steer_ratio, bias, band, gyro_column=None, iv_delay=0.25):
    """The per-sample arrays the estimators need: x = V (delta_sw - offset) / (N l) and r_c = r - bias, the
    band's analytic signals, the instruments. The steering offset: the mean of delta_sw - N l r_c / (G V) (the
    wheel angle at zero yaw; G from a first least-squares pass; the road's mean curvature is tiny on a
    straight so G matters little)."""
    t, v, sw = d["t"], d["v"], d["steering_wheel_angle"]
    dt = float(np.median(np.diff(t)))
    r_c = d["yaw_rate"] - bias
    x_raw = v * sw / (steer_ratio * wheelbase)
    g0 = float(np.cov(x_raw, r_c)[0, 1] / np.var(x_raw, ddof=1))
    offset = float(np.mean(sw - steer_ratio * wheelbase * r_c / (g0 * v)))
    x = v * (sw - offset) / (steer_ratio * wheelbase)
    k = max(1, int(round(iv_delay / dt)))
    x_delayed = np.concatenate([np.full(k, np.nan), x[:-k]])
    s = {"t": t, "v": v, "x": x, "r": r_c, "x_raw": x_raw, "r_raw": d["yaw_rate"], "offset": offset,
         "dt": dt, "x_delayed": x_delayed, "iv_delay": k * dt,
         "heading_rate": np.gradient(d["psi"], t),
         "xa": _band_analytic(x, band, 1.0 / dt), "ra": _band_analytic(r_c, band, 1.0 / dt)}
    if gyro_column:
        s["gyro"] = d[gyro_column]
    return s


def _cov(a, b):
    return float(np.mean((a - a.mean()) * (b - b.mean())))


def yaw_gain_estimates(s, idx, noise):
    """Every estimator of G on the samples idx (an index array; repeated indices for a bootstrap draw).
    noise: {name: (var of r's noise, var of x's noise)} for Deming. Returns {name: G}."""
    x, r = s["x"][idx], s["r"][idx]
    sxx, srr, sxr = _cov(x, x), _cov(r, r), _cov(x, r)
    out = {"ols": sxr / sxx, "reverse": srr / sxr}
    for name, (var_r, var_x) in noise.items():
        out["deming_" + name] = deming_slope(x, r, var_r / var_x)
    z = s["x_delayed"][idx]
    ok = np.isfinite(z)
    out["iv_delayed"] = _cov(z[ok], r[ok]) / _cov(z[ok], x[ok])
    for name in ("heading_rate", "gyro"):
        if name in s:
            z = s[name][idx]
            out["iv_" + name] = _cov(z, r) / _cov(z, x)
    xa, ra = s["xa"][idx], s["ra"][idx]
    pxx, prr = float(np.mean(np.abs(xa) ** 2)), float(np.mean(np.abs(ra) ** 2))
    pxr = complex(np.mean(np.conj(xa) * ra))
    out["h1"] = abs(pxr) / pxx
    out["h2"] = prr / abs(pxr)
    out["coherence"] = abs(pxr) ** 2 / (pxx * prr)
    return out


# key: (what it is, what biases it); in the order printed.
YAW_GAIN_METHODS = [
    ("ols", "least squares, r on V delta / l",
     "low: regressor noise and closed-loop steering (errors in variables), the yaw lag"),
    ("reverse", "reverse least squares, V delta / l on r, inverted",
     "high: all of r not caused by delta (sensor noise, disturbances)"),
    ("deming_quantisation", "Deming, noise variances of the quantisation steps",
     "as least squares when the wheel sensor is fine: it sees only sensor noise"),
    ("deming_fourth_difference", "Deming, noise variances from fourth differences",
     "as above; fourth differences undercount held signals"),
    ("deming_orthogonal", "orthogonal (total least squares), equal noise",
     "assumes r and V delta / l equally noisy [rad/s]: a choice, not a measurement"),
    ("iv_delayed", "instrumental variable: V delta / l delayed",
     "low: removes noise that decorrelates within the delay, not slow closed-loop steering"),
    ("iv_heading_rate", "instrumental variable: d(psi)/dt of the heading",
     "high: removes r's sensor noise, keeps the yaw that disturbances cause"),
    ("iv_gyro", "instrumental variable: the gyro", "high: as the heading rate"),
    ("h1", "H1 = S_xr / S_xx averaged over the band",
     "low: input noise in the band (steering against disturbances acts as such where the loop cancels "
     "them; near its crossover a few % either way)"),
    ("h2", "H2 = S_rr / S_rx averaged over the band",
     "high: output noise in the band (r's noise, yaw from disturbances the loop leaves)"),
]


def longitudinal_acceleration(t, v, cutoff=0.5):
    """dV/dt [m/s^2] of the speed low-passed at `cutoff` Hz (2nd-order Butterworth, zero phase)."""
    from scipy import signal
    sos = signal.butter(2, cutoff, fs=1.0 / float(np.median(np.diff(t))), output="sos")
    return np.gradient(signal.sosfiltfilt(sos, v), t)


def yaw_gain(d, wheelbase, steer_ratio, band=(0.1, 0.5), speed_bins=(), block=5.0, draws=1000, seed=1,
             gyro_column=None, bias=None, bias_window=10.0, iv_delay=0.25, accel_bins=()):
    """The yaw-gain analysis of a log read by read(): returns a dict (printed by print_yaw_gain). The
    estimators run on the whole log and on the samples of each speed bin [m/s] and longitudinal-acceleration
    bin [m/s^2] (LO <= value < HI); a bin with fewer samples than four bootstrap blocks is skipped."""
    for c in ("t", "psi", "yaw_rate", "v", "steering_wheel_angle") + ((gyro_column,) if gyro_column else ()):
        if c not in d:
            raise ValueError("yaw gain: the log has no column '%s'" % c)
    t, r = d["t"], d["yaw_rate"]
    nyquist = 0.5 / float(np.median(np.diff(t)))
    if not 0 < band[0] < band[1] < nyquist:
        raise ValueError("yaw gain: the band %g-%g Hz is not within 0 and the Nyquist frequency %g Hz" %
                         (band[0], band[1], nyquist))
    res = {"band": band, "block": block, "draws": draws, "wheelbase": wheelbase, "steer_ratio": steer_ratio}
    # 1. The yaw-rate bias against the heading references.
    refs = {"heading psi": d["psi"]}
    if "x" in d and "y" in d:
        refs["course from x, y"] = np.unwrap(np.arctan2(np.gradient(d["y"], t), np.gradient(d["x"], t)))
    res["bias_refs"] = {name: rate_bias_against_heading(t, r, h, bias_window) for name, h in refs.items()}
    if gyro_column:
        g = d[gyro_column]
        res["bias_gyro"] = mean_se(r - g)[:2]
        res["gyro_bias_refs"] = {name: rate_bias_against_heading(t, g, h, bias_window) for name, h in refs.items()}
    res["bias"] = res["bias_refs"]["heading psi"][0] if bias is None else bias
    res["bias_given"] = bias is not None
    # 2. The signals, the noise variances.
    s = yaw_gain_signals(d, wheelbase, steer_ratio, res["bias"], band, gyro_column, iv_delay)
    res["offset"] = s["offset"]
    res["iv_delay"] = s["iv_delay"]
    scale2 = float(np.mean((d["v"] / (steer_ratio * wheelbase)) ** 2))  # var(x noise) = scale2 var(sw noise)
    q_r, q_sw = held_level_step(r), held_level_step(d["steering_wheel_angle"])
    res["steps"] = (q_r, q_sw)
    noise = {}
    if math.isfinite(q_r) and math.isfinite(q_sw):
        noise["quantisation"] = (q_r * q_r / 12.0, scale2 * q_sw * q_sw / 12.0)
    noise["fourth_difference"] = (fourth_difference_variance(r),
                                  scale2 * fourth_difference_variance(d["steering_wheel_angle"]))
    res["noise"] = dict(noise)
    noise["orthogonal"] = (1.0, 1.0)
    if "gyro" in s:  # three measurements of one yaw rate (triple collocation): r's own noise
        rr, gg, hh = s["r"], s["gyro"], s["heading_rate"]
        res["r_noise_collocation"] = _cov(rr, rr) - _cov(rr, gg) * _cov(rr, hh) / _cov(gg, hh)
    res["var_x"], res["var_r"] = _cov(s["x"], s["x"]), _cov(s["r"], s["r"])
    # Plain least squares with an intercept on the raw signals (what docs/real_car.md first quoted).
    A = np.column_stack([s["x_raw"], np.ones_like(r)])
    res["ols_raw"] = tuple(float(u) for u in np.linalg.lstsq(A, r, rcond=None)[0])
    # 3. The estimators on the whole log and in the bins, with circular block bootstrap intervals.
    n_block = max(1, int(round(block / s["dt"])))
    groups = [("all", np.arange(len(t)))]
    acc = longitudinal_acceleration(t, d["v"]) if accel_bins else None
    for values, bins, unit in ((d["v"], speed_bins, "m/s"), (acc, accel_bins, "m/s^2 dV/dt")):
        for lo, hi in bins:
            idx = np.flatnonzero((values >= lo) & (values < hi))
            if len(idx) >= 4 * n_block:
                groups.append(("%g to %g %s" % (lo, hi, unit), idx))
            else:
                res.setdefault("skipped_bins", []).append(("%g to %g %s" % (lo, hi, unit), len(idx)))
    res["groups"] = []
    for name, idx in groups:
        rng = np.random.default_rng([seed, zlib.crc32(name.encode())])  # a group's draws: not the others'
        point = yaw_gain_estimates(s, idx, noise)
        boot = {k: [] for k in point}
        for _ in range(draws):
            e = yaw_gain_estimates(s, idx[circular_blocks(len(idx), n_block, rng)], noise)
            for k in e:
                boot[k].append(e[k])
        v = d["v"][idx]
        w_broad = (s["x"][idx] - s["x"][idx].mean()) ** 2
        w_band = np.abs(s["xa"][idx]) ** 2
        rows = {}
        nan = float("nan")
        for k, G in point.items():
            b = np.array(boot[k])
            lo, hi = np.percentile(b[np.isfinite(b)], [2.5, 97.5]) if np.isfinite(b).any() else (nan, nan)
            if k == "coherence":
                rows[k] = {"G": G, "lo": float(lo), "hi": float(hi)}
                continue
            w = w_band if k in ("h1", "h2") else w_broad
            K = understeer_from_gain(G, v, w, wheelbase)
            rows[k] = {"G": G, "lo": float(lo), "hi": float(hi), "K": K,  # a higher gain is a lower K
                       "K_lo": understeer_from_gain(hi, v, w, wheelbase),
                       "K_hi": understeer_from_gain(lo, v, w, wheelbase),
                       "G_mean_speed": gain_at(K, float(v.mean()), wheelbase) if math.isfinite(K) else nan}
        v_eff = math.sqrt(float(np.sum(v * v * w_broad) / np.sum(w_broad)))
        res["groups"].append({"name": name, "n": len(idx), "mean_speed": float(v.mean()),
                              "excitation_speed": v_eff, "rows": rows, "speed": v, "band_weight": w_band})
    # 4. Where least squares loses its gain: the frequency response by band (Welch, 10 s segments).
    res["spectrum"] = yaw_gain_spectrum(s["x"], s["r"], s["dt"])
    return res


def yaw_gain_spectrum(x, r, dt, segment=10.0, f_max=1.5):
    """Welch estimates per frequency up to f_max: the share of var(x), coherence, |H1|, |H2|, H1's phase."""
    from scipy import signal
    fs = 1.0 / dt
    n = int(round(segment * fs))
    f, pxx = signal.welch(x, fs=fs, nperseg=n)
    _, prr = signal.welch(r, fs=fs, nperseg=n)
    _, pxr = signal.csd(x, r, fs=fs, nperseg=n)
    keep = f <= f_max + 1e-9
    share = pxx / pxx.sum()
    return [(float(f[i]), float(share[i]), float(abs(pxr[i]) ** 2 / (pxx[i] * prr[i])),
             float(abs(pxr[i]) / pxx[i]), float(prr[i] / abs(pxr[i])), float(np.degrees(np.angle(pxr[i]))))
            for i in np.flatnonzero(keep)]


def print_yaw_gain(res, reference=None):
    """Prints the result of yaw_gain(); reference: (name, K) to compare with, or None."""
    l = res["wheelbase"]
    print("\nyaw-rate bias (slope of the integrated yaw rate minus the heading; se from %s windows):" %
          ", ".join("%d" % v[2] for v in res["bias_refs"].values()))
    for name, (b, se, _) in res["bias_refs"].items():
        print("  against the %-17s %+.5f +- %.5f rad/s" % (name + ":", b, se))
    if "bias_gyro" in res:
        print("  against the gyro (mean difference; includes the gyro's own bias): %+.5f +- %.5f rad/s" %
              res["bias_gyro"])
        for name, (b, se, _) in res["gyro_bias_refs"].items():
            print("    the gyro's own bias against the %s: %+.5f +- %.5f rad/s" % (name, b, se))
    print("  used: %+.5f rad/s (%s)" % (res["bias"], "given" if res["bias_given"] else "against the heading psi"))
    print("\nplain least squares of r on V delta / l with an intercept, raw signals, every sample (the usual "
          "first try): G = %.4f, intercept %+.5f rad/s" % res["ols_raw"])
    q_r, q_sw = res["steps"]
    print("\nsignals: r - bias; x = V (delta_sw - offset) / (N l), steering-wheel offset %+.3f deg (the wheel at "
          "zero yaw)" % math.degrees(res["offset"]))
    print("  held-level steps: yaw rate %.5f rad/s (%.3f deg/s), steering wheel %.5f rad (%.3f deg)" %
          (q_r, math.degrees(q_r), q_sw, math.degrees(q_sw)))
    print("  var(r) %.3g, var(x) %.3g (rad/s)^2; noise variances (r, x):" % (res["var_r"], res["var_x"]))
    for name, (vr, vx) in res["noise"].items():
        print("    %-18s %.3g (%.1f %% of var r), %.3g (%.2f %% of var x)" %
              (name, vr, 100 * vr / res["var_r"], vx, 100 * vx / res["var_x"]))
    if "r_noise_collocation" in res:
        vr = res["r_noise_collocation"]
        print("    r's noise by triple collocation with the gyro and d(psi)/dt: %.3g (%.1f %% of var r)" %
              (vr, 100 * vr / res["var_r"]))
    if reference:
        print("\nreference %s: K = %.5f rad s^2/m" % tuple(reference[:2]))
        if len(reference) > 2 and reference[2]:
            h = reference[2]
            print("  its single-track yaw response at the mean speed: |H| / G = %.3f at %g Hz, %.3f at %g Hz (the "
                  "band's average is the steady-state gain to within that)" %
                  (h[0], res["band"][0], h[1], res["band"][1]))
    print("\nestimators (band %g-%g Hz; 95 %% circular block bootstrap, %g s blocks, %d draws; K from the gain "
          "weighted over the excitation's speeds; G(mean V) = 1 / (1 + K V^2 / l)):" %
          (res["band"][0], res["band"][1], res["block"], res["draws"]))
    for grp in res["groups"]:
        rows = grp["rows"]
        extra = ""
        if reference:
            g_band = float(np.sum(grp["band_weight"] * gain_at(reference[1], grp["speed"], l)) /
                           np.sum(grp["band_weight"]))
            extra = "; reference G(mean V) %.3f, weighted as H1 and H2 %.3f" % (
                gain_at(reference[1], grp["mean_speed"], l), g_band)
        print("  %s: %d samples, mean speed %.1f m/s, excitation-weighted %.1f m/s, band coherence %.2f%s" %
              (grp["name"], grp["n"], grp["mean_speed"], grp["excitation_speed"], rows["coherence"]["G"], extra))
        for k, what, _ in YAW_GAIN_METHODS:
            if k not in rows:
                continue
            e = rows[k]
            print("    %-52s G %.3f [%.3f, %.3f]  K %.5f [%.5f, %.5f]  G(mean V) %.3f" %
                  (what, e["G"], e["lo"], e["hi"], e["K"], e["K_lo"], e["K_hi"], e["G_mean_speed"]))
        lo, hi = rows["h1"]["lo"], rows["h2"]["hi"]
        line = "    bracket H1..H2 (their outer bootstrap ends): G %.3f-%.3f" % (lo, hi)
        if reference:
            k_lo, k_hi = rows["h2"]["K_lo"], rows["h1"]["K_hi"]
            line += ", K %.5f-%.5f: the reference's K %s" % (
                k_lo, k_hi, "inside" if k_lo <= reference[1] <= k_hi else "OUTSIDE")
        print(line)
    for name, n in res.get("skipped_bins", []):
        print("  %s: %d samples, fewer than four bootstrap blocks: skipped" % (name, n))
    print("  what biases each:")
    for _, what, biased in YAW_GAIN_METHODS:
        print("    %s: %s" % (what, biased))
    print("\nfrequency response (Welch, 10 s segments): f, share of var(x), coherence, |H1|, |H2|, phase of H1")
    for f, share, coh, h1, h2, ph in res["spectrum"]:
        print("  %.2f Hz  %5.1f %%  %.2f  %.3f  %.3f  %+4.0f deg" % (f, 100 * share, coh, h1, h2, ph))


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("log")
    p.add_argument("--wheelbase", type=float, required=True)
    p.add_argument("--steer-ratio", type=float, required=True)
    p.add_argument("--straight", action="append", default=[], help="T0:T1 [s]: a straight (repeatable)")
    y = p.add_argument_group("yaw gain (--yaw-gain: the steady-state yaw gain instead of the checks)")
    y.add_argument("--yaw-gain", action="store_true")
    y.add_argument("--band", default="0.1:0.5", help="LO:HI [Hz]: the band of H1 and H2 (default 0.1:0.5)")
    y.add_argument("--speed-bins", default="", help="LO:HI,LO:HI [m/s]: speed bins besides the whole log")
    y.add_argument("--accel-bins", default="", help="LO:HI,LO:HI [m/s^2]: bins of dV/dt (speed low-passed "
                   "at 0.5 Hz), e.g. -0.3:0.3 for steady speed")
    y.add_argument("--block", type=float, default=5.0, help="bootstrap block length [s] (default 5)")
    y.add_argument("--draws", type=int, default=1000, help="bootstrap draws (default 1000)")
    y.add_argument("--seed", type=int, default=1)
    y.add_argument("--gyro-column", help="a second yaw-rate column (a gyro): instrument and bias reference")
    y.add_argument("--yaw-rate-bias", type=float, help="[rad/s] instead of the one measured against psi")
    y.add_argument("--iv-delay", type=float, default=0.25, help="[s] delay of the delayed-steering instrument")
    y.add_argument("--reference-stiffness", help="CF:CR [N/rad per axle]: a calibration to compare with "
                   "(needs --mass and --cg-to-rear-axle)")
    y.add_argument("--mass", type=float)
    y.add_argument("--yaw-inertia", type=float, help="[kg m^2] with --reference-stiffness: the reference's "
                   "frequency response over the band")
    y.add_argument("--cg-to-rear-axle", type=float)
    a = p.parse_args(argv)
    d = read(a.log)
    if a.yaw_gain:
        return yaw_gain_main(d, a, p)
    t = d["t"]
    dt = float(np.median(np.diff(t)))
    print("%s: %d rows, dt %.3f s, %.2f s" % (a.log, len(t), dt, t[-1] - t[0]))

    print("\nquantisation and hold (smallest non-zero step; share of samples equal to the previous; longest run):")
    for name in d:
        if name == "t":
            continue
        x = d[name]
        steps = np.abs(np.diff(x))
        nz = steps[steps > 1e-12]
        same = steps <= 1e-12
        run, best = 0, 0
        for s in same:
            run = run + 1 if s else 0
            best = max(best, run)
        print("  %-22s step %-10.3g hold %5.1f %%  longest run %d samples" %
              (name, nz.min() if len(nz) else float("nan"), 100 * same.mean(), best + 1))

    r, psi, v, ay = d["yaw_rate"], d["psi"], d["v"], d["ay"]
    sw = d["steering_wheel_angle"]
    psi_rate = np.gradient(psi, t)
    straight = np.zeros(len(t), bool)
    for s in a.straight:
        t0, t1 = (float(u) for u in s.split(":"))
        straight |= (t >= t0) & (t <= t1)

    print("\nyaw rate against d(psi)/dt (psi here: the GNSS course):")
    m, se, n = mean_se(r - psi_rate)
    print("  whole log: yaw_rate - dpsi/dt = %+.5f +- %.5f rad/s (n_eff %.0f)" % (m, se, n))
    if straight.any():
        m, se, n = mean_se((r - psi_rate)[straight])
        print("  straights: yaw_rate - dpsi/dt = %+.5f +- %.5f rad/s (n_eff %.0f)" % (m, se, n))
        m, se, n = mean_se(r[straight])
        print("  straights: yaw_rate itself     = %+.5f +- %.5f rad/s (n_eff %.0f)" % (m, se, n))
    tau, c = lag(psi_rate, r, dt, 20)
    print("  latency: yaw_rate behind dpsi/dt by %+.3f s (peak correlation %.3f)" % (tau, c))
    k = int(round(tau / dt))
    rr = r[max(0, k):len(r) + min(0, k)]
    pp = psi_rate[max(0, -k):len(r) - max(0, k)]
    print("  scale: yaw_rate = %.4f x dpsi/dt (orthogonal regression, aligned by the lag); "
          "plain least squares %.4f" % (tls_slope(pp, rr), float((pp - pp.mean()) @ (rr - rr.mean()) / ((pp - pp.mean()) @ (pp - pp.mean())))))

    print("\nlateral acceleration against v * yaw rate:")
    vr = v * r
    tau, c = lag(vr, ay, dt, 20)
    print("  latency: ay behind v*yaw_rate by %+.3f s (peak correlation %.3f)" % (tau, c))
    print("  scale: ay = %.4f x v*yaw_rate (orthogonal regression)" % tls_slope(vr, ay))
    m, se, n = mean_se(ay - vr)
    print("  offset: ay - v*yaw_rate = %+.3f +- %.3f m/s^2 (n_eff %.0f; includes road bank, roll and v*dbeta/dt)" % (m, se, n))

    print("\nsteering:")
    tau, c = lag(sw, r, dt, 20)
    print("  latency: yaw_rate behind the steering-wheel angle by %+.3f s (peak correlation %.3f; includes the "
          "vehicle's own yaw response)" % (tau, c))
    if straight.any():
        m, se, n = mean_se(sw[straight])
        print("  on the straights: steering-wheel angle %+.2f +- %.2f deg (n_eff %.0f) -> road wheel %+.2f mrad "
              "at ratio %g" % (math.degrees(m), math.degrees(se), n, 1000 * m / a.steer_ratio, a.steer_ratio))
        off = m
    else:
        off = 0.0
    corner = (np.abs(r) > 0.1) & (v > 5)
    if corner.any():
        kin = a.wheelbase * r[corner] / v[corner]
        ratio = (sw[corner] - off) / kin
        print("  kinematic steer ratio in the corners (|r| > 0.1 rad/s, offset removed): median %.1f, "
              "quartiles %.1f-%.1f (an upper bound of the ratio: understeer adds)" %
              (np.median(ratio), np.percentile(ratio, 25), np.percentile(ratio, 75)))

    if "x" in d and "y" in d:
        course = np.unwrap(np.arctan2(np.gradient(d["y"], t), np.gradient(d["x"], t)))
        moving = v > 3
        diff = np.degrees((psi - course + np.pi) % (2 * np.pi) - np.pi)[moving]
        m, se, n = mean_se(diff)
        print("\npsi - course from the positions: %+.3f +- %.3f deg (sd %.2f deg, n_eff %.0f)" %
              (m, se, diff.std(), n))
        tau, c = lag(np.gradient(course, t), psi_rate, dt, 20)
        print("  latency: d(psi)/dt behind the positions' course rate by %+.3f s (peak correlation %.3f)" % (tau, c))
    return 0


def _pair(text, what, parser):
    try:
        lo, hi = (float(u) for u in text.split(":"))
    except ValueError:
        parser.error("%s: expected LO:HI, got '%s'" % (what, text))
    return lo, hi


def yaw_gain_main(d, a, parser):
    band = _pair(a.band, "--band", parser)
    if not 0 < band[0] < band[1]:
        parser.error("--band: expected 0 < LO < HI, got '%s'" % a.band)
    bins = [_pair(b, "--speed-bins", parser) for b in a.speed_bins.split(",") if b.strip()]
    accel_bins = [_pair(b, "--accel-bins", parser) for b in a.accel_bins.split(",") if b.strip()]
    reference = None
    if a.reference_stiffness:
        if a.mass is None or a.cg_to_rear_axle is None:
            parser.error("--reference-stiffness needs --mass and --cg-to-rear-axle")
        c_f, c_r = _pair(a.reference_stiffness, "--reference-stiffness", parser)
        K = reference_understeer(a.mass, a.wheelbase, a.cg_to_rear_axle, c_f, c_r)
        reference = ["C_f %g, C_r %g N/rad, m %g kg, l_r %g m" % (c_f, c_r, a.mass, a.cg_to_rear_axle), K, None]
    try:
        res = yaw_gain(d, a.wheelbase, a.steer_ratio, band, bins, a.block, a.draws, a.seed, a.gyro_column,
                       a.yaw_rate_bias, iv_delay=a.iv_delay, accel_bins=accel_bins)
    except ValueError as e:
        print("lk_log_checks: %s: %s" % (a.log, e), file=sys.stderr)
        return 1
    if reference and a.yaw_inertia:
        speed = float(np.mean(d["v"]))
        h = [abs(single_track_yaw_response(f, speed, a.mass, a.yaw_inertia, a.wheelbase, a.cg_to_rear_axle,
                                           c_f, c_r)) / gain_at(K, speed, a.wheelbase) for f in band]
        reference[2] = h
    print("%s: %d rows, %.2f s; wheelbase %g m, steer ratio %g" %
          (a.log, len(d["t"]), d["t"][-1] - d["t"][0], a.wheelbase, a.steer_ratio))
    print_yaw_gain(res, reference)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
