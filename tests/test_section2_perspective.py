"""The perspective and stereo rows of the Section 2 table: counts, equations and minimal solvers.

Scenes come from ``bench.config_minimal_persp.scene`` (random body, the row's motion, pinhole
projection to pixels; no solver or derivation code): the truth must be among the solutions and
every listed solution must reproduce the pixels and be a rigid motion of the row's model.  The
counts are msolve's on random prime-field instances (skipped without msolve), and the
derivation's equations vanish at its own float64 construction.  A scene pushed far away
degenerates as the orthographic limit predicts.
"""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from bench.config_minimal_persp import CAMERA, scene, truth_listed
from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera, StereoRig

SOLVED = ("persp_rotation_free", "persp_uniform_rotation", "persp_fixed_axis_3pt", "stereo_free")
SCENES = {"persp_rotation_free": 40, "stereo_free": 40, "persp_uniform_rotation": 12,
          "persp_fixed_axis_3pt": 8}  # fmt: skip


def _solver(row: str):  # type: ignore[no-untyped-def]
    return importlib.import_module(f"curverecon.solvers.{row}")


@pytest.mark.parametrize("row", SOLVED)
def test_truth_listed_on_constructed_scenes(row: str) -> None:
    solver = _solver(row)
    rng = np.random.default_rng(17)
    for _ in range(SCENES[row]):
        s = scene(row, rng, solver.FRAMES)
        sol = solver.solve(s["points"], s["times"], s["camera"])
        assert truth_listed(sol, s)
        # every path accounted for: real, complex or failed (never dropped silently); the fixed
        # axis merges three solves, each real solution listed once
        passes = len(getattr(solver, "PASSES", (None,)))
        listed = sol.n_solutions + sol.n_complex + sol.n_failed_paths
        assert listed == sol.n_paths if passes == 1 else listed <= sol.n_paths


@pytest.mark.parametrize("row", ("persp_uniform_rotation", "persp_fixed_axis_3pt"))
def test_every_solution_is_a_rigid_motion_of_the_model(row: str) -> None:
    """Each listed solution reprojects to the pixels, has A's depth 1 in frame 0, and its
    rotations (about one axis, R_0 = I) map frame 0's differences to every frame's."""
    solver = _solver(row)
    s = scene(row, np.random.default_rng(5), solver.FRAMES)
    sol = solver.solve(s["points"], s["times"], s["camera"])
    assert sol.n_solutions >= 1
    for p3, rots, motion in zip(sol.points3, sol.rotations, sol.motion, strict=True):
        assert np.allclose(CAMERA.project(p3), s["points"], atol=1e-6)
        assert p3[0, 0, 2] == pytest.approx(1.0)
        axis = np.array(motion["axis"])
        for f in range(solver.FRAMES):
            assert np.allclose(rots[f] @ rots[f].T, np.eye(3), atol=1e-9)
            assert np.allclose(rots[f] @ axis, axis, atol=1e-7)
            assert np.allclose((p3[f, 1:] - p3[f, 0]), (p3[0, 1:] - p3[0, 0]) @ rots[f].T,
                               atol=1e-7)  # fmt: skip


def test_uniform_rotation_motion_parameters() -> None:
    """The listed solution that is the truth carries the construction's rate (a step below
    half a turn) and an angle per frame growing by one step."""
    solver = _solver("persp_uniform_rotation")
    rng = np.random.default_rng(23)
    s = scene("persp_uniform_rotation", rng, 5)
    sol = solver.solve(s["points"], s["times"], s["camera"])
    err = np.abs(sol.points3 - s["points3"][None]).reshape(sol.n_solutions, -1).max(axis=1)
    motion = sol.motion[int(np.argmin(err))]
    step = np.radians(motion["rate_deg"] * (s["times"][1] - s["times"][0]))
    assert np.allclose(np.diff(motion["angle_deg"]), np.degrees(step))
    d0 = s["points3"][0, 1] - s["points3"][0, 0]
    d1 = s["points3"][1, 1] - s["points3"][1, 0]
    axis = np.array(motion["axis"])
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    rot = np.eye(3) + np.sin(step) * k + (1 - np.cos(step)) * (k @ k)
    assert np.allclose(rot @ d0, d1, atol=1e-7)


@pytest.mark.parametrize("frames_turned", ((0, 1), (1, 2), (0, 2)))
def test_fixed_axis_half_turn_between_two_frames(frames_turned: tuple[int, int]) -> None:
    """A half turn between two frames (the real Cayley chart's infinity, where one solve in it
    missed the truth) is a finite point of the solver's chart: the truth is listed, with the
    constructed axis and angles.  The 3-D construction: three body points, one axis, the
    angles chosen so that frames ``frames_turned`` are 180 degrees apart, projected."""
    from bench.config_minimal import random_rotation, rotation

    solver = _solver("persp_fixed_axis_3pt")
    rng = np.random.default_rng(41)
    for _ in range(3):
        body = rng.normal(size=(3, 3)) * 0.3
        axis = random_rotation(rng)[:, 0]
        angles = np.concatenate([[0.0], rng.uniform(-np.pi, np.pi, 2)])
        i, j = frames_turned
        angles[j] = angles[i] + np.pi
        angles -= angles[0]
        x3 = np.array([body @ rotation(axis, a).T + [0.0, 0.0, 2.0] + rng.normal(size=3) * 0.2
                       for a in angles])  # fmt: skip
        s = {"points": CAMERA.project(x3), "points3": x3 / x3[0, 0, 2]}
        sol = solver.solve(s["points"], np.arange(3.0), CAMERA)
        assert truth_listed(sol, s)
        err = np.abs(sol.points3 - s["points3"][None]).reshape(sol.n_solutions, -1).max(axis=1)
        motion = sol.motion[int(np.argmin(err))]
        got = np.array(motion["axis"])
        sign = np.sign(got @ axis)
        assert np.allclose(got, sign * axis, atol=1e-7)
        turned = np.radians(motion["angle_deg"][j] - motion["angle_deg"][i])
        assert abs(np.cos(turned) + 1.0) < 1e-10


def test_rotation_free_degenerates_at_a_large_distance() -> None:
    """Pushed away, the rays of a body of size s at distance d differ by about s/d, and the
    rotation-free system's determinant falls like (s/d)^2: the orthographic twin leaves the
    depth of AB free.  Near: the truth; far: the depth of B relative to A tends to 1 (the
    orthographic limit) and at d = 1e7 s the system is singular to rounding: nothing listed."""
    solver = _solver("persp_rotation_free")
    rng = np.random.default_rng(3)
    body = rng.normal(size=(2, 3))
    shift = np.array([0.4, -0.3, 0.2])
    dets = []
    for distance in (10.0, 100.0, 1000.0, 1e7):
        x3 = np.array([body, body + shift]) + np.array([0.0, 0.0, distance])
        px = CAMERA.project(x3)
        m = CAMERA.rays(px)
        dets.append(abs(np.linalg.det(np.column_stack([m[0, 1], m[1, 0], m[1, 1]]))))
        sol = solver.solve(px, np.array([0.0, 1.0]), CAMERA)
        if distance < 1e6:
            assert sol.n_solutions == 1
            assert np.allclose(sol.points3[0], x3 / x3[0, 0, 2], rtol=1e-6 * distance)
        else:
            assert sol.n_solutions == 0
    ratios = np.array(dets[:-2]) / np.array(dets[1:-1])
    assert np.all((ratios > 50) & (ratios < 200))  # (s/d)^2: a factor 100 a decade


def test_stereo_chord_is_metric() -> None:
    """One stereo frame gives A and B in the baseline's units: c = |AB| as constructed."""
    solver = _solver("stereo_free")
    s = scene("stereo_free", np.random.default_rng(9), 1)
    sol = solver.solve(s["points"], s["times"], s["camera"])
    c = np.linalg.norm(sol.points3[0, 0, 1] - sol.points3[0, 0, 0])
    assert c == pytest.approx(np.linalg.norm(s["points3"][0, 1] - s["points3"][0, 0]), rel=1e-9)


@pytest.mark.parametrize(
    "make",
    [
        lambda: Camera(0.0, (1.0, 2.0)),
        lambda: Camera(float("nan"), (1.0, 2.0)),
        lambda: Camera(500.0, (1.0,)),
        lambda: StereoRig(CAMERA, CAMERA, np.eye(3) * 2, np.ones(3)),
        lambda: StereoRig(CAMERA, CAMERA, np.eye(3), np.zeros(3)),
    ],
)
def test_bad_cameras_refused(make) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(CurveReconError) as err:
        make()
    assert "\n" not in str(err.value)


def test_bad_input_refused() -> None:
    rf = _solver("persp_rotation_free")
    with pytest.raises(CurveReconError, match="shape"):
        rf.solve(np.zeros((3, 2, 2)), np.arange(3.0), CAMERA)
    with pytest.raises(CurveReconError, match="increasing"):
        rf.solve(np.ones((2, 2, 2)), np.array([1.0, 0.0]), CAMERA)
    with pytest.raises(CurveReconError, match="Camera"):
        rf.solve(np.ones((2, 2, 2)), np.arange(2.0), None)
    ur = _solver("persp_uniform_rotation")
    with pytest.raises(CurveReconError, match="equally spaced"):
        ur.solve(np.ones((5, 2, 2)), np.array([0.0, 1, 2, 3, 5]), CAMERA)
    for row in ("persp_free_4pt", "persp_force_field"):
        solver = _solver(row)
        assert solver.PRACTICAL is False
        with pytest.raises(CurveReconError, match="no practical minimal solver"):
            solver.solve(np.zeros((solver.FRAMES, len(solver.POINTS), 2)),
                         np.arange(float(solver.FRAMES)), CAMERA)  # fmt: skip


# --- the derivation ------------------------------------------------------------------------


def test_equations_vanish_at_the_construction() -> None:
    from derivations import section2_perspective as d

    rng = np.random.default_rng(4)
    for row in d.ROWS:
        assert d._check_row(row, rng) < 1e-9, row
    assert d._plane_depths_check(rng) < 1e-9


def test_force_field_needs_eleven_frames() -> None:
    from derivations import section2_perspective as d

    ranks = d.force_field_jacobian_ranks()
    assert ranks[10][0] < ranks[10][1]
    assert ranks[11][0] == ranks[11][1]


@pytest.mark.parametrize(
    ("row", "frames", "expected"),
    [("rotation_free", 2, 1), ("uniform_rotation", 5, 26), ("fixed_axis_3pt", 3, 88),
     ("free_4pt", 3, 0)],
)  # fmt: skip
def test_counts_on_random_instances(row: str, frames: int, expected: int) -> None:
    """msolve's count on a fresh random instance (seed 11, not the derivation's) equals the
    derived count; four points at three frames: none (overdetermined by one)."""
    from derivations import minimal_count as mc
    from derivations import section2_perspective as d

    try:
        mc.msolve_binary()
    except mc.MsolveMissingError:
        pytest.skip("msolve is not installed")
    count = d.count_system(row, frames, d._random_values(row, frames, 11))
    assert count.degree == expected
    assert count.dimension == (0 if expected else -1)


@pytest.mark.parametrize("row", ("persp_uniform_rotation", "persp_fixed_axis_3pt"))
def test_tracked_on_the_generated_kernels(row: str) -> None:
    """The solver tracks on the generated straight-line kernels, and at a random complex point
    they give the system of the generated tables (F and F_x, evaluated term by term)."""
    from curverecon.solvers import homotopy

    system = _solver(row)._system()
    assert system.tracker is not None and system.newton is not None
    rng = np.random.default_rng(3)
    shape = (system.n_unknowns,)
    x = rng.normal(size=shape) + 1j * rng.normal(size=shape)
    q = rng.normal(size=system.n_parameters) + 1j * rng.normal(size=system.n_parameters)
    f_tab, jac_tab = system.evaluate(x, q)
    tables = homotopy.PolynomialSystem.from_module(
        importlib.import_module(f"curverecon.generated.{row.removesuffix('_3pt')}_system")
    )
    assert tables.tracker is None
    k = importlib.import_module(f"curverecon.generated.{row.removesuffix('_3pt')}_kernel")
    w = np.empty(k.N_COEFFICIENTS, np.complex128)
    k.coefficients(q, w)
    f = np.empty(system.n_equations, np.complex128)
    jac = np.empty((system.n_equations, system.n_unknowns), np.complex128)
    k.residual_jacobian(x, w, f, jac)
    scale = 1 + np.abs(f_tab).max()
    assert np.abs(f - f_tab).max() <= 1e-12 * scale
    assert np.abs(jac - jac_tab).max() <= 1e-12 * (1 + np.abs(jac_tab).max())
