"""Section 4 on a row's poses: the whole curve from every frame's polyline.

Section 4 (``curve/section4.py``) takes rotations and translations directly (X_cam = R_f X + t_f);
a row gives them with the curve frame = frame 0's camera coordinates shifted to A: R_f the
row's rotation relative to frame 0 and t_f = (A's image, 0).  ``curve3d`` then comes out in frame
0's camera coordinates with A at z = 0, as for the paper's row.  The curve alone is fitted to
every polyline with the row's poses fixed (:func:`fit_spline`: a clamped cubic
B-spline through A and B, every other control point free, the curve bundle's residuals and
truncated-SVD Gauss-Newton, knot spans halved while the BIC improves), started from section 4's
points.  With free rotations (the free row, the force field) the curve bundle then runs from
those poses and that curve (its per-frame pose is those rows' own: a rotation and an image
shift), A' and B' its end points; with an axis the poses stay the motion model's.  The end
tangents of ``curve3d`` give alpha, beta, phi where no tangents were given.

Tuned numbers: ``K_START`` control points to start, at most ``K_MAX`` (the curve bundle's range).
"""

from __future__ import annotations

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve import section4
from curverecon.curve.lm import MAX_ITER, gauss_newton_tsvd
from curverecon.curve.residuals import Problem, bic
from curverecon.curve.spline import Basis
from curverecon.errors import CurveReconError
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState, frame_rotations, points3

K_START = 8
K_MAX = 43
SAMPLES = 200
SIGMA_FLOOR = 0.1
"""The fit's point noise at least this (px): with the noise stated near zero (noise-free input)
the Gauss-Newton steps stalled at k = 13, 0.07 px RMS, where 0.1 reached k = 43 and 5e-6 of the
length (free row, seed 5, 12 frames, 201-point polylines)."""


def fit_spline(
    curves: list[np.ndarray], m: np.ndarray, b: np.ndarray, start: np.ndarray, sigma: float
) -> np.ndarray:
    """(SAMPLES, 3) the fitted curve in frame 0's camera coordinates; m, b: (N, 3, 3), (N, 3)
    frame 0 camera -> frame f camera; start: (M, 3) a curve from A to B near it."""
    polys = [pl.as_polyline(c, name=f"frame {i} curve") for i, c in enumerate(curves)]
    a, bpt = start[0], start[-1]
    seg = np.linalg.norm(np.diff(start, axis=0), axis=1)
    u0 = np.concatenate([[0.0], np.cumsum(seg)]) / max(seg.sum(), 1e-300)
    best = None
    k = K_START
    pts, u = start, u0
    while k <= K_MAX:
        prob = Problem(polys, sigma, k, None, None, 1.0, 1.0)
        nb = Basis(k).values(u)
        rhs = pts - np.outer(nb[:, 0], a) - np.outer(nb[:, -1], bpt)
        inner = np.linalg.lstsq(nb[:, 1:-1], rhs, rcond=None)[0]
        # the Jacobian's columns: every control coordinate but P0's z; P_1 .. P_{K-2} free
        cols = np.arange(3, 3 * (k - 1)) - 1

        def ctrl_of(p, k=k):
            ctrl = np.zeros((k, 3))
            ctrl[0], ctrl[-1] = a, bpt
            ctrl[1:-1] = p.reshape(k - 2, 3)
            return ctrl

        def residual(p, jac=True, prob=prob, ctrl_of=ctrl_of, cols=cols):
            r, j, rms = prob.residuals(ctrl_of(p), m, b, jac=jac, poses=False)
            return r, (j[:, cols] if jac else None), rms

        p, _ = gauss_newton_tsvd(residual, inner.ravel(), MAX_ITER, 1e-4, 0.0)
        ctrl = ctrl_of(p)
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        crit = bic(prob, rms, 3 * (k - 2))
        if best is not None and crit >= best[1]:
            break
        best = (ctrl, crit)
        u = np.linspace(0.0, 1.0, 20 * k)
        pts = Basis(k).values(u) @ ctrl
        k = 2 * k - 3
    return Basis(len(best[0])).values(np.linspace(0.0, 1.0, SAMPLES)) @ best[0]


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


def planar_body(layout: Layout) -> bool:
    """Free rotations of a planar body without tangents (A, B, C; or A, B and the mass centre):
    each frame's depth reversal fits the points equally well, only the curve tells them apart."""
    n_points = len(layout.points) + (1 if layout.centred else 0)
    return layout.free_rotations and not layout.tangents and n_points == 3


def reversed_rotations(layout: Layout, state: RigidState) -> np.ndarray:
    """(N, 3, 3) every frame's other rotation S R_f H (S = diag(1, 1, -1), H the reflection in
    the body's plane): the same image of every point of the plane, the depths reversed."""
    from curverecon.rigid.model import body_vectors

    q = body_vectors(layout, state)
    normal = np.cross(q[1] - q[0], q[-1] - q[0]) if not layout.centred else np.cross(q[0], q[1])
    normal /= np.linalg.norm(normal)
    h = np.eye(3) - 2.0 * np.outer(normal, normal)
    return np.diag([1.0, 1.0, -1.0]) @ state.rotations @ h


def _misfit(curve0: np.ndarray, rot: np.ndarray, a0: np.ndarray, af: np.ndarray, poly) -> float:
    """Mean distance from the curve (frame 0 coordinates) seen in a frame to its polyline."""
    x = ((curve0 - a0) @ rot.T)[:, :2] + af[:2]
    return float(np.mean(np.min(np.linalg.norm(x[:, None] - poly[None], axis=2), axis=1)))


def choose_depth_branches(
    layout: Layout, state: RigidState, data: RigidData, curves: list[np.ndarray], curve0
) -> tuple[RigidState, int]:
    """The state with every frame (but frame 0) on the depth branch whose view of the curve
    ``curve0`` lies closer to its polyline; (state, number of frames switched)."""
    alt = reversed_rotations(layout, state)
    a = points3(layout, state, data.times)[:, 0]
    out = state.copy()
    switched = 0
    for f in range(1, data.n_frames):
        poly = np.asarray(curves[f], float)
        if _misfit(curve0, alt[f], a[0], a[f], poly) < _misfit(
            curve0, state.rotations[f], a[0], a[f], poly
        ):
            out.rotations[f] = alt[f]
            switched += 1
    return out, switched


def curve_on_poses(
    layout: Layout,
    state: RigidState,
    data: RigidData,
    curves: list[np.ndarray],
    tangents3: np.ndarray | None,
    sigma: float = 1.0,
) -> tuple[np.ndarray | None, np.ndarray | None, list[str], RigidState]:
    """(curve3d (M, 3) or None, the tangents at A and B (2, 3) to take the shape's angles from,
    warnings, the state with each frame on the depth branch the curve chose)."""
    rot, _ = frame_rotations(layout, state, data.times)
    a = points3(layout, state, data.times)[:, 0]
    tra = np.column_stack([a[:, :2], np.zeros(len(a))])
    try:
        res = section4.reconstruct_curve(curves, rot, tra)
        for _ in range(2 if planar_body(layout) else 0):
            state, switched = choose_depth_branches(layout, state, data, curves, res.points)
            if not switched:
                break
            rot = state.rotations
            res = section4.reconstruct_curve(curves, rot, tra)
    except CurveReconError as exc:
        warn = f"section 4 could not place the curve on the row's poses ({exc})"
        return None, tangents3, [warn], state
    curve3d = np.asarray(res.points, float)
    m = rot
    b = tra - np.einsum("fij,j->fi", rot, tra[0])
    try:
        curve3d = fit_spline(curves, m, b, curve3d, max(sigma, SIGMA_FLOOR))
    except (CurveReconError, np.linalg.LinAlgError, ValueError) as exc:
        return curve3d, tangents3, [*res.warnings, f"the curve fit failed ({exc})"], state
    warnings = list(res.warnings)
    if layout.free_rotations:
        curve3d = _bundle_curve(curves, rot, tra, curve3d, data, sigma, warnings)
    if tangents3 is None:
        tangents3 = end_tangents(curve3d - curve3d[0])
    return curve3d, tangents3, warnings, state


def _bundle_curve(curves, rot, tra, curve3d, data: RigidData, sigma: float, warnings: list):
    """Free rotations (the free row, the force field): the curve bundle (``curve.joint``) from
    the row's poses and the fixed-pose curve, A' and B' as its end points; its curve, or
    ``curve3d`` where it fails.  Its poses (a rotation and an image shift per frame, the
    free row's own parameters) are refitted to the polylines too, which the points alone
    leave a few pixels' worth uncertain (force field, 20 frames, 0.5 px: the curve's error
    from 1.3 % to 0.4 % of its length on a bench scene); the answer's poses stay the row's."""
    from curverecon.curve.joint import bundle_adjust

    try:
        br = bundle_adjust(
            curves, rot, tra, curve3d, ends=data.points[:, :2], point_sigma=max(sigma, SIGMA_FLOOR)
        )
    except (CurveReconError, np.linalg.LinAlgError, ValueError) as exc:
        warnings.append(f"the curve bundle failed on the row's poses ({exc}): poses fixed")
        return curve3d
    if br.stopped or not np.isfinite(br.cost):
        return curve3d
    return np.asarray(br.curve_points(SAMPLES), float)
