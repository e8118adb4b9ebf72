"""lk_fleet: run lane_keeping's command-line tools over many inputs on Dask.

  lk_fleet gap   --config nominal.yaml --logs 'DIR/**/*.csv' --out DIR [--scenarios MAP.yaml] ...
  lk_fleet sweep --config base.yaml --grid key=start:stop:step [--grid ...]
                 [--monte-carlo N --vary 'key=normal(mu,sigma)' ...] --out DIR ...

Run as `/usr/bin/python3 scripts/lk_fleet.py gap|sweep ...`, or `/usr/bin/python3 -m lk_fleet gap|sweep ...`
from scripts/. Thin by design: each task launches one C++ tool (lk_gap per log) with subprocess, or runs one
sweep point in the worker's process through the Python module lane_keeping; Dask only places the tasks. Every
task's result is written atomically to OUT/results/<task-id>.json, the task id being a hash of the task's
inputs, so a rerun of the same command skips what is done and the reports count each task once. Design and
measured figures: docs/fleet.md. Exit status: 0 every task has a result (a log the tool refused is a result:
the report lists it as failed), 1 a task Dask gave up on (its workers kept dying), 2 bad arguments, 130
interrupted (the results written so far are kept; a rerun resumes).

The modules, each depending only on those above it:

  messages      status lines on stderr; UsageError (a bad argument, exit 2)
  storage       atomic files: write, CSV text, publish an attempt's folder
  progress      the progress bar or lines on stderr
  tool          launching lk_gap / lk_simulate (on a worker, and the client's checks); their exit codes
  results       task ids; the result record of a task, stored and loaded (resume)
  gap           gap: the logs, their scenarios, one lk_gap task per log (gap_task runs on the workers)
  sweep         sweep: grid and Monte-Carlo points, one task per point run in-process (sweep_task, on the workers)
  fleet_report  gap's report: fleet.csv, fleet.md, plots/
  sweep_report  sweep's report: sweep.csv, sweep.png
  cluster       the Dask client (LocalCluster or --scheduler); the task functions shipped by value
  runner        resume, submit, gather: a command's tasks on Dask, whatever they run
  cli           the arguments, the gap and sweep commands, main

Importing the package imports none of them, nor Dask: the modules import Dask, numpy and matplotlib only in
the functions that need them, so that the argument checks answer at once.
"""
