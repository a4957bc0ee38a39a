"""Standardised residuals and Jacobians of the perspective and stereo rows (pinhole cameras).

The generated model (``generated/rigid_pinhole.py``, derivations/rigid_pinhole.py) gives each
point's pixel position X = T + R q projected, and each tangent's image angle, with Jacobians in
the rotation's left increment w, the body vector q and the position T.  Per frame the residual
vector is, for every view (camera 0, then camera 1 of a stereo pair), the points' (x, y) then
the tangent angles at A and B, predicted minus measured, divided by the point noise (pixels) or
the tangent noise (radians; wrapped to (-pi/2, pi/2]).  Camera 1 sees X1 = Rs X + ts, i.e. the
same model with R1 = Rs R and T1 = Rs T + ts, so its Jacobians in w and T are camera 1's times
Rs.  Global and local columns follow ``Layout`` (``rigid.model``): the reference position T_f
(three locals) or the force field's parabola (nine globals), then the rotation's parameters
through ``measurements.rotation_chain``.  Gauge-fixed parameters (``fixed_locals``,
``fixed_globals``) get zero columns.
"""

from __future__ import annotations

import numpy as np

from curverecon.generated import rigid_pinhole as gp
from curverecon.model.observations import wrap_line_angle
from curverecon.rigid.measurements import (
    RigidData,
    fixed_globals,
    fixed_locals,
    rotation_args,
    rotation_chain,
)
from curverecon.rigid.model import (
    Layout,
    RigidState,
    body_vectors,
    frame_positions,
    frame_rotations,
)


def views(data: RigidData) -> list[tuple]:
    """[(camera, Rs (3, 3), ts (3,), points (N, P, 2), angles (N, 2) or None)] per view."""
    if data.rig is None:
        return [(data.camera, np.eye(3), np.zeros(3), data.points, data.angles)]
    rig = data.rig
    rs, ts = np.asarray(rig.R, float), np.asarray(rig.t, float)
    return [
        (rig.camera0, np.eye(3), np.zeros(3), data.points, data.angles),
        (rig.camera1, rs, ts, data.points1, data.angles1),
    ]


def _measured(layout: Layout, data: RigidData) -> np.ndarray:
    """(N, m) the measurements in the residuals' order."""
    cols = []
    for _, _, _, pts, ang in views(data):
        cols.append(pts.reshape(len(pts), -1))
        if layout.tangents:
            cols.append(ang)
    return np.concatenate(cols, axis=1)


def _point_rows(layout: Layout) -> np.ndarray:
    """(m,) True for the rows of point coordinates (the rest are tangent angles)."""
    per = [True] * (2 * len(layout.points)) + [False] * (2 if layout.tangents else 0)
    return np.array(per * layout.views)


def pinhole_predict(layout: Layout, state: RigidState, times: np.ndarray, data: RigidData):
    """(N, m) predicted pixels and tangent angles (radians)."""
    return _evaluate(layout, state, data, times, jacobians=False)[0]


def pinhole_residuals(layout: Layout, state: RigidState, data: RigidData) -> np.ndarray:
    """(N, m) standardised residuals (prediction - measurement) / sigma."""
    pred = _evaluate(layout, state, data, data.times, jacobians=False)[0]
    return _standardise(layout, pred, data)


def _standardise(layout: Layout, pred: np.ndarray, data: RigidData) -> np.ndarray:
    rows = _point_rows(layout)
    diff = pred - _measured(layout, data)
    r = np.empty_like(diff)
    r[:, rows] = diff[:, rows] / data.point_sigma
    r[:, ~rows] = wrap_line_angle(diff[:, ~rows]) / data.tangent_sigma
    return r


def pinhole_residuals_and_jacobians(
    layout: Layout, state: RigidState, data: RigidData
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(r (N, m), J_global (N, m, G), J_local (N, m, L)), standardised (module docstring)."""
    pred, jg, jl = _evaluate(layout, state, data, data.times, jacobians=True)
    r = _standardise(layout, pred, data)
    rows = _point_rows(layout)
    for j in (jg, jl):
        j[:, rows] /= data.point_sigma
        j[:, ~rows] /= data.tangent_sigma
    jg[:, :, fixed_globals(layout)] = 0.0
    fl = fixed_locals(layout, data.n_frames)
    f, k = np.nonzero(fl)
    jl[f, :, k] = 0.0
    return r, jg, jl


def _position_chain(layout: Layout, jt: np.ndarray, t: np.ndarray, jg, jl, rows) -> None:
    """Add d(rows)/dT (N, r, 3) into the position's columns (locals, or the parabola)."""
    if not layout.centred:
        jl[:, rows, 0:3] += jt
        return
    g0 = 3 * layout.n_body + (4 if layout.tangents else 0)
    for i, coef in enumerate((np.ones_like(t), t, 0.5 * t * t)):
        jg[:, rows, g0 + 3 * i : g0 + 3 * i + 3] += jt * coef[:, None, None]


def _evaluate(layout, state, data, times, jacobians: bool):
    """(prediction (N, m), J_global, J_local) unstandardised (Jacobians None unless asked)."""
    n, m = len(times), layout.n_measurements
    rot, inc = frame_rotations(layout, state, times)
    pos = frame_positions(layout, state, times)
    q = body_vectors(layout, state)
    t = np.asarray(times, float)
    pred = np.zeros((n, m))
    jg = np.zeros((n, m, layout.n_global)) if jacobians else None
    jl = np.zeros((n, m, layout.n_local)) if jacobians else None
    per_view = m // layout.views
    p2 = 2 * len(layout.points)
    for v, (cam, rs, ts, _, _) in enumerate(views(data)):
        o = v * per_view
        rot_v, pos_v = rs @ rot, pos @ rs.T + ts
        intr = (float(cam.focal_px), *map(float, cam.principal_point))
        for k in range(len(layout.points)):
            p, jw, jq, jt = gp.pinhole_point(*rotation_args(rot_v), *q[k], *pos_v.T, *intr)
            rows = slice(o + 2 * k, o + 2 * k + 2)
            pred[:, rows] = p
            if jacobians:
                _chain(layout, (jw @ rs, jq, jt @ rs), k, inc, t, jg, jl, rows)
        if layout.tangents:
            for j in range(2):
                psi, tw, tq, tt, tu = gp.pinhole_tangent(
                    *rotation_args(rot_v), *q[j], *pos_v.T, *state.directions[j]
                )
                row = o + p2 + j
                pred[:, row] = psi
                if jacobians:
                    c0 = 3 * layout.n_body + 2 * j
                    jg[:, row, c0 : c0 + 2] += tu
                    jac = (tw[:, None] @ rs, tq[:, None], tt[:, None] @ rs)
                    _chain(layout, jac, j, inc, t, jg, jl, slice(row, row + 1))
    return pred, jg, jl


def _chain(layout, jac, k, inc, t, jg, jl, rows) -> None:
    """Add one point's Jacobians (in w, q, T; each (N, r, 3)) into the columns."""
    jw, jq, jt = jac
    b = k if layout.centred else k - 1
    if b >= 0:
        jg[:, rows, 3 * b : 3 * b + 3] += jq
    _position_chain(layout, jt, t, jg, jl, rows)
    for d, row in enumerate(range(rows.start, rows.stop)):
        rotation_chain(layout, jw[:, d], inc, t, jg, jl, row)
