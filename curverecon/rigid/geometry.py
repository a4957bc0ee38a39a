"""From 3-D geometry (a minimal solver's or a simulator's) to a row's parameters.

``state_from_geometry`` takes every traceable point in every frame's camera coordinates and the
rotations relative to frame 0 (the ``RigidSolutions`` convention of ``curverecon/solvers``) and
returns the :class:`~curverecon.rigid.model.RigidState` of a motion model: the axis and angles
from the rotations' logarithms, the rate by least squares on the angles, the force field's mass
centre and parabola by linear least squares (the images are linear in them once the rotations
are known), tangent directions from the image angles (each frame's angle puts the direction in
one plane: the least singular vector of the stacked plane normals).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState, axis_angles


def rotation_log(rot: np.ndarray) -> np.ndarray:
    """(N, 3) rotation vectors of (N, 3, 3) rotations (radians)."""
    return Rotation.from_matrix(np.asarray(rot, float)).as_rotvec()


def axis_and_angles(rot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The common axis n (3,) and every frame's angle about it (N,) of rotations about one axis
    (least squares: n the principal direction of the rotation vectors)."""
    v = rotation_log(rot)
    _, _, vt = np.linalg.svd(v, full_matrices=False)
    n = vt[0]
    ang = v @ n
    if np.sum(ang) < 0:
        n, ang = -n, -ang
    return n, ang


def fit_rate(times: np.ndarray, angles: np.ndarray) -> float:
    """Rate w (radians per unit of t) with angles = w (t - t_0) mod 2 pi: consecutive
    differences unwrapped, then least squares through the origin."""
    t = np.asarray(times, float) - float(times[0])
    steps = np.angle(np.exp(1j * np.diff(angles)))
    unwrapped = np.concatenate([[0.0], np.cumsum(steps)])
    return float(np.dot(t, unwrapped) / max(np.dot(t, t), 1e-300))


def tangent_directions(data: RigidData, rot: np.ndarray) -> np.ndarray:
    """(2, 2) polar, azimuth of the body tangents at A and B from the image angles: frame f's
    angle psi puts R_f u in the plane spanned by (cos psi, sin psi, 0) and the viewing axis."""
    out = np.zeros((2, 2))
    for j in range(2):
        psi = data.angles[:, j]
        normals = np.column_stack([-np.sin(psi), np.cos(psi), np.zeros_like(psi)])
        rows = np.einsum("fi,fij->fj", normals, rot)
        u = np.linalg.svd(rows)[2][-1]
        out[j] = [np.arccos(np.clip(u[2], -1.0, 1.0)), np.arctan2(u[1], u[0])]
    return out


def _force_field(points3: np.ndarray, rot: np.ndarray, times: np.ndarray, obs: np.ndarray):
    """(G's body vector relative to A (3,), parabola (3, 2)): linear least squares of
    x_k,f - [R_f X_k]_xy = g(t_f) - [R_f G]_xy over every point and frame."""
    n, p = obs.shape[:2]
    body = points3[0] - points3[0, :1]
    t = np.asarray(times, float)
    rows, rhs = [], []
    for f in range(n):
        for k in range(p):
            for d in range(2):
                row = np.zeros(9)
                row[:3] = rot[f, d]
                row[3 + d], row[5 + d], row[7 + d] = 1.0, t[f], 0.5 * t[f] ** 2
                rows.append(row)
                rhs.append(obs[f, k, d] - (rot[f, d] @ body[k]) + 0.0)
    sol = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)[0]
    # x = g(t) + [R (X - G)]_xy  with X - G = body_k - gvec: the row above has +R gvec' where
    # gvec' = -gvec (G relative to A, negated)
    return -sol[:3], sol[3:].reshape(3, 2)


def set_motion(layout: Layout, times: np.ndarray, rotations: np.ndarray, state: RigidState) -> None:
    """``state``'s axis and rate (uniform rotation) or angles (fixed axis, frame 0's angle 0)
    from the rotations relative to frame 0 (N, 3, 3); other motions leave it as it is."""
    if layout.motion in ("uniform-rotation", "fixed-axis"):
        n, ang = axis_and_angles(rotations)
        state.axis = axis_angles(n)
        if layout.motion == "uniform-rotation":
            state.rate = fit_rate(times, ang)
        else:
            state.angles = ang - ang[0]


def state_from_geometry(
    layout: Layout,
    data: RigidData,
    points3: np.ndarray,
    rotations: np.ndarray,
) -> RigidState:
    """The row's state from every point's 3-D position in every frame (N, P, 3; camera
    coordinates, any depth shift) and the rotations relative to frame 0 (N, 3, 3)."""
    pts = np.asarray(points3, float)
    rot = np.asarray(rotations, float)
    rel = pts[0] - pts[0, :1]
    state = RigidState(body=rel[1:].copy())
    if layout.tangents:
        state.directions = tangent_directions(data, rot)
    set_motion(layout, data.times, rot, state)
    if layout.free_rotations:
        state.rotations = rot.copy()
    if layout.centred:
        gvec, parabola = _force_field(pts, rot, data.times, data.points)
        state.body = rel - gvec
        state.parabola = parabola
    else:
        state.shifts = pts[:, 0, :2].copy()
    return state
