"""The stability analysis, as lk_stability runs it (docs/python_api.md, docs/stability.md)."""

import json

import numpy as np

from . import _lane_keeping
from ._inputs import config_layers


def critical_delay(config=None, *, overrides=None, tau2_max=0.05, steps=300, degree=24, count=6, reading=None):
    """The critical lower-level delay tau2 (both actuator delays moved together) and its crossing, with the
    rightmost roots at the configured point: `lk_stability critical` as a dict (without its wall time).
    Keys: tau2_critical_s, frequency_hz, omega_rad_s, found, crossing_root, tau2_configured_s,
    tau2_margin, stable_at_configured, spectral_abscissa_at_configured, rightmost_roots, point,
    equations, dde, scan. `reading`: an alternative reading of the paper's equations (lk_stability
    readings)."""
    text = _lane_keeping.critical_delay(config_layers(config, overrides), float(tau2_max), int(steps), int(degree),
                                        int(count), reading or "")
    return json.loads(text)


def rightmost_roots(config=None, *, overrides=None, degree=24, count=6, reading=None, as_array=True):
    """The rightmost characteristic roots of the linearised loop (Im >= 0, rightmost first): a complex
    numpy array; as_array=False: `lk_stability roots` as a dict."""
    result = json.loads(_lane_keeping.rightmost_roots(config_layers(config, overrides), int(degree), int(count),
                                                      reading or ""))
    if not as_array:
        return result
    return np.array([complex(r["re"], r["im"]) for r in result["rightmost_roots"]])


def stability_boundary(config=None, param="tau2", start=1e-5, stop=0.05, *, overrides=None, steps=300, uniform=False,
                       degree=24, reading=None):
    """The first loss of stability along configuration key `param` (or tau2) from `start` to `stop`:
    `lk_stability boundary` as a dict (critical, frequency_hz, crossing_root, ...)."""
    return json.loads(_lane_keeping.stability_boundary(config_layers(config, overrides), param, float(start),
                                                       float(stop), int(steps), bool(uniform), int(degree),
                                                       reading or ""))


def _axis(axis, name):
    """(key, min, max, n): n values from min to max inclusive, as lk_stability chart's --x KEY:MIN:MAX:N; or
    (key, values)."""
    if len(axis) == 4:
        key, low, high, n = axis
        return (str(key), float(low), float(high), int(n))
    if len(axis) == 2:
        key, values = axis
        return (str(key), [float(v) for v in np.asarray(values, dtype=np.float64).ravel()])
    raise ValueError(f"{name}: expected (key, min, max, n) or (key, values)")


def stability_chart(config=None, x=("tracker.k_psi", 0.0, 2.5, 50), y=("tracker.k_y", 0.0, 0.3, 50), *, overrides=None,
                    degree=20, threads=0, reading=None):
    """A stability chart over two configuration keys (Beregi Figs 3-5; `lk_stability chart`): at every
    grid point the loop is linearised and its rightmost roots computed.

    x, y: (key, min, max, n) or (key, values); a key is a numeric configuration key or tau2.
    Returns a dict of arrays with shape (len(y), len(x)): abscissa (largest real part [1/s]),
    frequency_hz of the rightmost root, unstable_roots, stable, contour_field (smooth across the
    boundary: its zero contour is the boundary), rightmost (the root itself); and x, y, their keys and
    units, wall_seconds, threads."""
    return _lane_keeping.stability_chart(config_layers(config, overrides), _axis(x, "x"), _axis(y, "y"), int(degree),
                                         int(threads), reading or "")
