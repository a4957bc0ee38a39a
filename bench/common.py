"""Shared pieces of the benchmark: seeding, true poses, error metrics, the worker pool.

Seeding: every scene gets its own generator ``numpy.random.default_rng(SeedSequence(seed,
spawn_key=(group, index)))``, so a scene's data never depend on which worker ran it or in what
order.  ``group`` is a small integer naming the experiment (see ``GROUPS``).

Errors of a shape estimate against the truth (both normalised: alpha, beta in [0, pi/2], phi in
[0, pi], the pipeline's conventions): c relative (``(c_est - c) / c``), angles in radians.
"""

from __future__ import annotations

import math
import os
import platform
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from curverecon.generated import measurement_model

from curverecon.model.observations import wrap_angle
from curverecon.model.pose import normalise
from curverecon.simulate import Scene, make_scene

PARAMETERS = ("c", "alpha", "beta", "phi")
SUCCESS_DEG = 5.0
"""A reconstruction succeeds when its worst angle error is below this (degrees)."""

GROUPS = {
    "accuracy": 2,
    "robustness": 3,
    "stability": 4,
    "stability_linear": 5,
    "speed": 6,
    "outliers_random": 7,
}
"""spawn_key prefix of each experiment's scenes."""


def scene_rng(seed: int, group: str, *key: int) -> np.random.Generator:
    """The generator of one scene: independent of scheduling (SeedSequence spawn key)."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(GROUPS[group], *key)))


def true_poses(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """The true shape (4,) and poses (N, 5) of a scene in the library's parametrisation.

    Built from the simulator's camera-frame geometry alone: per frame the canonical basis
    e1 = AB / c, e2 = the part of the tangent line at B (oriented towards A) perpendicular to AB,
    e3 = e1 x e2, so X_cam = [e1 e2 e3] X_canonical + A3; that rotation is split as
    R_z(theta) R_y(tau) R_x(delta) (docs/CONVENTIONS.md).  phi comes out signed; ``normalise``
    maps the solution to phi in [0, pi] without changing any prediction.
    """
    t = scene.truth
    a3, b3 = np.asarray(t.A3, float), np.asarray(t.B3, float)
    ab = b3 - a3
    c = np.linalg.norm(ab, axis=1)
    e1 = ab / c[:, None]
    tb = np.asarray(t.tangent_B3, float)
    tb = tb * np.where(np.sum(tb * e1, axis=1) > 0, -1.0, 1.0)[:, None]  # towards A
    e2 = tb - np.sum(tb * e1, axis=1)[:, None] * e1
    e2 /= np.linalg.norm(e2, axis=1)[:, None]
    e3 = np.cross(e1, e2)
    ta = np.asarray(t.tangent_A3, float)
    ta = ta * np.where(np.sum(ta * e1, axis=1) < 0, -1.0, 1.0)[:, None]  # away from A, to B
    phi = float(np.median(np.arctan2(np.sum(ta * e3, axis=1), np.sum(ta * e2, axis=1))))
    theta = np.arctan2(e1[:, 1], e1[:, 0])
    tau = np.arctan2(-e1[:, 2], np.hypot(e1[:, 0], e1[:, 1]))
    # R_x(delta) = R_y(tau)^T R_z(theta)^T Q; its (2,1), (1,1) entries are sin, cos delta.
    q = np.stack([e1, e2, e3], axis=-1)
    rz = measurement_model.rotation_matrix(0.0 * theta, 0.0 * theta, theta)
    ry = measurement_model.rotation_matrix(0.0 * tau, tau, 0.0 * tau)
    m = np.einsum("nji,nkj,nkl->nil", ry, rz, q)
    delta = np.arctan2(m[:, 2, 1], m[:, 1, 1])
    poses = np.column_stack([delta, tau, theta, a3[:, 0], a3[:, 1]])
    shape = np.array([float(np.mean(c)), t.alpha, t.beta, phi])
    return normalise(shape, poses)


def truth_consistency(scene: Scene, shape: np.ndarray, poses: np.ndarray) -> float:
    """Largest difference between the model's 3-D geometry and the simulator's true geometry.

    Points relative to c, tangent directions as sines of angles; modulo the depth mirror
    z -> -z that ``normalise`` may apply (an orthographic sequence cannot tell it).  About 1e-15
    when ``true_poses`` is right.
    """
    a3, b3, ta3, tb3 = measurement_model.points_3d(*shape, *poses.T)
    t = scene.truth
    c = shape[0]
    best = math.inf
    for flip in (np.array([1.0, 1.0, 1.0]), np.array([1.0, 1.0, -1.0])):
        errs = [
            np.max(np.abs(a3 - t.A3 * flip)) / c,
            np.max(np.abs(b3 - t.B3 * flip)) / c,
            np.max(np.linalg.norm(np.cross(ta3, t.tangent_A3 * flip), axis=1)),
            np.max(np.linalg.norm(np.cross(tb3, t.tangent_B3 * flip), axis=1)),
        ]
        best = min(best, float(max(errs)))
    return best


def shape_errors(estimate: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """(4,) errors: relative c, then alpha, beta, phi differences (radians), both normalised."""
    est = np.asarray(estimate, float)
    tru = np.asarray(truth, float)
    d = wrap_angle(est[1:] - tru[1:])
    return np.concatenate([[(est[0] - tru[0]) / tru[0]], d])


def worst_angle_deg(errors: np.ndarray) -> float:
    """Worst absolute angle error (degrees) of an error vector from ``shape_errors``."""
    return float(np.degrees(np.max(np.abs(errors[1:]))))


def log10_relative(errors: np.ndarray) -> float:
    """log10 of the largest error (relative c, angles in radians), floored at 1e-17."""
    e = float(np.max(np.abs(errors)))
    if not math.isfinite(e):
        return math.inf
    return math.log10(max(e, 1e-17))


def make(seed: int, group: str, key: Sequence[int], n_frames: int, **kwargs: Any) -> Scene:
    """A simulator scene from the scene's own generator."""
    return make_scene(scene_rng(seed, group, *key), n_frames, **kwargs)


def machine_info() -> dict[str, Any]:
    """Cores, Python, NumPy and the other library versions, the platform."""
    import matplotlib
    import scipy
    import sympy

    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        usable = os.cpu_count()
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {
        "cores": os.cpu_count(),
        "usable_cores": usable,
        "cpu": cpu,
        "platform": platform.platform(),
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "sympy": sympy.__version__,
        "matplotlib": matplotlib.__version__,
        "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS"),
    }


@dataclass
class Task:
    """One unit of pool work: ``function(*args)`` returning a list of per-scene records."""

    function: Callable[..., list[dict]]
    args: tuple
    n_scenes: int
    label: str


def _run_task(task: Task) -> tuple[str, list[dict], float]:
    start = time.perf_counter()
    out = task.function(*task.args)
    return task.label, out, time.perf_counter() - start


def run_tasks(
    tasks: Iterable[Task], workers: int, desc: str, progress: bool = True
) -> dict[str, list[dict]]:
    """Run tasks on ``workers`` processes (fork), tqdm progress on stderr (per scene).

    Returns the records grouped by task label, each group sorted by ``record["index"]`` so the
    result does not depend on scheduling.
    """
    from tqdm import tqdm

    tasks = list(tasks)
    total = sum(t.n_scenes for t in tasks)
    out: dict[str, list[dict]] = {}
    bar = tqdm(total=total, desc=desc, unit="scene", file=sys.stderr, disable=not progress)
    if workers <= 1:
        results: Iterable = map(_run_task, tasks)
        pool = None
    else:
        import multiprocessing as mp

        pool = mp.get_context("fork").Pool(workers, maxtasksperchild=200)
        results = pool.imap_unordered(_run_task, tasks)
    try:
        for label, records, _ in results:
            out.setdefault(label, []).extend(records)
            bar.update(len(records))
    finally:
        bar.close()
        if pool is not None:
            pool.close()
            pool.join()
    for records in out.values():
        records.sort(key=lambda r: r["index"])
    return out


def chunks(n: int, size: int) -> list[range]:
    """range(0, n) cut into consecutive ranges of at most ``size``."""
    return [range(i, min(n, i + size)) for i in range(0, n, size)]


def polylines_only(obs):  # type: ignore[no-untyped-def]
    """``obs`` with its end points and tangents removed (the polylines alone), through the
    public file format."""
    from curverecon.io import observations_from_dict, observations_to_dict

    doc = observations_to_dict(obs)
    for frame in doc["frames"]:
        for key in ("A", "B", "tangent_A", "tangent_B"):
            frame.pop(key)
    return observations_from_dict(doc)
