"""Running a command's tasks on Dask, resumably: skip the tasks with a stored result, submit the others
(largest first), gather their results as they finish with progress on stderr, record the tasks Dask gave up
on, and clear the attempt folders of dead workers.

Depends on messages, results, cluster and progress; it knows nothing of what a task runs."""
import glob
import os
import shutil
import time

from .cluster import open_client, running_count, ship_by_value
from .messages import status
from .progress import Progress
from .results import error_result, error_text, format_value, load_result, result_path, store_result


def collect(future, spec):
    """The result of a finished future; stored here too in case the worker could not write it (an --out
    directory the worker does not share)."""
    if future.status == "finished":
        result = future.result()
    else:
        exc = future.exception() if future.status == "error" else RuntimeError(f"task {future.status}")
        result = error_result(spec, exc)
    if result["status"] == "error" or not os.path.exists(result_path(spec["out"], spec["task_id"])):
        result = store_result(spec["out"], result)
    return result


def remove_stale_attempts(out, tids):
    """Report folders of attempts whose worker died mid-task (.<task-id>.<random>). Removed by the client
    once every task has finished, when no attempt of these tasks can still be writing."""
    for tid in tids:
        for folder in glob.glob(os.path.join(out, "reports", f".{tid}.*")):
            shutil.rmtree(folder, ignore_errors=True)


def run_tasks(args, fn, specs, skipped, total):
    """Submit the tasks not done yet and gather their results as they finish, keyed by task id."""
    from distributed import as_completed
    results = {}
    failed = sum(1 for r in skipped.values() if r["status"] != "ok")
    progress = Progress(total, len(skipped), interval=args.progress_interval)
    ship_by_value(fn)
    client, cluster = open_client(args)
    futures = {}
    try:
        for spec in specs:
            key = f"lk_fleet-{spec['kind']}-{spec['task_id']}"
            futures[client.submit(fn, spec, key=key, retries=args.retries, pure=False)] = spec
        running = running_count(client, {f.key for f in futures})
        pending = as_completed(futures)
        while not pending.is_empty():
            batch = pending.next_batch(block=False)
            for future in batch:
                spec = futures[future]
                result = collect(future, spec)
                results[spec["task_id"]] = result
                if result["status"] != "ok":
                    failed += 1
                    progress.note(f"[lk_fleet] {result['status']}: {describe(spec)}: {error_text(result)}")
                future.release()
            progress.update(len(skipped) + len(results), failed, running)
            if not batch:
                time.sleep(0.1)
        progress.finish(len(skipped) + len(results), failed)
    except KeyboardInterrupt:
        # Ctrl-C: cancel what has not finished, so that no queued task starts while the cluster shuts
        # down (a worker went on through its queue meanwhile: on a loaded machine an interrupted run had
        # finished every task). What is written stays; the same command resumes.
        try:
            client.cancel([f for f in futures if not f.done()], force=True)
        except Exception:  # best effort: the interrupt must not become another error
            pass
        raise
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return results


def describe(spec):
    inputs = spec["inputs"]
    return inputs.get("log") or " ".join(f"{k}={format_value(v)}" for k, v in inputs["point"].items())


def execute(args, fn, specs):
    """Resume, then run: tasks with a stored result are skipped; the rest run on Dask. Returns every
    task's result in the order of `specs`, each task once."""
    unique = list({spec["task_id"]: spec for spec in specs}.values())
    skipped = {}
    for spec in unique:
        stored = load_result(args.out, spec["task_id"])
        if stored is not None and not (args.retry_failed and stored["status"] == "failed"):
            skipped[spec["task_id"]] = stored
    todo = [spec for spec in unique if spec["task_id"] not in skipped]
    # Longest first: a big log started last would set the run's tail alone.
    todo.sort(key=lambda spec: -spec.get("size", 0))
    where = args.scheduler or f"a LocalCluster of {args.workers} workers"
    verb = "diagnose" if args.command == "gap" else "simulate"
    status(f"{len(unique)} tasks: {len(todo)} to {verb}, {len(skipped)} done before (skipped)"
           + (f"; running on {where}" if todo else ""))
    results = dict(skipped)
    if todo:
        results.update(run_tasks(args, fn, todo, skipped, len(unique)))
        remove_stale_attempts(args.out, [spec["task_id"] for spec in todo])
    return [results[spec["task_id"]] for spec in unique], len(skipped), len(todo)
