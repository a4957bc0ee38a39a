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
are tracked to the frames' rays (:mod:`curverecon.solvers.homotopy`) and the real ones kept.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from curverecon.generated import persp_fixed_axis_system as system_module
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

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B", "C")
ROW = "persp_fixed_axis_3pt"


@cache
def _system() -> homotopy.PolynomialSystem:
    """The tracked system (the generated tables)."""
    return homotopy.PolynomialSystem.from_module(system_module)


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Every real solution of three frames of A, B, C in pixels (``points`` (3, 3, 2),
    ``times`` (3,) increasing): ``points3`` in camera coordinates (A's depth in frame 0 = 1),
    ``rotations`` R_f = Rot(axis, angle_f), ``motion`` with ``axis`` (unit, frame 0's camera
    coordinates, its sign making frame 1's angle positive) and ``angle_deg`` per frame."""
    m, _ = rays_of(points, times, camera, FRAMES, POINTS, ROW)
    target = homotopy_parameters(m, ((0, 1), (0, 2), (1, 2)))
    rows, n_paths, n_complex, n_failed = real_solutions(_system(), target)
    points3, rotations, motion = [], [], []
    for b0, c0, n1, n2, *mus in rows:
        n = np.array([n1, n2, 1.0])
        rots = np.array([np.eye(3)] + [CHART.T @ cayley(mu * n) @ CHART for mu in mus])
        diffs = np.array([b0 * m[0, 1] - m[0, 0], c0 * m[0, 2] - m[0, 0]])
        points3.append(place(m, rots, diffs))
        rotations.append(rots)
        angles = [0.0] + [2 * np.degrees(np.arctan(mu * np.linalg.norm(n))) for mu in mus]
        sign = 1.0 if angles[1] >= 0 else -1.0  # (axis, angles) and (-axis, -angles) agree
        axis = CHART.T @ n / np.linalg.norm(n) * sign
        motion.append({"axis": axis.tolist(), "angle_deg": [sign * a for a in angles]})
    return make_solutions(
        points3, rotations, motion, n_paths, n_complex, n_failed, (FRAMES, len(POINTS))
    )
