"""Stereo, free motion, A and B, one frame: closed form (each point triangulated).

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): with camera 1 at
X1 = R X0 + t, a point seen at the rays m0 (camera 0) and m1 (camera 1) satisfies
lambda_1 m1 = R (lambda_0 m0) + t: three linear equations in the two depths
(``generated/section2_perspective.py``, ``stereo_linear``), consistent exactly when the epipolar
constraint holds; solved by least squares.  So one frame gives A and B in 3-D, metric in the
units of t, and with them the chord c = |AB|, as the seed's table says (2 points, 1 frame).  It
cannot give the tangents at A and B (alpha, beta, phi): two points say nothing about the curve
between them; those need the tangents or the curve's polylines in both views.  The free motion
plays no part in one frame; more frames give c again (its mean) and the motion between frames.
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.generated import section2_perspective as gen
from curverecon.solvers.camera import StereoRig
from curverecon.solvers.ortho_common import check_input
from curverecon.solvers.persp_common import solutions
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 1
POINTS: tuple[str, ...] = ("A", "B")
ROW = "stereo_free"
PARALLEL = 1e-12
"""Smallest sine of the angle between a point's two viewing rays (in camera 0's coordinates)
that is triangulated; below it the rays are parallel (a point at infinity or on the baseline)."""


def triangulate(m0: np.ndarray, m1: np.ndarray, rig: StereoRig) -> np.ndarray | None:
    """The point (camera 0 coordinates) seen at rays m0, m1, or None for parallel rays."""
    r, t = np.asarray(rig.R, dtype=float), np.asarray(rig.t, dtype=float)
    mat, rhs = gen.stereo_linear(*m0, *m1, *r.reshape(-1), *t)
    u, v = mat[:, 0], mat[:, 1]
    sine = np.linalg.norm(np.cross(u, v)) / (np.linalg.norm(u) * np.linalg.norm(v))
    if not sine > PARALLEL:
        return None
    (lam0, _), *_ = np.linalg.lstsq(mat, rhs[:, 0], rcond=None)
    return lam0 * m0


def solve(points: np.ndarray, times: np.ndarray, camera: StereoRig) -> RigidSolutions:
    """A and B of one stereo frame: ``points`` (1, 2, 2, 2) pixels as (frame, view, point, xy),
    view 0 camera 0's and view 1 camera 1's; ``times`` (1,).  ``points3`` (1, 1, 2, 3) in camera
    0's coordinates in the units of ``camera.t``; ``rotations`` the identity; ``motion`` {}.
    None listed when a point's rays are parallel."""
    if not isinstance(camera, StereoRig):
        raise CurveReconError(f"{ROW}: the solver needs a StereoRig (two cameras, R, t)")
    pts = np.asarray(points, dtype=float)
    if pts.shape != (FRAMES, 2, len(POINTS), 2):
        raise CurveReconError(
            f"{ROW}: the minimal solver needs points of shape (1, 2, 2, 2) (one frame, two views "
            f"of A, B), got {pts.shape}"
        )
    check_input(pts[:, 0], times, FRAMES, POINTS, ROW)
    check_input(pts[:, 1], times, FRAMES, POINTS, ROW)
    m0, m1 = camera.camera0.rays(pts[0, 0]), camera.camera1.rays(pts[0, 1])
    p3 = [triangulate(m0[i], m1[i], camera) for i in range(len(POINTS))]
    if any(p is None for p in p3):
        return solutions([], [], [], 1, 0, 0, (FRAMES, len(POINTS)))
    return solutions([np.array([p3])], [np.eye(3)[None]], [{}], 1, 0, 0, (0, 0))
