"""The Dask side of a run: the client (an embedded LocalCluster or a running scheduler, --scheduler), the
shipping of the task functions to the workers, and the count of our tasks the workers hold (for the progress).

Depends on messages."""
import logging
import sys

from .messages import UsageError


def ship_by_value(fn):
    """Send the task function `fn` to the workers by value, with the package's functions it calls, not by
    module path: a dask-worker started elsewhere (its own working directory, no PYTHONPATH, another
    machine) cannot import lk_fleet, and so needs only Python, Dask and the tools, as when the tasks were
    defined in the script's __main__ (which cloudpickle always ships by value). cloudpickle pickles the code
    of a registered module by value (of a registered package, of every module in it); distributed hands a
    function to cloudpickle only when the function's own module is registered: hence both."""
    import cloudpickle
    for name in (__package__, fn.__module__):
        cloudpickle.register_pickle_by_value(sys.modules[name])


def open_client(args):
    """An embedded LocalCluster (processes, one thread each: the tools are single-threaded and CPU
    bound), or the scheduler given by --scheduler."""
    from distributed import Client, LocalCluster
    if args.scheduler:
        try:
            return Client(args.scheduler, timeout=args.connect_timeout), None
        except (OSError, TimeoutError, ValueError) as exc:
            raise UsageError("--scheduler", f"cannot connect to '{args.scheduler}': {exc}")
    # A random dashboard port: the default 8787 may be taken by another cluster on the machine.
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.ERROR)
    return Client(cluster), cluster


def running_count(client, keys):
    """Tasks of ours the scheduler has placed on workers, capped by the threads: a worker may hold one
    queued task beside the one it runs."""
    def count():
        try:
            processing = client.processing()
            threads = sum(client.nthreads().values())
        except Exception:  # progress is best effort; a slow scheduler must not stop the run
            return 0
        return min(threads, sum(1 for tasks in processing.values() for k in tasks if k in keys))
    return count
