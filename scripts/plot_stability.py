#!/usr/bin/python3
"""Plots a stability chart written by `lk_stability chart|fig3|fig4|fig5` (PREFIX.json + PREFIX.csv).

Usage: /usr/bin/python3 scripts/plot_stability.py PREFIX.json [OUT.png]

One panel per value of the panel parameter, one colour per value of the series parameter; the
stable region (all characteristic roots in the left half plane) is shaded and bounded by the zero
contour of the spectral abscissa. Needs Debian's python3-matplotlib (the pyenv python3 lacks it).
"""
import csv
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

SYMBOLS = {
    "tracker.k_psi": (r"$k_\psi$", "1"),
    "tracker.k_y": (r"$k_y$", "1/m"),
    "actuator.p": (r"$p$", "1"),
    "tau2": (r"$\tau_2$", "s"),
    "delays.pose_to_tracker": (r"$\tau_1$", "s"),
    "delays.torque_to_plant": (r"$\tau_T$", "s"),
}
STYLES = ["-", "--", "-.", ":"]
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]


def scale_of(key, unit, values):
    """Display factor and unit: delays in ms when they are below 0.05 s."""
    if unit == "s" and values and max(abs(v) for v in values) < 0.05:
        return 1e3, "ms"
    return 1.0, unit


def label_of(axis, values):
    symbol, unit = SYMBOLS.get(axis["key"], (axis["key"], axis.get("unit", "")))
    factor, unit = scale_of(axis["key"], unit, values)
    return factor, f"{symbol} [{unit if unit else '1'}]"


def value_text(key, unit, value):
    symbol, _ = SYMBOLS.get(key, (key, unit))
    factor, shown = scale_of(key, unit, [value])
    v = value * factor
    text = f"{v:g}"
    return f"{symbol} = {text}" + (f" {shown}" if shown and shown != "1" else "")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    with open(sys.argv[1]) as f:
        meta = json.load(f)
    out = sys.argv[2] if len(sys.argv) > 2 else meta["png"]
    rows = []
    with open(meta["csv"]) as f:
        for r in csv.DictReader(f):
            rows.append(r)
    nx, ny = meta["n"]
    panels = meta["panels"]["values"] if meta.get("panels") else [float("nan")]
    series = meta["series"]["values"] if meta.get("series") else [float("nan")]

    def key_of(v):
        return "nan" if (isinstance(v, float) and math.isnan(v)) else f"{float(v):.10g}"

    grids = {}
    for r in rows:
        k = (key_of(float(r["panel"])), key_of(float(r["series"])))
        grids.setdefault(k, []).append(r)

    xs = sorted({float(r["x"]) for r in rows})
    ys = sorted({float(r["y"]) for r in rows})
    fx, xlabel = label_of(meta["x"], xs)
    fy, ylabel = label_of(meta["y"], ys)
    X, Y = np.meshgrid(np.array(xs) * fx, np.array(ys) * fy)

    n_panels = len(panels)
    shared_handles = []
    cols = 1 if n_panels == 1 else 2
    nrows = math.ceil(n_panels / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(6.4 * cols, 5.0 * nrows), squeeze=False)
    for index, pv in enumerate(panels):
        ax = axes[index // cols][index % cols]
        handles = []
        for si, sv in enumerate(series):
            cell = grids.get((key_of(pv), key_of(sv)), [])
            if len(cell) != nx * ny:
                continue
            a = np.array([float(r["abscissa"]) for r in cell]).reshape(ny, nx)
            colour = COLOURS[si % len(COLOURS)] if len(series) > 1 else "#2ca02c"
            style = STYLES[si % len(STYLES)] if len(series) > 1 else "-"
            stable = a < 0
            # contour_field: the spectral abscissa, with the crossing mode's real part at stable points
            # next to the boundary (lk_stability, stability_chart.h), so the zero contour interpolates
            # one mode between grid points. The k_y = 0 or p = 0 edges carry a root at exactly 0.
            field = np.clip(np.array([float(r["contour_field"]) for r in cell]).reshape(ny, nx), -1e3, 1e3)
            if stable.any():
                ax.contourf(X, Y, field, levels=[-2e3, 0.0], colors=[colour],
                            alpha=0.16 if len(series) > 1 else 0.35)
                if not stable.all():
                    ax.contour(X, Y, field, levels=[0.0], colors=[colour], linewidths=1.8, linestyles=style)
            if len(series) > 1:
                label = value_text(meta["series"]["key"], meta["series"].get("unit", ""), sv)
                if not stable.any():
                    label += " (no stable point)"
                handles.append(Line2D([0], [0], color=colour, lw=2.0, ls=style, label=label))
            else:
                handles.append(Patch(facecolor=colour, alpha=0.35, label="stable (all roots Re < 0)"))
                handles.append(Line2D([0], [0], color=colour, lw=1.8, label="stability boundary"))
                f = np.array([float(r["frequency_hz"]) for r in cell]).reshape(ny, nx)
                mask = a >= 0
                if mask.any():
                    lo, hi = np.percentile(f[mask], [5, 95])
                    handles.append(Patch(facecolor="white", edgecolor="grey",
                                         label=f"unstable (rightmost root {lo:.3g}-{hi:.3g} Hz)"))
        if len(series) > 1:
            handles.append(Patch(facecolor="grey", alpha=0.3, label="shaded: stable"))
        for m in meta.get("markers", []):
            if "panel" in m and not (key_of(m["panel"]) == key_of(pv)):
                continue
            ax.plot(m["x"] * fx, m["y"] * fy, "k*", ms=11, zorder=5)
            ax.annotate(m["label"], (m["x"] * fx, m["y"] * fy), xytext=(6, 6), textcoords="offset points", fontsize=9)
        ax.set_xlim(X.min(), X.max())
        ax.set_ylim(Y.min(), Y.max())
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        if not (isinstance(pv, float) and math.isnan(pv)):
            ax.set_title(value_text(meta["panels"]["key"], meta["panels"].get("unit", ""), pv))
        if n_panels == 1:
            ax.legend(handles=handles, loc="upper right", fontsize=8, framealpha=0.9)
        else:
            shared_handles = handles
    for index in range(n_panels, nrows * cols):
        axes[index // cols][index % cols].axis("off")
    point = meta.get("point", {})
    fixed = (f"tires: {point.get('tire_front', '?')}/{point.get('tire_rear', '?')}; "
             f"equations: {meta.get('equations', 'printed')}"
             + ("\n" if n_panels == 1 else "; ") + "shaded: stable (linearised, all roots Re < 0)")
    fig.suptitle(f"{meta.get('title', '')}\n{fixed}", fontsize=11 if n_panels > 1 else 10)
    if n_panels > 1:
        # One legend for all panels, below them (it would hide boundaries inside a panel).
        fig.legend(handles=shared_handles, loc="lower center", ncol=min(len(shared_handles), 6), fontsize=9)
        fig.tight_layout(rect=(0, 0.05, 1, 1))
    else:
        fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
