"""Perspective, rotation about a fixed direction, A, B and C, three frames: parameter homotopy.

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): each edge of the
triangle ABC lies in the plane through the camera centre and its image line, so per frame
(m_P x m_Q) . (X_Q - X_P) = 0 for PQ = AB, AC, BC (m the rays); the three together say the
triangle is inscribed in the three rays.  With X_f - A_f = R_f (X_0 - A_0),
R_f = cayley(mu_f n) about one axis n, and frame 0's differences b0 m_B0 - m_A0,
c0 m_C0 - m_A0 (A's depth in frame 0 is 1), two later frames give six equations in
(b0, c0, n1, n2, mu1, mu2): three frames, as the seed's table says.  msolve counts 88 complex
solutions (random and noise-free instances; four frames leave the truth alone); 84 of them are
reached by monodromy from constructed scenes (``generated/persp_fixed_axis_system.py``), the
other four lie on a component no real scene's truth is on.  No closed form was found, so the 84
are tracked to the frames' rays (:mod:`curverecon.solvers.homotopy`, on the straight-line kernels
of ``generated/persp_fixed_axis_kernel.py``: 3.4 times faster than the tables) and the real ones
kept, three times: with each frame as the reference (a half turn from the reference is the
Cayley form's singularity) and two of them in a perpendicular chart (``PASSES``); the real
solutions of the three solves are merged.
"""

from __future__ import annotations

from dataclasses import replace
from functools import cache

import numba
import numpy as np

from curverecon import jit_cache
from curverecon.generated import persp_fixed_axis_kernel as kernel_module
from curverecon.generated import persp_fixed_axis_system as system_module
from curverecon.solvers import homotopy
from curverecon.solvers.camera import Camera
from curverecon.solvers.persp_common import (
    CHART,
    SECOND_CHART,
    cayley,
    homotopy_parameters,
    place,
    rays_of,
    real_solutions,
)
from curverecon.solvers.persp_common import solutions as make_solutions
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B", "C")
ROW = "persp_fixed_axis_3pt"


@numba.njit(cache=True, nogil=True)
def _track_kernels(q0, q1, d, x_start, opts, plan, x_end, status, steps, t_end):  # type: ignore[no-untyped-def]
    """The homotopy tracker on the generated straight-line kernels
    (``generated/persp_fixed_axis_kernel.py``, ``homotopy.track_generated``)."""
    k = kernel_module
    homotopy.track_generated(
        k.coefficients, k.coefficients_t, k.coefficient_rates, k.residual_jacobian,
        k.residual_jacobian_t, k.solve_pair, k.N_COEFFICIENTS,
        q0, q1, d, x_start, opts, plan, x_end, status, steps, t_end,
    )  # fmt: skip


@numba.njit(cache=True, nogil=True)
def _newton_kernels(xs, q, plan, iterations):  # type: ignore[no-untyped-def]
    """Newton's method on the generated kernels (``homotopy.newton_generated``)."""
    k = kernel_module
    homotopy.newton_generated(
        k.coefficients, k.residual_jacobian, k.N_COEFFICIENTS, xs, q, plan, iterations
    )


# numba caches the two above on this file's source alone (curverecon.jit_cache)
jit_cache.drop_stale((_track_kernels, _newton_kernels), (homotopy, kernel_module))


@cache
def _system() -> homotopy.PolynomialSystem:
    """The tracked system: the generated tables, tracked on the generated kernels when these
    were written for the same system and elimination plan."""
    tables = homotopy.PolynomialSystem.from_module(system_module)
    k = kernel_module
    same = (k.UNKNOWNS, k.PARAMETERS) == (system_module.UNKNOWNS, system_module.PARAMETERS)
    if not same or not np.array_equal(getattr(k, "ELIMINATION", ()), tables.elimination):
        return tables
    return replace(tables, tracker=_track_kernels, newton=_newton_kernels)


PASSES = ((0, 1, 2), CHART), ((1, 0, 2), SECOND_CHART), ((2, 0, 1), SECOND_CHART)
"""(frame order, chart) of the solves whose solutions are merged.  The Cayley form is singular at
a half turn from the reference frame and the chart at axes with n3 = 0: one solve missed the
truth on 1.8 % of the bench's scenes (seed 0), half of them a half turn between frames 0 and 1,
which is singular from either of them; every frame as the reference once, two of them in a
perpendicular chart, leaves only scenes with two half turns."""


def _one_pass(m: np.ndarray, order: tuple[int, ...], chart: np.ndarray) -> tuple[list, tuple]:
    """Solutions of one solve (frames in ``order``, rays turned by ``chart``), converted to the
    original frames and scale: [(points3, rotations, axis, angles in degrees)], counts."""
    mm = m[list(order)]
    target = homotopy_parameters(mm, ((0, 1), (0, 2), (1, 2)), chart)
    rows, n_paths, n_complex, n_failed = real_solutions(_system(), target)
    back = [order.index(f) for f in range(FRAMES)]  # original frame f is mm's frame back[f]
    out = []
    for b0, c0, n1, n2, *mus in rows:
        n = np.array([n1, n2, 1.0])
        rots = np.array([np.eye(3)] + [chart.T @ cayley(mu * n) @ chart for mu in mus])
        diffs = np.array([b0 * mm[0, 1] - mm[0, 0], c0 * mm[0, 2] - mm[0, 0]])
        p3 = place(mm, rots, diffs)[back]
        angles = np.array([0.0] + [2 * np.degrees(np.arctan(mu * np.linalg.norm(n))) for mu in mus])
        ref = back[0]
        rots = np.array([rots[back[f]] @ rots[ref].T for f in range(FRAMES)])
        angles = angles[back] - angles[ref]
        out.append((p3 / p3[0, 0, 2], rots, chart.T @ n / np.linalg.norm(n), angles))
    return out, (n_paths, n_complex, n_failed)


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Every real solution of three frames of A, B, C in pixels (``points`` (3, 3, 2),
    ``times`` (3,) increasing): ``points3`` in camera coordinates (A's depth in frame 0 = 1),
    ``rotations`` R_f = Rot(axis, angle_f), ``motion`` with ``axis`` (unit, frame 0's camera
    coordinates, its sign making frame 1's angle positive) and ``angle_deg`` per frame.  The
    solutions of the solves of ``PASSES`` are merged (a solution several list, to 1e-7
    relative, once); the counts are the solves' sums."""
    m, _ = rays_of(points, times, camera, FRAMES, POINTS, ROW)
    points3, rotations, motion = [], [], []
    counts = np.zeros(3, dtype=int)
    for order, chart in PASSES:
        found, tracked = _one_pass(m, order, chart)
        counts += tracked
        for p3, rots, axis, angles in found:
            size = np.ptp(p3.reshape(-1, 3), axis=0).max()
            if any(np.max(np.abs(p3 - q)) <= 1e-7 * size for q in points3):
                continue
            sign = 1.0 if (angles[1] + 180) % 360 - 180 >= 0 else -1.0
            points3.append(p3)
            rotations.append(rots)
            wrapped = [float(sign * ((a + 180) % 360 - 180)) for a in angles]
            motion.append({"axis": (sign * axis).tolist(), "angle_deg": wrapped})
    n_paths, n_complex, n_failed = (int(c) for c in counts)
    return make_solutions(
        points3, rotations, motion, n_paths, n_complex, n_failed, (FRAMES, len(POINTS))
    )
