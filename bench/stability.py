"""Numerical stability: log10 relative error on noise-free scenes at (near-)minimal frame counts.

Default pipeline (``reconstruct``, no truth) at 4, 5, 6 frames; the linearisation alone at its
minimal frame counts (38, 39, 40) as an extra.  Error of a scene: the largest of |dc| / c and the
angle errors in radians (both normalised).  A scene fails when that is above 1e-6.  With 4 frames
a noise-free scene has several exact solutions; "truth listed" counts scenes whose answer or one
of the listed alternatives is within 1e-6.
"""

from __future__ import annotations

import math
import time
import warnings
from typing import Any

import numpy as np

from bench.common import log10_relative, make, shape_errors, true_poses
from curverecon.errors import CurveReconError
from curverecon.pipeline import reconstruct


def run_scenes(
    seed: int, n_frames: int, indices: range, chord: tuple[float, float], deadline: float = math.inf
) -> list[dict[str, Any]]:
    """Default pipeline on noise-free scenes (a pool task).

    Scenes are skipped once the wall clock (``time.time()``) is past ``deadline``.
    """
    out = []
    for i in indices:
        if time.time() > deadline:
            break
        scene = make(seed, "stability", (n_frames, i), n_frames, chord=chord)
        shape, _ = true_poses(scene)
        rec: dict[str, Any] = {"index": i, "n_frames": n_frames}
        t0 = time.perf_counter()
        try:
            r = reconstruct(scene.observations)
            rec["log10_error"] = log10_relative(shape_errors(r.shape, shape))
            alts = [log10_relative(shape_errors(a.shape, shape)) for a in r.alternatives]
            rec["log10_error_listed"] = min([rec["log10_error"], *alts])
            rec["n_alternatives"] = len(r.alternatives)
        except (CurveReconError, ValueError, np.linalg.LinAlgError) as exc:
            rec["log10_error"] = math.inf
            rec["log10_error_listed"] = math.inf
            rec["exception"] = str(exc)[:200]
        rec["seconds"] = time.perf_counter() - t0
        out.append(rec)
    return out


def run_linear_scenes(
    seed: int, n_frames: int, indices: range, chord: tuple[float, float], deadline: float = math.inf
) -> list[dict[str, Any]]:
    """The linearisation alone on noise-free scenes (a pool task).

    Scenes are skipped once the wall clock (``time.time()``) is past ``deadline``.
    """
    from curverecon.solvers.linear import solve_linear

    out = []
    for i in indices:
        if time.time() > deadline:
            break
        scene = make(seed, "stability_linear", (n_frames, i), n_frames, chord=chord)
        shape, _ = true_poses(scene)
        rec: dict[str, Any] = {"index": i, "n_frames": n_frames}
        t0 = time.perf_counter()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                lin = solve_linear(scene.observations)
            rec["log10_error"] = log10_relative(shape_errors(lin.shape, shape))
        except (CurveReconError, ValueError, np.linalg.LinAlgError) as exc:
            rec["log10_error"] = math.inf
            rec["exception"] = str(exc)[:200]
        rec["log10_error_listed"] = rec["log10_error"]
        rec["seconds"] = time.perf_counter() - t0
        out.append(rec)
    return out


def failure_rate_listed_at_four(records: list[dict[str, Any]], threshold: float) -> float | None:
    """Failure rate where a four-frame scene fails only when the truth is not listed.

    Four noise-free frames have several exact solutions (the minimal problem), which the
    pipeline returns as ``alternatives``; from five frames on the answer must be the truth.
    """
    if not records:
        return None
    lt = math.log10(threshold)
    fail = [
        (r["log10_error_listed"] if r["n_frames"] == 4 else r["log10_error"]) > lt for r in records
    ]
    return float(np.mean(fail))


def summarise_records(records: list[dict[str, Any]], threshold: float) -> dict[str, Any]:
    """Failure rate (error above ``threshold``), quantiles, and the 1e-9 rate."""
    n = len(records)
    if not n:
        return {"n": 0}
    e = np.array([r["log10_error"] for r in records], float)
    listed = np.array([r["log10_error_listed"] for r in records], float)
    lt = math.log10(threshold)
    finite = e[np.isfinite(e)]
    return {
        "n": n,
        "failure_rate": float(np.mean(e > lt)),
        "failure_rate_truth_not_listed": float(np.mean(listed > lt)),
        "rate_below_1e-9": float(np.mean(e <= -9.0)),
        "n_exceptions": int(sum("exception" in r for r in records)),
        "median_log10": float(np.median(finite)) if finite.size else None,
        "p99_log10": float(np.quantile(e, 0.99)) if np.isfinite(e).all() else None,
        "seconds_mean": float(np.mean([r["seconds"] for r in records])),
    }
