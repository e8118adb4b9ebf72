"""The command line: lk_fleet's arguments, the checks shared by both commands, the gap and sweep commands
(tasks, run, report, summary line) and main, which maps a bad argument to exit status 2 and Ctrl-C to 130.

Depends on messages, tool, gap, sweep, fleet_report, sweep_report and runner; only __main__ depends on it."""
import argparse
import os
import re
import shlex
import sys

from .fleet_report import write_fleet_report
from .gap import gap_specs, gap_task
from .messages import UsageError, status
from .runner import execute
from .sweep import SWEEP_METRICS, check_sweep_arguments, sweep_specs, sweep_task
from .sweep_report import write_sweep_report
from .tool import check_config, find_tool

# The repository holds scripts/lk_fleet/cli.py; its build tree holds the tools.
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_LK_BIN = os.path.join(REPO, "build", "ws", "devel", "lib", "lane_keeping")
# The first line of the package's docstring, shown by --help.
DESCRIPTION = "lk_fleet: run lane_keeping's command-line tools over many inputs on Dask."


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def build_parser():
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--config", required=True, help="the nominal (gap) or base (sweep) configuration YAML")
    common.add_argument("--out", required=True, help="output directory (results/, reports, plots)")
    common.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786; "
                                            "default: an embedded LocalCluster")
    common.add_argument("--workers", type=positive_int, default=os.cpu_count() or 1,
                        help="LocalCluster worker processes (default: the CPU count)")
    common.add_argument("--lk-bin", default=os.environ.get("LK_BIN_DIR", DEFAULT_LK_BIN),
                        help="directory of the lane_keeping tools (default: $LK_BIN_DIR or the build tree)")
    common.add_argument("--retries", type=int, default=2,
                        help="reruns of a task whose worker or tool died (default 2)")
    common.add_argument("--task-timeout", type=float, default=None, help="seconds before a task is failed")
    common.add_argument("--retry-failed", action="store_true",
                        help="run again the tasks whose tool failed before (a fixed log, a fixed tool)")
    common.add_argument("--progress-interval", type=float, default=5.0,
                        help="seconds between progress lines when stdout is not a terminal")
    common.add_argument("--connect-timeout", type=float, default=10.0,
                        help="seconds to wait for the --scheduler (default 10)")
    parser = argparse.ArgumentParser(prog="lk_fleet", description=DESCRIPTION)
    commands = parser.add_subparsers(dest="command", required=True)
    gap = commands.add_parser("gap", parents=[common], help="lk_gap on every log, and a fleet report")
    gap.add_argument("--logs", action="append", required=True,
                     help="glob of logs (.csv, .bag; '**' recurses); repeatable")
    gap.add_argument("--scenarios", help="YAML map: log glob or name -> scenario file")
    gap.add_argument("--extra-args", "--lk-gap-args", dest="extra_args", default="",
                     help="more lk_gap arguments, e.g. '--effects a,b --noise-reference-draws 19'")
    gap.add_argument("--per-log-plots", action="store_true", help="let lk_gap draw each log's plots")
    sweep = commands.add_parser("sweep", parents=[common], help="lk_simulate over a grid or Monte-Carlo draws")
    sweep.add_argument("--grid", action="append", default=[],
                       help="key=start:stop:step or key=v1,v2,...; key a+b sets both keys")
    sweep.add_argument("--monte-carlo", type=int, metavar="N", help="draws per grid point")
    sweep.add_argument("--vary", action="append", default=[], help="key=normal(mu,sigma) or key=uniform(a,b)")
    sweep.add_argument("--seed", type=int, default=0, help="seed of the Monte-Carlo draws")
    sweep.add_argument("--set", action="append", default=[], help="fixed override key=value, e.g. "
                                                                  "simulation.duration=5")
    sweep.add_argument("--metric", default="late_rms_e_y", choices=SWEEP_METRICS,
                       help="the plotted figure (default: RMS lateral error over the last quarter of the run)")
    sweep.add_argument("--keep-logs", action="store_true", help="keep each point's CSV under OUT/runs/")
    return parser


def check_common(args):
    if not os.path.isfile(args.config):
        raise UsageError("--config", f"'{args.config}' is not a file")
    if args.scheduler and not re.match(r"^(tcp|tls|inproc|ucx)://[^/]+$|^[\w.-]+:\d+$", args.scheduler):
        raise UsageError("--scheduler", f"'{args.scheduler}' is not an address like tcp://host:port")
    if args.retries < 0:
        raise UsageError("--retries", "must not be negative")
    args.out = os.path.abspath(args.out)
    os.makedirs(os.path.join(args.out, "results"), exist_ok=True)


def command_gap(args):
    lk_gap = find_tool(args.lk_bin, "lk_gap")
    specs = gap_specs(args, lk_gap)
    if os.access(os.path.join(args.lk_bin, "lk_simulate"), os.X_OK):
        check_config(find_tool(args.lk_bin, "lk_simulate"), args.config, [], "--config")
    results, skipped, ran = execute(args, gap_task, specs)
    write_fleet_report(args.out, results, " ".join(shlex.quote(a) for a in sys.argv), ran, skipped)
    return summary_line("gap", results, os.path.join(args.out, "fleet.md"))


def command_sweep(args):
    lk_simulate = find_tool(args.lk_bin, "lk_simulate")
    specs, axes, laws = sweep_specs(args, lk_simulate)
    check_sweep_arguments(lk_simulate, args, specs)
    results, _, _ = execute(args, sweep_task, specs)
    write_sweep_report(args.out, results, axes, laws, args.metric)
    return summary_line("sweep", results, os.path.join(args.out, "sweep.csv"))


def summary_line(command, results, report):
    failed = sum(1 for r in results if r["status"] == "failed")
    lost = sum(1 for r in results if r["status"] == "error")
    status(f"{command}: {len(results) - failed - lost} ok, {failed} failed, {lost} lost; report: {report}")
    return 1 if lost else 0


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        check_common(args)
        return command_gap(args) if args.command == "gap" else command_sweep(args)
    except UsageError as exc:
        parser.error(f"{args.command}: {exc}")  # prints usage and exits 2
    except KeyboardInterrupt:
        status("interrupted: the results written so far are kept; the same command resumes")
        return 130
