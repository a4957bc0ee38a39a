"""The curve stage under a calibrated pinhole camera.

Two entry points:

- :func:`curve_on_pinhole_poses`: the curve on given poses (the perspective rows' curve stage):
  every frame-0 polyline point's depth searched along its ray against the other frames'
  polylines (section 4 under a pinhole: the non-traceable points from all frames), a spline
  through them, then the curve bundle with the poses held.
- :func:`reconstruct_perspective_curve`: the ordinary camera beyond the Section 2 table (free
  motion, A and B, a polyline in every frame): the paper's orthographic pipeline on the frames
  in normalised coordinates (weak perspective) as the start, its curve and its mirror image,
  every frame's pose searched against each and refined with the curve by the pinhole curve
  bundle (every frame's rotation R_f, its 3-D translation T_f and the curve), the better kept.

Conventions (curverecon.solvers.camera): camera coordinates x right, y down, z along the optical
axis; pixels (u, v) = f (x / z, y / z) + (cx, cy).  Frame f's coordinates X_f = R_f X_0 + T_f
(frame 0: R = I, T = 0).  The curve is a clamped cubic B-spline (curverecon.curve.spline) in frame
0's camera coordinates, A its first control point, B its last.  Residuals in units of the pixel
noise ``point_sigma``: every sampled polyline point's signed distance from the projected curve
(along the projected curve's normal at the nearest point), A' and B' (two rows each), and a
fourth-difference penalty on the control points (it fixes their slide along the curve, which
the images leave free; as ``CurveOptions.bundle_smooth_weight``).  Tangents, when given, are used
by the start only: the polylines carry the end directions.

Units of :func:`reconstruct_perspective_curve`: A's depth in frame 0 is 1, or |AB| =
``configuration.length_ab`` when given (CONTRACT.md, "Configurations").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve.spline import Basis, arc_parameters, fit_spline
from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera

CONTROL_POINTS = 14
"""Control points of the curve's spline.  bench/persp_curve.py's scenes (five curve families,
20 frames, 0.5 px): the bundle started from the truth puts the curve within 1 % of its length
in every scene (the oracle rate there)."""

SAMPLES_PER_FRAME = 40
"""Polyline points per frame the bundle fits: the polyline's own points nearest to equal steps
in arc length (not interpolated, so that points on the curve stay on it)."""

SMOOTH_WEIGHT = 0.1
"""Weight of the fourth-difference penalty, per pixel of control-point movement (as
``CurveOptions.bundle_smooth_weight`` at 1 px noise); not divided by the noise, so that
noise-free polylines give the exact curve (the penalty's pull vanishes against them)."""

MIRROR_DCHI2 = 9.0
"""Below this chi2 gap between the answer and its mirror image (the curve's depth reversed
about A, every rotation mirrored, refitted) the perspective does not tell them apart: a
warning says the answer is the orthographic one's, either mirror image.  bench/persp_curve.py
measures the gap against the object's distance."""

MAX_ITERATIONS = 200


def _error(message: str) -> CurveReconError:
    return CurveReconError(message)


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _rotation(w: np.ndarray) -> np.ndarray:
    """exp([w]x): the rotation by |w| radians about w."""
    angle = float(np.linalg.norm(w))
    if angle < 1e-12:
        return np.eye(3) + _skew(w)
    k = _skew(w / angle)
    return np.eye(3) + np.sin(angle) * k + (1.0 - np.cos(angle)) * (k @ k)


def _project(
    camera: Camera, y: np.ndarray, kappa: float = 1.0, z_ref: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pixels (..., 2) of camera points y (..., 3), d pixel / d y (..., 2, 3) and d pixel /
    d z_ref (..., 2).  The divisor is d = kappa z + (1 - kappa) z_ref: the pinhole at kappa 1,
    weak perspective at the depth z_ref (...,) at kappa 0 (the orthographic limit)."""
    f = float(camera.focal_px)
    z = y[..., 2] if kappa == 1.0 else kappa * y[..., 2] + (1.0 - kappa) * z_ref
    if np.any(z <= 0):
        raise _error("the curve passes behind the camera")
    p = f * y[..., :2] / z[..., None] + np.asarray(camera.principal_point, float)
    jac = np.zeros(y.shape[:-1] + (2, 3))
    jac[..., 0, 0] = f / z
    jac[..., 1, 1] = f / z
    jd = -f * y[..., :2] / (z**2)[..., None]  # d pixel / d divisor
    jac[..., :, 2] = kappa * jd
    return p, jac, (1.0 - kappa) * jd


@dataclass
class PinholeFit:
    """A fitted pinhole curve bundle.

    control: (K, 3) spline control points in frame 0's camera coordinates.
    rot, trans: (N, 3, 3), (N, 3) with X_f = rot[f] X_0 + trans[f].
    cost: sum of squared residuals (units of the pixel noise), penalty included.
    rms: (N,) RMS distance (pixels) of each frame's polyline points from the projected curve.
    cov: covariance of the free parameters (``free`` selects them from the full vector:
        control points, then per frame a rotation increment and T), or None.
    """

    control: np.ndarray
    rot: np.ndarray
    trans: np.ndarray
    cost: float
    rms: np.ndarray
    cov: np.ndarray | None
    free: np.ndarray
    converged: bool
    iterations: int


@dataclass
class _Data:
    camera: Camera
    samples: np.ndarray  # (N, S, 2) pixels
    a_px: np.ndarray  # (N, 2)
    b_px: np.ndarray  # (N, 2)
    sigma: float
    smooth: float  # penalty weight in residual units per unit of control-point length
    kappa: float = 1.0  # the projection's perspective strength (see _project)

    @property
    def n(self) -> int:
        return len(self.samples)


def _feet(
    data: _Data, basis: Basis, ctrl, rot, tra, frames: np.ndarray, coarse: bool = False
) -> np.ndarray:
    """(F, S) curve parameters u of the points of the projected curves nearest to the
    polyline samples of ``frames`` (F,) under poses ``rot`` (F, 3, 3), ``tra`` (F, 3)."""
    q = data.samples[frames]
    kap = data.kappa
    z_ref = (rot @ ctrl[0] + tra)[:, 2]
    # a fine grid so that where the projected curve passes near itself the nearest grid point
    # lies on the right strand (the pose search's batches of candidates, ``coarse``, and more
    # than 64 frames take a coarser one)
    grid = np.linspace(0.0, 1.0, (12 if coarse or len(frames) > 64 else 48) * basis.k)
    p, _, _ = _project(data.camera, np.einsum("fij,gj->fgi", rot, basis.values(grid) @ ctrl)
                       + tra[:, None], kap, z_ref[:, None])  # fmt: skip
    # |q - p|^2 less |q|^2 (the same for every grid point): one matrix product
    d2 = np.sum(p * p, axis=-1)[:, None, :] - 2.0 * np.matmul(q, p.transpose(0, 2, 1))
    u = grid[np.argmin(d2, axis=2)]
    for _ in range(4):
        shape = u.shape
        x = (basis.values(u.ravel()) @ ctrl).reshape(shape + (3,))
        dx = (basis.d1(u.ravel()) @ ctrl).reshape(shape + (3,))
        y = np.einsum("fij,fsj->fsi", rot, x) + tra[:, None]
        pt, jp, _ = _project(data.camera, y, kap, z_ref[:, None])
        t = np.einsum("fsij,fsj->fsi", jp, np.einsum("fij,fsj->fsi", rot, dx))
        step = np.sum(t * (pt - q), axis=2) / np.maximum(np.sum(t * t, axis=2), 1e-300)
        u = np.clip(u - step, 0.0, 1.0)
    return u


def _frame_rows(
    data: _Data, basis: Basis, ctrl, rot, tra, frames: np.ndarray | None = None, coarse=False
):
    """Residuals and Jacobian blocks of ``frames`` (default: all) under poses ``rot``
    (F, 3, 3), ``tra`` (F, 3): r (F, S+4), d r / d ctrl (F, S+4, K, 3), d r / d(w, T)
    (F, S+4, 6) (w: a rotation increment, R <- exp([w]x) R); ``coarse``: the feet from a
    coarser grid (:func:`_feet`)."""
    frames = np.arange(data.n) if frames is None else np.asarray(frames)
    q, a_px, b_px = data.samples[frames], data.a_px[frames], data.b_px[frames]
    u = _feet(data, basis, ctrl, rot, tra, frames, coarse)
    nf, ns = u.shape
    nb = basis.values(u.ravel()).reshape(nf, ns, basis.k)
    rx = np.einsum("fij,fsj->fsi", rot, nb @ ctrl)
    ra = rot @ ctrl[0]
    z_ref = (ra + tra)[:, 2]
    p, jp, jr = _project(data.camera, rx + tra[:, None], data.kappa, z_ref[:, None])
    t = np.einsum("fsij,fsj->fsi", jp, np.einsum("fij,fsj->fsi", rot, basis.d1(u.ravel())
                  .reshape(nf, ns, basis.k) @ ctrl))  # fmt: skip
    normal = np.stack([-t[..., 1], t[..., 0]], axis=-1)
    normal /= np.maximum(np.linalg.norm(t, axis=-1), 1e-300)[..., None]
    g = np.einsum("fsi,fsij->fsj", normal, jp)  # d r / d y
    r_curve = np.sum(normal * (p - q), axis=-1)
    h = np.sum(normal * jr, axis=-1)  # d r / d z_ref
    r_ends = np.empty((nf, 4))
    h_ends = np.empty((nf, 4))
    g_ends = np.empty((nf, 4, 3))
    rx_ends = np.empty((nf, 4, 3))
    for j, (point, obs) in enumerate(((ctrl[0], a_px), (ctrl[-1], b_px))):
        y = rot @ point
        pe, je, jre = _project(data.camera, y + tra, data.kappa, z_ref)
        r_ends[:, 2 * j : 2 * j + 2] = pe - obs
        h_ends[:, 2 * j : 2 * j + 2] = jre
        g_ends[:, 2 * j : 2 * j + 2] = je
        rx_ends[:, 2 * j : 2 * j + 2] = y[:, None]
    e_basis = np.zeros((4, basis.k))
    e_basis[:2, 0] = 1.0
    e_basis[2:, -1] = 1.0
    g_all = np.concatenate([g, g_ends], axis=1)
    b_all = np.concatenate([nb, np.broadcast_to(e_basis, (nf, 4, basis.k))], axis=1)
    d_ctrl = b_all[..., None] * np.einsum("fsi,fij->fsj", g_all, rot)[:, :, None, :]
    rx_all = np.concatenate([rx, rx_ends], axis=1)
    d_pose = np.concatenate([np.cross(rx_all, g_all), g_all], axis=-1)
    if data.kappa != 1.0:  # z_ref = (R P_0 + T)_z: through A's control point, w and T
        h_all = np.concatenate([h, h_ends], axis=1)[..., None]
        d_ctrl[:, :, 0, :] += h_all * rot[:, None, 2, :]
        d_pose[..., :3] += h_all * np.cross(ra, [0.0, 0.0, 1.0])[:, None, :]
        d_pose[..., 5] += h_all[..., 0]
    r = np.concatenate([r_curve, r_ends], axis=1)
    return r / data.sigma, d_ctrl / data.sigma, d_pose / data.sigma


def _system(data: _Data, basis: Basis, ctrl, rot, tra) -> tuple[np.ndarray, np.ndarray]:
    """Every residual and the full Jacobian (columns: 3K control, then 6 per frame)."""
    k, n = basis.k, data.n
    r, dc, dp = _frame_rows(data, basis, ctrl, rot, tra)
    rows = r.shape[1]
    jac = np.zeros((n, rows, 3 * k + 6 * n))
    jac[:, :, : 3 * k] = dc.reshape(n, rows, 3 * k)
    for f in range(n):
        jac[f, :, 3 * k + 6 * f : 3 * k + 6 * f + 6] = dp[f]
    d4 = np.diff(np.eye(k), 4, axis=0) * data.smooth
    pen = np.zeros((3 * (k - 4), 3 * k + 6 * n))
    pen[:, : 3 * k] = np.kron(d4, np.eye(3))
    r_all = np.concatenate([r.ravel(), (d4 @ ctrl).ravel()])
    return r_all, np.vstack([jac.reshape(n * rows, -1), pen])


def _step(ctrl, rot, tra, delta: np.ndarray, k: int):
    """The state moved by a full-length parameter step."""
    new_ctrl = ctrl + delta[: 3 * k].reshape(k, 3)
    d = delta[3 * k :].reshape(-1, 6)
    new_rot = np.stack([_rotation(d[f, :3]) @ rot[f] for f in range(len(rot))])
    return new_ctrl, new_rot, tra + d[:, 3:]


def bundle(
    data: _Data, ctrl: np.ndarray, rot: np.ndarray, tra: np.ndarray, free: np.ndarray
) -> PinholeFit:
    """Levenberg-Marquardt over the free parameters (``free``: mask of the full vector)."""
    basis = Basis(len(ctrl))
    k = basis.k
    try:
        r, jac = _system(data, basis, ctrl, rot, tra)
    except CurveReconError as exc:
        raise _error(f"pinhole curve bundle: the start is not valid ({exc})") from None
    cost, lam, converged, iterations = float(r @ r), 1e-3, False, 0
    for it in range(1, MAX_ITERATIONS + 1):
        iterations = it
        jf = jac[:, free]
        h, g = jf.T @ jf, jf.T @ r
        diag = np.maximum(np.diag(h), 1e-12)
        improved = False
        while lam < 1e12:
            try:
                dx = np.linalg.solve(h + lam * np.diag(diag), -g)
            except np.linalg.LinAlgError:
                lam *= 10.0
                continue
            delta = np.zeros(jac.shape[1])
            delta[free] = dx
            trial = _step(ctrl, rot, tra, delta, k)
            try:
                r_new, jac_new = _system(data, basis, *trial)
            except CurveReconError:
                lam *= 10.0
                continue
            cost_new = float(r_new @ r_new)
            if cost_new < cost:
                improved = True
                break
            lam *= 10.0
        if not improved:
            converged = True
            break
        ctrl, rot, tra = trial
        drop = cost - cost_new
        r, jac, cost = r_new, jac_new, cost_new
        lam = max(lam / 10.0, 1e-9)
        if drop < 1e-10 * max(cost, 1e-20) or drop < 1e-24:
            converged = True
            break
    jf = jac[:, free]
    try:
        cov = np.linalg.inv(jf.T @ jf)
    except np.linalg.LinAlgError:
        cov = None
    return PinholeFit(ctrl, rot, tra, cost, _frame_rms(data, basis, ctrl, rot, tra), cov,
                      free, converged, iterations)  # fmt: skip


SEARCH_ROTATIONS = 600
"""Rotations tried per frame by :func:`pose_search` (a fixed random set; a frame's true rotation
can lie 30 degrees from the nearest), each with the translation that puts A and B on their
rays; the best ``SEARCH_REFINED`` refined."""


def _rotation_grid() -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.random(SEARCH_ROTATIONS, random_state=20261128).as_matrix()


SEARCH_REFINED = 48
"""The lowest-cost rotations of the grid that :func:`pose_search` refines together (a few
Levenberg-Marquardt steps each, :func:`_batch_refine`) before the best four are refined to the
end: a grid rotation can lie 30 degrees from the frame's true one, whose cost then ranks among
the first few dozen (bench/persp_curve.py scene 0, frame 19, against a fitted curve: the five
nearest the truth ranked 29th-74th, below four on wrong branches)."""


def _frame_costs(data: _Data, basis: Basis, ctrl, rot, tra, f: int):
    """Frame f's residuals (n, S+4), pose Jacobians (n, S+4, 6) and costs (n,) under n poses;
    a pose that puts the curve behind the camera costs inf (its rows zero)."""
    try:
        r, _, dp = _frame_rows(data, basis, ctrl, rot, tra, np.full(len(rot), f), True)
        return r, dp, np.sum(r**2, axis=1)
    except CurveReconError:
        pass
    rows = SAMPLES_PER_FRAME + 4
    r, dp, cost = (
        np.zeros((len(rot), rows)),
        np.zeros((len(rot), rows, 6)),
        np.full(len(rot), np.inf),
    )
    for i in range(len(rot)):
        try:
            ri, _, dpi = _frame_rows(
                data, basis, ctrl, rot[i : i + 1], tra[i : i + 1], np.array([f]), True
            )
        except CurveReconError:
            continue
        r[i], dp[i], cost[i] = ri[0], dpi[0], float(np.sum(ri**2))
    return r, dp, cost


def _batch_refine(data: _Data, basis: Basis, ctrl, rot, tra, f: int, iterations: int = 6):
    """n poses of frame f refined side by side, the curve held (Levenberg-Marquardt per pose,
    ``iterations`` steps): (rot (n, 3, 3), tra (n, 3), cost (n,))."""
    rot, tra = rot.copy(), tra.copy()
    r, dp, cost = _frame_costs(data, basis, ctrl, rot, tra, f)
    lam = np.full(len(rot), 1e-3)
    for _ in range(iterations):
        h = np.einsum("nsi,nsj->nij", dp, dp)
        g = np.einsum("nsi,ns->ni", dp, r)
        damp = lam[:, None] * np.maximum(np.einsum("nii->ni", h), 1e-12)
        dx = np.linalg.solve(h + damp[:, :, None] * np.eye(6), -g[..., None])[..., 0]
        new_rot = np.stack([_rotation(d[:3]) @ m for d, m in zip(dx, rot, strict=True)])
        new_tra = tra + dx[:, 3:]
        r_new, dp_new, c_new = _frame_costs(data, basis, ctrl, new_rot, new_tra, f)
        ok = c_new < cost
        rot[ok], tra[ok], r[ok], dp[ok], cost[ok] = (
            new_rot[ok],
            new_tra[ok],
            r_new[ok],
            dp_new[ok],
            c_new[ok],
        )
        lam = np.where(ok, np.maximum(lam / 10.0, 1e-9), lam * 10.0)
    return rot, tra, cost


def _refine_pose(data: _Data, basis: Basis, ctrl, rot, tra, f: int, iterations: int = 15):
    """Frame f's pose alone fitted to its polyline and ends (the curve held): (R, T, cost)."""
    frames = np.array([f])
    r, _, dp = _frame_rows(data, basis, ctrl, rot[None], tra[None], frames)
    cost, lam = float(np.sum(r**2)), 1e-3
    for _ in range(iterations):
        j = dp[0]
        h, g = j.T @ j, j.T @ r[0]
        while lam < 1e8:
            dx = np.linalg.solve(h + lam * np.diag(np.maximum(np.diag(h), 1e-12)), -g)
            new_rot, new_tra = _rotation(dx[:3]) @ rot, tra + dx[3:]
            try:
                r_new, _, dp_new = _frame_rows(data, basis, ctrl, new_rot[None], new_tra[None],
                                               frames)  # fmt: skip
            except CurveReconError:
                lam *= 10.0
                continue
            if float(np.sum(r_new**2)) < cost:
                break
            lam *= 10.0
        else:
            break
        drop = cost - float(np.sum(r_new**2))
        rot, tra, r, dp, cost = new_rot, new_tra, r_new, dp_new, cost - drop
        lam = max(lam / 10.0, 1e-9)
        if drop < 1e-8 * cost:
            break
    return rot, tra, cost


def pose_search(data: _Data, ctrl, rot, tra, frames) -> tuple[np.ndarray, np.ndarray, int]:
    """Every frame of ``frames`` searched for its pose against the curve held: the rotations
    of :func:`_rotation_grid` and the current one, each with the translation putting A and B
    on their rays, the best ``SEARCH_REFINED`` refined side by side (:func:`_batch_refine`),
    the best four of those to the end; the lowest cost kept.  Returns (rot, tra, number of
    frames whose rotation moved by more than ``MOVED_DEG``)."""
    basis = Basis(len(ctrl))
    rot, tra = rot.copy(), tra.copy()
    grid = _rotation_grid()
    changed = 0
    for f in frames:
        cands = np.concatenate([rot[f][None], grid])
        ma, mb = data.camera.rays(data.a_px[f]), data.camera.rays(data.b_px[f])
        lhs = np.vstack([_skew(ma), _skew(mb)])
        rhs = -np.concatenate([cands @ ctrl[0] @ _skew(ma).T, cands @ ctrl[-1] @ _skew(mb).T], 1)
        ts = rhs @ np.linalg.pinv(lhs).T
        ts[0] = tra[f]
        along = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 50)) @ ctrl
        ok = np.all(np.einsum("cij,mj->cmi", cands, along)[..., 2] + ts[:, None, 2] > 0, axis=1)
        cost = np.full(len(cands), np.inf)
        idx = np.flatnonzero(ok)
        try:
            r, _, _ = _frame_rows(data, basis, ctrl, cands[idx], ts[idx], np.full(len(idx), f))
            cost[idx] = np.sum(r**2, axis=1)
        except CurveReconError:  # some candidate puts the curve behind the camera: one by one
            for i in idx:
                try:
                    r, _, _ = _frame_rows(data, basis, ctrl, cands[i : i + 1], ts[i : i + 1],
                                          np.array([f]))  # fmt: skip
                    cost[i] = float(np.sum(r**2))
                except CurveReconError:
                    continue
        best = (rot[f], tra[f], cost[0])
        top = [i for i in np.argsort(cost)[:SEARCH_REFINED] if np.isfinite(cost[i])]
        b_rot, b_tra, b_cost = _batch_refine(data, basis, ctrl, cands[top], ts[top], f)
        for i in np.argsort(b_cost)[:4]:
            if not np.isfinite(b_cost[i]):
                continue
            try:
                cand = _refine_pose(data, basis, ctrl, b_rot[i], b_tra[i], f)
            except CurveReconError:
                continue
            if cand[2] < best[2] * (1.0 - 1e-9):
                best = cand
        if best[2] < cost[0] and _angle_deg(best[0], rot[f]) > MOVED_DEG:
            changed += 1
        rot[f], tra[f] = best[0], best[1]
    return rot, tra, changed


MOVED_DEG = 5.0
"""A searched pose counts as changed (:func:`pose_search`) when its rotation moved by more than
this: a refinement in the same basin is left to the bundle."""


def _angle_deg(r1: np.ndarray, r2: np.ndarray) -> float:
    """The rotation angle (degrees) between two rotations."""
    return float(np.degrees(np.arccos(np.clip((np.trace(r1.T @ r2) - 1.0) / 2.0, -1.0, 1.0))))


def regauged(ctrl, rot, tra, r0: np.ndarray, t0: np.ndarray):
    """The state re-expressed in frame 0's new pose (r0, t0) (the curve seen at r0 X + t0 in
    frame 0, X its current frame-0 coordinates): every other frame's pose composed with its
    inverse, frame 0's pose the identity, lengths rescaled so that A's depth is 1 again."""
    new_ctrl = ctrl @ r0.T + t0
    new_rot = rot @ r0.T
    new_tra = tra - np.einsum("fij,j->fi", new_rot, t0)
    new_rot[0], new_tra[0] = np.eye(3), 0.0
    unit = float(new_ctrl[0, 2])
    if not unit > 0:
        raise _error("pinhole curve: a regauged frame 0 puts A behind the camera")
    return new_ctrl / unit, new_rot, new_tra / unit


def _frame_rms(data: _Data, basis: Basis, ctrl, rot, tra) -> np.ndarray:
    """(N,) RMS distance (pixels) of every frame's polyline samples from the projected curve."""
    r, _, _ = _frame_rows(data, basis, ctrl, rot, tra)
    return np.sqrt(np.mean(r[:, :-4] ** 2, axis=1)) * data.sigma


def _prepare(
    camera: Camera, polylines, a_px: np.ndarray, b_px: np.ndarray, sigma: float, scale: float
) -> _Data:
    """The bundle's data: every polyline sampled (A' first), the ends, the noise.  ``scale``:
    a typical depth, so that the penalty is in pixels as the other rows."""
    samples = []
    for f, poly in enumerate(polylines):
        q = pl.as_polyline(poly, name=f"frame {f} curve")
        if np.hypot(*(q[-1] - a_px[f])) < np.hypot(*(q[0] - a_px[f])):
            q = q[::-1]
        s = pl.arc_length(q)
        steps = np.linspace(0.0, s[-1], SAMPLES_PER_FRAME + 2)[1:-1]  # A', B': the end rows
        at = np.interp(steps, s, np.arange(len(q)))
        samples.append(q[np.round(at).astype(int)])
    smooth = SMOOTH_WEIGHT * float(camera.focal_px) / scale
    return _Data(
        camera, np.array(samples), np.asarray(a_px, float), np.asarray(b_px, float), sigma, smooth
    )


def curve_points_and_std(
    fit: PinholeFit, n_out: int = 200, length_ab: float | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(curve3d (M, 3), std (M,), normal std (M,)) in frame 0's coordinates from a fit; with
    ``length_ab`` rescaled so that |AB| = length_ab, the std then with that gauge (the
    points' Jacobian through the scale factor length_ab / |AB|)."""
    ctrl = fit.control
    k = len(ctrl)
    basis = Basis(k)
    u = arc_parameters(ctrl, n_out)
    nb = basis.values(u)
    pts = nb @ ctrl
    tang = basis.d1(u) @ ctrl
    tang /= np.linalg.norm(tang, axis=1)[:, None]
    jac = np.einsum("mk,ij->mikj", nb, np.eye(3)).reshape(n_out, 3, 3 * k)
    factor = 1.0
    if length_ab is not None:
        ab = ctrl[-1] - ctrl[0]
        c = float(np.linalg.norm(ab))
        factor = length_ab / c
        dc = np.zeros(3 * k)
        dc[:3], dc[-3:] = -ab / c, ab / c
        jac = factor * (jac - np.einsum("mi,j->mij", pts, dc) / c)
    if fit.cov is None:
        nan = np.full(n_out, np.nan)
        return factor * pts, nan, nan
    nfree = int(fit.free[: 3 * k].sum())
    jf = jac[:, :, fit.free[: 3 * k]]
    cov = np.einsum("mik,kl,mjl->mij", jf, fit.cov[:nfree, :nfree], jf)
    std = np.sqrt(np.maximum(np.einsum("mii->m", cov), 0.0))
    proj = np.eye(3)[None] - np.einsum("mi,mj->mij", tang, tang)
    ncov = np.einsum("mij,mjk,mkl->mil", proj, cov, proj)
    nstd = np.sqrt(np.maximum(np.einsum("mii->m", ncov), 0.0))
    return factor * pts, std, nstd


def _depth_search(
    camera: Camera, rot, tra, samples: list[np.ndarray], polylines, depths: np.ndarray
) -> np.ndarray:
    """Frame 0's polyline points placed in depth: per point the depth along its ray (among
    ``depths``) whose projections lie nearest to the other frames' polylines (median distance
    over the frames), then a running median along the curve."""
    rays = camera.rays(samples[0])
    best = np.empty(len(rays))
    for i, ray in enumerate(rays):
        cand = depths[:, None] * ray[None]
        dist = []
        for f in range(1, len(rot)):
            y = cand @ rot[f].T + tra[f]
            ok = y[:, 2] > 0
            d = np.full(len(cand), np.inf)
            if ok.any():
                d[ok] = pl.distance_to_polyline(camera.project(y[ok]), polylines[f])[0]
            dist.append(d)
        best[i] = depths[int(np.argmin(np.median(np.array(dist), axis=0)))]
    half = 2
    padded = np.concatenate([[best[0]] * half, best, [best[-1]] * half])
    smooth = np.array([np.median(padded[i : i + 2 * half + 1]) for i in range(len(best))])
    return smooth[:, None] * rays


def curve_on_pinhole_poses(
    camera: Camera,
    frame_poses: np.ndarray,
    polylines,
    points3_frame0: np.ndarray,
    point_sigma: float,
) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """The curve on given pinhole poses (the perspective rows' curve stage).

    Args:
        camera: the calibrated camera of every frame.
        frame_poses: (N, 3, 4) [R_f | T_f], X_f = R_f X_0 + T_f (frame 0's: [I | 0]).
        polylines: N image polylines (pixels), each from A' to B' (either order accepted: the
            end nearer A's projection is taken as A').
        points3_frame0: (P, 3) the traceable points in frame 0's camera coordinates, A and B
            first (the curve's ends; the others unused).
        point_sigma: the polylines' pixel noise (standard deviation per coordinate).
    Returns:
        (curve3d (200, 3) in frame 0's camera coordinates from A to B, its std (200,) from the
        bundle's covariance with the poses held, warnings).
    Raises:
        CurveReconError: shapes or numbers that do not fit, a curve behind the camera.
    """
    poses = np.asarray(frame_poses, float)
    pts = np.asarray(points3_frame0, float)
    if poses.ndim != 3 or poses.shape[1:] != (3, 4) or not np.all(np.isfinite(poses)):
        raise _error("frame_poses must be an (N, 3, 4) array of finite numbers")
    if polylines is None or len(polylines) != len(poses):
        raise _error(f"{len(poses)} frame poses need {len(poses)} polylines")
    if pts.ndim != 2 or pts.shape[0] < 2 or pts.shape[1] != 3 or not np.all(np.isfinite(pts)):
        raise _error("points3_frame0 must be a (P, 3) array, A and B first")
    if not (np.isfinite(point_sigma) and point_sigma > 0):
        raise _error("point_sigma must be a positive number")
    if len(poses) < 2:
        raise _error("the curve under a pinhole needs at least two frames")
    rot, tra = poses[:, :, :3], poses[:, :, 3]
    a3, b3 = pts[0], pts[1]
    if a3[2] <= 0 or b3[2] <= 0:
        raise _error("A and B must lie in front of the camera in frame 0 (z > 0)")
    a_px = camera.project(np.einsum("fij,j->fi", rot, a3) + tra)
    b_px = camera.project(np.einsum("fij,j->fi", rot, b3) + tra)
    scale = 0.5 * (a3[2] + b3[2])
    data = _prepare(camera, polylines, a_px, b_px, point_sigma, scale)
    zmin, zmax = min(a3[2], b3[2]), max(a3[2], b3[2])
    extent = float(np.linalg.norm(b3 - a3))
    depths = np.linspace(max(zmin - 1.5 * extent, 1e-3 * zmin), zmax + 1.5 * extent, 241)
    line = _depth_search(camera, rot, tra, data.samples, polylines, depths)
    line[0], line[-1] = a3, b3
    ctrl = fit_spline(line, CONTROL_POINTS)
    free = np.zeros(3 * CONTROL_POINTS + 6 * len(poses), bool)
    free[: 3 * CONTROL_POINTS] = True
    fit = bundle(data, ctrl, rot, tra, free)
    curve, std, _ = curve_points_and_std(fit)
    warnings = []
    worst = float(np.max(fit.rms))
    if worst > 5.0 * point_sigma:
        warnings.append(
            f"the curve on the given poses fits frame {int(np.argmax(fit.rms))}'s polyline "
            f"only to {worst:.2g} px RMS ({worst / point_sigma:.1f} times the point noise)"
        )
    return curve, std, warnings


def _check_ordinary(obs) -> None:
    """The ordinary camera's input: perspective, free motion, A and B, a polyline per frame."""
    cfg = obs.configuration
    if cfg.projection != "perspective" or cfg.camera is None:
        raise _error("the pinhole curve reconstruction needs projection perspective and a camera")
    if cfg.motion != "free":
        raise _error(f'the pinhole curve reconstruction is for motion "free", not {cfg.motion}')
    if obs.curves is None:
        raise _error(
            "perspective, free motion with fewer than four points needs a polyline of the curve "
            "in every frame (the Section 2 table needs A, B, C and D otherwise)"
        )
    if obs.n_frames < MIN_FRAMES:
        raise _error(
            f"{obs.n_frames} frame(s) given; free motion under perspective with A, B and "
            f"polylines needs at least {MIN_FRAMES} (its start is the orthographic pipeline's)"
        )


MIN_FRAMES = 4
"""Fewest frames of :func:`reconstruct_perspective_curve`: its start, the paper's pipeline,
needs four (``curverecon.model.observations.MIN_FRAMES``)."""


START_SIGMA_FLOOR_PX = 0.5
"""The orthographic start is told at least this pixel noise: the weak-perspective model's own
error (depth variation over distance times the image size) is not noise-free even when the
polylines are."""


def _orthographic_start(obs, options):
    """The paper's pipeline on the frames in normalised coordinates (weak perspective): its
    curve (A at depth 1) and every frame's rotation relative to frame 0."""
    from dataclasses import replace

    from curverecon.model.observations import Observations
    from curverecon.pipeline import reconstruct

    camera = obs.configuration.camera
    a_px, b_px = obs.point("A"), obs.point("B")
    if obs.tangents is not None:
        ta, tb = obs.tangents[:, 0], obs.tangents[:, 1]
    else:
        ends = [pl.end_tangents(c) for c in obs.curves]
        ta, tb = np.array([e[0] for e in ends]), np.array([e[1] for e in ends])
    ortho = Observations(
        camera.rays(a_px)[:, :2],
        camera.rays(b_px)[:, :2],
        ta,
        tb,
        [camera.rays(c)[:, :2] for c in obs.curves],
        tangents_from_curve=obs.tangents is None,
    )
    sigma = max(options.point_sigma, START_SIGMA_FLOOR_PX) / camera.focal_px
    opts = replace(options, point_sigma=sigma, progress=False)
    try:
        rec = reconstruct(ortho, options=opts)
    except CurveReconError as exc:
        raise _error(f"perspective curve: the weak-perspective start failed ({exc})") from None
    if rec.curve3d is None:
        raise _error("perspective curve: the weak-perspective start gave no curve")
    rot = rec.rotations()
    rel = np.einsum("fij,kj->fik", rot, rot[0])
    return rec.curve3d + np.array([0.0, 0.0, 1.0]), rel


def _translations(camera: Camera, rot, a3, b3, a_px, b_px) -> np.ndarray:
    """Every frame's T_f placing A and B (frame 0 coordinates) on their rays (least squares
    of m x (R X + T) = 0)."""
    out = np.empty((len(rot), 3))
    ma, mb = camera.rays(a_px), camera.rays(b_px)
    for f in range(len(rot)):
        sa, sb = _skew(ma[f]), _skew(mb[f])
        lhs = np.vstack([sa, sb])
        rhs = -np.concatenate([sa @ rot[f] @ a3, sb @ rot[f] @ b3])
        out[f] = np.linalg.lstsq(lhs, rhs, rcond=None)[0]
    return out


def _free(n_frames: int) -> np.ndarray:
    """The free parameters: all but A's depth (the unit) and frame 0's pose (the reference)."""
    free = np.ones(3 * CONTROL_POINTS + 6 * n_frames, bool)
    free[2] = False
    free[3 * CONTROL_POINTS : 3 * CONTROL_POINTS + 6] = False
    return free


def _start_state(data: _Data, curve0: np.ndarray, rel: np.ndarray):
    """(ctrl, rot, tra) of a curve in frame 0 and relative rotations, every T_f putting A and B
    on their rays; a frame whose start puts the curve behind the camera searched."""
    ctrl = fit_spline(curve0, CONTROL_POINTS)
    rot = rel.copy()
    rot[0] = np.eye(3)
    tra = _translations(data.camera, rot, ctrl[0], ctrl[-1], data.a_px, data.b_px)
    tra[0] = 0.0
    along = Basis(CONTROL_POINTS).values(np.linspace(0.0, 1.0, 50)) @ ctrl
    depth = np.einsum("fij,mj->fmi", rot, along)[..., 2] + tra[:, None, 2]
    behind = [f for f in np.flatnonzero(depth.min(axis=1) < 0.05 * ctrl[0, 2]) if f > 0]
    if behind:
        rot, tra, _ = pose_search(data, ctrl, rot, tra, behind)
    return ctrl, rot, tra


SWEEP_ROUNDS = 4
"""Most rounds of :func:`_swept` (search every frame's pose, bundle); it stops earlier when no
frame's rotation moves by more than ``MOVED_DEG`` or the cost does not drop."""


def _swept(data: _Data, fit: PinholeFit, rounds: int = SWEEP_ROUNDS) -> PinholeFit:
    """Every frame's pose, frame 0's too, searched against the fitted curve
    (:func:`pose_search`; a regauge when frame 0's moves) and the bundle rerun, while that
    lowers the cost: a frame whose start put it on another rotation branch shapes the curve
    less than the other frames, which find its pose."""
    free = _free(data.n)
    for _ in range(rounds):
        state = _searched(data, (fit.control, fit.rot, fit.trans))
        if all(_angle_deg(a, b) <= MOVED_DEG for a, b in zip(state[1], fit.rot, strict=True)):
            break
        new = bundle(data, *state, free)
        if not new.cost < fit.cost:
            break
        fit = new
    return fit


def _searched(data: _Data, state):
    """Every frame's pose, frame 0's too, searched against the state's curve
    (:func:`pose_search`), the state regauged when frame 0's moved."""
    ctrl, rot, tra = state
    rot, tra, _ = pose_search(data, ctrl, rot, tra, range(data.n))
    if _angle_deg(rot[0], np.eye(3)) > MOVED_DEG:
        ctrl, rot, tra = regauged(ctrl, rot, tra, rot[0], tra[0])
    rot[0], tra[0] = np.eye(3), 0.0
    return ctrl, rot, tra


_MIRROR = np.diag([1.0, 1.0, -1.0])


def mirrored_state(data: _Data, ctrl, rot):
    """The depth-reversed state: the curve mirrored about A's depth plane, every relative
    rotation conjugated by that mirror, translations from the rays again (the other depth
    order, of equal cost under weak perspective)."""
    a = ctrl[0]
    curve = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 200)) @ ctrl
    return _start_state(
        data, a + (curve - a) @ _MIRROR, np.einsum("ij,fjk,kl->fil", _MIRROR, rot, _MIRROR)
    )


PLANAR_TURN = 0.05
"""A fitted curve whose third singular value (of its points about their mean) is below this
fraction of its first is nearly planar: every frame then has a second pose of almost the same
image (turned over about the curve's plane, seen from the same place), which weak perspective
does not tell apart, and :func:`_turned_over` tries them (bench/persp_curve.py seed 0 at 50
times the depth variation: planarity 0.008, 16 of 19 frames turned over by the start)."""


def _turn(ctrl, rot, tra, frames):
    """Every frame of ``frames`` turned over: R_f <- M_f R_f S (S the reflection in the curve's
    plane through its mean, M_f the reflection along frame f's ray to that mean), the same
    image under weak perspective for a planar curve, the curve's mean held where it was seen:
    (rot, tra) (the callers put A and B on their rays instead)."""
    pts = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 200)) @ ctrl
    mid = pts.mean(axis=0)
    normal = np.linalg.svd(pts - mid)[2][2]
    s_ref = np.eye(3) - 2.0 * np.outer(normal, normal)
    rot, tra = rot.copy(), tra.copy()
    for f in frames:
        seen = rot[f] @ mid + tra[f]
        ray = seen / np.linalg.norm(seen)
        rot[f] = (np.eye(3) - 2.0 * np.outer(ray, ray)) @ rot[f] @ s_ref
        tra[f] = seen - rot[f] @ mid
    return rot, tra


def planarity(ctrl) -> float:
    """The curve's third singular value over its first (its points about their mean)."""
    pts = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 200)) @ ctrl
    sv = np.linalg.svd(pts - pts.mean(axis=0), compute_uv=False)
    return float(sv[2] / sv[0])


def _turned_over(data: _Data, fit: PinholeFit) -> PinholeFit:
    """A nearly planar curve's fit with every frame but frame 0 turned over (:func:`_turn`;
    the start may turn most frames over, which the bundle then bends the curve to fit), the
    bundle; then each frame's own turn-over refitted against the held curve and kept where it
    fits its frame better, the bundle and the sweep (:func:`_swept`)."""
    basis = Basis(len(fit.control))
    ctrl, free = fit.control, _free(data.n)
    rot = _turn(ctrl, fit.rot, fit.trans, range(1, data.n))[0]
    tra = _translations(data.camera, rot, ctrl[0], ctrl[-1], data.a_px, data.b_px)
    tra[0] = 0.0
    new = bundle(data, ctrl, rot, tra, free)
    ctrl, rot, tra = new.control, new.rot.copy(), new.trans.copy()
    r, _, _ = _frame_rows(data, basis, ctrl, rot, tra)
    own = np.sum(r**2, axis=1)
    turned = _turn(ctrl, rot, tra, range(1, data.n))[0]
    moved = False
    for f in range(1, data.n):
        t_f = _translations(data.camera, turned[f : f + 1], ctrl[0], ctrl[-1],
                            data.a_px[f : f + 1], data.b_px[f : f + 1])[0]  # fmt: skip
        try:
            cand = _refine_pose(data, basis, ctrl, turned[f], t_f, f)
        except CurveReconError:
            continue
        if cand[2] < own[f]:
            rot[f], tra[f], moved = cand[0], cand[1], True
    if moved:
        new = bundle(data, ctrl, rot, tra, free)
    return _swept(data, new)


def reconstruct_perspective_curve(obs, options=None):
    """The ordinary camera beyond the Section 2 table: free motion, one calibrated pinhole
    camera, A and B (tangents optional) and a polyline of the curve in every frame.

    The start is the paper's pipeline on the frames in normalised coordinates (weak
    perspective: pixels to rays), its curve placed at A's depth 1, and its mirror image (the
    depth order weak perspective leaves open).  From each: every frame's pose, frame 0's too,
    searched against the start's curve (:func:`pose_search`, a regauge when frame 0's moves),
    the pinhole curve bundle (every frame's rotation, 3-D translation and the curve), then the
    search and the bundle again while the cost drops (:func:`_swept`); for a nearly planar
    curve (``PLANAR_TURN``) also its frames turned over (:func:`_turned_over`); the lowest
    cost kept, and its mirror image refitted (:func:`mirrored_state`): the cost gap between the
    two depth orders is ``curve_bundle["mirror_dchi2"]``, the lower one the answer; below
    ``MIRROR_DCHI2`` the other is listed in ``alternatives`` (its shape and chi2) and its curve
    in ``curve_bundle["mirror_curve3d"]`` (with ``"mirror_chi2"``).

    Args:
        obs: ``RigidObservations`` with projection "perspective", motion "free", curves.
        options: ``ReconstructOptions`` (``point_sigma``: the pixel noise).
    Returns:
        A ``Reconstruction`` with ``curve3d``, ``curve3d_std``, ``curve3d_normal_std``,
        ``frame_poses``, ``points3`` (frame coordinates), the shape (c, alpha, beta, phi) of the
        fitted curve with its std, the paper's poses; lengths in units of A's depth in frame 0,
        or |AB| = ``length_ab`` when the configuration gives it.
    Raises:
        CurveReconError: input other than the above, too few frames, a failed start.
    """
    from curverecon.options import ReconstructOptions

    opts = options or ReconstructOptions()
    _check_ordinary(obs)
    camera = obs.configuration.camera
    curve0, rel = _orthographic_start(obs, opts)
    data = _prepare(camera, obs.curves, obs.point("A"), obs.point("B"), opts.point_sigma, 1.0)
    fits = []
    mirror = (
        curve0[0] + (curve0 - curve0[0]) * [1.0, 1.0, -1.0],
        np.einsum("ij,fjk,kl->fil", _MIRROR, rel, _MIRROR),
    )
    for curve, rots in ((curve0, rel), mirror):
        try:
            state = _searched(data, _start_state(data, curve, rots))
            fits.append(_swept(data, bundle(data, *state, _free(data.n))))
            if planarity(fits[-1].control) < PLANAR_TURN:
                fits.append(_turned_over(data, fits[-1]))
        except CurveReconError:
            continue
    if not fits:
        raise _error("perspective curve: the pinhole bundle found no curve in front of the camera")
    best = min(fits, key=lambda fit: fit.cost)
    try:  # the other depth order: the best fit's mirror image refitted
        other = bundle(data, *mirrored_state(data, best.control, best.rot), _free(data.n))
        gap = other.cost - best.cost
    except CurveReconError:
        other, gap = None, np.inf
    if gap < 0:
        best, other, gap = other, best, -gap
    return _answer(obs, best, gap, data, other if gap < MIRROR_DCHI2 else None)


def _shape_std(fit: PinholeFit, length_ab: float | None) -> np.ndarray | None:
    """Std of (c, alpha, beta, phi) from the control points' covariance (numerical Jacobian
    of the shape through the end control points; the length unit as the answer's)."""
    from curverecon.curve.spline import BundleResult, shape_and_poses

    if fit.cov is None:
        return None
    k = len(fit.control)
    free_ctrl = np.flatnonzero(fit.free[: 3 * k])

    def shape_of(ctrl):
        factor = 1.0 if length_ab is None else length_ab / np.linalg.norm(ctrl[-1] - ctrl[0])
        br = BundleResult(ctrl * factor, fit.rot[:1], fit.trans[:1], 1.0, fit.rms, 0, 0, 0, True)
        return shape_and_poses(br)[0]

    base = shape_of(fit.control)
    jac = np.zeros((4, len(free_ctrl)))
    for j, col in enumerate(free_ctrl):
        h = 1e-7 * max(1.0, float(np.abs(fit.control).max()))
        moved = fit.control.copy().ravel()
        moved[col] += h
        diff = shape_of(moved.reshape(k, 3)) - base
        diff[1:] = (diff[1:] + np.pi) % (2 * np.pi) - np.pi
        jac[:, j] = diff / h
    cov = jac @ fit.cov[: len(free_ctrl), : len(free_ctrl)] @ jac.T
    return np.sqrt(np.maximum(np.diag(cov), 0.0))


def _shape_poses(fit: PinholeFit, factor: float, sigma: float):
    """(shape, paper poses) of a fit, lengths times ``factor``, normalised."""
    from curverecon.curve.spline import BundleResult, shape_and_poses
    from curverecon.model.pose import normalise

    br = BundleResult(fit.control * factor, fit.rot, fit.trans * factor, sigma, fit.rms,
                      fit.cost, fit.cost, fit.iterations, fit.converged)  # fmt: skip
    shape, poses, _ = shape_and_poses(br)
    return normalise(shape, poses)


def _mirror_alternative(fit: PinholeFit | None, length_ab: float | None, sigma: float):
    """The mirror image's refit listed beside the answer (its depth order not decided):
    ([Alternative], {"mirror_chi2", "mirror_curve3d"}), or ([], {}) without one."""
    from curverecon.model.reconstruction import Alternative

    if fit is None:
        return [], {}
    c_depth = float(np.linalg.norm(fit.control[-1] - fit.control[0]))
    factor = 1.0 if length_ab is None else length_ab / c_depth
    shape, poses = _shape_poses(fit, factor, sigma)
    curve, _, _ = curve_points_and_std(fit, 200, length_ab)
    alt = Alternative(shape, poses, float(fit.cost), _shape_std(fit, length_ab))
    return [alt], {"mirror_chi2": float(fit.cost), "mirror_curve3d": curve.tolist()}


def _answer(obs, fit: PinholeFit, gap: float, data: _Data, mirror: PinholeFit | None = None):
    """The Reconstruction of a fitted pinhole bundle (see reconstruct_perspective_curve);
    ``mirror``: its mirror image's refit, listed as an alternative when given."""
    from curverecon.rigid.answer import configuration_answer

    cfg = obs.configuration
    ctrl = fit.control
    c_depth = float(np.linalg.norm(ctrl[-1] - ctrl[0]))
    factor = 1.0 if cfg.length_ab is None else cfg.length_ab / c_depth
    curve3d, std, nstd = curve_points_and_std(fit, 200, cfg.length_ab)
    tra = fit.trans * factor
    shape, poses = _shape_poses(fit, factor, data.sigma)
    alternatives, mirror_keys = _mirror_alternative(mirror, cfg.length_ab, data.sigma)
    a_f = np.einsum("fij,j->fi", fit.rot, ctrl[0] * factor) + tra
    b_f = np.einsum("fij,j->fi", fit.rot, ctrl[-1] * factor) + tra
    # every frame's rows: its polyline samples and A', B'; the degrees of freedom count them
    # less every free parameter (the penalty's rows, in fit.cost, fix the control points' slide)
    rows = _frame_rows(data, Basis(len(ctrl)), ctrl, fit.rot, fit.trans)[0]
    info = {
        "camera": "pinhole",
        "control_points": int(len(ctrl)),
        "sigma_px": float(data.sigma),
        "frame_rms_px": [float(v) for v in fit.rms],
        "iterations": int(fit.iterations),
        "converged": bool(fit.converged),
        "mirror_dchi2": None if not np.isfinite(gap) else float(gap),
        **mirror_keys,
    }
    return configuration_answer(
        cfg,
        "free",
        shape=shape,
        poses=poses,
        std=_shape_std(fit, cfg.length_ab),
        inliers=np.ones(obs.n_frames, bool),
        chi2=fit.cost,
        frame_chi2=np.sum(rows**2, axis=1),
        dof=rows.size - int(fit.free.sum()),
        alternatives=alternatives,
        estimator="curve-bundle",
        points3=np.stack([a_f, b_f], axis=1),
        names=("A", "B"),
        motion_parameters={},
        warnings=list(obs.warnings) + _warnings(fit, gap, data),
        frame_poses=np.concatenate([fit.rot, tra[:, :, None]], axis=2),
        curve3d=curve3d,
        curve3d_std=std,
        curve3d_normal_std=nstd,
        curve_bundle=info,
    )


def _warnings(fit: PinholeFit, gap: float, data: _Data) -> list[str]:
    out = []
    if gap < MIRROR_DCHI2:
        out.append(
            f"the perspective is too weak to tell the curve from its mirror image (depth order "
            f"reversed; chi2 {gap:.2g} apart, {MIRROR_DCHI2:g} needed): the mirror image is "
            "listed in alternatives and curve_bundle.mirror_curve3d"
        )
    worst = float(np.max(fit.rms))
    if worst > 5.0 * data.sigma:
        out.append(
            f"frame {int(np.argmax(fit.rms))}: the fitted curve stays {worst:.2g} px (RMS) from "
            f"its polyline ({worst / data.sigma:.1f} times the point noise)"
        )
    if not fit.converged:
        out.append("the pinhole curve bundle stopped at its iteration limit")
    return out
