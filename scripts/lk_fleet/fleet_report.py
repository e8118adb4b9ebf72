"""The gap command's fleet report, rebuilt from every task's result: fleet.csv (one row per log), fleet.md
(verdict counts, parameter plots, unexplained and failed logs, every log) and plots/<effect>.<parameter>.png.

Depends on storage and results."""
import os
import re

from .results import error_text
from .storage import csv_text, write_text_atomic


def gap_rows(results):
    """One flat row per log; the verdict's fitted parameters as columns 'effect.parameter'."""
    rows = []
    for r in sorted(results, key=lambda r: r["inputs"]["log"]):
        s = r.get("summary", {})
        row = {"task_id": r["task_id"], "log": r["inputs"]["log"], "scenario": r["inputs"]["scenario"] or "",
               "status": r["status"], "exit_code": r["exit_code"], "effect": s.get("effect", ""),
               "form": s.get("form", ""), "confidence": s.get("confidence", ""), "where": s.get("where", ""),
               "shrink": s.get("shrink", ""), "how_far_shrink": s.get("how_far_shrink", ""),
               "gap_before": s.get("gap_before", ""), "gap_after": s.get("gap_after", ""),
               "wall_seconds": round(r["wall_seconds"], 3), "error": error_text(r)}
        for name, value in s.get("params", {}).items():
            row[f"{s['effect']}.{name}"] = value
        rows.append(row)
    return rows


def parameter_values(results):
    """{'effect.parameter': [values]} over the logs whose verdict is that effect."""
    values = {}
    for r in results:
        s = r.get("summary", {})
        for name, value in s.get("params", {}).items():
            values.setdefault(f"{s['effect']}.{name}", []).append(value)
    return values


def plot_parameters(out, values):
    """One histogram per fitted parameter of the verdicts, OUT/plots/<effect>.<parameter>.png
    (matplotlib, Agg: no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    os.makedirs(os.path.join(out, "plots"), exist_ok=True)
    files = []
    for label, xs in sorted(values.items()):
        fig, ax = plt.subplots(figsize=(5, 3.2))
        ax.hist(xs, bins=max(5, min(30, len(xs) // 3)), color="#4878a8", edgecolor="white")
        ax.plot(xs, np.zeros(len(xs)), "|", color="black", markersize=12)  # each log, under the bars
        ax.set_xlabel(label)
        ax.set_ylabel("logs")
        ax.set_title(f"{label}: {len(xs)} log{'s' if len(xs) > 1 else ''}, median {np.median(xs):.4g}")
        fig.tight_layout()
        filename = os.path.join("plots", re.sub(r"[^\w.-]+", "_", label) + ".png")
        fig.savefig(os.path.join(out, filename), dpi=110)
        plt.close(fig)
        files.append(filename)
    return files


def markdown_counts(results):
    ok = [r for r in results if r["status"] == "ok"]
    effects = {}
    for r in ok:
        effects[r["summary"]["effect"]] = effects.get(r["summary"]["effect"], 0) + 1
    lines = ["## Verdicts", "", "| effect | logs |", "|---|---|"]
    lines += [f"| {effect} | {n} |" for effect, n in sorted(effects.items(), key=lambda kv: (-kv[1], kv[0]))]
    return lines


def markdown_unexplained(results):
    unexplained = [r for r in results if r["status"] == "ok" and r["summary"]["effect"] == "unexplained"]
    lines = [f"## Unexplained ({len(unexplained)})", ""]
    lines += [f"- `{r['inputs']['log']}` (where: {r['summary']['where']}): {r['summary']['reason']}"
              for r in unexplained] or ["None."]
    return lines


def markdown_failed(results):
    bad = [r for r in results if r["status"] != "ok"]
    lines = [f"## Failed ({len(bad)})", ""]
    for r in bad:
        lines += [f"- `{r['inputs']['log']}`: {r['error_kind']}", "", "  ```",
                  *["  " + line for line in r["error"].splitlines()], "  ```"]
    return lines + ([] if bad else ["None."])


def markdown_every_log(results):
    lines = ["## Every log", "", "| log | status | effect | confidence | parameters | shrink | where | wall s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in sorted(results, key=lambda r: r["inputs"]["log"]):
        s = r.get("summary", {})
        params = ", ".join(f"{k} = {v:.4g}" for k, v in s.get("params", {}).items())
        lines.append(f"| `{r['inputs']['log']}` | {r['status']} | {s.get('effect', '')} | "
                     f"{fmt(s.get('confidence'))} | {params} | {fmt(s.get('shrink'))} | {s.get('where', '')} | "
                     f"{r['wall_seconds']:.1f} |")
    return lines


def fleet_markdown(results, plots, command, ran, skipped):
    ok = sum(1 for r in results if r["status"] == "ok")
    lines = ["# Fleet gap report", "", f"`{command}`", "",
             f"{len(results)} logs: {ok} diagnosed, {len(results) - ok} failed.",
             f"{ran} diagnosed by this run, {skipped} by earlier runs (resumed).", ""]
    lines += markdown_counts(results) + [""]
    lines += ["## Fitted parameters", ""] + ([f"![{p}]({p})" for p in plots] or ["No verdict fitted a parameter."])
    lines += [""] + markdown_unexplained(results) + [""] + markdown_failed(results) + [""]
    lines += markdown_every_log(results)
    return "\n".join(lines) + "\n"


def fmt(value):
    return f"{value:.3f}" if isinstance(value, (int, float)) else ""


def write_fleet_report(out, results, command, ran, skipped):
    rows = gap_rows(results)
    base = ["task_id", "log", "scenario", "status", "exit_code", "effect", "form", "confidence", "where",
            "shrink", "how_far_shrink", "gap_before", "gap_after", "wall_seconds", "error"]
    params = sorted({k for row in rows for k in row if k not in base})
    write_text_atomic(os.path.join(out, "fleet.csv"), csv_text(base + params, rows))
    plots = plot_parameters(out, parameter_values(results))
    write_text_atomic(os.path.join(out, "fleet.md"), fleet_markdown(results, plots, command, ran, skipped))
