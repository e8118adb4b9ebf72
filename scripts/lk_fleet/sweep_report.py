"""The sweep command's report, rebuilt from every task's result: sweep.csv (one row per point) and sweep.png
(a colour map over two grid axes, a line over one, a histogram of Monte-Carlo draws).

Depends on messages, storage, results and sweep (the metrics' names)."""
import os

from .messages import status
from .results import error_text
from .storage import csv_text, write_text_atomic
from .sweep import SWEEP_METRICS


def sweep_rows(results, keys):
    rows = []
    for r in results:
        s = r.get("summary", {})
        row = {"task_id": r["task_id"], "draw": "" if r["inputs"]["draw"] is None else r["inputs"]["draw"],
               "status": r["status"], "exit_code": r["exit_code"], "wall_seconds": round(r["wall_seconds"], 4),
               "error": error_text(r)}
        row.update({k: r["inputs"]["point"][k] for k in keys})
        row.update({k: s.get(k, "") for k in ("diverged", "finite", "bounded", "t_end", "rows") + SWEEP_METRICS})
        rows.append(row)
    return rows


def plot_sweep(path, rows, axes, laws, metric):
    """A colour map for two grid axes, a line for one, a histogram of the metric for Monte-Carlo draws.
    Unbounded points (diverged or non-finite) are marked: their metric is where the run stopped."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    ok = [r for r in rows if r["status"] == "ok"]
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    if laws:
        # Unbounded runs stopped early: their figure is not comparable; the title counts them.
        values = [r[metric] for r in ok if r["bounded"]]
        ax.hist(values, bins=max(5, min(40, len(values) // 4)), color="#4878a8")
        ax.set_xlabel(metric)
        ax.set_ylabel("bounded runs")
        ax.set_title(f"{len(ok)} draws, {len(ok) - len(values)} diverged ({', '.join(k for k, *_ in laws)})",
                     fontsize=10)
    elif len(axes) == 1:
        key = axes[0][0]
        ok.sort(key=lambda r: r[key])
        ax.plot([r[key] for r in ok], [r[metric] for r in ok], "o-", color="#4878a8", label=metric)
        unbounded = [r for r in ok if not r["bounded"]]
        if unbounded:
            ax.plot([r[key] for r in unbounded], [r[metric] for r in unbounded], "x", color="red",
                    markersize=10, label="diverged / not finite (where the run stopped)")
        ax.set_xlabel(axis_label(key))
        ax.set_ylabel(metric)
        ax.legend()
    elif len(axes) == 2:
        (kx, xs), (ky, ys) = axes
        # Unbounded runs stopped early: their figure is not comparable, the cell stays grey.
        grid = np.full((len(ys), len(xs)), np.nan)
        for r in ok:
            if r["bounded"]:
                grid[ys.index(r[ky]), xs.index(r[kx])] = r[metric]
        cmap = matplotlib.colormaps["viridis"].copy()
        cmap.set_bad("#d0d0d0")
        mesh = ax.pcolormesh(cell_edges(xs), cell_edges(ys), np.ma.masked_invalid(grid), shading="flat",
                             cmap=cmap, norm=colour_norm(grid))
        fig.colorbar(mesh, ax=ax, label=metric)
        unbounded = [r for r in ok if not r["bounded"]]
        ax.plot([r[kx] for r in unbounded], [r[ky] for r in unbounded], "x", color="red", markersize=10,
                label="diverged / not finite")
        if unbounded:
            ax.legend(loc="upper right")
        ax.set_xlabel(axis_label(kx))
        ax.set_ylabel(axis_label(ky))
    else:
        plt.close(fig)
        return False
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def axis_label(key):
    """'a.b.c+a.b.d' (keys set together) reads 'c = d'."""
    return " = ".join(k.split(".")[-1] for k in key.split("+")) if "+" in key else key


def colour_norm(grid):
    """A log colour scale when the values span decades (a diverged corner next to decaying runs)."""
    from matplotlib.colors import LogNorm
    import numpy as np
    positive = grid[np.isfinite(grid) & (grid > 0)]
    if len(positive) and positive.size == np.isfinite(grid).sum() and positive.max() > 100 * positive.min():
        return LogNorm(positive.min(), positive.max())
    return None


def cell_edges(values):
    """Cell boundaries around grid values (midpoints; half a step beyond the ends)."""
    if len(values) == 1:
        return [values[0] - 0.5, values[0] + 0.5]
    mids = [(a + b) / 2 for a, b in zip(values, values[1:])]
    return [2 * values[0] - mids[0]] + mids + [2 * values[-1] - mids[-1]]


def write_sweep_report(out, results, axes, laws, metric):
    keys = [k for k, _ in axes] + [k for k, *_ in laws]
    rows = sweep_rows(results, keys)
    header = ["task_id"] + keys + ["draw", "status", "exit_code", "diverged", "finite", "bounded", "t_end",
                                   "rows", *SWEEP_METRICS, "wall_seconds", "error"]
    write_text_atomic(os.path.join(out, "sweep.csv"), csv_text(header, rows))
    if not plot_sweep(os.path.join(out, "sweep.png"), rows, axes, laws, metric):
        status(f"no plot for {len(axes)} grid axes (one or two, or Monte-Carlo draws)")
