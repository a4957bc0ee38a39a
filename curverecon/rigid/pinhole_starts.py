"""Start states of the perspective and stereo rows, and LO-RANSAC over their minimal samples.

* Stereo: every point of every frame triangulated (the closed form of
  ``solvers/stereo_free.py``, every frame at once), the body from one frame, each frame's
  rotation from its triangulated points (:func:`rotations_from_points3`), the motion model's
  parameters from the rotations (``rigid.geometry``); LO-RANSAC draws one frame (the minimal
  sample) as the body.
* Perspective, rotation-free: the all-frame linear solve lambda_Pf m_Pf - lambda_Af m_Af = D_P
  (lambda_A0 = 1), the closed form of ``solvers/persp_rotation_free.py`` on every frame;
  LO-RANSAC draws two frames.
* Perspective, uniform rotation at equally spaced times: LO-RANSAC over five frames in
  arithmetic progression through ``solvers/persp_uniform_rotation.py`` (parameter homotopy),
  each solution extended to every frame by its rate (A's depth from the chord, ``place``).
* Every other perspective row (and the uniform rotation beside its samples): weak perspective.
  The orthographic row on the rays' normalised coordinates (pixels -> (x - cx) / f) gives the
  body, the rotations and the image path at unit depth; both mirror images (the orthographic
  ambiguity a pinhole resolves) become starts, A at depth 1 + its relative depth (the free row
  also from the orthographic row's all-frame starts, ``FREE_STARTS``).  The fixed
  axis with three frames (too few for the orthographic row) uses
  ``solvers/persp_fixed_axis_3pt.py``; the force field with A and B adds the minima of its
  global search (``rigid/pinhole_force_field.py``).
Each start then goes through the consensus fit and maximum likelihood of ``rigid.estimate``.
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.rigid.geometry import set_motion
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import (
    Layout,
    RigidState,
    axis_angles,
    frame_rotations,
    normalise,
    points3,
    rodrigues,
)
from curverecon.rigid.starts import kabsch


def triangulate(data: RigidData) -> np.ndarray:
    """(N, P, 3) every point of every stereo frame in camera 0's coordinates (least squares of
    lambda1 m1 = Rs lambda0 m0 + ts per point)."""
    rig = data.rig
    rs, ts = np.asarray(rig.R, float), np.asarray(rig.t, float)
    m0, m1 = rig.camera0.rays(data.points), rig.camera1.rays(data.points1)
    a = np.stack([m0 @ rs.T, -m1], axis=-1)  # (N, P, 3, 2)
    ata = np.einsum("...ki,...kj->...ij", a, a)
    atb = np.einsum("...ki,k->...i", a, -ts)
    lam = np.linalg.solve(ata, atb[..., None])[..., 0]
    return lam[..., :1] * m0


def _min_rotation(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The least rotation taking unit a to unit b."""
    axis = np.cross(a, b)
    s, c = np.linalg.norm(axis), float(a @ b)
    if s < 1e-12:
        return np.eye(3)
    return rodrigues(axis / s * np.arctan2(s, c))


def rotations_from_points3(layout: Layout, p3: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotations R_f with X_f - A_f ~ R_f (X_0 - A_0): the triads aligned (three
    points or more); two points: about the axis the chord's directions turn around (axis
    motions: the direction keeps its component along it), else the least rotation of the
    chord."""
    rel = p3[:, 1:] - p3[:, :1]
    n = len(p3)
    if layout.motion == "rotation-free":
        return np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
    if rel.shape[1] >= 2:
        tri = np.concatenate([rel, np.cross(rel[:, :1], rel[:, 1:2])], axis=1)
        return kabsch(tri[0], tri)
    d = rel[:, 0] / np.linalg.norm(rel[:, 0], axis=1, keepdims=True)
    if layout.motion not in ("uniform-rotation", "fixed-axis"):
        return np.array([_min_rotation(d[0], d[f]) for f in range(n)])
    axis = np.linalg.svd(d - d.mean(axis=0))[2][-1]
    perp = d - np.outer(d @ axis, axis)
    ang = np.arctan2(np.cross(perp[0], perp) @ axis, perp @ perp[0])
    return rodrigues(np.outer(ang, axis))


def tangent_planes(layout: Layout, data: RigidData, p3: np.ndarray, rots: np.ndarray):
    """(2, 2) polar, azimuth of the body tangents at A and B: each view's image angle psi puts
    the frame's tangent R_f u in the plane of the ray to the point and the image direction
    (cos psi, sin psi, 0); the least singular vector of the stacked normals R_f^T n."""
    from curverecon.rigid.pinhole import views

    out = np.zeros((2, 2))
    for j in range(2):
        rows = []
        for _cam, rs, ts, _, ang in views(data):
            x = p3[:, j] @ rs.T + ts
            line = np.stack([np.cos(ang[:, j]), np.sin(ang[:, j]), 0 * ang[:, j]], axis=1)
            normal = np.cross(x, line) @ rs  # back in camera 0's coordinates
            normal /= np.linalg.norm(normal, axis=1, keepdims=True)
            rows.append(np.einsum("fi,fij->fj", normal, rots))
        u = np.linalg.svd(np.concatenate(rows))[2][-1]
        out[j] = [np.arccos(np.clip(u[2], -1.0, 1.0)), np.arctan2(u[1], u[0])]
    return out


def state_from_points3(
    layout: Layout, data: RigidData, p3: np.ndarray, rots: np.ndarray | None = None
) -> RigidState:
    """A pinhole row's state from every point in every frame (N, P, 3; camera coordinates with
    depth) and the rotations relative to frame 0 (default :func:`rotations_from_points3`);
    perspective rows rescaled to their gauge (A's depth in frame 0, the force field's g0_z)."""
    rots = rotations_from_points3(layout, p3) if rots is None else rots
    rel = p3[0] - p3[0, :1]
    state = RigidState(body=rel[1:].copy())
    if layout.tangents:
        state.directions = tangent_planes(layout, data, p3, rots)
    set_motion(layout, data.times, rots, state)
    if layout.free_rotations:
        state.rotations = np.einsum("fij,kj->fik", rots, rots[0])
    if not layout.centred:
        state.translations = p3[:, 0].copy()
        scale = 1.0 / p3[0, 0, 2]
    else:
        gvec, parabola = _parabola(p3, rots, data.times)
        state.body, state.parabola = rel - gvec, parabola
        scale = 1.0 / parabola[0, 2]
    return rescale(state, scale) if layout.projection == "perspective" else state


def _parabola(p3: np.ndarray, rots: np.ndarray, times: np.ndarray):
    """(G relative to A in frame 0 (3,), parabola (3, 3)): least squares of
    X_fk - R_f (X_0k - A_0) = g0 + g1 t + g2 t^2 / 2 - R_f gvec over every point and frame."""
    t = np.asarray(times, float)
    rel = p3[0] - p3[0, :1]
    rows, rhs = [], []
    for f in range(len(p3)):
        for k in range(p3.shape[1]):
            block = np.zeros((3, 12))
            block[:, :3] = -rots[f]
            block[:, 3:] = np.kron([1.0, t[f], 0.5 * t[f] ** 2], np.eye(3))
            rows.append(block)
            rhs.append(p3[f, k] - rots[f] @ rel[k])
    sol = np.linalg.lstsq(np.concatenate(rows), np.concatenate(rhs), rcond=None)[0]
    return sol[:3], sol[3:].reshape(3, 3)


def rescale(state: RigidState, s: float) -> RigidState:
    """Every length of the state times ``s`` (the perspective scale)."""
    out = state.copy()
    out.body = out.body * s
    if out.translations is not None:
        out.translations = out.translations * s
    if out.parabola is not None:
        out.parabola = out.parabola * s
    return out


def rotation_free_points3(data: RigidData, frames: np.ndarray | None = None) -> np.ndarray | None:
    """(F, P, 3) the rotation-free closed form on ``frames`` (default all): least squares of
    lambda_Pf m_Pf - lambda_Af m_Af = D_P with lambda_A0 = 1; None when singular."""
    idx = np.arange(data.n_frames) if frames is None else np.asarray(frames)
    m = data.camera.rays(data.points[idx])
    f_n, p = m.shape[:2]
    n_unk = 3 * (p - 1) + f_n * p - 1  # D_P, every depth but lambda_A0
    rows, rhs = [], []
    for f in range(f_n):
        for k in range(1, p):
            block = np.zeros((3, n_unk))
            block[:, 3 * (k - 1) : 3 * k] = -np.eye(3)
            base = 3 * (p - 1) + f * p - 1
            block[:, base + k] = m[f, k]
            if f == 0:
                rhs.append(m[0, 0])
            else:
                block[:, base] = -m[f, 0]
                rhs.append(np.zeros(3))
            rows.append(block)
    a, b = np.concatenate(rows), np.concatenate(rhs)
    sol, *_, sv = np.linalg.lstsq(a, b, rcond=None)
    if sv[-1] < 1e-10 * sv[0]:
        return None
    lam = np.concatenate([[1.0], sol[3 * (p - 1) :]]).reshape(f_n, p)
    return lam[..., None] * m


FREE_STARTS = 3
"""The free row also starts from this many of the orthographic row's all-frame starts (frame 0's
depths on a grid, ``rigid.starts.free_starts``), both mirror images: from the best orthographic
fit alone 3 of 8 noise-free six-frame scenes (four points, bench seed 0) reached the truth, with
3 more starts 6 (and with 6 more, still 6)."""


def weak_perspective(layout: Layout, data: RigidData) -> list[RigidState]:
    """Starts from the orthographic row on normalised coordinates (module docstring)."""
    from scipy.stats import chi2 as chi2_dist

    from curverecon.rigid.estimate import best_fit, frame_dof

    cam = data.camera
    pp, f = np.asarray(cam.principal_point, float), float(cam.focal_px)
    ortho = Layout(layout.motion, layout.points, layout.tangents)
    odata = RigidData(
        data.times, (data.points - pp) / f, data.angles, data.point_sigma / f, data.tangent_sigma
    )
    thr = float(chi2_dist.isf(1e-3, frame_dof(ortho)))
    states = []
    try:
        with np.errstate(all="ignore"):
            states.append(best_fit(ortho, odata, thr)[0].state)
    except (CurveReconError, np.linalg.LinAlgError, ValueError):
        pass
    if layout.motion == "free":
        from curverecon.rigid.starts import free_starts

        states += free_starts(ortho, odata, FREE_STARTS)
    out = []
    for state, mirror in ((s, m) for s in states for m in (False, True)):
        st = normalise(ortho, state, data.times, mirror=mirror)
        p3 = points3(ortho, st, data.times)
        p3[..., 2] += 1.0
        rots = frame_rotations(ortho, st, data.times)[0]
        try:
            out.append(state_from_points3(layout, data, p3, rots))
        except (np.linalg.LinAlgError, ValueError):
            continue
    return out


def pinhole_starts(layout: Layout, data: RigidData) -> list[RigidState]:
    """Start states of a pinhole row from all of its frames (module docstring)."""
    if layout.projection == "stereo":
        return [state_from_points3(layout, data, triangulate(data))]
    if layout.motion == "rotation-free":
        p3 = rotation_free_points3(data)
        return [] if p3 is None else [state_from_points3(layout, data, p3)]
    out = []
    if layout.motion == "fixed-axis" and data.n_frames == 3:
        out += solver_states(layout, data, np.arange(3))
    elif layout.motion == "fixed-axis" and len(layout.points) == 3:
        n = data.n_frames
        out += _best(layout, data, solver_states(layout, data, np.array([0, n // 3, 2 * n // 3])))
    elif layout.motion == "free" and len(layout.points) >= 4:
        from curverecon.rigid.pinhole_search import search_starts

        out += search_starts(layout, data)
    elif layout.motion == "force-field":
        from curverecon.rigid.pinhole_force_field import force_field_starts

        out += force_field_starts(layout, data)
    return out + weak_perspective(layout, data)


SOLVER_STARTS = 2
"""Of the fixed-axis solver's solutions on three spread frames, extended to every frame, the
best this many by the robust cost start the consensus fit (beside weak perspective)."""


def _best(layout: Layout, data: RigidData, states: list[RigidState]) -> list[RigidState]:
    """The ``SOLVER_STARTS`` states of least trimmed chi2 (the frames' chi2 summed over the
    best ``1 - starts.TRIM`` of them: outlier frames do not decide, and a start on a grid of
    angles is not yet within any noise threshold)."""
    from curverecon.rigid.measurements import residuals
    from curverecon.rigid.starts import trimmed_sum

    costs = []
    for st in states:
        with np.errstate(all="ignore"):
            r = residuals(layout, st, data)
        chi2 = np.where(np.isfinite(np.sum(r * r, 1)), np.sum(r * r, 1), np.inf)
        costs.append(float(trimmed_sum(chi2)))
    order = np.argsort(costs, kind="stable")[:SOLVER_STARTS]
    return [states[i] for i in order]


ANGLE_GRID = 72
"""Angles about the axis tried per frame when a solution is extended to every frame (5
degrees apart; the consensus fit refines them)."""


def extend_axis(
    layout: Layout, data: RigidData, body: np.ndarray, axis: np.ndarray, ref: int
) -> RigidState | None:
    """A fixed-axis state over every frame from a solution's body (P - 1, 3; relative to A, in
    frame ``ref``'s orientation) and axis n: per frame the angle phi about n (a grid) whose
    rotated body, with A on its ray at the depth fitting B - A, reprojects best; A's depth in
    frame 0 rescaled to 1.  None when frame 0's A is not in front of the camera."""
    cam = data.camera
    m = cam.rays(data.points)  # (N, P, 3)
    grid = np.linspace(-np.pi, np.pi, ANGLE_GRID, endpoint=False)
    rot = rodrigues(np.outer(grid, axis))  # (G, 3, 3)
    d = np.einsum("gij,pj->gpi", rot, body)  # (G, P-1, 3)
    a = np.stack([-m[:, 0], m[:, 1]], axis=-1)  # (N, 3, 2)
    ata = np.einsum("fki,fkj->fij", a, a)
    atb = np.einsum("fki,gk->fgi", a, d[:, 0])
    lam = np.linalg.solve(ata[:, None], atb[..., None])[..., 0, 0]  # (N, G)
    pa = lam[..., None] * m[:, None, 0]  # (N, G, 3)
    pts = np.concatenate([pa[:, :, None], pa[:, :, None] + d[None]], axis=2)
    with np.errstate(all="ignore"):
        err = np.sum((cam.project(pts) - data.points[:, None]) ** 2, axis=(2, 3))
    err = np.where((lam > 0) & np.isfinite(err), err, np.inf)
    best = np.argmin(err, axis=1)
    f = np.arange(len(best))
    if not lam[0, best[0]] > 0:
        return None
    phi = grid[best]
    state = RigidState(
        body=body @ rodrigues(phi[0] * axis).T,
        axis=axis_angles(axis),
        angles=np.angle(np.exp(1j * (phi - phi[0]))),
        translations=pa[f, best],
    )
    return rescale(state, 1.0 / state.translations[0, 2])


def solver_states(layout: Layout, data: RigidData, frames: np.ndarray) -> list[RigidState]:
    """Every real solution of the fixed-axis three-point solver on three frames as a state over
    every frame (:func:`extend_axis` where the frames are not all of them)."""
    from curverecon.solvers import persp_fixed_axis_3pt as solver

    try:
        sol = solver.solve(data.points[frames], data.times[frames], data.camera)
    except (CurveReconError, np.linalg.LinAlgError, ValueError):
        return []
    if len(frames) == data.n_frames:
        return [
            state_from_points3(layout, data, sol.points3[s], sol.rotations[s])
            for s in range(sol.n_solutions)
        ]
    out = []
    for s in range(sol.n_solutions):
        p3 = sol.points3[s]
        axis = np.asarray(sol.motion[s]["axis"], float)
        got = extend_axis(layout, data, p3[0, 1:] - p3[0, :1], axis, int(frames[0]))
        if got is not None:
            out.append(got)
    return out


__all__ = ["pinhole_starts", "state_from_points3"]


def flip_frames(layout: Layout, state: RigidState, data: RigidData, refine_locals) -> RigidState:
    """Every frame (but frame 0) on the better of its rotation R_f and the depth-reversed
    S R_f M (S = diag(1, 1, -1) about A, M the reflection through the body's best plane): for
    a nearly flat body the two give nearly the same image, the orthographic per-frame ambiguity
    a weak-perspective start inherits.  ``refine_locals(state) -> fit or None`` fits every
    frame's own parameters with the body and motion held."""
    if not layout.free_rotations or len(layout.points) < 3:
        return state
    from curverecon.rigid.model import body_vectors

    q = body_vectors(layout, state)
    normal = np.linalg.svd(q - q[0])[2][-1]
    mirror = np.eye(3) - 2.0 * np.outer(normal, normal)
    flip = np.diag([1.0, 1.0, -1.0])
    other = state.copy()
    other.rotations[1:] = flip @ state.rotations[1:] @ mirror
    a, b = refine_locals(state), refine_locals(other)
    if a is None or b is None:
        return state if b is None else b.state
    better = b.frame_chi2 < a.frame_chi2
    better[0] = False
    out = a.state.copy()
    for name in ("rotations", "translations"):
        arr = getattr(out, name)
        if arr is not None:
            arr[better] = getattr(b.state, name)[better]
    return out
