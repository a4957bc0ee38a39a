"""``curverecon batch`` on Dask: one task per input, the summary written by the client.

The cluster is a ``dask.distributed.LocalCluster`` of worker processes (one per core, one thread
each, BLAS/OpenMP/numba threads set to 1 in the workers), or the one at ``scheduler``, or the
caller's ``client``.  Each input is one task (:func:`curverecon.batch.task.process`) that
writes its own outputs and returns a small row; a worker that dies takes its task to another
worker (the scheduler's ``allowed-failures``; ``retries`` for an exception that escapes the
task), and a task run again finds what this run already wrote and does not redo it.  The client
collects the rows as they arrive and writes ``summary.csv`` and ``summary.parquet`` (temporary
name, then ``os.replace``) once every input has its row, in the order of the inputs.
"""

from __future__ import annotations

import math
import os
import sys
import time
from collections.abc import Sequence
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from curverecon.batch.inputs import Job, check_out_dir, expand
from curverecon.batch.task import COLUMNS, TEMP_SUFFIX, done_row, error_row, process
from curverecon.errors import CurveReconError

INSTALL_HINT = 'curverecon batch needs Dask, pandas and pyarrow: pip install "curverecon[batch]"'

THREAD_ENV = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
"""Set in every local worker process before it imports NumPy: the cluster already runs one task
per core, more threads per task would only compete for the cores.  numba's threads are set to
one by each task (``numba.set_num_threads``): ``NUMBA_NUM_THREADS`` in the environment of a
Dask worker conflicts with numba's own reading of it when a function compiles."""

RETRIES = 2
"""Dask ``retries`` of a task whose exception escapes it (the task turns bad input into a row,
so this covers the unexpected: a file system hiccup, a lost connection)."""

ALLOWED_FAILURES = 3
"""Workers that may die while running one task before the input is given up as failed (a local
cluster's scheduler; Dask's default).  An input that kills every worker it runs on (out of
memory) then gets an error row instead of stopping the batch."""

STARTED_MARKER = ".batch-started"
"""Touched in the output folder when a ``--force`` run starts: its mtime, on the output's own
file system clock, is the time before which an output is redone."""

SUMMARY = ("summary.csv", "summary.parquet")


def require_extra() -> None:
    """Raise a one-line :class:`CurveReconError` when the ``batch`` extra is not installed
    (looked up, not imported: a batch of one input never imports Dask)."""
    import importlib.util

    for name in ("dask.distributed", "distributed", "pandas", "pyarrow"):
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            raise CurveReconError(INSTALL_HINT)


def run(
    inputs: Sequence[str | os.PathLike[str]],
    out_dir: str | os.PathLike[str],
    client: Any = None,
    workers: int | None = None,
    force: bool = False,
    *,
    scheduler: str | None = None,
    progress: bool | None = None,
    verbose: bool = False,
) -> Any:
    """Trace and reconstruct every input into ``out_dir``; returns the summary (a DataFrame).

    Args:
        inputs: observation files, videos, folders of frames, folders of those
            (:mod:`curverecon.batch.inputs`).
        out_dir: the output folder (created); it must be on a file system the workers share.
        client: a ``dask.distributed.Client`` to run on; None: ``scheduler``'s cluster, or a
            local cluster of ``workers`` processes (default: one per core).
        force: redo every input (otherwise only those whose reconstruction is missing or
            older than the input).
        progress: a progress bar on stderr (default: when stderr is a terminal).
        verbose: print the local cluster's dashboard address on stderr.

    The DataFrame's ``attrs`` hold ``skipped`` (inputs already done) and ``seconds``.
    Raises :class:`CurveReconError` before anything runs for bad arguments (no inputs, one that
    does not exist, two of one name, an output folder that cannot be written, a scheduler that
    cannot be reached, the extra not installed).
    """
    require_extra()
    if workers is not None and workers < 1:
        raise CurveReconError("--workers must be at least 1")
    t0 = time.perf_counter()
    jobs = expand(inputs, out_dir)
    out = check_out_dir(out_dir)
    _remove_stale_temporaries(out)
    not_before = _touch(out / STARTED_MARKER) if force else None
    if progress is None:
        progress = sys.stderr.isatty()
    rows: list[dict[str, Any] | None] = [
        error_row(j, j.problem, 0.0) if j.kind == "empty" else done_row(j, str(out), not_before)
        for j in jobs
    ]
    todo = [i for i, row in enumerate(rows) if row is None]
    skipped = sum(row is not None and row["status"] == "ok" for row in rows)
    if len(todo) == 1 and client is None and scheduler is None:
        rows[todo[0]] = _run_here(jobs[todo[0]], str(out), not_before, progress)
    elif todo:
        with ExitStack() as stack:
            if client is None:  # a local cluster no larger than the work
                n = min(workers or os.cpu_count() or 1, len(todo))
                client = stack.enter_context(_client(scheduler, n, verbose))
            done = _run_jobs(client, [jobs[i] for i in todo], str(out), not_before, progress)
        for i, row in zip(todo, done, strict=True):
            rows[i] = row
    for row in rows:
        row.pop("skipped", None)
    frame = write_summary(out, rows)
    frame.attrs.update(skipped=skipped, seconds=round(time.perf_counter() - t0, 3))
    return frame


def _run_here(job: Job, out: str, not_before: float | None, progress: bool) -> dict[str, Any]:
    """One input left to do and no cluster given: run it in this process.  Starting a local
    cluster (worker processes that import the pipeline) costs seconds and buys nothing for a
    single task; ``bench.batch``'s ``batch_overhead_seconds`` measures the difference."""
    bar = _Progress(1, progress, None)
    row = process(job, out, not_before, limit_threads=False)
    bar.update(row["status"] == "ok")
    bar.close()
    return row


def _touch(path: Path) -> float:
    path.write_text("")
    return path.stat().st_mtime


def _remove_stale_temporaries(out: Path) -> None:
    """Temporary files a killed run left behind (never read: removing them only tidies)."""
    for p in out.glob(f".*{TEMP_SUFFIX}"):
        p.unlink(missing_ok=True)


def _client(scheduler: str | None, workers: int | None, verbose: bool) -> Any:
    """A client of the cluster at ``scheduler``, or of a new local cluster (closed on exit)."""
    from dask.distributed import Client

    if scheduler is not None:
        try:
            return Client(scheduler, timeout="20s")
        except Exception as exc:  # any failure to connect is a bad argument, one line
            raise CurveReconError(
                f"cannot connect to the scheduler at {scheduler}: {_one_line(exc)}"
            ) from None
    n = workers or os.cpu_count() or 1
    cluster = local_cluster(n)
    dashboard = cluster.dashboard_link if _has_bokeh() else None
    if verbose:
        where = dashboard or "none (pip install bokeh to get one)"
        print(
            f"curverecon: batch: local cluster of {n} workers, dashboard: {where}",
            file=sys.stderr,
            flush=True,
        )
    client = Client(cluster)
    return _Closing(client, cluster)


def local_cluster(n: int) -> Any:
    """A ``LocalCluster`` of ``n`` worker processes of one thread each, quiet (the batch's
    errors go into its summary, not into worker logs), the dashboard on a free port when bokeh
    is installed."""
    import logging

    import dask
    from dask.distributed import LocalCluster

    try:
        with dask.config.set({"distributed.scheduler.allowed-failures": ALLOWED_FAILURES}):
            return LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                env=THREAD_ENV,
                dashboard_address=":0" if _has_bokeh() else None,
                silence_logs=logging.CRITICAL,
            )
    except Exception as exc:  # a cluster that cannot start: one line, no traceback
        raise CurveReconError(f"cannot start a local Dask cluster: {_one_line(exc)}") from None


def _has_bokeh() -> bool:
    """Whether the dashboard can be served (Dask's dashboard needs bokeh)."""
    import importlib.util

    return importlib.util.find_spec("bokeh") is not None


class _Closing:
    """Context of a client and its local cluster: both closed on exit."""

    def __init__(self, client: Any, cluster: Any) -> None:
        self.client, self.cluster = client, cluster

    def __enter__(self) -> Any:
        return self.client

    def __exit__(self, *exc: object) -> None:
        self.client.close()
        self.cluster.close()


def _one_line(exc: BaseException) -> str:
    return " ".join(str(exc).split()) or type(exc).__name__


def _failure_message(exc: BaseException | None) -> str:
    from distributed.scheduler import KilledWorker

    if isinstance(exc, KilledWorker):
        return (
            f"the workers running this input died {ALLOWED_FAILURES + 1} times (out of memory, "
            "or a crash): given up"
        )
    if exc is None:
        return "the task was cancelled"
    return f"{type(exc).__name__}: {_one_line(exc)}"


def _run_jobs(
    client: Any, jobs: list[Job], out: str, not_before: float | None, progress: bool
) -> list[dict[str, Any]]:
    """Every job's row, in the jobs' order."""
    from dask.distributed import as_completed

    rows: list[dict[str, Any] | None] = [None] * len(jobs)
    futures = client.map(
        process,
        jobs,
        out_dir=out,
        not_before=not_before,
        retries=RETRIES,
        pure=False,
        key=[f"curverecon-batch-{i}-{j.name}-{time.time_ns()}" for i, j in enumerate(jobs)],
    )
    index = {f.key: i for i, f in enumerate(futures)}
    bar = _Progress(len(jobs), progress, client)
    try:
        for future in as_completed(futures):
            i = index[future.key]
            if future.status == "finished":
                row = future.result()
            else:
                row = error_row(jobs[i], _failure_message(future.exception()))
            rows[i] = row
            future.release()  # its result lives on a worker: one that dies must not redo it
            bar.update(row["status"] == "ok")
    except BaseException:
        client.cancel(futures)
        raise
    finally:
        bar.close()
    return [r for r in rows if r is not None]


class _Progress:
    """tqdm over the inputs (done, failed, running, rate) when enabled, else nothing."""

    def __init__(self, total: int, enabled: bool, client: Any) -> None:
        self.enabled, self.client = enabled, client
        self.failed = 0
        self.last = 0.0
        if enabled:
            from tqdm import tqdm

            self.bar = tqdm(total=total, desc="batch", unit="input", file=sys.stderr)

    def update(self, ok: bool) -> None:
        self.failed += not ok
        if not self.enabled:
            return
        self.bar.update(1)
        now = time.monotonic()
        if now - self.last > 0.5 or self.bar.n == self.bar.total:
            self.last = now
            try:  # tasks a worker holds beyond its threads are queued, not running
                if self.client is None:
                    raise RuntimeError("no cluster")
                threads = self.client.nthreads()
                processing = self.client.processing().items()
                running = sum(min(len(keys), threads.get(w, 1)) for w, keys in processing)
            except Exception:  # a progress figure is not worth a failed batch
                running = math.nan
            self.bar.set_postfix(failed=self.failed, running=running, refresh=False)

    def close(self) -> None:
        if self.enabled:
            self.bar.close()


def write_summary(out: Path, rows: list[dict[str, Any]]) -> Any:
    """``summary.csv`` and ``summary.parquet`` (contract columns, one row per input), each
    written to a temporary name and renamed; returns the DataFrame."""
    import pandas as pd

    frame = pd.DataFrame(rows, columns=list(COLUMNS))
    frame["frames"] = frame["frames"].astype("Int64")
    for column in ("input", "status", "error", "outlier_frames"):
        frame[column] = frame[column].fillna("").astype(str)
    stamp = f"{os.getpid()}.{time.monotonic_ns()}{TEMP_SUFFIX}"
    for name in SUMMARY:
        path = out / name
        tmp = out / f".{name}.{stamp}"
        try:
            if name.endswith(".csv"):
                frame.to_csv(tmp, index=False)
            else:
                frame.to_parquet(tmp, index=False)
            os.replace(tmp, path)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            raise CurveReconError(f"cannot write {path}: {exc.strerror or exc}") from None
    return frame
