"""The curve seen by a calibrated stereo pair: matched along epipolar lines and triangulated.

Conventions (curverecon/solvers/camera.py): camera coordinates x right, y down, z along the
optical axis; camera 1's coordinates are X1 = R X0 + t, so lengths are in the units of the rig's
``t``.  Polylines are (K, 2) pixel positions ordered from A' to B' in each view; ``point_sigma``
(pixels) is the noise of a polyline point across the curve, the same in both views.

Matching: every point of camera 0's polyline has its epipolar line in camera 1; its match is
where that line crosses camera 1's curve (a cubic spline through the polyline, parametrised by
its chord length).  Which crossing, where the line cuts the curve several times or only touches
it, the order along the curve decides: a dynamic programme chooses the matches non-decreasing
along camera 1's curve, A' matched to A' and B' to B', and a crossing where the epipolar plane
turns the other way along the curve than in camera 0 is penalised (no true match does; near an
epipolar tangency this picks the right one of two close crossings).  Where the line misses the
curve (noise at a tangency), the curve's closest approach to it is taken.

Std: a matched point is determined across the curve only (along the curve the match is free: a
slide along the curve moves no point of it).  Each view's curve, shifted by ``point_sigma``
across itself, moves its crossing with the epipolar line by point_sigma / tau along the line
(tau: |sin| of the angle between the curve and the line, lessened by one std of the curve's
fitted direction); the two rays then fix the point within its epipolar plane.  The std of an
interior point is the root of the trace of that in-plane covariance (first order): it is what
the point's distance from the true curve is to be compared with, and somewhat more where the
curve runs obliquely to the plane (part of the in-plane error is then a slide).  Where the curve
runs along the epipolar line (tau -> 0) the std grows without bound; it is capped at the
point's depth (nothing known along the ray).  A and B are triangulated from both coordinates in
both views and their std is the root of the trace of their full 3x3 covariance.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from curverecon.curve.polyline import arc_length, as_polyline, noise_level
from curverecon.curve.stereo_place import pixel_jacobian as _jacobian
from curverecon.curve.stereo_place import place_shape
from curverecon.curve.stereo_smooth import smooth_curve
from curverecon.curve.stereo_turn import best_turn, turned_pose
from curverecon.errors import CurveReconError
from curverecon.solvers.camera import Camera, StereoRig

#: Samples of camera 1's curve per polyline point in the dynamic programme (at least
#: ``_MIN_GRID``, at most ``_MAX_GRID``); the match is then refined between samples.
_GRID_PER_POINT = 8
_MIN_GRID = 400
_MAX_GRID = 6000

#: Pixels of cost per unit transversality for a match where the epipolar plane turns the other
#: way along camera 1's curve than along camera 0's (impossible for a true match; soft, since
#: the turn's sign is unreliable where the curve runs along the epipolar line).
_TURN_PENALTY = 100.0

#: Half-width of the local fits giving a noisy curve's direction, in multiples of its
#: measured noise: chosen on the 0.5 px scenes of tests/test_stereo_curve.py (std coverage).
_FIT_NOISE_WIDTHS = 12.0

#: Rounds of placing the fused shape in every frame by its reprojection and fusing again.
_PLACEMENTS = 2

#: Points of a long fused curve whose feet are searched at a time (memory).
_CHUNK = 256


def _intrinsics(camera: Camera) -> np.ndarray:
    cx, cy = (float(v) for v in camera.principal_point)
    f = float(camera.focal_px)
    return np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])


def fundamental_matrix(rig: StereoRig) -> np.ndarray:
    """(3, 3) F with ``[p1, 1] F [p0, 1]^T = 0`` for pixels p0, p1 of one 3-D point."""
    t = np.asarray(rig.t, float)
    tx = np.array([[0.0, -t[2], t[1]], [t[2], 0.0, -t[0]], [-t[1], t[0], 0.0]])
    k0 = np.linalg.inv(_intrinsics(rig.camera0))
    k1 = np.linalg.inv(_intrinsics(rig.camera1))
    return k1.T @ tx @ np.asarray(rig.R, float) @ k0


def _checked(polyline: object, name: str) -> np.ndarray:
    """A polyline of at least 2 distinct points whose ends A' and B' differ."""
    p = as_polyline(polyline, name=name, min_points=2)
    length = float(arc_length(p)[-1])
    if float(np.hypot(*(p[-1] - p[0]))) <= 1e-9 * max(length, 1.0):
        raise CurveReconError(f"{name}: A' and B' coincide (its first and last points)")
    return p


class _Spline:
    """Camera 1's curve: a cubic spline through the polyline on its chord length (pixels)."""

    def __init__(self, points: np.ndarray) -> None:
        from scipy.interpolate import CubicSpline

        self.s = arc_length(points)
        self.length = float(self.s[-1])
        kind = "not-a-knot" if len(points) >= 4 else "natural"
        self._f = CubicSpline(self.s, points, bc_type=kind)

    def __call__(self, s: np.ndarray) -> np.ndarray:
        return self._f(np.clip(s, 0.0, self.length))


def _line_distance(lines: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Signed distance (pixels) of ``points`` (..., 2) from ``lines`` (..., 3)."""
    return (lines[..., 0] * points[..., 0] + lines[..., 1] * points[..., 1] + lines[..., 2]) / (
        np.hypot(lines[..., 0], lines[..., 1])
    )


def _dp_order(lines: np.ndarray, view0: _View, view1: _View) -> np.ndarray:
    """Grid index per point of camera 0 (non-decreasing, first 0, last the grid's end)
    minimising the summed distances (pixels) of the chosen grid points from the epipolar lines,
    plus ``_TURN_PENALTY`` times the lesser transversality where the epipolar plane turns the
    other way along camera 1's curve than along camera 0's (no true match does)."""
    n, m = len(lines), len(view1.points)
    idx = np.arange(m)
    back = np.zeros((n, m), dtype=np.int32)
    cost = np.full(m, np.inf)
    cost[0] = 0.0
    for i in range(1, n):
        run = np.minimum.accumulate(cost)
        back[i] = np.maximum.accumulate(np.where(cost <= run, idx, 0))
        wrong = (view1.turn != view0.turn[i]) & (view1.turn != 0) & (view0.turn[i] != 0)
        penalty = _TURN_PENALTY * np.minimum(view1.transversal, view0.transversal[i]) * wrong
        cost = run + np.abs(_line_distance(lines[i], view1.points)) + penalty
    order = np.empty(n, dtype=np.int64)
    order[-1] = m - 1
    for i in range(n - 1, 0, -1):
        order[i - 1] = back[i, order[i]]
    return order


def _refine(spline: _Spline, lines: np.ndarray, s_grid: np.ndarray, order, turn0):
    """Camera 1's arc position of every match: the crossing of the epipolar line with the curve
    nearest the programme's choice (one where the plane turns as in camera 0 first; bisection),
    else the curve's closest approach to the line."""
    n, step = len(lines), s_grid[1] - s_grid[0]
    rows = np.arange(n)
    centre = s_grid[order]
    lo = np.clip(centre - 2 * step, 0.0, spline.length)
    hi = np.clip(centre + 2 * step, 0.0, spline.length)
    u = np.linspace(0.0, 1.0, 33)
    samples = lo[:, None] + (hi - lo)[:, None] * u[None, :]
    g = _line_distance(lines[:, None, :], spline(samples))
    change = np.sign(g[:, :-1]) * np.sign(g[:, 1:]) <= 0
    # the distance from the line falls where the plane's angle rises (F's orientation)
    wrong = np.sign(g[:, 1:] - g[:, :-1]) == turn0[:, None]
    mid = 0.5 * (samples[:, :-1] + samples[:, 1:])
    gap = np.where(change, np.abs(mid - centre[:, None]) + 4 * step * wrong, np.inf)
    k = np.argmin(gap, axis=1)
    crossing = np.isfinite(gap[rows, k])
    a, b = samples[rows, k], samples[rows, k + 1]
    ga = g[rows, k]
    for _ in range(60):
        c = 0.5 * (a + b)
        gc = _line_distance(lines, spline(c))
        left = np.sign(gc) * np.sign(ga) <= 0
        b, a, ga = np.where(left, c, b), np.where(left, a, c), np.where(left, ga, gc)
    s1 = np.where(crossing, 0.5 * (a + b), 0.0)
    # no crossing: the closest approach (golden section on |g| around the nearest sample)
    k = np.argmin(np.abs(g), axis=1)
    a = samples[rows, np.maximum(k - 1, 0)]
    b = samples[rows, np.minimum(k + 1, 32)]
    ratio = 0.5 * (np.sqrt(5.0) - 1.0)
    for _ in range(60):
        c, d = b - ratio * (b - a), a + ratio * (b - a)
        keep_left = np.abs(_line_distance(lines, spline(c))) < np.abs(
            _line_distance(lines, spline(d))
        )
        b, a = np.where(keep_left, d, b), np.where(keep_left, a, c)
    s1 = np.where(crossing, s1, 0.5 * (a + b))
    s1[0], s1[-1] = 0.0, spline.length
    return np.maximum.accumulate(s1)


def _on_ray0(rig: StereoRig, p0: np.ndarray, p1: np.ndarray) -> np.ndarray:
    """(K, 3) camera-0 points on the rays of ``p0`` nearest the rays of ``p1``."""
    rot, t = np.asarray(rig.R, float), np.asarray(rig.t, float)
    d0 = rig.camera0.rays(p0)
    d1 = rig.camera1.rays(p1) @ rot  # R^T m1, camera-0 directions
    c1 = -rot.T @ t
    a, b, c = (d0 * d0).sum(1), (d0 * d1).sum(1), (d1 * d1).sum(1)
    e, g = d0 @ c1, d1 @ c1
    den = a * c - b * b
    lam = np.where(den > 1e-15 * a * c, (c * e - b * g) / np.where(den > 0, den, 1.0), 0.0)
    return lam[:, None] * d0


def _end_point(rig: StereoRig, p0: np.ndarray, p1: np.ndarray, sigma: float):
    """A traceable end seen in both views: Gauss-Newton on the reprojection error from the
    rays' nearest point; returns (point (3,), std: root of the trace of its covariance)."""
    rot, t = np.asarray(rig.R, float), np.asarray(rig.t, float)
    x = _on_ray0(rig, p0[None], p1[None])[0]
    if x[2] <= 0:
        raise CurveReconError("stereo curve: an end (A' or B') does not triangulate in front")
    for _ in range(8):
        x1 = rot @ x + t
        res = np.concatenate([rig.camera0.project(x) - p0, rig.camera1.project(x1) - p1])
        jac = np.vstack([_jacobian(rig.camera0, x), _jacobian(rig.camera1, x1) @ rot])
        x = x - np.linalg.lstsq(jac, res, rcond=None)[0]
    x1 = rot @ x + t
    jac = np.vstack([_jacobian(rig.camera0, x), _jacobian(rig.camera1, x1) @ rot])
    std = sigma * float(np.sqrt(np.trace(np.linalg.inv(jac.T @ jac))))
    return x, std


def _fit_slopes(s: np.ndarray, points: np.ndarray, h: float, sigma: float):
    """Unit tangents (K, 2) at a polyline's own points (K >= 7) from local quadratic fits of
    x(s), y(s) (tricube weights over +-h of arc, wider where fewer than six neighbours fall
    inside), and their angle std (radians) for noise sigma.  Banded: each point sees only the
    points within its window."""
    k = len(s)
    idx = np.arange(k)
    ahead = np.searchsorted(s, s + h, side="right") - 1 - idx
    behind = idx - np.searchsorted(s, s - h, side="left")
    band = int(max(7, ahead.max(), behind.max())) + 1
    cols = idx[:, None] + np.arange(-band, band + 1)[None, :]
    valid = (cols >= 0) & (cols < k)
    cols = np.clip(cols, 0, k - 1)
    d = np.where(valid, s[cols] - s[:, None], np.inf)
    # at least six neighbours inside every window (sparse polylines)
    hh = np.maximum(h, 1.05 * np.partition(np.abs(d), 6, axis=1)[:, 6])
    w = np.where(valid, np.clip(1.0 - np.abs(d / hh[:, None]) ** 3, 0.0, None) ** 3, 0.0)
    d = np.where(valid, d, 0.0)
    powers = d[..., None] ** np.arange(5)  # (K, band, 5)
    mom = np.einsum("ek,ekp->ep", w, powers)
    mom2 = np.einsum("ek,ekp->ep", w * w, powers)
    ij = np.add.outer(np.arange(3), np.arange(3))
    a_mat, b_mat = mom[:, ij], mom2[:, ij]
    rhs = np.einsum("ek,ekp,ekc->epc", w, powers[..., :3], points[cols])
    coef = np.linalg.solve(a_mat, rhs)
    slope = coef[:, 1, :]
    inv = np.linalg.inv(a_mat)
    var = np.einsum("eij,ejk,eki->ei", inv, b_mat, inv)[:, 1]
    norm = np.maximum(np.hypot(slope[:, 0], slope[:, 1]), 1e-300)
    return slope / norm[:, None], sigma * np.sqrt(np.maximum(var, 0.0)) / norm


class _Directions:
    """Unit tangents of a view's curve at any arc positions, and their angle std (radians).

    A polyline with noise (``noise_level``): local quadratic fits over +-``_FIT_NOISE_WIDTHS``
    times its measured noise (at least two steps) at its points, interpolated; without noise
    to speak of, the spline's own direction (std 0)."""

    def __init__(self, points: np.ndarray, spline: _Spline, sigma: float) -> None:
        self.spline = spline
        s = spline.s
        self.step = float(np.median(np.diff(s)))
        h = _FIT_NOISE_WIDTHS * noise_level(points)  # 0 for polylines of fewer than 11 points
        self.fits = None
        if h >= 0.5 * self.step:
            self.fits = _fit_slopes(s, points, max(h, 2.0 * self.step), sigma)

    def __call__(self, s_eval: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if self.fits is None:
            w = 0.01 * self.step
            chord = self.spline(s_eval + w) - self.spline(s_eval - w)
            norm = np.maximum(np.hypot(chord[:, 0], chord[:, 1]), 1e-300)
            return chord / norm[:, None], np.zeros(len(s_eval))
        s, (tangent, da) = self.spline.s, self.fits
        t = np.column_stack([np.interp(s_eval, s, tangent[:, k]) for k in range(2)])
        norm = np.maximum(np.hypot(t[:, 0], t[:, 1]), 1e-300)
        return t / norm[:, None], np.interp(s_eval, s, da)


class _View:
    """One view's curve as the matching needs it, at arc positions ``s`` of ``spline`` with
    unit tangents ``tangent``: points, the sign of the epipolar plane's turn along the curve
    (the same in both views at a true match), the epipolar lines' unit normals and the
    transversality |sin| of the curve to the epipolar line."""

    def __init__(self, rig: StereoRig, which: int, spline: _Spline, s: np.ndarray, tangent):
        camera = rig.camera0 if which == 0 else rig.camera1
        rot = np.asarray(rig.R, float)
        baseline = -rot.T @ np.asarray(rig.t, float)  # camera 1's centre, camera-0 coordinates
        epipole = _intrinsics(camera) @ (baseline if which == 0 else np.asarray(rig.t, float))
        self.points = spline(s)
        eps = 1e-3 * tangent
        turn = _plane_angle(rig, which, camera, self.points + eps) - _plane_angle(
            rig, which, camera, self.points - eps
        )
        self.turn = np.sign(np.angle(np.exp(1j * turn)))
        lines = np.cross(epipole, np.column_stack([self.points, np.ones(len(s))]))
        nu = lines[:, :2] / np.maximum(np.hypot(lines[:, 0], lines[:, 1]), 1e-300)[:, None]
        self.line_normals = nu
        self.transversal = np.abs((nu * tangent).sum(1))


def _plane_angle(rig: StereoRig, which: int, camera: Camera, pixels: np.ndarray) -> np.ndarray:
    """Angle of the epipolar plane through each pixel's ray about the baseline (radians)."""
    rot = np.asarray(rig.R, float)
    b = -rot.T @ np.asarray(rig.t, float)
    b = b / np.linalg.norm(b)
    u1 = np.cross(b, np.eye(3)[int(np.argmin(np.abs(b)))])
    u1 /= np.linalg.norm(u1)
    u2 = np.cross(b, u1)
    rays = camera.rays(pixels)
    if which == 1:
        rays = rays @ rot
    n = np.cross(b, rays)
    return np.arctan2(n @ u2, n @ u1)


def _line_directions(view: _View) -> np.ndarray:
    """Unit directions (K, 2) of the epipolar lines through a view's points."""
    return np.column_stack([-view.line_normals[:, 1], view.line_normals[:, 0]])


def _plane_std(rig: StereoRig, x0: np.ndarray, views, angle_std, sigma: float) -> np.ndarray:
    """Std of each matched point within its epipolar plane (camera-0 coordinates, units of t).

    A view's curve shifted by e across itself moves its crossing with the epipolar line by
    e / tau along the line (tau = |sin| of the curve's angle to the line, made smaller by one
    std of the curve's direction, ``angle_std``); the two positions along the lines fix the
    point in the plane (two rays), so its covariance is sigma^2 (M^T W M)^-1 with M the
    positions' derivatives in the plane and W = diag(tau0^2, tau1^2).  Unlike the curve's
    3-D tangent (the two views' tangent planes meet at the narrow angle the baseline
    subtends), tau is well determined from the images wherever the curve crosses the lines
    clearly.  Capped at the depth where tau vanishes (nothing known along the ray)."""
    rot, t = np.asarray(rig.R, float), np.asarray(rig.t, float)
    x1 = x0 @ rot.T + t
    a0 = np.einsum("ki,kij->kj", _line_directions(views[0]), _jacobian(rig.camera0, x0))
    a1 = np.einsum("ki,kij->kj", _line_directions(views[1]), _jacobian(rig.camera1, x1)) @ rot
    e1 = x0 / np.linalg.norm(x0, axis=1)[:, None]
    normal = np.cross(-rot.T @ t, x0)
    e2 = np.cross(normal / np.linalg.norm(normal, axis=1)[:, None], e1)
    m = np.stack(
        [np.stack([(a * e1).sum(1), (a * e2).sum(1)], axis=1) for a in (a0, a1)], axis=1
    )  # (K, 2, 2): rows the two lines' positions, columns the plane's axes
    tau = []
    for view, da in zip(views, angle_std, strict=True):
        angle = np.arcsin(np.clip(view.transversal, 0.0, 1.0)) - da
        tau.append(np.sin(np.clip(angle, 0.0, None)))
    info = np.einsum("kri,kr,krj->kij", m, np.stack(tau, axis=1) ** 2, m)
    det = info[:, 0, 0] * info[:, 1, 1] - info[:, 0, 1] ** 2
    depth = np.abs(x0[:, 2])
    scale = np.einsum("kri,kri->k", m, m)
    ok = det > 1e-18 * scale**2
    var = (info[:, 0, 0] + info[:, 1, 1]) / np.where(ok, det, 1.0)
    return np.where(ok, sigma * np.sqrt(np.maximum(var, 0.0)), depth).clip(max=depth)


def _match(rig: StereoRig, polyline0, polyline1, point_sigma: float):
    """``match_stereo_curve`` plus camera 0's checked polyline."""
    sigma = float(point_sigma)
    if not (np.isfinite(sigma) and sigma > 0):
        raise CurveReconError(f"stereo curve: point_sigma must be positive, got {sigma}")
    p0 = _checked(polyline0, "stereo curve: camera 0's polyline")
    p1 = _checked(polyline1, "stereo curve: camera 1's polyline")
    spline0, spline1 = _Spline(p0), _Spline(p1)
    n_grid = int(np.clip(_GRID_PER_POINT * len(p1), _MIN_GRID, _MAX_GRID))
    s_grid = np.linspace(0.0, spline1.length, n_grid)
    directions1 = _Directions(p1, spline1, sigma)
    t0, da0 = _Directions(p0, spline0, sigma)(spline0.s)
    view0 = _View(rig, 0, spline0, spline0.s, t0)
    lines = np.column_stack([p0, np.ones(len(p0))]) @ fundamental_matrix(rig).T
    t_grid, _ = directions1(s_grid)
    order = _dp_order(lines, view0, _View(rig, 1, spline1, s_grid, t_grid))
    s1 = _refine(spline1, lines, s_grid, order, view0.turn)
    t1, da1 = directions1(s1)
    view1 = _View(rig, 1, spline1, s1, t1)
    x = _on_ray0(rig, p0, view1.points)
    std = _plane_std(rig, x, (view0, view1), (da0, da1), sigma)
    for k in (0, len(p0) - 1):
        x[k], std[k] = _end_point(rig, p0[k], p1[k], sigma)
    if np.any(x[:, 2] <= 0):
        raise CurveReconError(
            "stereo curve: matched points triangulate behind camera 0 (do the two polylines "
            "show the same curve, in the same order from A' to B'?)"
        )
    return x, std, p0


def match_stereo_curve(
    rig: StereoRig, polyline0: np.ndarray, polyline1: np.ndarray, point_sigma: float
) -> tuple[np.ndarray, np.ndarray]:
    """Triangulate every point of camera 0's polyline with its match on camera 1's.

    rig: the calibrated pair (X1 = R X0 + t).  polyline0, polyline1: (K0, 2), (K1, 2) pixels,
    each from A' to B' (consecutive duplicate points are dropped).  point_sigma: pixels, noise
    of a polyline point across the curve in either view.

    Returns (points3 (M, 3) in camera 0's coordinates, units of t; std (M,)), M the number of
    distinct points of polyline0, in its order: A first, B last.  ``std`` covers the distance
    from the true curve (see the module's docstring); A's and B's cover their full error.
    Raises CurveReconError for polylines of fewer than 2 points, non-finite values, A' and B'
    coinciding, or matches that land behind the camera.
    """
    x, std, _ = _match(rig, polyline0, polyline1, point_sigma)
    return x, std


def _project_on(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Normalised arc position (0 at A, 1 at B) of each point's foot on a 3-D polyline."""
    if len(points) > _CHUNK:
        return np.concatenate(
            [_project_on(points[k : k + _CHUNK], curve) for k in range(0, len(points), _CHUNK)]
        )
    seg = np.diff(curve, axis=0)
    len2 = np.maximum((seg * seg).sum(1), 1e-300)
    rel = points[:, None, :] - curve[None, :-1, :]
    u = np.clip((rel * seg[None]).sum(2) / len2[None], 0.0, 1.0)
    foot = curve[None, :-1, :] + u[..., None] * seg[None]
    k = np.argmin(((points[:, None, :] - foot) ** 2).sum(2), axis=1)
    cum = np.concatenate([[0.0], np.cumsum(np.sqrt(len2))])
    pos = cum[k] + u[np.arange(len(points)), k] * np.sqrt(len2[k])
    return pos / cum[-1]


def _fuse(curves, stds, params, m: int):
    """Every frame resampled at m common arc positions, averaged with weights 1 / std^2."""
    grid = np.linspace(0.0, 1.0, m)
    wsum, acc = np.zeros(m), np.zeros((m, 3))
    for x, s, u in zip(curves, stds, params, strict=True):
        xi = np.column_stack([np.interp(grid, u, x[:, k]) for k in range(3)])
        w = 1.0 / np.maximum(np.interp(grid, u, s), 1e-300) ** 2
        wsum += w
        acc += w[:, None] * xi
    return acc / wsum[:, None], 1.0 / np.sqrt(wsum)


def _checked_poses(polylines0, polylines1, frame_poses) -> np.ndarray:
    poses = np.asarray(frame_poses, dtype=float)
    n = len(polylines0)
    if n == 0 or len(polylines1) != n or poses.shape != (n, 3, 4):
        raise CurveReconError(
            f"stereo curve: {len(polylines0)} and {len(polylines1)} polylines for frame poses "
            f"of shape {poses.shape} (expected one (3, 4) pose per frame)"
        )
    if not np.all(np.isfinite(poses)):
        raise CurveReconError("stereo curve: frame poses must be finite numbers")
    return poses.copy()


def _align_turns(frames, poses: np.ndarray, chord: np.ndarray) -> None:
    """Every frame's pose turned about the chord (A, B in frame 0's coordinates, in place):
    first each curve laid on the best-determined frame's (least median std), then each on the
    frames fused, and all turned back together by frame 0's turn (a start for ``_placed``,
    which places the whole in frame 0 by frame 0's images)."""
    a0 = np.asarray(chord[0], float)
    axis = np.asarray(chord[1], float) - a0
    norm = float(np.linalg.norm(axis))
    if not (np.isfinite(norm) and norm > 0):
        raise CurveReconError("stereo curve: the chord's ends A and B coincide")
    axis = axis / norm
    given = poses.copy()
    total = np.zeros(len(frames))

    def moved(f: int) -> np.ndarray:
        return (frames[f][0] - poses[f, :, 3]) @ poses[f, :, :3]

    best = int(np.argmin([np.median(std) for _, std, _ in frames]))
    reference = moved(best)
    for search in (True, False, False):
        for f in range(len(frames)):
            if search and f == best:
                continue
            total[f] += best_turn(moved(f), frames[f][1], reference, a0, axis, search)
            poses[f] = turned_pose(given[f], a0, axis, total[f])
        reference = _fused_frames(frames, poses)[0]
    for f in range(len(frames)):
        poses[f] = turned_pose(given[f], a0, axis, total[f] - total[0])


def _fused_frames(frames, poses: np.ndarray):
    """Frames [(points in frame f's camera-0 coordinates, std, camera-0 arc positions)] moved
    to frame 0 and fused (``stereo_curve3d``)."""
    curves = [(x - pose[:, 3]) @ pose[:, :3] for (x, _, _), pose in zip(frames, poses, strict=True)]
    stds = [std for _, std, _ in frames]
    params = [u for _, _, u in frames]
    if len(frames) == 1:
        return curves[0], stds[0], params[0]
    m = max(len(c) for c in curves)
    fused, std = _fuse(curves, stds, params, m)
    for _ in range(2):
        params = [np.maximum.accumulate(_project_on(c, fused)) for c in curves]
        for u in params:
            u[0], u[-1] = 0.0, 1.0
        fused, std = _fuse(curves, stds, params, m)
    return fused, std, np.linspace(0.0, 1.0, m)


def _placed(rig: StereoRig, frames, poses: np.ndarray, views, sigma: float):
    """(curve (M, 3) in frame 0's camera-0 coordinates, std (M,), poses (N, 3, 4)): the fused
    shape placed in every frame by its reprojection onto that frame's two polylines
    (``curve.stereo_place``), the frames fused again on these placements, ``_PLACEMENTS``
    times; the answer is the shape placed in frame 0 the same way (not through frame 0's
    triangulated points, which run far off where its curve lies along the epipolar lines),
    its std the fused std and that placement's together, the poses relative to frame 0's
    placement (frame 0 keeps the pose given, ``poses[0]``: the identity unless the first
    frame given is another)."""
    placed = poses.copy()
    for _ in range(_PLACEMENTS):
        shape, std, _ = _fused_frames(frames, placed)
        placed = np.array(
            [
                place_shape(rig, shape, placed[f], views[f], sigma, std)[0]
                for f in range(len(frames))
            ]
        )
    shape, std, _ = _fused_frames(frames, placed)
    placed[0], std0 = place_shape(rig, shape, placed[0], views[0], sigma, std)
    # the answer's coordinates are frame 0's: X_first = G X_0 with G the first frame's pose
    to_shape = _compose(_inverse(placed[0]), poses[0])  # X_0 -> Y
    for f in range(len(frames)):
        poses[f] = _compose(placed[f], to_shape)
    back = _inverse(to_shape)
    return shape @ back[:, :3].T + back[:, 3], np.hypot(std, std0), poses


def _compose(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(3, 4) pose of x -> a(b(x)) for (3, 4) poses [R | T] (x -> R x + T)."""
    return np.column_stack([a[:, :3] @ b[:, :3], a[:, :3] @ b[:, 3] + a[:, 3]])


def _inverse(a: np.ndarray) -> np.ndarray:
    """(3, 4) pose of the inverse motion of [R | T]: [R^T | -R^T T]."""
    return np.column_stack([a[:, :3].T, -a[:, :3].T @ a[:, 3]])


def stereo_curve_and_poses(
    rig: StereoRig,
    polylines0: Sequence[np.ndarray],
    polylines1: Sequence[np.ndarray],
    frame_poses: np.ndarray,
    point_sigma: float,
    chord: np.ndarray | None = None,
    smooth: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`stereo_curve3d` and the frame poses it used: with ``chord`` ((2, 3) A and B in
    frame 0's camera-0 coordinates), for poses whose turn about the chord the points leave free
    (A and B alone), each frame's turn is first taken from its curve (a global search laying
    its triangulated curve on the best-seen frame's, then closest points on the fused curve),
    then the fused shape is placed in every frame by its reprojection onto that frame's two
    polylines (``curve.stereo_place``; a frame that triangulates its curve badly, running along
    its epipolar lines, still places a known shape well) and the frames fused again on those
    placements; the curve returned is the shape placed in frame 0 (the first frame given: its
    pose is kept), its std the fused std and that placement's together, and the poses are the
    placements relative to frame 0's.  Without ``chord`` the poses as given.  ``smooth``: each
    frame's points smoothed along the curve (``curve.stereo_smooth``).  Returns (curve3d
    (M, 3), std (M,), poses (N, 3, 4))."""
    poses = _checked_poses(polylines0, polylines1, frame_poses)
    frames = []
    for f in range(len(poses)):
        x, std, p0 = _match(rig, polylines0[f], polylines1[f], point_sigma)
        s = arc_length(p0)
        u = s / s[-1]
        if smooth:  # each frame's own scatter, before the frames' poses and fusion
            x, std = smooth_curve(u, x, std)
        frames.append((x, std, u))
    if chord is None or len(frames) == 1:
        curve, std, _ = _fused_frames(frames, poses)
        return curve, std, poses
    _align_turns(frames, poses, np.asarray(chord, float))
    views = [
        (np.asarray(a, float), np.asarray(b, float))
        for a, b in zip(polylines0, polylines1, strict=True)
    ]
    curve, std, poses = _placed(rig, frames, poses, views, float(point_sigma))
    return curve, std, poses


def stereo_curve3d(
    rig: StereoRig,
    polylines0: Sequence[np.ndarray],
    polylines1: Sequence[np.ndarray],
    frame_poses: np.ndarray,
    point_sigma: float,
    chord: np.ndarray | None = None,
    smooth: bool = True,
) -> tuple[np.ndarray, np.ndarray]:
    """The curve from every stereo frame, in frame 0's camera-0 coordinates, fused.

    polylines0, polylines1: per frame camera 0's and camera 1's polylines (A' to B').
    frame_poses: (N, 3, 4) [R_f | T_f] with X_f = R_f X_0 + T_f (frame 0's camera-0 coordinates
    to frame f's).  Each frame is matched and triangulated (:func:`match_stereo_curve`), moved
    by X_0 = R_f^T (X_f - T_f), and the frames are fused: resampled at common arc positions
    (each frame's points placed by their foot on the fused curve, twice refined) and averaged
    with weights 1 / std^2; the std is 1 / sqrt(sum of the weights) (frames independent).
    One frame: its own points.  ``chord``: (2, 3) A and B in frame 0's coordinates when each
    frame's turn about AB is free (:func:`stereo_curve_and_poses`).  Returns (curve3d (M, 3),
    std (M,)); M is the largest frame's point count.  Raises CurveReconError for inconsistent
    frame counts or poses.
    """
    curve, std, _ = stereo_curve_and_poses(
        rig, polylines0, polylines1, frame_poses, point_sigma, chord, smooth
    )
    return curve, std


__all__ = [
    "fundamental_matrix",
    "match_stereo_curve",
    "stereo_curve3d",
    "stereo_curve_and_poses",
]
