"""The orthographic minimal solvers of the Section 2 rows against an independent 3-D construction.

Scenes come from ``bench.config_minimal.scene`` (random body, the row's motion, orthographic
projection; no solver code): the truth must be among the solutions, every listed solution must
reproduce the images exactly and be a rigid motion of the row's model, and bad input shapes are
refused with a one-line CurveReconError.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from bench.config_minimal import scene, truth_listed
from curverecon.errors import CurveReconError

ROWS = ("ortho_fixed_axis", "ortho_uniform_rotation", "ortho_free_3pt")


def _solver(row: str):  # type: ignore[no-untyped-def]
    return importlib.import_module(f"curverecon.solvers.{row}")


@pytest.mark.parametrize("row", ROWS)
def test_truth_listed_on_constructed_scenes(row: str) -> None:
    solver = _solver(row)
    rng = np.random.default_rng(11)
    for _ in range(40):
        s = scene(row, rng, solver.FRAMES)
        sol = solver.solve(s["points"], s["times"])
        assert truth_listed(sol, s)
        assert sol.n_failed_paths == 0


@pytest.mark.parametrize("row", ROWS)
def test_every_solution_is_a_rigid_motion_of_the_model(row: str) -> None:
    """Noise-free exactness: each solution reproduces the images, keeps A's depth 0, and its
    rotations map frame 0's differences to every frame's (R_0 = I, orthonormal, det 1)."""
    solver = _solver(row)
    rng = np.random.default_rng(12)
    for _ in range(10):
        s = scene(row, rng, solver.FRAMES)
        sol = solver.solve(s["points"], s["times"])
        assert sol.n_solutions >= 2 and sol.n_solutions % 2 == 0  # mirror pairs
        size = np.abs(s["points3"]).max()
        for p3, rots in zip(sol.points3, sol.rotations, strict=True):
            assert np.allclose(p3[:, :, :2], s["points"], rtol=0, atol=1e-12 * size)
            assert np.all(p3[:, 0, 2] == 0)
            assert np.allclose(rots[0], np.eye(3), atol=1e-9)
            for f in range(solver.FRAMES):
                assert np.allclose(rots[f] @ rots[f].T, np.eye(3), atol=1e-9)
                assert np.linalg.det(rots[f]) == pytest.approx(1.0, abs=1e-9)
                moved = (rots[f] @ (p3[0] - p3[0, 0]).T).T
                assert np.allclose(moved, p3[f] - p3[f, 0], atol=1e-7 * size)
        mirrored = sol.points3 * np.array([1, 1, -1])
        for p3 in mirrored:  # the mirror image of every solution is listed too
            err = np.abs(sol.points3 - p3[None]).reshape(len(sol.points3), -1).max(axis=1)
            assert err.min() < 1e-7 * size


def test_axis_motion_parameters_match_rotations() -> None:
    """Fixed axis and uniform rotation: R_f = Rot(axis, angle_f), the rate times the elapsed time
    for the uniform rotation, frame 1's angle in [0, 180] degrees."""
    from curverecon.solvers.ortho_common import rotation

    for row in ("ortho_fixed_axis", "ortho_uniform_rotation"):
        solver = _solver(row)
        s = scene(row, np.random.default_rng(13), solver.FRAMES)
        sol = solver.solve(s["points"], s["times"])
        for rots, m in zip(sol.rotations, sol.motion, strict=True):
            axis, angles = np.array(m["axis"]), np.radians(m["angle_deg"])
            assert np.linalg.norm(axis) == pytest.approx(1.0)
            assert 0 <= angles[1] <= np.pi
            for f in range(solver.FRAMES):
                assert np.allclose(rotation(axis, angles[f]), rots[f], atol=1e-9)
            if row == "ortho_uniform_rotation":
                rate = np.radians(m["rate_deg"])
                assert np.allclose(angles, rate * (s["times"] - s["times"][0]), atol=1e-9)


@pytest.mark.parametrize("row", ROWS)
def test_bad_shapes_refused(row: str) -> None:
    solver = _solver(row)
    s = scene(row, np.random.default_rng(14), solver.FRAMES)
    pts, times = s["points"], s["times"]
    bad = {
        "frames": (pts[:-1], times[:-1]),
        "points": (pts[:, :1], times),
        "times shape": (pts, times[:-1]),
        "times not increasing": (pts, times[::-1]),
        "times repeated": (pts, np.full_like(times, 1.0)),
        "not finite": (np.where(pts == pts[0, 0, 0], np.nan, pts), times),
    }
    for case, (p, t) in bad.items():
        with pytest.raises(CurveReconError) as err:
            solver.solve(p, t)
        assert "\n" not in str(err.value), case
        assert solver.ROW in str(err.value), case


def test_force_field_has_no_practical_minimal_solver() -> None:
    from curverecon.solvers import ortho_force_field

    assert ortho_force_field.FRAMES == 9 and ortho_force_field.POINTS == ("A", "B")
    with pytest.raises(CurveReconError, match="no practical minimal solver"):
        ortho_force_field.solve(np.zeros((9, 2, 2)), np.arange(9.0))


@pytest.mark.parametrize("row", ROWS)
def test_frames_alike_give_no_solutions(row: str) -> None:
    """Every frame the same image: a curve of solutions, none listed, no exception."""
    solver = _solver(row)
    one = np.random.default_rng(15).normal(size=(1, len(solver.POINTS), 2)) * 50
    sol = solver.solve(np.repeat(one, solver.FRAMES, axis=0), np.arange(solver.FRAMES) * 0.5)
    assert sol.n_solutions == 0 and sol.points3.shape[1:] == (solver.FRAMES, len(solver.POINTS), 3)


@pytest.mark.parametrize("row", ("ortho_fixed_axis", "ortho_uniform_rotation"))
def test_axis_along_the_viewing_direction_gives_no_solutions(row: str) -> None:
    """A rotation in the image plane at a uniform rate leaves the depth free (docs/derivation.md:
    dimension 1): nothing listed."""
    solver = _solver(row)
    times = np.arange(solver.FRAMES, dtype=float)
    angles = 0.4 * times
    d = np.column_stack([np.cos(angles), np.sin(angles)]) * 40.0
    pts = np.zeros((solver.FRAMES, 2, 2))
    pts[:, 0] = [5.0, 7.0]
    pts[:, 1] = pts[:, 0] + d
    assert solver.solve(pts, times).n_solutions == 0


def test_bench_helper_returns_every_key() -> None:
    from bench.config_minimal import ROWS as BENCH_ROWS
    from bench.config_minimal import run

    out = run(seed=3, scenes=5)
    for row in BENCH_ROWS:
        assert out[f"config_{row}_minimal_truth_listed_rate"] == 1.0
        assert out[f"config_{row}_solve_seconds_median"] > 0
