"""Frames in any order: ``python -m bench --only unordered`` (or ``python -m bench.unordered``).

Each scene is reconstructed twice: as simulated (A the same end in every frame) and with a
random 40 % of its frames (never frame 0) relabelled -- A and B, tangent_A and tangent_B
swapped, the polyline reversed -- and the document flagged ``"ends_identified": false``
(``curverecon.robust.labels``).  The relabelled run names A and B as frame 0 does, so both are
scored against the same truth.

- points and tangents: 20 frames, 1 px on every point, 1 degree on every tangent (the headline
  cell); success as in the headline and accuracy tables: worst angle error of alpha, beta, phi
  below ``bench.common.SUCCESS_DEG`` (5 degrees).  Keys ``ordered_success_rate``,
  ``unordered_success_rate``, and ``unordered_success_rate_up_to_warned_naming`` (also counted:
  an answer right with alpha and beta exchanged that warned that frame 0 fits both labellings,
  so that the data cannot say which end frame 0 calls A), and
  ``unordered_success_rate_up_to_naming`` (right up to the naming, warned or not: the oracle
  with frame 0's labelling given; the oracle with every frame's labelling given is the
  consistent run itself); the CPU time of the relabelled runs over the consistent ones,
  ``unordered_time_ratio_20_frames`` (``time.process_time``, summed over the scenes);
- curves: 16 frames, 0.5 px on every point of the polylines (0.5 degrees on the tangents);
  the curve error as ``bench.curve_end_to_end`` measures it (symmetric mean distance between
  the recovered and the true 3-D curve over the true curve's length, best over the mirror
  image), within 1 % counted.  Keys ``ordered_curve_within_1pct_rate``,
  ``unordered_curve_within_1pct_rate``, the median errors and the time ratio at 16 frames.

Scenes come from spawn keys (``GROUP``, kind, scene index) of the bench's seed, on ``WORKERS``
processes.  ``python -m bench.unordered [--seed N] [--scenes K] [--curve-scenes K] [--quick]``
prints the keys as JSON without touching the report.
"""

from __future__ import annotations

import json
import os
import sys
import time

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import warnings  # noqa: E402
from dataclasses import replace  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

from bench.common import (  # noqa: E402
    SUCCESS_DEG,
    Task,
    chunks,
    run_tasks,
    shape_errors,
    true_poses,
    worst_angle_deg,
)
from bench.config import Config  # noqa: E402
from bench.curve_end_to_end import curve_error  # noqa: E402
from curverecon.errors import CurveReconError  # noqa: E402
from curverecon.pipeline import reconstruct  # noqa: E402
from curverecon.robust.labels import exchange  # noqa: E402
from curverecon.simulate import make_scene  # noqa: E402

GROUP = 20
"""spawn_key prefix of this section's scenes (``bench.common.GROUPS`` uses 2-7)."""
SHARE = 0.4
"""Share of the frames relabelled."""
SCENES = 60
"""Point-and-tangent scenes (about 1.2 s a scene for both runs, one core)."""
CURVE_SCENES = 24
"""Curve scenes (about 4 s a scene for both runs, one core)."""
WORKERS = 2
CHUNK = 4


def _scene_rng(seed: int, kind: int, index: int) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(GROUP, kind, index)))


def _relabel(obs, rng: np.random.Generator):  # type: ignore[no-untyped-def]
    """``obs`` with ``SHARE`` of its frames (never frame 0) relabelled, flagged as such."""
    n = obs.n_frames
    mask = np.zeros(n, bool)
    mask[1 + rng.choice(n - 1, int(round(SHARE * n)), replace=False)] = True
    return replace(exchange(obs, mask), ends_identified=False), mask


def _timed(obs):  # type: ignore[no-untyped-def]
    start = time.process_time()
    try:
        rec = reconstruct(obs)
    except (CurveReconError, ArithmeticError, ValueError, np.linalg.LinAlgError):
        rec = None
    return rec, time.process_time() - start


def point_scenes(seed: int, scenes: range) -> list[dict]:
    """Per scene: the worst angle error (degrees) of both runs, their CPU times, and how many
    frames the relabelled run labelled differently from the truth."""
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    out = []
    for i in scenes:
        rng = _scene_rng(seed, 0, i)
        sc = make_scene(rng, 20, 1.0, 1.0, chord=(100.0, 300.0))
        unordered, mask = _relabel(sc.observations, rng)
        truth, _ = true_poses(sc)
        rec = {"index": i}
        for name, obs in (("ordered", sc.observations), ("unordered", unordered)):
            r, seconds = _timed(obs)
            rec[f"{name}_worst_deg"] = (
                np.inf if r is None else worst_angle_deg(shape_errors(r.shape, truth))
            )
            rec[f"{name}_seconds"] = seconds
            if name == "unordered" and r is not None:
                rec["labels_wrong"] = int(np.sum(r.ends_exchanged != mask))
                swapped = worst_angle_deg(shape_errors(r.shape, truth[[0, 2, 1, 3]]))
                warned = any("frame 0 fits both labellings" in w for w in r.warnings)
                rec["unordered_naming_deg"] = min(rec["unordered_worst_deg"], swapped)
                rec["frame0_undecided"] = warned
        out.append(rec)
    return out


def curve_scenes(seed: int, scenes: range) -> list[dict]:
    """Per scene: the relative curve error of both runs and their CPU times."""
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    out = []
    for i in scenes:
        rng = _scene_rng(seed, 1, i)
        sc = make_scene(rng, 16, 0.5, 0.5, with_curve=True)
        unordered, mask = _relabel(sc.observations, rng)
        rec = {"index": i}
        for name, obs in (("ordered", sc.observations), ("unordered", unordered)):
            r, seconds = _timed(obs)
            ok = r is not None and r.curve3d is not None
            rec[f"{name}_curve_error"] = curve_error(r.curve3d, sc.curve_3d) if ok else np.inf
            rec[f"{name}_seconds"] = seconds
            if name == "unordered" and r is not None:
                rec["labels_wrong"] = int(np.sum(r.ends_exchanged != mask))
        out.append(rec)
    return out


def summarise(points: list[dict], curves: list[dict]) -> dict[str, Any]:
    """The section's keys from the per-scene records."""
    out: dict[str, Any] = {}
    for name in ("ordered", "unordered"):
        worst = np.array([r[f"{name}_worst_deg"] for r in points])
        err = np.array([r[f"{name}_curve_error"] for r in curves])
        out[f"{name}_success_rate"] = round(float(np.mean(worst < SUCCESS_DEG)), 3)
        out[f"{name}_curve_within_1pct_rate"] = round(float(np.mean(err < 0.01)), 3)
        out[f"{name}_curve_error_median_pct"] = round(100 * float(np.median(err)), 3)
    # the answer warned that frame 0 fits both labellings, and it is right up to the naming
    # of A and B (alpha and beta exchanged): what the data determine
    naming = [
        r["unordered_worst_deg"] < SUCCESS_DEG
        or (r.get("frame0_undecided", False) and r["unordered_naming_deg"] < SUCCESS_DEG)
        for r in points
    ]
    out["unordered_success_rate_up_to_warned_naming"] = round(float(np.mean(naming)), 3)
    # frame 0's labelling given (which physical end frame 0 calls A): the label search's cost
    # does not depend on the naming, so this oracle is the answer right up to the naming
    named = [r.get("unordered_naming_deg", np.inf) < SUCCESS_DEG for r in points]
    out["unordered_success_rate_up_to_naming"] = round(float(np.mean(named)), 3)
    out["unordered_frame0_undecided_scenes"] = [
        r["index"] for r in points if r.get("frame0_undecided", False)
    ]
    for key, records in (("20_frames", points), ("curves_16_frames", curves)):
        ordered = sum(r["ordered_seconds"] for r in records)
        unordered = sum(r["unordered_seconds"] for r in records)
        out[f"unordered_time_ratio_{key}"] = round(unordered / max(ordered, 1e-9), 2)
    out["unordered_scenes"] = len(points)
    out["unordered_curve_scenes"] = len(curves)
    out["unordered_failed_scenes"] = [
        r["index"] for r in points if not r["unordered_worst_deg"] < SUCCESS_DEG
    ]
    out["unordered_curve_missed_scenes"] = [
        r["index"] for r in curves if not r["unordered_curve_error"] < 0.01
    ]
    out["unordered_frames_labelled_wrong"] = int(sum(r.get("labels_wrong", 0) for r in points))
    out["unordered_curve_frames_labelled_wrong"] = int(
        sum(r.get("labels_wrong", 0) for r in curves)
    )
    return out


def run(
    quick: bool = False,
    seed: int | None = None,
    scenes: int | None = None,
    curve_scenes_count: int | None = None,
    workers: int = WORKERS,
) -> dict:
    """The section's report keys (``--only unordered``)."""
    seed = Config().seed if seed is None else seed
    n = (4 if quick else SCENES) if scenes is None else scenes
    m = (2 if quick else CURVE_SCENES) if curve_scenes_count is None else curve_scenes_count
    tasks = [Task(point_scenes, (seed, r), len(r), "points") for r in chunks(n, CHUNK)]
    tasks += [Task(curve_scenes, (seed, r), len(r), "curves") for r in chunks(m, CHUNK)]
    results = run_tasks(tasks, workers, "unordered scenes", progress=False)
    out = summarise(results.get("points", []), results.get("curves", []))
    out["unordered_seed"] = seed
    return out


if __name__ == "__main__":
    args = sys.argv[1:]

    def _arg(name: str) -> int | None:
        return int(args[args.index(name) + 1]) if name in args else None

    t0 = time.time()
    w = _arg("--workers") or WORKERS
    result = run("--quick" in args, _arg("--seed"), _arg("--scenes"), _arg("--curve-scenes"), w)
    result["unordered_section_seconds"] = round(time.time() - t0, 1)
    print(json.dumps(result, indent=1))
