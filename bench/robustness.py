"""Robustness: success rate of the default pipeline without the truth, with outlier frames.

Scenes of the headline cell (1 px, 1 degree, 20 frames) with a fraction of outlier frames (the
simulator's ``outlier_fraction``: gross tangent errors of 15-40 degrees, ``truth.inliers``
False).  Success: worst angle error below 5 degrees.  Flagging: the frames the pipeline left out
(``Reconstruction.inliers`` False) against the true outlier frames.  The 0 % row is the default
pipeline's headline accuracy cell (same scenes as the accuracy table).

What flagging could reach: each frame has six measurements and five pose parameters, so a frame
shows only the part of its error that no pose can absorb.  "Detectable at the true shape" counts
the true outlier frames whose chi2, with the shape held at the truth and the frame's pose at its
best over the branches of (10) (``switch_branches``), is above the pipeline's outlier
threshold (``OutlierOptions.false_alarm``, chi2(1): an oracle that knows the
shape, which the pipeline has to estimate from data the outliers pull.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from bench.common import SUCCESS_DEG, make, shape_errors, true_poses, worst_angle_deg
from curverecon.errors import CurveReconError
from curverecon.options import OutlierOptions
from curverecon.pipeline import reconstruct
from curverecon.refine.ml import standardised_residuals
from curverecon.robust.search import switch_branches


def run_scenes(
    seed: int,
    fraction_id: int,
    fraction: float,
    noise: float,
    n_frames: int,
    indices: range,
    chord: tuple[float, float],
    deadline: float = math.inf,
    outlier_model: str = "gross",
    group: str = "robustness",
) -> list[dict[str, Any]]:
    """Per-scene records: errors, success, flagged and true outlier frames (a pool task).

    Scenes are skipped once the wall clock (``time.time()``) is past ``deadline``.  Scene i
    comes from spawn key (``group``, ``fraction_id``, i) with the simulator's ``outlier_model``
    ("gross", this module's rows; "random", ``bench.outliers``).
    """
    out = []
    for i in indices:
        if time.time() > deadline:
            break
        scene = make(
            seed,
            group,
            (fraction_id, i),
            n_frames,
            point_sigma=noise,
            tangent_sigma_deg=noise,
            chord=chord,
            outlier_fraction=fraction,
            outlier_model=outlier_model,
        )
        shape, poses = true_poses(scene)
        true_out = ~np.asarray(scene.truth.inliers, bool)
        rec: dict[str, Any] = {
            "index": i,
            "fraction": fraction,
            "n_true_outliers": int(true_out.sum()),
            "detectable": _detectable(scene, shape, poses, true_out, noise),
        }
        t0 = time.perf_counter()
        try:
            r = reconstruct(scene.observations, point_sigma=noise, tangent_sigma_deg=noise)
            err = shape_errors(r.shape, shape)
            flagged = ~np.asarray(r.inliers, bool)
            rec["errors"] = [float(v) for v in err]
            rec["worst_deg"] = worst_angle_deg(err)
            rec["true_flagged"] = int(np.sum(flagged & true_out))
            rec["false_flagged"] = int(np.sum(flagged & ~true_out))
        except (CurveReconError, ValueError, np.linalg.LinAlgError) as exc:
            rec["errors"] = None
            rec["worst_deg"] = math.inf
            rec["exception"] = str(exc)[:200]
        rec["seconds"] = time.perf_counter() - t0
        out.append(rec)
    return out


def _detectable(
    scene: Any, shape: np.ndarray, poses: np.ndarray, true_out: np.ndarray, noise: float
) -> int:
    """True outlier frames whose chi2 at the true shape (best pose over the branches of (10))
    is above the pipeline's outlier threshold (module docstring)."""
    obs = scene.observations
    w8 = np.array([1.0 / noise] * 4 + [1.0 / math.radians(noise)] * 2)
    best = switch_branches(obs, shape, poses, w8)
    r = standardised_residuals(shape, best, obs.measurements(), w8)
    frame_chi2 = np.sum(r * r, axis=1)
    return int(np.sum(true_out & (frame_chi2 > chi2_dist.isf(OutlierOptions().false_alarm, 1))))


def summarise_records(records: list[dict[str, Any]], fraction: float) -> dict[str, Any]:
    """Success rate, flagging rates and timing of one outlier fraction."""
    n = len(records)
    worst = np.array([r["worst_deg"] for r in records], float)
    out: dict[str, Any] = {
        "fraction": fraction,
        "n": n,
        "success_rate": float(np.mean(worst < SUCCESS_DEG)) if n else None,
        "n_exceptions": int(sum(r.get("errors") is None for r in records)),
        "median_worst_deg": float(np.median(worst)) if n else None,
        "seconds_mean": float(np.mean([r["seconds"] for r in records])) if n else None,
    }
    n_true = sum(r["n_true_outliers"] for r in records)
    answered = [r for r in records if r.get("errors") is not None]
    hit = sum(r["true_flagged"] for r in answered)
    out["true_outlier_frames"] = n_true
    out["outliers_flagged_rate"] = hit / n_true if n_true else None
    out["outliers_detectable_rate"] = (
        sum(r.get("detectable", 0) for r in records) / n_true if n_true else None
    )
    out["scenes_all_outliers_flagged"] = (
        float(np.mean([r["true_flagged"] == r["n_true_outliers"] for r in answered]))
        if answered
        else None
    )
    out["false_flags_per_scene"] = (
        float(np.mean([r["false_flagged"] for r in answered])) if answered else None
    )
    return out


def summarise_baseline(accuracy_records: list[dict[str, Any]]) -> dict[str, Any]:
    """The 0 % row from the headline accuracy cell's default-pipeline records."""
    ran = [r for r in accuracy_records if "default_s" in r]
    worst = np.array(
        [math.inf if r["default"] is None else worst_angle_deg(np.array(r["default"])) for r in ran]
    )
    n = len(ran)
    return {
        "fraction": 0.0,
        "n": n,
        "success_rate": float(np.mean(worst < SUCCESS_DEG)) if n else None,
        "n_exceptions": int(sum(r["default"] is None for r in ran)),
        "median_worst_deg": float(np.median(worst)) if n else None,
        "seconds_mean": float(np.mean([r["default_s"] for r in ran])) if n else None,
        "true_outlier_frames": 0,
        "outliers_flagged_rate": None,
        "outliers_detectable_rate": None,
        "scenes_all_outliers_flagged": None,
        "false_flags_per_scene": (
            float(np.mean([r.get("default_outliers", 0) for r in ran if r["default"] is not None]))
            if n
            else None
        ),
    }
