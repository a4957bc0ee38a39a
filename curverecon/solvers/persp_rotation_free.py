"""Perspective, rotation-free motion, A and B, two frames: closed form (one linear solve).

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): without rotation
the difference D = B - A is the same in every frame, D_f = lambda_Bf m_Bf - lambda_Af m_Af with
m the rays (normalised coordinates) and lambda the depths.  With lambda_A0 = 1 (the contract's
scale) two frames give three linear equations in (lambda_B0, lambda_A1, lambda_B1)
(``generated/section2_perspective.py``, ``rotation_free_linear``): one solution, as the seed's
table says (2 points, 2 frames; msolve's count is 1 on random and noise-free instances).
Degenerate when the rays m_B0, m_A1, m_B1 are coplanar (e.g. the body translates along AB, or
A and B keep their image positions): then no isolated solution and none is listed.
"""

from __future__ import annotations

import numpy as np

from curverecon.generated import section2_perspective as gen
from curverecon.solvers.camera import Camera
from curverecon.solvers.persp_common import rays_of, solutions
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 2
POINTS: tuple[str, ...] = ("A", "B")
ROW = "persp_rotation_free"
SINGULAR = 1e-12
"""Smallest |det| of the 3 x 3 system, relative to the product of its column norms, that is
solved (below it the rays are coplanar to rounding: no isolated solution)."""


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """The solution of two frames of A, B in pixels (``points`` (2, 2, 2), ``times`` (2,)
    increasing): ``points3`` (1, 2, 2, 3) in camera coordinates, A's depth in frame 0 = 1;
    ``rotations`` the identity; ``motion`` {} (the model has no parameters)."""
    m, _ = rays_of(points, times, camera, FRAMES, POINTS, ROW)
    mat, rhs = gen.rotation_free_linear(*m.reshape(-1))
    scale = np.prod(np.linalg.norm(mat, axis=0))
    if not abs(np.linalg.det(mat)) > SINGULAR * scale:
        return solutions([], [], [], 1, 0, 0, (FRAMES, len(POINTS)))
    lb0, la1, lb1 = np.linalg.solve(mat, rhs[:, 0])
    p3 = np.array([[m[0, 0], lb0 * m[0, 1]], [la1 * m[1, 0], lb1 * m[1, 1]]])
    return solutions([p3], [np.array([np.eye(3)] * FRAMES)], [{}], 1, 0, 0, (0, 0))
