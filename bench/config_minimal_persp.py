"""Minimal solvers of the seed's Section 2 perspective and stereo rows:
``python -m bench.config_minimal_persp``.

For each row with a practical minimal solver (``curverecon/solvers/persp_<row>.py`` and
``stereo_free.py``: rotation-free, uniform rotation, fixed axis, stereo; the four-point and
force-field rows have none), ``scenes`` noise-free scenes at the least number of frames, each
built by its own 3-D construction here (independent of the solvers and of ``derivations/``):
random body points (standard normal times 0.3 m) about 2 m in front of a 640 x 480 camera with a
focal length of 800 px, a random start orientation, the row's motion (pure translation; one
axis and one rate over equally spaced times, below half a turn a step; one axis and any angles),
a random translation per frame that keeps the body in front of the camera, and the pinhole
projection to pixels.  Stereo: a second camera 0.3 m to the side, turned by a few degrees.
Per row:

- ``config_<row>_minimal_truth_listed_rate``: the truth (every point of every frame, camera
  coordinates in units of A's depth in frame 0; stereo in metres) among the solutions to 1e-6
  relative to the body's size;
- ``config_<row>_solve_seconds_median``: ``solve`` alone, one core, compiled and warm;
  ``config_<row>_solve_cpu_seconds_median`` the same in CPU time (the process's), the figure
  that holds on a loaded machine;
- ``config_<row>_real_solutions_mean`` and ``config_<row>_failed_paths``.

``run(seed, scenes)`` returns the keys.
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

from bench.config_minimal import random_rotation, rotation  # noqa: E402
from curverecon.solvers.camera import Camera, StereoRig  # noqa: E402

ROWS = ("persp_rotation_free", "persp_uniform_rotation", "persp_fixed_axis_3pt", "stereo_free")
CAMERA = Camera(800.0, (320.0, 240.0))
SIZE = 0.3
"""Body size (metres)."""
DISTANCE = 2.0
"""Distance of the body from the camera (metres)."""
TOLERANCE = 1e-6
"""Truth listed: max |point error| / body size below this."""


def _motion(row: str, rng: np.random.Generator, frames: int) -> tuple[list, np.ndarray]:
    """(rotations relative to frame 0, times) of the row's model."""
    times = np.cumsum(rng.uniform(0.3, 2.0, frames)) + rng.uniform(-5, 5)
    axis = random_rotation(rng)[:, 0]
    if row == "persp_uniform_rotation":
        times = times[0] + rng.uniform(0.1, 2.0) * np.arange(frames)
        step = np.radians(rng.uniform(10, 150)) * rng.choice([-1.0, 1.0])
        return [rotation(axis, step * f) for f in range(frames)], times
    if row == "persp_fixed_axis_3pt":
        angles = np.concatenate([[0.0], rng.uniform(-np.pi, np.pi, frames - 1)])
        return [rotation(axis, a) for a in angles], times
    return [np.eye(3)] * frames, times


def scene(row: str, rng: np.random.Generator, frames: int) -> dict:
    """One noise-free scene: ``points`` pixels ((F, P, 2); stereo (1, 2, P, 2)), ``times``,
    ``points3`` (F, P, 3) camera coordinates in the solver's units, ``camera``."""
    npts = 3 if row == "persp_fixed_axis_3pt" else 2
    body = rng.normal(size=(npts, 3)) * SIZE
    body = body @ random_rotation(rng).T
    rel, times = _motion(row, rng, frames)
    centre = np.array([0.0, 0.0, DISTANCE])
    x3 = np.array([(r @ body.T).T + centre + rng.normal(size=3) * 0.2 for r in rel])
    if row == "stereo_free":
        rig = StereoRig(CAMERA, CAMERA, rotation(rng.normal(size=3), np.radians(5)),
                        np.array([-0.3, 0.01, 0.02]))  # fmt: skip
        x1 = x3 @ rig.R.T + rig.t
        points = np.stack([CAMERA.project(x3), CAMERA.project(x1)], axis=1)
        return {"points": points, "times": times, "points3": x3, "camera": rig}
    return {"points": CAMERA.project(x3), "times": times, "points3": x3 / x3[0, 0, 2],
            "camera": CAMERA}  # fmt: skip


def truth_listed(solutions: object, truth: dict) -> bool:
    """The truth's points in every frame among the solutions (TOLERANCE relative)."""
    p3 = solutions.points3  # type: ignore[attr-defined]
    if len(p3) == 0:
        return False
    t3 = truth["points3"]
    size = np.ptp(t3.reshape(-1, 3), axis=0).max()
    err = np.abs(p3 - t3[None]).reshape(len(p3), -1).max(axis=1) / size
    return bool(err.min() < TOLERANCE)


def run_row(row: str, seed: int, scenes: int) -> dict[str, float]:
    """The row's figures over ``scenes`` seeded scenes."""
    solver = importlib.import_module(f"curverecon.solvers.{row}")
    rng = np.random.default_rng([seed, ROWS.index(row), 1])
    warm = scene(row, rng, solver.FRAMES)
    solver.solve(warm["points"], warm["times"], warm["camera"])
    listed, seconds, cpu, reals, failed = 0, [], [], [], 0
    for _ in range(scenes):
        s = scene(row, rng, solver.FRAMES)
        t0, c0 = time.perf_counter(), time.process_time()
        sol = solver.solve(s["points"], s["times"], s["camera"])
        seconds.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        listed += truth_listed(sol, s)
        reals.append(sol.n_solutions)
        failed += sol.n_failed_paths
    return {
        f"config_{row}_minimal_truth_listed_rate": listed / scenes,
        f"config_{row}_solve_seconds_median": float(np.median(seconds)),
        f"config_{row}_solve_cpu_seconds_median": float(np.median(cpu)),
        f"config_{row}_real_solutions_mean": float(np.mean(reals)),
        f"config_{row}_failed_paths": int(failed),
        f"config_{row}_minimal_scenes": scenes,
    }


def run(seed: int, scenes: int, rows: tuple[str, ...] = ROWS) -> dict:
    """Every row's figures (keys ``config_<row>_...``) over ``scenes`` scenes per row."""
    out: dict = {}
    for row in rows:
        out.update(run_row(row, seed, scenes))
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m bench.config_minimal_persp")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--scenes", type=int, default=1000)
    parser.add_argument("--rows", nargs="*", default=list(ROWS), choices=ROWS)
    args = parser.parse_args(argv)
    json.dump(run(args.seed, args.scenes, tuple(args.rows)), sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
