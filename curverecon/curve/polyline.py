"""Image polylines: validation, arc length, end tangents, crossings and distances.

Conventions: a polyline is an ``(M, 2)`` array of image points ``(x, y)`` in pixels, ordered from
the traceable point A (first row) to B (last row). Lengths are in pixels; angles in radians.
"""

from __future__ import annotations

import numpy as np

#: Fewest points accepted for a polyline (a local fit of the end needs a handful).
MIN_POINTS = 5


def _error(message: str) -> Exception:
    from curverecon.errors import CurveReconError

    return CurveReconError(message)


def as_polyline(
    points: object, *, name: str = "polyline", min_points: int = MIN_POINTS
) -> np.ndarray:
    """Validate ``points``; return a float ``(M, 2)`` array with consecutive duplicates removed.

    Raises ``CurveReconError`` for a wrong shape, non-finite values, fewer than ``min_points``
    distinct points, or a polyline of zero length.
    """
    try:
        arr = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise _error(f"{name}: points must be a list of [x, y] numbers") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise _error(f"{name}: expected a list of [x, y] points, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise _error(f"{name}: contains NaN or infinite coordinates")
    if len(arr) == 0:
        raise _error(f"{name}: is empty")
    step = np.hypot(*np.diff(arr, axis=0).T)
    scale = max(float(np.ptp(arr, axis=0).max()), 1e-300)
    keep = np.concatenate([[True], step > 1e-12 * scale])
    arr = arr[keep]
    if len(arr) < min_points:
        raise _error(f"{name}: needs at least {min_points} distinct points, got {len(arr)}")
    length = float(np.hypot(*np.diff(arr, axis=0).T).sum())
    if not length > 0:
        raise _error(f"{name}: has zero length")
    if float(np.hypot(*(arr - arr[0]).T).max()) < 1e-9 * max(length, 1.0):
        raise _error(f"{name}: all points coincide")
    return arr


def arc_length(points: np.ndarray) -> np.ndarray:
    """Cumulative chord length ``(M,)`` of a polyline, starting at 0 (pixels)."""
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])


def resample(points: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` points equally spaced in arc length along the polyline (end points included).

    Returns ``(samples (n, 2), arc positions (n,))``.
    """
    s = arc_length(points)
    t = np.linspace(0.0, s[-1], n)
    return np.column_stack([np.interp(t, s, points[:, 0]), np.interp(t, s, points[:, 1])]), t


def bin_average(points: np.ndarray, n: int) -> np.ndarray:
    """A long polyline reduced to ``n`` points: the mean of its points in ``n - 2`` bins of equal
    arc length, between its first and last points (kept as they are: they are A' and B').

    Linear in the number of points.  Averaging (not decimating) keeps the information of every
    point: the means are as many times less noisy as the bins hold points.
    """
    points = np.asarray(points, float)
    if len(points) <= n:
        return points
    s = arc_length(points)
    inner = points[1:-1]
    k = n - 2
    bins = np.minimum((s[1:-1] / s[-1] * k).astype(int), k - 1)
    counts = np.bincount(bins, minlength=k)
    sums = np.column_stack([np.bincount(bins, inner[:, j], minlength=k) for j in range(2)])
    full = counts > 0
    means = sums[full] / counts[full, None]
    return np.vstack([points[:1], means, points[-1:]])


def _end_fit(
    points: np.ndarray, s: np.ndarray, fit_length: float, degree: int
) -> tuple[np.ndarray, float]:
    """Tangent at points[0], pointing into the curve, from a polynomial fit of x(s), y(s) against
    chord arc length over the stretch s <= fit_length.

    Returns ``(unit tangent, angle standard deviation per pixel of noise)`` (radians / pixel): the
    least-squares slope variance, sigma^2 [(V^T V)^-1]_11, over the slope's length.
    """
    n_min = degree + 3
    n = max(int(np.searchsorted(s, fit_length, side="right")), n_min)
    n = min(n, len(points))
    ss = s[:n]
    deg = min(degree, n - 2)
    scale = ss[-1] if ss[-1] > 0 else 1.0
    v = np.vander(ss / scale, deg + 1, increasing=True)
    coef, *_ = np.linalg.lstsq(v, points[:n], rcond=None)
    d = coef[1] if deg >= 1 else points[n - 1] - points[0]
    norm = float(np.hypot(*d))
    if not norm > 0:
        d = points[n - 1] - points[0]
        norm = float(np.hypot(*d))
    sd_per_px = float(np.sqrt(np.linalg.inv(v.T @ v)[1, 1]) / norm) if deg >= 1 else np.inf
    return d / norm, sd_per_px


#: Confidence-interval half-width (in standard deviations) of the adaptive fit length.
ICI_GAMMA = 2.0
#: Noise floor (pixels) of the adaptive fit length: float rounding and sub-pixel tracing.
ICI_NOISE_FLOOR = 0.001
#: Longest stretch the adaptive fit may use, as a fraction of the arc length.
ICI_MAX_FRACTION = 0.35


def _end_fit_adaptive(points: np.ndarray, s: np.ndarray, sigma: float, degree: int) -> np.ndarray:
    """Tangent at points[0] with the fit length chosen by intersection of confidence intervals.

    Windows grow geometrically (x1.2) from the fewest points a fit needs up to
    ``ICI_MAX_FRACTION`` of the arc length.  Each window's tangent angle gets the interval
    angle +- ICI_GAMMA * sd (sd from the fit, for the pixel noise ``sigma``); the longest window
    whose interval still meets all shorter windows' intervals is used.  Longer windows average
    the noise; a window that reaches into curvature the quadratic cannot follow moves the angle
    out of the shorter windows' intervals and stops the growth (the bias-variance balance of
    Goldenshluger and Nemirovski's ICI rule).  This matters at foreshortened ends: where the 3-D
    tangent points nearly along the view, the projected curve turns sharply right at its end,
    and any fixed fraction of the length is biased by degrees there.
    """
    n_min = degree + 3
    h_max = ICI_MAX_FRACTION * float(s[-1])
    h = float(s[min(n_min, len(s)) - 1])
    lo, hi = -np.inf, np.inf
    best: np.ndarray | None = None
    ref: float | None = None
    last_n = 0
    while True:
        n = min(max(int(np.searchsorted(s, h, side="right")), n_min), len(points))
        if n != last_n:
            t, sd_per_px = _end_fit(points, s, float(s[n - 1]), degree)
            angle = float(np.arctan2(t[1], t[0]))
            ref = angle if ref is None else ref
            a = (angle - ref + np.pi) % (2 * np.pi) - np.pi
            half = ICI_GAMMA * sigma * sd_per_px
            lo, hi = max(lo, a - half), min(hi, a + half)
            if lo > hi:
                break
            best, last_n = t, n
        if h >= h_max or n >= len(points):
            break
        h = min(1.2 * h, h_max)
    assert best is not None  # the first window always fits
    return best


def end_tangents(
    points: np.ndarray, *, fit_length: float | None = None, degree: int = 2
) -> tuple[np.ndarray, np.ndarray]:
    """Unit image tangent directions at the two ends of a polyline ordered from A to B.

    Returns ``(t_a, t_b)``: ``t_a`` at the first point, pointing into the curve (from A towards B
    along the curve); ``t_b`` at the last point, also pointing into the curve (from B back along
    it). Both are unit 2-D vectors in image coordinates (a tangent is a line, so callers may flip).

    Method: x(s) and y(s) are fitted by a polynomial of ``degree`` (default 2) in the chord arc
    length s over the first (last) ``fit_length`` pixels of the curve, and the derivative at the
    end is returned. A quadratic absorbs the curvature at the end (bias grows with the curvature's
    derivative times fit_length squared) while a stretch of many points averages pixel noise (the
    slope's variance falls like sigma^2 / (L^3 density)).  Without ``fit_length`` the length is
    chosen per end by intersection of confidence intervals (:func:`_end_fit_adaptive`) for the
    pixel noise estimated from the polyline (:func:`noise_level`, at least ``ICI_NOISE_FLOOR``).

    Raises ``CurveReconError`` for fewer than 5 distinct points, NaN, or a degenerate polyline.
    """
    pts = as_polyline(points, name="curve")
    rev = pts[::-1]
    if fit_length is None:
        sigma = max(noise_level(pts), ICI_NOISE_FLOOR)
        t_a = _end_fit_adaptive(pts, arc_length(pts), sigma, degree)
        t_b = _end_fit_adaptive(rev, arc_length(rev), sigma, degree)
        return t_a, t_b
    if not (np.isfinite(fit_length) and fit_length > 0):
        raise _error(f"fit_length must be a positive number, got {fit_length!r}")
    t_a, _ = _end_fit(pts, arc_length(pts), float(fit_length), degree)
    t_b, _ = _end_fit(rev, arc_length(rev), float(fit_length), degree)
    return t_a, t_b


def segment_line_crossings(
    points: np.ndarray, origin: np.ndarray, direction: np.ndarray, *, extend: float = 0.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Crossings of the infinite line ``origin + u * direction`` with a polyline.

    Returns ``(u, arc, sin_angle)``: the line parameter of each crossing, the arc-length position of
    the crossing on the polyline (pixels from the first point) and |sin| of the angle between the
    line and the crossed segment. ``extend`` (pixels) lengthens the first and last segments beyond
    the polyline's ends so a line through an end point is not lost to rounding.
    """
    p0 = points[:-1]
    p1 = points[1:].copy()
    seg = p1 - p0
    seglen = np.hypot(*seg.T)
    if extend > 0 and len(seg) > 0:
        p0 = p0.copy()
        p0[0] -= seg[0] / seglen[0] * extend
        p1[-1] += seg[-1] / seglen[-1] * extend
        seg = p1 - p0
    dnorm = float(np.hypot(*direction))
    dirn = direction / dnorm
    # Signed distance of the segment ends from the line.
    nrm = np.array([-dirn[1], dirn[0]])
    h0 = (p0 - origin) @ nrm
    h1 = (p1 - origin) @ nrm
    cross = (h0 <= 0) & (h1 > 0) | (h0 >= 0) & (h1 < 0) | (h0 == 0) & (h1 == 0)
    idx = np.nonzero(cross)[0]
    if len(idx) == 0:
        empty = np.zeros(0)
        return empty, empty, empty
    dh = h0[idx] - h1[idx]
    frac = np.where(dh != 0, h0[idx] / np.where(dh != 0, dh, 1.0), 0.0)
    pt = p0[idx] + frac[:, None] * seg[idx]
    u = ((pt - origin) @ dirn) / dnorm
    s = arc_length(points)
    ext_len = np.hypot(*seg[idx].T)
    # Arc position measured from the original first point (negative / beyond the total length on
    # the extended end segments).
    arc = s[:-1][idx] + frac * ext_len - np.where(idx == 0, extend, 0.0)
    seg_dir = seg[idx] / np.hypot(*seg[idx].T)[:, None]
    sin_angle = np.abs(seg_dir[:, 0] * dirn[1] - seg_dir[:, 1] * dirn[0])
    return u, arc, sin_angle


def parallel_line_crossings(
    points: np.ndarray, origins: np.ndarray, direction: np.ndarray, *, extend: float = 0.0
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Crossings of many parallel lines ``origins[k] + u * direction`` with one polyline.

    Returns flat arrays ``(line index k, u, |sin| of the crossing angle)``; see
    :func:`segment_line_crossings` for ``extend`` (pixels).
    """
    p0 = points[:-1].copy()
    p1 = points[1:].copy()
    seg = p1 - p0
    seglen = np.hypot(*seg.T)
    if extend > 0 and len(seg) > 0:
        p0[0] -= seg[0] / seglen[0] * extend
        p1[-1] += seg[-1] / seglen[-1] * extend
        seg = p1 - p0
    dnorm = float(np.hypot(*direction))
    dirn = direction / dnorm
    nrm = np.array([-dirn[1], dirn[0]])
    off = origins @ nrm  # (K,)
    h0 = (p0 @ nrm)[None, :] - off[:, None]  # (K, S)
    h1 = (p1 @ nrm)[None, :] - off[:, None]
    cross = ((h0 <= 0) & (h1 > 0)) | ((h0 >= 0) & (h1 < 0))
    kk, jj = np.nonzero(cross)
    dh = h0[kk, jj] - h1[kk, jj]
    frac = h0[kk, jj] / dh
    pt = p0[jj] + frac[:, None] * seg[jj]
    u = ((pt - origins[kk]) @ dirn) / dnorm
    seg_dir = seg[jj] / np.hypot(*seg[jj].T)[:, None]
    sin_angle = np.abs(seg_dir[:, 0] * dirn[1] - seg_dir[:, 1] * dirn[0])
    return kk, u, sin_angle


def distance_to_polyline(queries: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distance from each query point ``(Q, 2)`` to a polyline, and the arc position of the foot.

    Returns ``(distance (Q,), arc (Q,))`` in pixels. Memory is O(Q * M); callers chunk large Q.
    """
    q = np.atleast_2d(np.asarray(queries, dtype=float))
    p0 = points[:-1]
    seg = points[1:] - p0
    l2 = np.einsum("ij,ij->i", seg, seg)
    l2 = np.where(l2 > 0, l2, 1.0)
    rel = q[:, None, :] - p0[None, :, :]
    t = np.clip(np.einsum("qmj,mj->qm", rel, seg) / l2, 0.0, 1.0)
    foot = p0[None] + t[..., None] * seg[None]
    d2 = np.sum((q[:, None, :] - foot) ** 2, axis=-1)
    j = np.argmin(d2, axis=1)
    rows = np.arange(len(q))
    s = arc_length(points)
    arc = s[j] + t[rows, j] * np.sqrt(l2[j])
    return np.sqrt(d2[rows, j]), arc


def noise_level(points: np.ndarray, *, window: int = 9) -> float:
    """Rough estimate of the pixel noise of a polyline (pixels, standard deviation per coordinate).

    Residuals of local quadratic fits over ``window`` consecutive points, corrected for the
    degrees of freedom; a robust median over the curve. Returns 0 for very short polylines.
    """
    m = len(points)
    if m < window + 2:
        return 0.0
    half = window // 2
    u = np.arange(-half, half + 1, dtype=float)
    v = np.vander(u, 3, increasing=True)
    hat = v @ np.linalg.pinv(v)
    centre = hat[half]
    # Residual at the window centre: e = x_c - fitted; Var(e) = sigma^2 * (1 - hat_cc).
    # every window at once: (m - 2 half, 2, window), each centre's residual
    w = np.lib.stride_tricks.sliding_window_view(np.asarray(points, float), window, axis=0)
    r = w[:, :, half] - w @ centre
    var_factor = 1.0 - hat[half, half]
    mad = np.median(np.abs(r)) / 0.6745
    return float(mad / np.sqrt(var_factor))


def smooth(points: np.ndarray, half_width: float) -> np.ndarray:
    """Local quadratic regression of x(s), y(s) over arc length windows of +-half_width pixels.

    Tricube weights; one-sided windows at the ends (the end points are fitted too). Used to
    take pixel noise out of a polyline before intersecting it with lines.
    """
    s = arc_length(points)
    out = np.empty_like(points)
    lo = np.searchsorted(s, s - half_width, side="left")
    hi = np.searchsorted(s, s + half_width, side="right")
    for k in range(len(points)):
        a, b = int(lo[k]), int(hi[k])
        if b - a < 5:
            a, b = max(0, k - 2), min(len(points), k + 3)
        u = (s[a:b] - s[k]) / max(half_width, 1e-12)
        w = np.clip(1 - np.abs(u) ** 3, 0, None) ** 3 + 1e-6
        v = np.vander(u, 3, increasing=True)
        vw = v * w[:, None]
        coef, *_ = np.linalg.lstsq(vw.T @ v, vw.T @ points[a:b], rcond=None)
        out[k] = coef[0]
    return out
