"""One input of ``curverecon batch`` on a worker: trace, reconstruct, write, return its row.

The task writes its own outputs (the folder is on a file system every worker and the client
see) and returns a small summary row.  Every file is written to a temporary name in the output
folder and then ``os.replace``d, so a worker killed mid-write leaves a ``.*.tmp`` file that no
run reads, never a half-written output.  An input whose reconstruction is already there and not
older than the input is not redone: its row comes from the file.  Bad input becomes a row with
``status = "error"`` and the one-line message, and so does an unexpected exception (a defect:
"internal error: ..."); nothing leaves :func:`process` but its row, except the death of the
worker itself (which Dask answers by running the task on another worker).
"""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Any

from curverecon.batch.inputs import Job, input_mtime
from curverecon.errors import CurveReconError

RECONSTRUCTION_SUFFIX = ".reconstruction.json"
OBSERVATIONS_SUFFIX = ".observations.json"
TEMP_SUFFIX = ".tmp"
BATCH_KEY = "batch"
"""Key the batch adds to each reconstruction document: ``{"input": ..., "seconds": ...}``
(the contract allows added keys), so that a later run's summary row of a skipped input is the
row of the run that made it."""

SHAPE_KEYS = ("c", "alpha_deg", "beta_deg", "phi_deg")
COLUMNS = (
    "input",
    "status",
    "error",
    *SHAPE_KEYS,
    *(f"{k}_std" for k in SHAPE_KEYS),
    "chi2",
    "frames",
    "outlier_frames",
    "seconds",
)
"""The summary's columns, in the contract's order."""


def output_paths(job: Job, out_dir: str) -> tuple[Path, Path]:
    """Where a job's reconstruction and (traced inputs) observations go."""
    out = Path(out_dir)
    return out / f"{job.name}{RECONSTRUCTION_SUFFIX}", out / f"{job.name}{OBSERVATIONS_SUFFIX}"


def write_atomic(path: Path, doc: dict) -> None:
    """Write ``doc`` as JSON to a temporary file beside ``path``, then rename it over ``path``
    (non-finite numbers as null, as every command writes them)."""
    from curverecon.io import write_json

    tmp = path.with_name(f".{path.name}.{os.getpid()}.{time.monotonic_ns()}{TEMP_SUFFIX}")
    try:
        write_json(tmp, doc)
        os.replace(tmp, path)
    except (OSError, CurveReconError) as exc:
        tmp.unlink(missing_ok=True)
        raise CurveReconError(f"cannot write {path}: {exc}") from None


def error_row(job: Job, message: str, seconds: float = math.nan) -> dict[str, Any]:
    row: dict[str, Any] = dict.fromkeys(COLUMNS, math.nan)
    row.update(input=job.input, status="error", error=" ".join(str(message).split()))
    row.update(frames=None, outlier_frames="", seconds=seconds)
    return row


def row_from_document(job: Job, doc: dict, seconds: float) -> dict[str, Any]:
    """The summary row of a reconstruction document."""
    row: dict[str, Any] = dict.fromkeys(COLUMNS, math.nan)
    row.update(input=job.input, status="ok", error="", seconds=seconds)
    std = doc.get("std") or {}
    for k in SHAPE_KEYS:
        row[k] = _number(doc.get(k))
        row[f"{k}_std"] = _number(std.get(k))
    row["chi2"] = _number(doc.get("chi2"))
    row["frames"] = len(doc.get("frames") or [])
    row["outlier_frames"] = " ".join(str(i) for i in doc.get("outlier_frames") or [])
    return row


def _number(value: Any) -> float:
    if isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    return math.nan


def _existing(path: Path, not_before: float) -> dict | None:
    """The document at ``path`` if it is a reconstruction written at ``not_before`` or later."""
    try:
        if path.stat().st_mtime < not_before:
            return None
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(doc, dict) or doc.get("format") != "curverecon.reconstruction/1":
        return None
    return doc


def _limit_threads() -> None:
    """One thread for numba's parallel loops: the cluster already runs a task per core."""
    try:
        import numba

        numba.set_num_threads(1)
    except (ImportError, ValueError):  # pragma: no cover - numba is a dependency
        pass


def done_row(job: Job, out_dir: str, not_before: float | None = None) -> dict[str, Any] | None:
    """The row of an input whose reconstruction is already there and current (see
    :func:`process`), marked ``"skipped"``; None when the input is to be done."""
    if job.kind == "empty":
        return None
    try:
        threshold = input_mtime(job) if not_before is None else not_before
    except OSError:
        return None
    doc = _existing(output_paths(job, out_dir)[0], threshold)
    if doc is None:
        return None
    seconds = _number((doc.get(BATCH_KEY) or {}).get("seconds"))
    return {**row_from_document(job, doc, seconds), "skipped": True}


def process(
    job: Job, out_dir: str, not_before: float | None = None, limit_threads: bool = True
) -> dict[str, Any]:
    """Trace (images, video) and reconstruct one input; write its outputs; return its row.

    ``limit_threads``: one numba thread (a cluster worker, which shares the cores with the
    others); False where the input runs alone in the calling process.

    ``not_before``: redo the input unless its reconstruction was written at this time or later
    (``--force``: the run's start, so that a task Dask runs again after a worker died does not
    redo what this run wrote); None: unless it is not older than the input.
    """
    t0 = time.perf_counter()

    def elapsed() -> float:
        return round(time.perf_counter() - t0, 3)

    rec_path, obs_path = output_paths(job, out_dir)
    try:  # checked here again: Dask runs a task again when its worker died after it wrote
        if job.kind == "empty":
            raise CurveReconError(job.problem)
        done = done_row(job, out_dir, not_before)
        if done is not None:
            return done
        threshold = input_mtime(job) if not_before is None else not_before
        if limit_threads:
            _limit_threads()
        doc = _reconstruct(job, obs_path, threshold)
        seconds = elapsed()
        doc[BATCH_KEY] = {"input": job.input, "seconds": seconds}
        write_atomic(rec_path, doc)
        return row_from_document(job, doc, seconds)
    except CurveReconError as exc:
        return error_row(job, str(exc), elapsed())
    except MemoryError:
        return error_row(job, "not enough memory for this input", elapsed())
    except OSError as exc:
        return error_row(job, f"cannot read {job.input}: {exc.strerror or exc}", elapsed())
    except Exception as exc:  # a defect, not bad input: recorded, not retried (it would recur)
        return error_row(job, f"internal error: {type(exc).__name__}: {exc}", elapsed())


def _reconstruct(job: Job, obs_path: Path, threshold: float) -> dict:
    """The reconstruction document of a job (tracing it first if it is images or a video)."""
    import numpy as np

    from curverecon.io import load_observations, observations_from_dict
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct

    with np.errstate(all="ignore"):
        if job.traced:
            obs = observations_from_dict(_traced_observations(job, obs_path, threshold))
        else:
            obs = load_observations(job.path)
        rec = reconstruct(obs, options=ReconstructOptions(progress=False))
    return rec.to_json_dict()


def _traced_observations(job: Job, obs_path: Path, threshold: float) -> dict:
    """The observations document of a traced input: the one written before if it is not older
    than ``threshold`` (a run stopped between tracing and reconstruction), otherwise traced now
    (as ``curverecon trace`` does, default options) and written."""
    from curverecon.io import OBSERVATIONS_FORMAT
    from curverecon.trace.options import TraceOptions
    from curverecon.trace.stage import trace_inputs

    try:
        if obs_path.stat().st_mtime >= threshold:
            doc = json.loads(obs_path.read_text(encoding="utf-8"))
            if isinstance(doc, dict) and doc.get("format") == OBSERVATIONS_FORMAT:
                return doc
    except (OSError, ValueError):
        pass
    result = trace_inputs([job.path], TraceOptions())
    doc = dict(result.document)
    if result.warnings:
        doc["trace_warnings"] = list(result.warnings)
    write_atomic(obs_path, doc)
    return doc
