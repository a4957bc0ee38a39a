"""The curve seen by a calibrated stereo pair: matched along epipolar lines and triangulated.

Conventions (curverecon/solvers/camera.py): camera coordinates x right, y down, z along the
optical axis; camera 1's coordinates are X1 = R X0 + t, so lengths are in the units of the rig's
``t``.  Polylines are (K, 2) pixel positions ordered from A' to B' in each view; ``point_sigma``
(pixels) is the noise of a polyline point across the curve, the same in both views.

Matching: every point of camera 0's polyline has its epipolar line in camera 1; its match is
where that line crosses camera 1's curve (a cubic spline through the polyline, parametrised by
its chord length).  Which crossing, where the line cuts the curve several times or only touches
it, the order along the curve decides: a dynamic programme chooses the matches non-decreasing
along camera 1's curve, A' matched to A' and B' to B'.

Std: a matched point is determined across the curve only (along the curve the match is free: a
slide along the curve moves no point of it).  The std of an interior point is the root of the
trace of its covariance in the plane normal to the curve, from ``point_sigma`` along each view's
image normal (first order): it is what the point's distance from the true curve is to be
compared with.  Where the epipolar plane contains the curve's tangent the two views constrain
the same direction and the std grows without bound; it is capped at the point's depth (nothing
known along the ray).  A and B are triangulated from both coordinates in both views and their
std is the root of the trace of their full 3x3 covariance.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from curverecon.curve.polyline import arc_length, as_polyline, noise_level
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
    back = np.zeros((n, m), dtype=np.int64)
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


def _jacobian(camera: Camera, x: np.ndarray) -> np.ndarray:
    """(..., 2, 3) derivative of the pixel position by the camera-coordinate point."""
    f = float(camera.focal_px)
    z = x[..., 2]
    jac = np.zeros(x.shape[:-1] + (2, 3))
    jac[..., 0, 0] = jac[..., 1, 1] = f / z
    jac[..., 0, 2] = -f * x[..., 0] / z**2
    jac[..., 1, 2] = -f * x[..., 1] / z**2
    return jac


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


def _unit_normals(tangents: np.ndarray) -> np.ndarray:
    norm = np.hypot(tangents[:, 0], tangents[:, 1])
    return np.column_stack([-tangents[:, 1], tangents[:, 0]]) / np.maximum(norm, 1e-300)[:, None]


def _tangent_window(points: np.ndarray) -> float:
    """Half-width (pixels of arc) of the chord giving a curve's direction at a point: twenty
    times the polyline's measured noise (``noise_level``), at least a hundredth of a step (the
    spline's own direction when the polyline has no noise), at most an eighth of the curve."""
    s = arc_length(points)
    step = float(np.median(np.diff(s)))
    return min(max(0.01 * step, 80.0 * noise_level(points)), s[-1] / 8.0)


class _View:
    """One view's curve as the matching needs it, at arc positions ``s`` of ``spline``:
    points, unit normals, the sign of the epipolar plane's turn along the curve (the same in
    both views at a true match) and the transversality |sin| of the curve to the epipolar line."""

    def __init__(self, rig: StereoRig, which: int, spline: _Spline, s: np.ndarray, w: float):
        rot = np.asarray(rig.R, float)
        camera = rig.camera0 if which == 0 else rig.camera1
        baseline = -rot.T @ np.asarray(rig.t, float)  # camera 1's centre, camera-0 coordinates
        epipole = _intrinsics(camera) @ (baseline if which == 0 else np.asarray(rig.t, float))
        self.points = spline(s)
        lo, hi = spline(s - w), spline(s + w)
        chord = hi - lo
        self.normals = _unit_normals(chord)
        tangent = chord / np.maximum(np.hypot(chord[:, 0], chord[:, 1]), 1e-300)[:, None]
        turn = _plane_angle(rig, which, camera, hi) - _plane_angle(rig, which, camera, lo)
        self.turn = np.sign(np.angle(np.exp(1j * turn)))
        lines = np.cross(epipole, np.column_stack([self.points, np.ones(len(s))]))
        nu = lines[:, :2] / np.maximum(np.hypot(lines[:, 0], lines[:, 1]), 1e-300)[:, None]
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


def _normal_std(rig, x0, n0, n1, sigma):
    """Std across the curve: rows r_k = n_k^T dpi_k/dX; root of sigma^2 trace((A A^T)^-1)
    with A = [r0; r1] (the min-norm error lies in the plane normal to the tangent r0 x r1)."""
    rot, t = np.asarray(rig.R, float), np.asarray(rig.t, float)
    x1 = x0 @ rot.T + t
    r0 = np.einsum("ki,kij->kj", n0, _jacobian(rig.camera0, x0))
    r1 = np.einsum("ki,kij->kj", n1, _jacobian(rig.camera1, x1)) @ rot
    cross = np.linalg.norm(np.cross(r0, r1), axis=1)
    top = np.sqrt((r0 * r0).sum(1) + (r1 * r1).sum(1))
    depth = np.abs(x0[:, 2])
    ok = cross > 1e-12 * top**2
    return np.where(ok, sigma * top / np.where(ok, cross, 1.0), depth).clip(max=depth)


def _turned(normals: np.ndarray, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return normals @ np.array([[c, s], [-s, c]])


def _robust_std(rig, x0, views, windows, sigma):
    """:func:`_normal_std` at its largest over the image normals turned by plus or minus their
    own std (a chord of half-width w between points of noise sigma: sigma / (sqrt(2) w)): the
    std is most sensitive to them where the curve runs near the epipolar line."""
    da = [sigma / (np.sqrt(2.0) * w) for w in windows]
    out = _normal_std(rig, x0, views[0].normals, views[1].normals, sigma)
    for s0 in (-1.0, 1.0):
        for s1 in (-1.0, 1.0):
            n0 = _turned(views[0].normals, s0 * da[0])
            n1 = _turned(views[1].normals, s1 * da[1])
            out = np.maximum(out, _normal_std(rig, x0, n0, n1, sigma))
    return out


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
    w0, w1 = _tangent_window(p0), _tangent_window(p1)
    view0 = _View(rig, 0, spline0, spline0.s, w0)
    lines = np.column_stack([p0, np.ones(len(p0))]) @ fundamental_matrix(rig).T
    order = _dp_order(lines, view0, _View(rig, 1, spline1, s_grid, w1))
    s1 = _refine(spline1, lines, s_grid, order, view0.turn)
    view1 = _View(rig, 1, spline1, s1, w1)
    x = _on_ray0(rig, p0, view1.points)
    std = _robust_std(rig, x, (view0, view1), (w0, w1), sigma)
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


def stereo_curve3d(
    rig: StereoRig,
    polylines0: Sequence[np.ndarray],
    polylines1: Sequence[np.ndarray],
    frame_poses: np.ndarray,
    point_sigma: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The curve from every stereo frame, in frame 0's camera-0 coordinates, fused.

    polylines0, polylines1: per frame camera 0's and camera 1's polylines (A' to B').
    frame_poses: (N, 3, 4) [R_f | T_f] with X_f = R_f X_0 + T_f (frame 0's camera-0 coordinates
    to frame f's).  Each frame is matched and triangulated (:func:`match_stereo_curve`), moved
    by X_0 = R_f^T (X_f - T_f), and the frames are fused: resampled at common arc positions
    (each frame's points placed by their foot on the fused curve, twice refined) and averaged
    with weights 1 / std^2; the std is 1 / sqrt(sum of the weights) (frames independent).
    One frame: its own points.  Returns (curve3d (M, 3), std (M,)); M is the largest frame's
    point count.  Raises CurveReconError for inconsistent frame counts or poses.
    """
    poses = np.asarray(frame_poses, dtype=float)
    n = len(polylines0)
    if n == 0 or len(polylines1) != n or poses.shape != (n, 3, 4):
        raise CurveReconError(
            f"stereo curve: {len(polylines0)} and {len(polylines1)} polylines for frame poses "
            f"of shape {poses.shape} (expected one (3, 4) pose per frame)"
        )
    if not np.all(np.isfinite(poses)):
        raise CurveReconError("stereo curve: frame poses must be finite numbers")
    curves, stds, params = [], [], []
    for f in range(n):
        x, std, p0 = _match(rig, polylines0[f], polylines1[f], point_sigma)
        rot, tr = poses[f, :, :3], poses[f, :, 3]
        curves.append((x - tr) @ rot)
        stds.append(std)
        s = arc_length(p0)
        params.append(s / s[-1])
    if n == 1:
        return curves[0], stds[0]
    m = max(len(c) for c in curves)
    fused, std = _fuse(curves, stds, params, m)
    for _ in range(2):
        params = [np.maximum.accumulate(_project_on(c, fused)) for c in curves]
        for u in params:
            u[0], u[-1] = 0.0, 1.0
        fused, std = _fuse(curves, stds, params, m)
    return fused, std


__all__ = ["fundamental_matrix", "match_stereo_curve", "stereo_curve3d"]
