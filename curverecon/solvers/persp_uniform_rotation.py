"""Perspective, uniform rotation, A and B, five equally spaced frames: parameter homotopy.

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): the difference
D_f = B_f - A_f lies in the plane through the camera centre and the image line A'_f B'_f, so
(m_Af x m_Bf) . D_f = 0 with m the rays, free of the depths.  Uniform rotation about an axis n
with equally spaced times makes D_f = Q^f D_0, Q = cayley(mu n) one time step's rotation, and
D_0 = b0 m_B0 - m_A0 (A's depth in frame 0 is 1): four equations in (n1, n2, mu, b0) for five
frames, as the seed's table says.  msolve counts 26 complex solutions (random and noise-free
instances; no symmetry: the chart n = (n1, n2, 1) and mu fix the rotation's sign), six frames
leave the truth alone.  No closed form was found, so the 26 solutions at generic complex rays
(``generated/persp_uniform_rotation_system.py``, found by monodromy) are tracked to the frames'
rays (:mod:`curverecon.solvers.homotopy`, on the straight-line kernels of
``generated/persp_uniform_rotation_kernel.py``: 2.5 times faster than the tables), the real ones
kept.  General times are not
polynomial (cos w t); the solver takes equally spaced times (a constant frame rate) and refuses
others.  The step angle is the principal one (|w dt| < 180 degrees): w + 360 k / dt degrees
fit the frames as well (aliasing), as for the orthographic row.
"""

from __future__ import annotations

from dataclasses import replace
from functools import cache

import numba
import numpy as np

from curverecon import jit_cache
from curverecon.errors import CurveReconError
from curverecon.generated import persp_uniform_rotation_kernel as kernel_module
from curverecon.generated import persp_uniform_rotation_system as system_module
from curverecon.solvers import homotopy
from curverecon.solvers.camera import Camera
from curverecon.solvers.persp_common import (
    CHART,
    cayley,
    homotopy_parameters,
    place,
    rays_of,
    real_solutions,
)
from curverecon.solvers.persp_common import solutions as make_solutions
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 5
POINTS: tuple[str, ...] = ("A", "B")
ROW = "persp_uniform_rotation"
SPACING_TOLERANCE = 1e-6
"""Largest deviation of a time step from the mean step, relative to it, taken as equal."""


@numba.njit(cache=True, nogil=True)
def _track_kernels(q0, q1, d, x_start, opts, plan, x_end, status, steps, t_end):  # type: ignore[no-untyped-def]
    """The homotopy tracker on the generated straight-line kernels
    (``generated/persp_uniform_rotation_kernel.py``, ``homotopy.track_generated``)."""
    k = kernel_module
    homotopy.track_generated(
        k.coefficients, k.coefficients_t, k.coefficient_rates, k.residual_jacobian,
        k.residual_jacobian_t, homotopy.loop_solve_pair, k.N_COEFFICIENTS,
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
    were written for the same system."""
    tables = homotopy.PolynomialSystem.from_module(system_module)
    k = kernel_module
    same = (k.UNKNOWNS, k.PARAMETERS) == (system_module.UNKNOWNS, system_module.PARAMETERS)
    if not same:
        return tables
    return replace(tables, tracker=_track_kernels, newton=_newton_kernels)


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Every real solution of five equally spaced frames of A, B in pixels (``points``
    (5, 2, 2), ``times`` (5,)): ``points3`` in camera coordinates (A's depth in frame 0 = 1),
    ``rotations`` R_f = Rot(axis, f w dt), ``motion`` with ``axis`` (unit, frame 0's camera
    coordinates, its sign making the rate positive), ``rate_deg`` (degrees per unit of t) and
    ``angle_deg`` per frame."""
    m, t = rays_of(points, times, camera, FRAMES, POINTS, ROW)
    steps = np.diff(t)
    if np.max(np.abs(steps - steps.mean())) > SPACING_TOLERANCE * steps.mean():
        raise CurveReconError(
            f"{ROW}: the minimal solver needs equally spaced times (a constant frame rate), got "
            f"{t.tolist()}"
        )
    target = homotopy_parameters(m, ((0, 1),))
    rows, n_paths, n_complex, n_failed = real_solutions(_system(), target)
    points3, rotations, motion = [], [], []
    for n1, n2, mu, b0 in rows[:, :4]:
        n = np.array([n1, n2, 1.0])
        step = cayley(mu * n)
        rots = np.array([CHART.T @ np.linalg.matrix_power(step, f) @ CHART for f in range(5)])
        d0 = b0 * m[0, 1] - m[0, 0]
        points3.append(place(m, rots, d0[None]))
        rotations.append(rots)
        angle = 2 * np.degrees(np.arctan(mu * np.linalg.norm(n)))
        axis = CHART.T @ n / np.linalg.norm(n) * (1.0 if angle >= 0 else -1.0)
        angle = abs(angle)  # (axis, angle) and (-axis, -angle) are one rotation: rate >= 0
        motion.append(
            {
                "axis": axis.tolist(),
                "rate_deg": float(angle / steps.mean()),
                "angle_deg": [float(angle * f) for f in range(FRAMES)],
            }
        )
    return make_solutions(
        points3, rotations, motion, n_paths, n_complex, n_failed, (FRAMES, len(POINTS))
    )
