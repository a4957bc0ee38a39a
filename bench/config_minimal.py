"""Minimal solvers of the seed's Section 2 orthographic rows: ``python -m bench.config_minimal``.

For each row with a practical minimal solver (``curverecon/solvers/ortho_<row>.py``: uniform
rotation, fixed axis, three points; the force field has none), ``scenes`` noise-free scenes at
the least number of frames, each built by its own 3-D construction here (independent of the
solvers and of ``derivations/``): random body points (standard normal, lengths about 1 in input
units times ``SCALE``), a random start orientation, the row's motion (one random axis and any
angles; one axis and one rate; a random rotation per frame), a random translation per frame,
increasing random times, orthographic projection (x, y kept).  Per row:

- ``config_<row>_minimal_truth_listed_rate``: the truth (every point of every frame, depth
  relative to A) among the solutions to 1e-6 relative (to the body's size);
- ``config_<row>_solve_seconds_median``: ``solve`` alone, one core, compiled and warm;
- ``config_<row>_real_solutions_mean`` and ``config_<row>_failed_paths``.

Uniform rotation: the rotation between consecutive frames is below half a turn (drawn from
10-150 degrees), the sampling condition the solver assumes.  ``run(seed, scenes)`` returns the
keys; the configurations section (``bench/configurations.py``) calls it.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import importlib  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

ROWS = ("ortho_uniform_rotation", "ortho_fixed_axis", "ortho_free_3pt")
SCALE = 100.0
"""Body size in input units (pixels)."""
SCENES = 1000
"""Scenes per row by default (the target asks >= 1,000)."""
TOLERANCE = 1e-6
"""Truth listed: max |point error| / body size below this."""


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rot(axis, angle) by the matrix exponential of the skew matrix (Rodrigues' formula)."""
    n = axis / np.linalg.norm(axis)
    k = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


def random_rotation(rng: np.random.Generator) -> np.ndarray:
    """A uniformly random rotation (random unit quaternion)."""
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])  # fmt: skip


def scene(row: str, rng: np.random.Generator, frames: int) -> dict:
    """One noise-free scene: ``points`` (F, P, 2), ``times`` (F,), ``points3`` (F, P, 3) with
    depth relative to A, the motion's ``axis``, ``angles`` (radians) and ``rotations``."""
    npts = 3 if row == "ortho_free_3pt" else 2
    body = rng.normal(size=(npts, 3)) * SCALE
    start = random_rotation(rng)
    times = np.cumsum(rng.uniform(0.3, 2.0, frames)) + rng.uniform(-5, 5)
    axis = random_rotation(rng)[:, 0]
    if row == "ortho_uniform_rotation":
        step = np.radians(rng.uniform(10, 150)) * rng.choice([-1.0, 1.0])
        rate = step / (times[1] - times[0])
        gaps = np.diff(times)
        rate = min(abs(rate), 0.95 * np.pi / gaps.max()) * np.sign(rate)  # below half a turn
        angles = rate * (times - times[0])
    else:
        angles = np.concatenate([[0.0], rng.uniform(-np.pi, np.pi, frames - 1)])
    if row == "ortho_free_3pt":
        rel = [np.eye(3)] + [random_rotation(rng) for _ in range(frames - 1)]
    else:
        rel = [rotation(axis, a) for a in angles]
    x3 = np.array([(r @ start @ body.T).T + rng.normal(size=3) * SCALE for r in rel])
    p3 = x3 - x3[:, :1] * np.array([0, 0, 1.0])  # depth relative to A
    return {"points": x3[:, :, :2], "times": times, "points3": p3, "axis": axis,
            "angles": angles, "rotations": np.array(rel)}  # fmt: skip


def truth_listed(solutions: object, truth: dict) -> bool:
    """The truth's points in every frame among the solutions (TOLERANCE relative)."""
    p3 = solutions.points3  # type: ignore[attr-defined]
    if len(p3) == 0:
        return False
    size = np.abs(truth["points3"]).max()
    err = np.abs(p3 - truth["points3"][None]).reshape(len(p3), -1).max(axis=1) / size
    return bool(err.min() < TOLERANCE)


def run_row(row: str, seed: int, scenes: int) -> dict[str, float]:
    """The row's figures over ``scenes`` seeded scenes."""
    solver = importlib.import_module(f"curverecon.solvers.{row}")
    rng = np.random.default_rng([seed, ROWS.index(row)])
    warm = scene(row, rng, solver.FRAMES)
    solver.solve(warm["points"], warm["times"])
    listed, seconds, reals, failed = 0, [], [], 0
    for _ in range(scenes):
        s = scene(row, rng, solver.FRAMES)
        t0 = time.perf_counter()
        sol = solver.solve(s["points"], s["times"])
        seconds.append(time.perf_counter() - t0)
        listed += truth_listed(sol, s)
        reals.append(sol.n_solutions)
        failed += sol.n_failed_paths
    return {
        f"config_{row}_minimal_truth_listed_rate": listed / scenes,
        f"config_{row}_solve_seconds_median": float(np.median(seconds)),
        f"config_{row}_real_solutions_mean": float(np.mean(reals)),
        f"config_{row}_failed_paths": int(failed),
        f"config_{row}_minimal_scenes": scenes,
    }


def run(seed: int, scenes: int | None = None) -> dict:
    """Every row's figures (keys ``config_<row>_...``) over ``scenes`` scenes per row (None:
    SCENES)."""
    out: dict = {}
    for row in ROWS:
        out.update(run_row(row, seed, SCENES if scenes is None else scenes))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.config_minimal")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--scenes", type=int, default=SCENES)
    args = parser.parse_args(argv)
    json.dump(run(args.seed, args.scenes), sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
