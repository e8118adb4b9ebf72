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
"""
import argparse
import math
import sys

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


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("log")
    p.add_argument("--wheelbase", type=float, required=True)
    p.add_argument("--steer-ratio", type=float, required=True)
    p.add_argument("--straight", action="append", default=[], help="T0:T1 [s]: a straight (repeatable)")
    a = p.parse_args(argv)
    d = read(a.log)
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


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
