"""Standardised residuals of a row and their Jacobians, from the generated model.

Per frame the residual vector is (x_A, y_A, x_B, y_B, ..., psi_A, psi_B) predicted minus measured,
points divided by the point noise, angles (wrapped to (-pi/2, pi/2]: a tangent is a line) by the
tangent noise.  The Jacobians come from ``generated/rigid_model.py`` (derivations/rigid_model.py)
and the chain rule through the motion model: a rotation parameter p of the axis motions enters as
d(prediction)/dp = d(prediction)/dw . w_p (w the left increment of the frame's rotation).

Global columns follow ``Layout.global_names()``; local columns per frame are (sx, sy) for every
row but the force field, then (w1, w2, w3) for free rotations, then theta for the fixed axis.
Frame 0's rotation parameters are fixed (R_0 = I, theta_0 = 0): their columns are zero.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.generated import rigid_model as gm
from curverecon.model.observations import wrap_line_angle
from curverecon.rigid.model import (
    Layout,
    RigidState,
    body_vectors,
    frame_rotations,
    frame_shifts,
    rodrigues,
)


@dataclass
class RigidData:
    """The measurements of one row: times (N,), points (N, P, 2) in ``Layout.points`` order,
    tangent angles (N, 2) at A and B (radians) or None, and the noise (input units, radians).
    Pinhole rows add the ``camera`` (perspective) or the ``rig`` (stereo, whose camera 1 sees
    ``points1`` and ``angles1`` as above; the fields above are camera 0's)."""

    times: np.ndarray
    points: np.ndarray
    angles: np.ndarray | None
    point_sigma: float
    tangent_sigma: float
    camera: object | None = None
    rig: object | None = None
    points1: np.ndarray | None = None
    angles1: np.ndarray | None = None

    @property
    def n_frames(self) -> int:
        return len(self.times)

    def subset(self, keep: np.ndarray) -> RigidData:
        return RigidData(
            self.times[keep],
            self.points[keep],
            None if self.angles is None else self.angles[keep],
            self.point_sigma,
            self.tangent_sigma,
            self.camera,
            self.rig,
            None if self.points1 is None else self.points1[keep],
            None if self.angles1 is None else self.angles1[keep],
        )


def rotation_args(rot: np.ndarray) -> tuple[np.ndarray, ...]:
    return tuple(rot[:, i, j] for i in range(3) for j in range(3))


def predict(layout: Layout, state: RigidState, times: np.ndarray) -> np.ndarray:
    """(N, m) predicted measurements (points in input units, then tangent angles in radians).
    Orthographic rows only (pinhole rows: ``rigid.pinhole``)."""
    rot, _ = frame_rotations(layout, state, times)
    shift = frame_shifts(layout, state, times)
    q = body_vectors(layout, state)
    cols = []
    for k in range(len(layout.points)):
        pred, _, _ = gm.point_prediction(*rotation_args(rot), *q[k], shift[:, 0], shift[:, 1])
        cols.append(np.asarray(pred, float))
    if layout.tangents:
        for j in range(2):
            psi = gm.tangent_prediction(*rotation_args(rot), *state.directions[j])[0]
            cols.append(np.asarray(psi, float)[:, None])
    return np.concatenate(cols, axis=1)


def residuals(layout: Layout, state: RigidState, data: RigidData) -> np.ndarray:
    """(N, m) standardised residuals (prediction - measurement) / sigma."""
    if layout.pinhole:
        from curverecon.rigid.pinhole import pinhole_residuals

        return pinhole_residuals(layout, state, data)
    pred = predict(layout, state, data.times)
    p = len(layout.points)
    r = np.empty_like(pred)
    r[:, : 2 * p] = (pred[:, : 2 * p] - data.points.reshape(len(pred), -1)) / data.point_sigma
    if layout.tangents:
        r[:, 2 * p :] = wrap_line_angle(pred[:, 2 * p :] - data.angles) / data.tangent_sigma
    return r


def rotation_chain(layout: Layout, jw: np.ndarray, inc: np.ndarray | None, times, jg, jl, row):
    """Add d(row)/dw (N, 3) through the rotation's parameters into the global / local columns."""
    g0 = 3 * layout.n_body + (4 if layout.tangents else 0)
    if layout.motion == "uniform-rotation":
        jg[:, row, g0] += np.einsum("fk,fk->f", jw, inc[:, 0])
        jg[:, row, g0 + 1] += np.einsum("fk,fk->f", jw, inc[:, 1])
        dt = np.asarray(times, float) - float(times[0])
        jg[:, row, g0 + 2] += np.einsum("fk,fk->f", jw, inc[:, 2]) * dt
    elif layout.motion == "fixed-axis":
        jg[:, row, g0] += np.einsum("fk,fk->f", jw, inc[:, 0])
        jg[:, row, g0 + 1] += np.einsum("fk,fk->f", jw, inc[:, 1])
        jl[1:, row, layout.angle_local] += np.einsum("fk,fk->f", jw[1:], inc[1:, 2])
    elif layout.free_rotations:
        l0 = layout.rotation_local
        jl[1:, row, l0 : l0 + 3] += jw[1:]


def residuals_and_jacobians(
    layout: Layout, state: RigidState, data: RigidData
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(r (N, m), J_global (N, m, G), J_local (N, m, L)), standardised (see the module doc)."""
    if layout.pinhole:
        from curverecon.rigid.pinhole import pinhole_residuals_and_jacobians

        return pinhole_residuals_and_jacobians(layout, state, data)
    times = data.times
    n, m = data.n_frames, layout.n_measurements
    rot, inc = frame_rotations(layout, state, times)
    shift = frame_shifts(layout, state, times)
    q = body_vectors(layout, state)
    jg = np.zeros((n, m, layout.n_global))
    jl = np.zeros((n, m, layout.n_local))
    pred = np.zeros((n, m))
    t = np.asarray(times, float)
    for k in range(len(layout.points)):
        p, jw, jq = gm.point_prediction(*rotation_args(rot), *q[k], shift[:, 0], shift[:, 1])
        rows = slice(2 * k, 2 * k + 2)
        pred[:, rows] = p
        b = k if layout.centred else k - 1
        if b >= 0:
            jg[:, rows, 3 * b : 3 * b + 3] = jq
        if layout.centred:
            g0 = 3 * layout.n_body + (4 if layout.tangents else 0)
            for d in range(2):
                jg[:, 2 * k + d, g0 + d] = 1.0
                jg[:, 2 * k + d, g0 + 2 + d] = t
                jg[:, 2 * k + d, g0 + 4 + d] = 0.5 * t * t
        else:
            jl[:, 2 * k, 0] = 1.0
            jl[:, 2 * k + 1, 1] = 1.0
        for d in range(2):
            rotation_chain(layout, np.asarray(jw)[:, d], inc, times, jg, jl, 2 * k + d)
    p2 = 2 * len(layout.points)
    if layout.tangents:
        for j in range(2):
            psi, jw, ju, _ = gm.tangent_prediction(*rotation_args(rot), *state.directions[j])
            pred[:, p2 + j] = psi
            c0 = 3 * layout.n_body + 2 * j
            jg[:, p2 + j, c0 : c0 + 2] = ju
            rotation_chain(layout, np.asarray(jw), inc, times, jg, jl, p2 + j)
    r = np.empty((n, m))
    r[:, :p2] = (pred[:, :p2] - data.points.reshape(n, -1)) / data.point_sigma
    jg[:, :p2] /= data.point_sigma
    jl[:, :p2] /= data.point_sigma
    if layout.tangents:
        r[:, p2:] = wrap_line_angle(pred[:, p2:] - data.angles) / data.tangent_sigma
        jg[:, p2:] /= data.tangent_sigma
        jl[:, p2:] /= data.tangent_sigma
    return r, jg, jl


def fixed_locals(layout: Layout, n: int) -> np.ndarray:
    """(N, L) True for the local parameters fixed by the gauge (frame 0's rotation)."""
    out = np.zeros((n, layout.n_local), bool)
    l0 = layout.rotation_local
    if layout.free_rotations:
        out[0, l0 : l0 + 3] = True
    if layout.motion == "fixed-axis":
        out[0, layout.angle_local] = True
    if layout.projection == "perspective" and not layout.centred:
        out[0, 2] = True  # A's depth in frame 0 is the unit
    return out


def fixed_globals(layout: Layout) -> np.ndarray:
    """(G,) True for the globals fixed by the gauge: the perspective force field's g0_z (the
    scale; every other row fixes a local, ``fixed_locals``)."""
    out = np.zeros(layout.n_global, bool)
    if layout.projection == "perspective" and layout.centred:
        out[3 * layout.n_body + (4 if layout.tangents else 0) + 2] = True
    return out


def apply_step(
    layout: Layout, state: RigidState, dg: np.ndarray, dl: np.ndarray, times: np.ndarray
) -> RigidState:
    """The state moved by a step (global dg (G,), local dl (N, L)); rotations by left
    increments exp([dw]_x) R."""
    s = state.copy()
    i = 3 * layout.n_body
    s.body = s.body + dg[:i].reshape(-1, 3)
    if layout.tangents:
        s.directions = s.directions + dg[i : i + 4].reshape(2, 2)
        i += 4
    if layout.motion in ("uniform-rotation", "fixed-axis"):
        s.axis = s.axis + dg[i : i + 2]
        if layout.motion == "uniform-rotation":
            s.rate = float(s.rate + dg[i + 2])
    k = layout.position_size
    if layout.centred:
        s.parabola = s.parabola + dg[i : i + 3 * k].reshape(3, k)
    if not layout.centred and layout.pinhole:
        s.translations = s.translations + dl[:, :3]
    elif not layout.centred:
        s.shifts = s.shifts + dl[:, :2]
    if layout.free_rotations:
        l0 = layout.rotation_local
        s.rotations = rodrigues(dl[:, l0 : l0 + 3]) @ s.rotations
    if layout.motion == "fixed-axis":
        s.angles = s.angles + dl[:, layout.angle_local]
    return s
