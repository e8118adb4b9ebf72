#!/usr/bin/python3
"""Plots of the sim-to-real gap report (lk_gap): reads DIR/report.json and the CSV files below, writes PNGs.

Usage:
    /usr/bin/python3 scripts/gap_report_plots.py DIR [--dpi N]
    /usr/bin/python3 scripts/gap_report_plots.py --example DIR   # write synthetic inputs into DIR, then plot

Run it with Debian's /usr/bin/python3 (numpy + matplotlib); run it before the Markdown report is written,
which links only the PNG files that exist.

Inputs (all in DIR; the diagnosis engine writes them in exactly these formats)
------------------------------------------------------------------------------
Every CSV file: one header row of column names, then one row per sample; comma-separated; numbers in any
float notation (the engine writes %.17g); "nan" or an empty cell for a missing value; CR LF accepted.
Column order is free and extra columns are ignored. A subsystem column may be absent or all-NaN: its panel
or curve then reads "no data".

residuals.csv -- nominal-model open-loop replay residual per subsystem against time
    t          time [s], increasing
    steering   normalised residual of the steering subsystem (torque -> delta)            [-]
    chassis    normalised residual of the chassis (delta -> yaw rate, psi, y, ay)         [-]
    tracker    normalised residual of the path tracker (pose -> delta_des)                [-]
    actuator   normalised residual of the actuator (delta_des, delta -> torque)           [-]
    A subsystem's normalised residual is (replayed - measured) / RMS(measured) for its output; with several
    outputs, the root mean square over outputs of those ratios (then >= 0). NaN where a subsystem has no value
    (e.g. before its replay starts, or in skipped rows).

spectrum.csv -- one-sided power spectral density of each subsystem's normalised residual
    f          frequency [Hz], increasing (a 0 Hz row is allowed; it is left out of the log-scale plot)
    steering, chassis, tracker, actuator   PSD [1/Hz]; NaN where not computed

overlay.csv -- held-out closed-loop replay: the real log, the nominal simulation, the simulation with the
winning effect added (corrected columns all NaN, or absent, when the verdict is "unexplained")
    t                                                   [s]
    y_real, y_nominal, y_corrected                      lateral position of G in map [m]
    yaw_rate_real, yaw_rate_nominal, yaw_rate_corrected [rad/s]
    delta_real, delta_nominal, delta_corrected          front-wheel steering angle [rad]

report.json -- the report (src/core/gap/report/gap_report.cpp documents the layout). Used here: logs_t0 (each
    log's first sample in its own time), where.subsystem, where.subsystems[].name/nrmse, where.windows[] (t0, t1,
    share, log_t0; largest first), where.bands[] (f0, f1, share), ranking[] (effect, heldout_gap_before,
    heldout_gap_after, shrink, closed_loop_bounded), verdict (effect, confidence, shrink), how_far (before,
    after, not_run). null means "not a number". Without report.json the plots are still drawn, without windows,
    bands and nrmse annotations; ranking.png needs it.

Times are drawn in seconds since the log's first sample (report.json logs_t0): a log stamped in epoch time
(t ~ 1.7e9 s) would otherwise read 1.692e+09 on the axis and in the titles.

Outputs (in DIR)
----------------
residuals.png  one panel per subsystem, residual vs time, the top 5 windows of report.json shaded with their share
spectrum.png   left: PSD per subsystem (log-log) with the bands shaded; right: bar chart of the band shares
overlay.png    y, yaw rate, delta: real vs nominal vs corrected on the held-out data; not drawn when the
               closed-loop replay did not run (report.json how_far.not_run, or an overlay.csv without rows)
ranking.png    held-out gap before/after per candidate effect (bars), shrink annotated, verdict highlighted,
               fits that make the logged closed loop unbounded hatched

A missing or unreadable input skips its plot with a message on stderr (and removes a PNG of that name left by an
earlier run, so that report.md does not show it); other plots are still drawn.
Exit status: 0 when every plot was drawn or skipped for a missing input, 1 if a plot failed on malformed
input, 2 on bad usage.
"""
import argparse
import csv
import json
import math
import os
import sys
import textwrap

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.patches
    import matplotlib.pyplot as plt
except ImportError as error:  # the pyenv python3 on PATH lacks them
    sys.stderr.write("gap_report_plots: %s; run with /usr/bin/python3 (Debian's numpy + matplotlib)\n" % error)
    sys.exit(1)

SUBSYSTEMS = ["steering", "chassis", "tracker", "actuator"]
SUBSYSTEM_LABEL = {
    "steering": "steering (torque → δ)",
    "chassis": "chassis (δ → yaw rate, ψ, y, a_y)",
    "tracker": "tracker (pose → δ_des)",
    "actuator": "actuator (δ_des, δ → torque)",
}
COLOURS = {"steering": "tab:blue", "chassis": "tab:orange", "tracker": "tab:green", "actuator": "tab:purple"}
TOP_WINDOWS = 5


class SkipPlot(Exception):
    """An input is missing: skip the plot with a message (not an error)."""


def message(text):
    sys.stderr.write("gap_report_plots: %s\n" % text)


def to_float(text):
    text = text.strip().strip('"')
    if not text:
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise ValueError("cannot parse %r as a number" % text)


def read_csv(path):
    """Columns of a CSV file as {name: numpy array}. Raises SkipPlot if the file is missing."""
    if not os.path.isfile(path):
        raise SkipPlot("%s not found" % path)
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    rows = [r for r in rows if any(cell.strip() for cell in r)]
    if not rows:
        raise ValueError("%s: empty file (no header row)" % path)
    header = [name.strip().lstrip("\ufeff") for name in rows[0]]
    columns = {name: [] for name in header}
    for line, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise ValueError("%s:%d: %d cells, the header has %d" % (path, line, len(row), len(header)))
        for name, cell in zip(header, row):
            try:
                columns[name].append(to_float(cell))
            except ValueError as error:
                raise ValueError("%s:%d: column %r: %s" % (path, line, name, error))
    return {name: np.asarray(values, dtype=float) for name, values in columns.items()}


def require(columns, names, path):
    missing = [n for n in names if n not in columns]
    if missing:
        raise ValueError("%s: missing column(s) %s; found %s" % (path, ", ".join(missing), ", ".join(columns)))


def number(value):
    """A JSON number (null -> NaN)."""
    return math.nan if value is None else float(value)


def read_report(directory):
    path = os.path.join(directory, "report.json")
    if not os.path.isfile(path):
        message("%s not found: plots drawn without windows, bands and nrmse" % path)
        return None
    try:
        with open(path) as handle:
            return json.load(handle)
    except (OSError, ValueError) as error:
        message("%s unreadable (%s): plots drawn without it" % (path, error))
        return None


def log_start(report, first_t):
    """The first sample's time of the log a series starting at first_t belongs to (report.json logs_t0): the
    latest log start at or before it; 0 without report.json or for series before every start."""
    starts = [number(v) for v in ((report or {}).get("logs_t0") or {}).values()]
    starts = [v for v in starts if math.isfinite(v) and (not math.isfinite(first_t) or v <= first_t + 1e-6)]
    return max(starts) if starts else 0.0


def time_label(offset):
    label = "time since the log's start [s]"
    return label + (" (its first sample: t = %.3f s)" % offset if offset != 0.0 else "")


def percent(fraction):
    return "n/a" if not math.isfinite(fraction) else "%.0f %%" % (100.0 * fraction)


def has_data(values):
    return values is not None and np.any(np.isfinite(values))


def plot_residuals(directory, report, dpi):
    path = os.path.join(directory, "residuals.csv")
    data = read_csv(path)
    require(data, ["t"], path)
    t = data["t"]
    offset = log_start(report, float(np.nanmin(t)) if t.size else math.nan)
    t = t - offset
    where = (report or {}).get("where", {})
    nrmse = {s.get("name"): number(s.get("nrmse")) for s in where.get("subsystems", [])}
    windows = where.get("windows", [])[:TOP_WINDOWS]
    gap_subsystem = where.get("subsystem")
    # Each window in seconds since its own log's start (log_t0; older reports: the series' offset).
    spans = []
    for rank, w in enumerate(windows):
        start = number(w.get("log_t0")) if w.get("log_t0") is not None else offset
        t0, t1 = number(w.get("t0")) - start, number(w.get("t1")) - start
        if math.isfinite(t0) and math.isfinite(t1):
            spans.append((rank, t0, t1, number(w.get("share"))))
    # Labels "#k" on top of the first panel, stacked in rows where they would overlap (adjacent windows).
    x_range = (float(np.nanmax(t)) - float(np.nanmin(t))) if t.size else 1.0
    label_rows = {}
    placed = []  # (centre, row)
    for rank, t0, t1, _ in sorted(spans, key=lambda s: 0.5 * (s[1] + s[2])):
        centre = 0.5 * (t0 + t1)
        row = 0
        while any(r == row and abs(c - centre) < 0.04 * max(x_range, 1e-9) for c, r in placed):
            row += 1
        placed.append((centre, row))
        label_rows[rank] = row

    fig, axes = plt.subplots(len(SUBSYSTEMS), 1, sharex=True, figsize=(10, 9.5), constrained_layout=True)
    for ax, name in zip(axes, SUBSYSTEMS):
        for rank, t0, t1, _ in spans:
            ax.axvspan(t0, t1, facecolor="gold", alpha=0.35, edgecolor="darkgoldenrod", lw=0.8)
            if name == SUBSYSTEMS[0]:
                ax.annotate("#%d" % (rank + 1), xy=(0.5 * (t0 + t1), 1.0), xycoords=("data", "axes fraction"),
                            xytext=(0, 2 + 10 * label_rows[rank]), textcoords="offset points",
                            ha="center", va="bottom", fontsize=8)
        values = data.get(name)
        if has_data(values):
            ax.plot(t, values, color=COLOURS[name], lw=0.9, label=name)
        else:
            ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center", color="grey")
        ax.axhline(0.0, color="black", lw=0.5)
        title = SUBSYSTEM_LABEL[name]
        if name in nrmse:
            title += ", nrmse %.3g" % nrmse[name]
        if name == gap_subsystem:
            title += "  ← carries the gap"
        # Above the window labels of the first panel.
        pad = 6 + (12 * (1 + max(label_rows.values())) if name == SUBSYSTEMS[0] and label_rows else 0)
        ax.set_title(title, fontsize=10, loc="left", fontweight="bold" if name == gap_subsystem else "normal", pad=pad)
        ax.set_ylabel("residual [-]")
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(time_label(offset))
    fig.suptitle("Nominal-model normalised residual per subsystem\n(open-loop replay with logged inputs)", fontsize=11)
    if spans:
        # The windows' list below the panels, wrapped to the figure's width (a one-line title ran off the page).
        # (No-break spaces inside an entry: a line breaks only between windows.)
        text = "shaded: top windows by share of residual energy — " + ", ".join(
            ("#%d %.2f–%.2f s %s" % (rank + 1, t0, t1, percent(share))).replace(" ", "\u00a0")
            for rank, t0, t1, share in spans)
        fig.supxlabel("\n".join(textwrap.wrap(text, 110)), fontsize=9)
    out = os.path.join(directory, "residuals.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def plot_spectrum(directory, report, dpi):
    path = os.path.join(directory, "spectrum.csv")
    data = read_csv(path)
    require(data, ["f"], path)
    f = data["f"]
    positive = f > 0
    bands = (report or {}).get("where", {}).get("bands", [])

    fig, (ax, bar_ax) = plt.subplots(1, 2, figsize=(12, 5), gridspec_kw={"width_ratios": [2, 1]},
                                     constrained_layout=True)
    drawn = False
    for name in SUBSYSTEMS:
        values = data.get(name)
        if not has_data(values):
            continue
        mask = positive & np.isfinite(values) & (values > 0)
        if np.any(mask):
            ax.loglog(f[mask], values[mask], color=COLOURS[name], lw=1.0, label=name)
            drawn = True
    if not drawn:
        ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center", color="grey")
    for i, b in enumerate(bands):
        f0, f1, share = number(b.get("f0")), number(b.get("f1")), number(b.get("share"))
        if not (math.isfinite(f0) and math.isfinite(f1)):
            continue
        lo = f0 if f0 > 0 else (f[positive].min() if np.any(positive) else 1e-3)
        ax.axvspan(lo, f1, color="grey" if i % 2 == 0 else "lightsteelblue", alpha=0.15, lw=0)
        ax.annotate(percent(share), xy=(math.sqrt(lo * f1), 0.98), xycoords=("data", "axes fraction"),
                    ha="center", va="top", fontsize=8)
    ax.set_xlabel("frequency f [Hz]")
    ax.set_ylabel("PSD of normalised residual [1/Hz]")
    ax.set_title("Residual spectra (bands shaded, share of residual energy on top)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    if drawn:
        ax.legend(fontsize=8, loc="lower left")

    if bands:
        labels = ["%.3g–%.3g" % (number(b.get("f0")), number(b.get("f1"))) for b in bands]
        shares = [100.0 * number(b.get("share")) for b in bands]
        shares = [s if math.isfinite(s) else 0.0 for s in shares]
        bar_ax.bar(range(len(bands)), shares, color="tab:gray")
        bar_ax.set_xticks(range(len(bands)))
        bar_ax.set_xticklabels(labels, rotation=45, ha="right", fontsize=8)
        for i, s in enumerate(shares):
            bar_ax.annotate("%.0f %%" % s, xy=(i, s), ha="center", va="bottom", fontsize=8)
        bar_ax.set_ylim(0, max(shares + [1.0]) * 1.15)
    else:
        bar_ax.text(0.5, 0.5, "no bands in report.json", transform=bar_ax.transAxes, ha="center", va="center",
                    color="grey")
    bar_ax.set_xlabel("band [Hz]")
    bar_ax.set_ylabel("share of residual energy [%]")
    bar_ax.set_title("Band shares (report.json where.bands)", fontsize=10)
    bar_ax.grid(True, axis="y", alpha=0.3)
    out = os.path.join(directory, "spectrum.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def plot_overlay(directory, report, dpi):
    not_run = (report or {}).get("how_far", {}).get("not_run")
    if not_run:
        raise SkipPlot("the closed-loop replay did not run (%s)" % not_run)
    path = os.path.join(directory, "overlay.csv")
    data = read_csv(path)
    require(data, ["t"], path)
    if data["t"].size == 0:
        raise SkipPlot("%s has no rows (no closed-loop replay)" % path)
    offset = log_start(report, float(np.nanmin(data["t"])))
    t = data["t"] - offset
    verdict = (report or {}).get("verdict", {})
    effect = verdict.get("effect")
    corrected_label = "nominal + %s" % effect if effect and effect != "unexplained" else "corrected"
    signals = [("y", "lateral position y [m]"), ("yaw_rate", "yaw rate [rad/s]"), ("delta", "steering angle δ [rad]")]
    fig, axes = plt.subplots(len(signals), 1, sharex=True, figsize=(10, 8), constrained_layout=True)
    legend_drawn = False
    for ax, (signal, label) in zip(axes, signals):
        styles = [("real", "real (log)", dict(color="black", lw=1.4)),
                  ("nominal", "nominal model", dict(color="tab:red", lw=1.0, ls="--")),
                  ("corrected", corrected_label, dict(color="tab:blue", lw=1.0))]
        any_drawn = False
        for suffix, name, style in styles:
            values = data.get("%s_%s" % (signal, suffix))
            if has_data(values):
                ax.plot(t, values, label=name, **style)
                any_drawn = True
        if not any_drawn:
            ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center", color="grey")
        elif not legend_drawn:  # one legend, above the first panel with data
            ax.legend(fontsize=8, ncol=3, loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)
            legend_drawn = True
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(time_label(offset))
    title = "Held-out closed-loop replay: real vs nominal vs corrected"
    how_far = (report or {}).get("how_far", {})
    before, after = number(how_far.get("before")), number(how_far.get("after"))
    if math.isfinite(before):
        title += "\nclosed-loop gap %.3g → %.3g" % (before, after)
        if before > 0 and math.isfinite(after):
            title += " (shrink %s)" % percent(1.0 - after / before)
        # Net of the logs' noise (how_far.h): what a perfect model would leave is taken out.
        net_before, net_after = number(how_far.get("net_before")), number(how_far.get("net_after"))
        if math.isfinite(net_before) and math.isfinite(net_after):
            title += "; net of noise %.3g → %.3g" % (net_before, net_after)
            if net_before > 0:
                title += " (%s)" % percent(1.0 - net_after / net_before)
    fig.suptitle(title)
    out = os.path.join(directory, "overlay.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def plot_ranking(directory, report, dpi):
    if report is None:
        raise SkipPlot("ranking.png needs report.json")
    ranking = report.get("ranking", [])
    if not ranking:
        raise SkipPlot("report.json has an empty ranking")
    verdict = report.get("verdict", {})
    names = [e.get("effect", "?") for e in ranking]
    before = np.array([number(e.get("heldout_gap_before")) for e in ranking])
    after = np.array([number(e.get("heldout_gap_after")) for e in ranking])
    shrink = [number(e.get("shrink")) for e in ranking]
    # A fit whose closed loop leaves the logged bounds cannot be the cause (report.json, optional key).
    unbounded = [e.get("closed_loop_bounded", True) is False for e in ranking]
    y = np.arange(len(ranking))[::-1]  # best (first) at the top
    height = 0.38
    fig, ax = plt.subplots(figsize=(10, 1.0 + 0.45 * len(ranking)), constrained_layout=True)
    ax.barh(y + height / 2, np.nan_to_num(before, nan=0.0), height, color="lightgray", edgecolor="gray",
            label="nominal (before)")
    colours = ["tab:green" if n == verdict.get("effect") else ("white" if u else "tab:blue")
               for n, u in zip(names, unbounded)]
    bars = ax.barh(y - height / 2, np.nan_to_num(after, nan=0.0), height, color=colours, edgecolor="tab:blue",
                   label="with the effect (after)")
    for bar, u in zip(bars, unbounded):
        if u:
            bar.set_hatch("//")
    finite = np.concatenate([before[np.isfinite(before)], after[np.isfinite(after)]])
    top = float(finite.max()) if finite.size else 1.0
    for yi, b, a, s, u in zip(y, before, after, shrink, unbounded):
        ax.annotate("shrink %s" % percent(s) if math.isfinite(a) else "n/a",
                    xy=(max(a if math.isfinite(a) else 0.0, 0.0) + 0.01 * top, yi - height / 2),
                    va="center", fontsize=8)
    ax.set_yticks(y)
    ax.set_yticklabels(["%s ★" % n if n == verdict.get("effect") else (n + " (unbounded)" if u else n)
                        for n, u in zip(names, unbounded)])
    ax.set_xlim(0, top * 1.25 if top > 0 else 1.0)
    ax.set_xlabel("held-out gap (normalised) [-]")
    ax.grid(True, axis="x", alpha=0.3)
    handles, _ = ax.get_legend_handles_labels()
    if any(unbounded):
        handles.append(matplotlib.patches.Patch(facecolor="white", edgecolor="tab:blue", hatch="//",
                                                label="fit makes the logged closed loop unbounded: not a cause"))
    ax.legend(handles=handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=3)
    confidence = number(verdict.get("confidence"))
    ax.set_title("Candidate effects on held-out data — verdict: %s (confidence %s)"
                 % (verdict.get("effect", "?"), "n/a" if not math.isfinite(confidence) else "%.2f" % confidence),
                 fontsize=10)
    out = os.path.join(directory, "ranking.png")
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def write_example(directory):
    """Synthetic inputs (seeded): a chassis gap concentrated near 1.5 Hz, 12-14 s, explained by tire_lag."""
    os.makedirs(directory, exist_ok=True)
    rng = np.random.default_rng(5)
    t = np.arange(0.0, 20.0, 0.01)
    burst = np.exp(-((t - 13.0) / 0.8) ** 2)
    res = {
        "steering": 0.02 * rng.standard_normal(t.size),
        "chassis": 0.5 * burst * np.sin(2 * np.pi * 1.5 * t) + 0.02 * rng.standard_normal(t.size),
        "tracker": 0.005 * rng.standard_normal(t.size),
        "actuator": 0.01 * rng.standard_normal(t.size),
    }
    res["tracker"][:50] = np.nan
    with open(os.path.join(directory, "residuals.csv"), "w") as out:
        out.write("t,tracker,actuator,steering,chassis\n")
        for i in range(t.size):
            out.write("%.17g,%.17g,%.17g,%.17g,%.17g\n" % (t[i], res["tracker"][i], res["actuator"][i],
                                                          res["steering"][i], res["chassis"][i]))
    f = np.fft.rfftfreq(t.size, 0.01)
    with open(os.path.join(directory, "spectrum.csv"), "w") as out:
        out.write("f,tracker,actuator,steering,chassis\n")
        psd = {}
        for name, values in res.items():
            v = np.nan_to_num(values)
            psd[name] = 2.0 * 0.01 / t.size * np.abs(np.fft.rfft(v)) ** 2
        for i in range(f.size):
            out.write("%.17g,%.17g,%.17g,%.17g,%.17g\n" % (f[i], psd["tracker"][i], psd["actuator"][i],
                                                          psd["steering"][i], psd["chassis"][i]))
    y_real = 1.75 * np.sin(2 * np.pi * 0.1 * t) * (t > 2)
    with open(os.path.join(directory, "overlay.csv"), "w") as out:
        out.write("t,y_real,y_nominal,y_corrected,yaw_rate_real,yaw_rate_nominal,yaw_rate_corrected,"
                  "delta_real,delta_nominal,delta_corrected\n")
        for i in range(t.size):
            yr = y_real[i] + 0.01 * rng.standard_normal()
            yn = y_real[i] * 0.9 + 0.2 * burst[i] * math.sin(2 * math.pi * 1.5 * t[i])
            yc = y_real[i] * 0.99
            rr = 0.1 * math.cos(2 * math.pi * 0.1 * t[i]) * (t[i] > 2)
            out.write(",".join("%.17g" % v for v in [
                t[i], yr, yn, yc, rr + 0.003 * rng.standard_normal(), rr * 0.85 + 0.05 * burst[i], rr * 0.98,
                0.03 * rr, 0.03 * rr * 0.8, 0.03 * rr * 0.97]) + "\n")
    report = {
        "format": "lane_keeping.gap_report", "version": 1, "logs": ["example.csv"], "heldout": ["example.csv[1000:2000]"],
        "rows_used": int(t.size), "rows_skipped": 3, "notes": [],
        "where": {
            "subsystem": "chassis",
            "subsystems": [{"name": n, "nrmse": float(np.sqrt(np.nanmean(res[n] ** 2))), "noise_floor": 0.02,
                            "outputs": []} for n in SUBSYSTEMS],
            "windows": [{"t0": 12.5, "t1": 13.5, "share": 0.45}, {"t0": 11.5, "t1": 12.5, "share": 0.2},
                        {"t0": 13.5, "t1": 14.5, "share": 0.2}],
            "bands": [{"f0": 0.0, "f1": 0.3, "share": 0.05}, {"f0": 0.3, "f1": 1.0, "share": 0.1},
                      {"f0": 1.0, "f1": 3.0, "share": 0.8}, {"f0": 3.0, "f1": 10.0, "share": 0.04},
                      {"f0": 10.0, "f1": 50.0, "share": 0.01}],
            "regimes": [],
        },
        "ranking": [
            {"effect": "tire_lag", "params": {"relaxation_length": 0.6}, "heldout_gap_before": 0.3,
             "heldout_gap_after": 0.04, "shrink": 1 - 0.04 / 0.3},
            {"effect": "sensing_delay", "params": {"delay": 0.01}, "heldout_gap_before": 0.3,
             "heldout_gap_after": 0.17, "shrink": 1 - 0.17 / 0.3},
            {"effect": "cornering_stiffness", "params": {"scale": 0.9}, "heldout_gap_before": 0.3,
             "heldout_gap_after": 0.27, "shrink": 0.1},
            {"effect": "steering_compliance", "params": {"stiffness": 5e5}, "heldout_gap_before": 0.3,
             "heldout_gap_after": 0.2, "shrink": 1 - 0.2 / 0.3, "closed_loop_bounded": False},
            {"effect": "pose_bias", "params": {}, "heldout_gap_before": 0.3, "heldout_gap_after": None,
             "shrink": None},
        ],
        "verdict": {"effect": "tire_lag", "confidence": 0.9, "gap_before": 0.3, "gap_after": 0.04,
                    "shrink": 1 - 0.04 / 0.3},
        "how_far": {"before": 0.35, "after": 0.05},
    }
    with open(os.path.join(directory, "report.json"), "w") as out:
        json.dump(report, out, indent=2)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dir", help="report directory (holds report.json and the CSV files)")
    parser.add_argument("--dpi", type=int, default=110)
    parser.add_argument("--example", action="store_true", help="first write synthetic inputs into DIR")
    args = parser.parse_args(argv)
    if args.example:
        write_example(args.dir)
    if not os.path.isdir(args.dir):
        message("%s is not a directory" % args.dir)
        return 2
    report = read_report(args.dir)
    status = 0
    for plot in (plot_residuals, plot_spectrum, plot_overlay, plot_ranking):
        try:
            out = plot(args.dir, report, args.dpi)
            message("wrote %s" % out)
        except SkipPlot as skip:
            name = plot.__name__.replace("plot_", "") + ".png"
            message("skipped %s: %s" % (name, skip))
            stale = os.path.join(args.dir, name)
            if os.path.isfile(stale):  # an earlier run's: report.md links every PNG that exists
                os.remove(stale)
        except Exception as error:  # malformed input: report it, draw the other plots
            message("failed %s: %s: %s" % (plot.__name__.replace("plot_", "") + ".png", type(error).__name__, error))
            plt.close("all")
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
