"""Section 4 on a row's poses: the whole curve from every frame's polyline.

Section 4 (``curve/section4.py``) takes rotations and translations directly (X_cam = R_f X + t_f);
a row gives them with the curve frame = frame 0's camera coordinates shifted to A: R_f the
row's rotation relative to frame 0 and t_f = (A's image, 0).  ``curve3d`` then comes out in frame
0's camera coordinates with A at z = 0, as for the paper's row.  The curve bundle is not run: it
refits the paper's free poses and would leave the row's motion model.  The end tangents of
``curve3d`` (a spline through its points) give alpha, beta, phi where no tangents were given.
"""

from __future__ import annotations

import numpy as np

from curverecon.curve import section4
from curverecon.errors import CurveReconError
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState, frame_rotations, points3


def end_tangents(curve3d: np.ndarray) -> np.ndarray:
    """(2, 3) unit tangents into the curve at A (its first point) and B (its last), from a
    quadratic fit to the first and last few points."""
    out = []
    for pts in (curve3d, curve3d[::-1]):
        k = min(6, len(pts))
        seg = pts[:k]
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(seg, axis=0), axis=1))])
        coef = np.polyfit(s, seg, 2 if k > 2 else 1)
        d = coef[-2]
        out.append(d / np.linalg.norm(d))
    return np.array(out)


def curve_on_poses(
    layout: Layout,
    state: RigidState,
    data: RigidData,
    curves: list[np.ndarray],
    tangents3: np.ndarray | None,
) -> tuple[np.ndarray | None, np.ndarray | None, list[str]]:
    """(curve3d (M, 3) or None, the tangents at A and B (2, 3) to take the shape's angles from,
    warnings)."""
    rot, _ = frame_rotations(layout, state, data.times)
    a = points3(layout, state, data.times)[:, 0]
    tra = np.column_stack([a[:, :2], np.zeros(len(a))])
    try:
        res = section4.reconstruct_curve(curves, rot, tra)
    except CurveReconError as exc:
        return None, tangents3, [f"section 4 could not place the curve on the row's poses ({exc})"]
    curve3d = np.asarray(res.points, float)
    if tangents3 is None:
        tangents3 = end_tangents(curve3d - curve3d[0])
    return curve3d, tangents3, list(res.warnings)
