"""Section 4 of the paper: recover the non-traceable points of the curve once the poses are known.

Conventions (docs/CONVENTIONS.md): the pose of frame i maps curve coordinates to camera
coordinates, ``X_cam = R_i X_curve + t_i``; orthographic projection keeps camera (x, y); A is the
curve frame's origin, so ``A_cam = t_i`` and the translations put A at depth z = 0. Polylines are
``(M_i, 2)`` image arrays ordered from A to B, in pixels. The result is expressed in frame 0's
camera coordinates (the contract's ``curve3d``), in pixels.

Method. A point X0 of frame 0's polyline fixes the line of sight ``(x0, y0, z)``, z free. Mapped
through frame 0's pose into the curve frame and through frame i's pose into frame i, it is the
3-D line ``P_i + z r_i`` whose image crosses frame i's polyline where the curve point X projects.
Each crossing gives a depth candidate ``z`` with a standard error ``sigma / (|r_i,xy| sin g)``
(g the crossing angle, sigma the pixel noise). Candidates from all frames are scored by how well
the 3-D point ``(x0, y0, z)`` reprojects onto every frame's polyline (truncated squared distance),
a dynamic programme along the curve picks one candidate per sample under a continuity penalty, and
each chosen depth is refined as the inverse-variance mean of the per-frame crossings that agree
with it. A is at z = 0 exactly; B is triangulated from the polylines' last points.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from curverecon.curve import polyline as pl
from curverecon.curve.section4_kernel import Grid, depth_path

#: Crossings flatter than this (|sin| of the angle between the projected line of sight and the
#: polyline) are rejected as grazing.
MIN_CROSSING_SIN = 0.1
#: Frames whose projected line-of-sight direction is shorter than this (|r_xy|, i.e. the sine of
#: the angle between the frame's and frame 0's viewing directions) carry no depth information.
MIN_VIEW_SIN = 0.05
#: |det[AB, t_A, t_B]| (unit vectors) below this: A, B and the tangents are nearly coplanar.
COPLANAR_THRESHOLD = 0.05


@dataclass
class CurveResult:
    """Recovered curve in frame 0's camera coordinates.

    points: (K, 3) curve samples from A to B (pixels; A at z = 0).
    warnings: human-readable one-line warnings.
    depth_std: (K,) estimated standard error of each sample's depth (pixels; inf where unknown).
    n_frames_used: (K,) number of frames whose crossing supports each sample's depth.
    interpolated: (K,) True where no frame gave a usable crossing and the depth was interpolated.
    coplanarity: |det| of the unit vectors AB, t_A, t_B (0 = coplanar); NaN when unavailable.
    frame_residual: (N,) median distance (pixels) from the reprojected curve to each frame's
        polyline; large values flag frames whose pose disagrees with the others; inf for the
        frames a search's ``residual_limit`` left unmeasured.
    """

    points: np.ndarray
    warnings: list[str] = field(default_factory=list)
    depth_std: np.ndarray | None = None
    n_frames_used: np.ndarray | None = None
    interpolated: np.ndarray | None = None
    coplanarity: float = float("nan")
    frame_residual: np.ndarray | None = None


def _error(message: str) -> Exception:
    from curverecon.errors import CurveReconError

    return CurveReconError(message)


def _check_inputs(
    polylines: Sequence[np.ndarray], rotations: np.ndarray, translations: np.ndarray
) -> tuple[list[np.ndarray], np.ndarray, np.ndarray]:
    rot = np.asarray(rotations, dtype=float)
    tr = np.asarray(translations, dtype=float)
    n = len(polylines)
    if rot.shape != (n, 3, 3):
        raise _error(f"rotations: expected shape ({n}, 3, 3), got {rot.shape}")
    if tr.shape != (n, 3):
        raise _error(f"translations: expected shape ({n}, 3), got {tr.shape}")
    if not (np.all(np.isfinite(rot)) and np.all(np.isfinite(tr))):
        raise _error("rotations/translations contain NaN or infinite values")
    err = np.abs(np.einsum("nij,nkj->nik", rot, rot) - np.eye(3)).max() if n else 0.0
    if err > 1e-6:
        raise _error("rotations are not orthonormal")
    if n < 2:
        raise _error(f"curve reconstruction needs at least 2 frames, got {n}")
    polys = [_valid_polyline(p, f"frame {i} curve") for i, p in enumerate(polylines)]
    return polys, rot, tr


def _default_samples(p0: np.ndarray) -> int:
    return int(np.clip(2 * len(p0), 20, 200))


def default_samples(polyline) -> int:
    """The number of samples :func:`reconstruct_curve` gives by default for a sequence whose
    frame 0 has this polyline: min(200, 2 M_0), at least 20 (M_0 its validated points)."""
    return _default_samples(_valid_polyline(polyline, "frame 0 curve"))


def _memo(cache: dict, key, make: Callable[[], Any]) -> Any:
    """``cache[key]``, made by ``make()`` on a miss (the section's caches by content; a cache
    is emptied when it holds ``_TREES_MAX`` entries)."""
    value = cache.get(key)
    if value is None:
        value = make()
        if len(cache) >= _TREES_MAX:
            cache.clear()
        cache[key] = value
    return value


#: validated polylines (``polyline.as_polyline``) by content: the branch search passes the same
#: polylines to :func:`reconstruct_curve` dozens of times (validating them every time was 8 %
#: of its time at 20 frames)
_VALID: dict[bytes, np.ndarray] = {}


def _valid_polyline(points, name: str) -> np.ndarray:
    """``polyline.as_polyline(points, name=name)``, by content for float arrays (read-only: the
    same array is handed out again)."""
    if not (isinstance(points, np.ndarray) and points.dtype == float):
        return pl.as_polyline(points, name=name)

    def make() -> np.ndarray:
        arr = pl.as_polyline(points, name=name)
        arr.setflags(write=False)
        return arr

    return _memo(_VALID, _poly_key(points), make)


def triangulate_point(
    image_points: np.ndarray, rotations: np.ndarray, translations: np.ndarray
) -> np.ndarray:
    """Least-squares curve-frame point X with ``(R_i X + t_i)[:2] = image_points[i]`` for all i."""
    a = rotations[:, :2, :].reshape(-1, 3)
    b = (image_points - translations[:, :2]).reshape(-1)
    x, *_ = np.linalg.lstsq(a, b, rcond=None)
    return x


def triangulate_direction(image_dirs: np.ndarray, rotations: np.ndarray) -> np.ndarray:
    """Unit curve-frame direction d whose projections ``(R_i d)[:2]`` are parallel to image_dirs."""
    nrm = np.column_stack([-image_dirs[:, 1], image_dirs[:, 0]])
    nrm /= np.hypot(*nrm.T)[:, None]
    a = np.einsum("nk,nkj->nj", nrm, rotations[:, :2, :])
    _, _, vt = np.linalg.svd(a)
    d = vt[-1]
    # Orient along the first image direction.
    if (rotations[0, :2, :] @ d) @ image_dirs[0] < 0:
        d = -d
    return d / np.linalg.norm(d)


def coplanarity(ab: np.ndarray, tangent_a: np.ndarray, tangent_b: np.ndarray) -> float:
    """|det| of the unit vectors along AB, the tangent at A and the tangent at B (0 = coplanar)."""
    m = np.array([v / np.linalg.norm(v) for v in (ab, tangent_a, tangent_b)])
    return float(abs(np.linalg.det(m)))


def _robust_sigma(polys: list[np.ndarray]) -> float:
    """Pixel noise used for weights and gates (never below 0.3 px: polyline discretisation)."""
    est = [noise_level(p) for p in polys]
    return max(float(np.median(est)), 0.3)


def polyline_sigma(polylines: Sequence[np.ndarray]) -> float:
    """The polylines' pixel noise as section 4 weighs them (median of every polyline's
    ``polyline.noise_level``, at least 0.3 px)."""
    return _robust_sigma([np.asarray(p, float) for p in polylines])


#: ``polyline.noise_level`` by content (the branch search reconstructs the same polylines
#: dozens of times, and the curve bundle measures them again in every run)
_NOISE: dict[tuple, float] = {}


def noise_level(poly: np.ndarray) -> float:
    """``polyline.noise_level(poly)`` by content (the same value; computed once per polyline:
    section 4, its smoothing and every run of the curve bundle ask for it again)."""
    poly = np.ascontiguousarray(poly, dtype=float)
    return _memo(_NOISE, _poly_key(poly), lambda: pl.noise_level(poly))


def _distances_for_frame(
    pts_xy: np.ndarray, poly: np.ndarray, spacing: float = 0.1, bound: float = np.inf
) -> np.ndarray:
    """Distance (pixels) of points to a polyline via a KD-tree on the densified polyline.

    The densified vertices are at most ``spacing`` apart, so the distance is over-estimated by at
    most spacing / 2 (spacing = 0.1 px here, far below the pixel noise the costs are scaled by).
    ``bound``: distances beyond it are returned as inf (the tree stops searching there: the
    truncated costs of the candidates need no more, and most candidates are far from most
    frames' polylines).  A finite bound searches a grid of cells one bound wide
    (``section4_kernel.Grid``: the same distances as the tree's, faster for many points).
    """
    if np.isfinite(bound) and bound > 0:
        return _dense_grid(poly, spacing, bound).query(pts_xy, bound)
    return _dense_tree(poly, spacing).query(pts_xy, distance_upper_bound=bound)[0]


def _median_distance(pts_xy: np.ndarray, poly: np.ndarray, grid_w: float) -> float:
    """``np.median`` of :func:`_distances_for_frame` without a bound, on the grid of cells
    ``grid_w`` wide (``section4_kernel.Grid.nearest``: rings of cells outwards, the k-d tree's
    distances; its queries of wrong-branch trials' far points, and before them the bounded
    grid's, were 14 % and then a quarter of the branch search's time).

    The distances within ``grid_w`` first (``Grid.query``: the same values where finite); the
    far points' only when fewer than half the points are within it (otherwise the median is
    among the near ones: the far points' rings of cells were most of the branch search's
    median time)."""
    grid = _dense_grid(poly, 0.1, grid_w)
    dist = grid.query(pts_xy, grid_w)
    far = ~np.isfinite(dist)
    if len(dist) - np.count_nonzero(far) < len(dist) // 2 + 1:
        dist[far] = grid.nearest(np.asarray(pts_xy)[far])
    return _median(dist)


def _median(values: np.ndarray) -> float:
    """``np.median`` of a 1-D array without NaN (its partition and mean, without its
    dispatch: the branch search takes thousands of medians of 60 values)."""
    n = len(values)
    half = n // 2
    if n == 0 or np.isnan(values).any():
        return float(np.median(values))
    if n % 2:
        return float(np.partition(values, half)[half])
    part = np.partition(values, [half - 1, half])
    return float((part[half - 1] + part[half]) / 2.0)


#: Grids of the densified polylines (:class:`section4_kernel.Grid`) by content and bound.
_GRIDS: dict[tuple, Grid] = {}


def _dense_grid(poly: np.ndarray, spacing: float, bound: float) -> Grid:
    poly = np.ascontiguousarray(poly, dtype=float)
    # the densified points only: the grids need no k-d tree (building one per polyline was a
    # tenth of the branch search's time)
    key = (_poly_key(poly), spacing, bound)
    return _memo(_GRIDS, key, lambda: Grid(_dense_points(poly, spacing), bound))


#: Densified polylines (length / spacing vertices, about ``spacing`` apart) by content: the
#: branch search calls :func:`reconstruct_curve` dozens of times on the same polylines
#: (densifying them was 40 % of the curve stage's time at 20 frames).
_DENSE: dict[tuple, np.ndarray] = {}
#: KD-trees of the densified polylines by content (:func:`_distances_for_frame` without a bound)
_TREES: dict[tuple, object] = {}
_TREES_MAX = 4096


def _dense_points(poly: np.ndarray, spacing: float) -> np.ndarray:
    """``poly`` resampled about ``spacing`` apart (length / spacing points, at least its own
    number, at most 200,000; read-only)."""
    poly = np.ascontiguousarray(poly, dtype=float)
    key = (_poly_key(poly), spacing)

    def make() -> np.ndarray:
        s = pl.arc_length(poly)
        n = int(min(max(len(poly), s[-1] / spacing), 200_000))
        dense = np.ascontiguousarray(pl.resample(poly, n)[0], dtype=float)
        dense.setflags(write=False)
        return dense

    return _memo(_DENSE, key, make)


def _dense_tree(poly: np.ndarray, spacing: float):
    from scipy.spatial import cKDTree

    poly = np.ascontiguousarray(poly, dtype=float)
    key = (_poly_key(poly), spacing)
    return _memo(_TREES, key, lambda: cKDTree(_dense_points(poly, spacing)))


#: Truncated squared distances of one frame's crossing candidates from another frame's
#: polyline, by content (see the unary cost of :func:`reconstruct_curve`).
_UNARY: dict[tuple, np.ndarray] = {}
_UNARY_MAX = 50_000


def _poly_key(poly: np.ndarray) -> bytes:
    """A polyline's content as a cache key.  The read-only arrays :func:`_valid_polyline` hands
    out are keyed once, by identity (the entry holds the array: its id is not reused while
    there; read-only and owning its data, not a view of another array: its content does not
    change): the branch search asks for the keys of the same polylines thousands of times."""
    memo = isinstance(poly, np.ndarray) and not poly.flags.writeable and poly.base is None
    if memo:
        hit = _KEYS.get(id(poly))
        if hit is not None and hit[0] is poly:
            return hit[1]
    key = np.ascontiguousarray(poly, dtype=float).tobytes() + repr(np.shape(poly)).encode()
    if memo:
        if len(_KEYS) >= _TREES_MAX:
            _KEYS.clear()
        _KEYS[id(poly)] = (poly, key)
    return key


#: :func:`_poly_key` of read-only polylines by identity (the array, its key)
_KEYS: dict[int, tuple[np.ndarray, bytes]] = {}
#: arc length of polylines by content
_LENGTHS: dict[bytes, float] = {}


def _length(poly: np.ndarray) -> float:
    """``pl.arc_length(poly)[-1]`` by content."""
    return _memo(_LENGTHS, _poly_key(poly), lambda: float(pl.arc_length(poly)[-1]))


#: Crossing candidates of one frame (:func:`_frame_candidates`) by content.
_CROSSINGS: dict[tuple, tuple | None] = {}


def _frame_candidates(poly, mi, bi, xy, sigma: float, length: float):
    """Frame i's crossings with frame 0's lines of sight through the samples ``xy`` (frame 0
    camera -> frame i camera ``mi``, ``bi``), merged where pixel noise splits one: (sample,
    depth, |sin| of the crossing angle) per candidate, by sample then depth; None if none."""
    r = mi[:, 2]
    view_sin = np.hypot(r[0], r[1])
    origin = (mi[:, :2] @ xy.T).T + bi  # (K, 3): z = 0 point on each line of sight
    extend = 2.0 * sigma + 0.01 * length
    kk, u, sn = pl.parallel_line_crossings(poly, origin[:, :2], r[:2], extend=extend)
    ok = sn >= MIN_CROSSING_SIN
    kk, u, sn = kk[ok], u[ok], sn[ok]
    order = np.lexsort((u, kk))
    kk, u, sn = kk[order], u[order], sn[order]
    if kk.size == 0:
        return None
    # Merge the crossings that pixel noise splits into a tight cluster (wiggles of a noisy
    # polyline near one true crossing): image distance along the line below 4 sigma.
    gap_px = np.diff(u) * view_sin
    new_group = np.concatenate([[True], (np.diff(kk) != 0) | (gap_px > 4.0 * sigma)])
    gid = np.cumsum(new_group) - 1
    n_g = int(gid[-1]) + 1 if len(gid) else 0
    cnt = np.bincount(gid, minlength=n_g)
    g_k = kk[new_group]
    g_z = np.bincount(gid, weights=u, minlength=n_g) / np.maximum(cnt, 1)
    g_s = np.bincount(gid, weights=sn, minlength=n_g) / np.maximum(cnt, 1)
    return g_k, g_z, g_s


def _project_xy(pts: np.ndarray, m: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Image (x, y) of frame-0 camera points in a frame (``m @ p + b``), row by row: the same
    rounding for a point whatever rows it comes with (the cache of the unary cost)."""
    x = pts[:, 0] * m[0, 0] + pts[:, 1] * m[0, 1] + pts[:, 2] * m[0, 2] + b[0]
    y = pts[:, 0] * m[1, 0] + pts[:, 1] * m[1, 1] + pts[:, 2] * m[1, 2] + b[1]
    return np.column_stack([x, y])


def reconstruct_curve(
    polylines: Sequence[np.ndarray],
    rotations: np.ndarray,
    translations: np.ndarray,
    *,
    n_samples: int | None = None,
    tangents: tuple[np.ndarray, np.ndarray] | None = None,
    smooth: bool = True,
    residual_limit: float = np.inf,
    residual_frames: np.ndarray | None = None,
) -> CurveResult:
    """Recover the 3-D curve from every frame's polyline and the (known) poses (paper, section 4).

    polylines: N arrays (M_i, 2), image points from A to B (pixels), one per frame.
    rotations: (N, 3, 3), translations: (N, 3); ``X_cam = R_i X_curve + t_i`` and A_cam = t_i.
    n_samples: number of output samples along frame 0's polyline (default min(200, 2 M_0),
        at least 20); the samples are equally spaced in frame 0's image arc length.
    tangents: optional 3-D unit tangent directions at A and at B in frame 0's camera coordinates
        (for the coplanarity check); estimated from the polylines' end tangents when omitted.
    smooth: apply a light local-quadratic smoothing along the curve (window ~3 % of the samples,
        at least 5) to the depth and, when frame 0's polyline is noisy, to x and y; it averages
        per-sample noise without visible bias on smooth curves.
    residual_limit, residual_frames: for a search that only needs to know whether the sum of
        ``frame_residual`` over ``residual_frames`` (bool (N,); default every frame) is at most
        ``residual_limit``: once the frames measured so far (in frame order) sum to more, the
        other frames' residuals are not measured and are inf (the sum is then inf; it would
        have exceeded the limit anyway).  The default measures every frame.

    Returns a :class:`CurveResult` with points (K, 3) in frame 0's camera coordinates.
    Raises ``CurveReconError`` for inconsistent shapes, non-finite values, or bad polylines.
    """
    polys, rot, tr = _check_inputs(polylines, rotations, translations)
    n_frames = len(polys)
    warnings: list[str] = []
    # Polylines run from A to B; A's image is t_i[:2]. Reverse any given from B to A.
    flipped = []
    for i, p in enumerate(polys):
        if np.hypot(*(p[-1] - tr[i, :2])) < np.hypot(*(p[0] - tr[i, :2])):
            polys[i] = p[::-1].copy()
            flipped.append(i)
    if flipped:
        warnings.append(f"frames {flipped}: curve given from B to A; reversed")
    sigma = _robust_sigma(polys)

    p0 = polys[0]
    if n_samples is None:
        n_samples = _default_samples(p0)
    if n_samples < 3:
        raise _error(f"n_samples must be at least 3, got {n_samples}")
    xy, _ = pl.resample(p0, int(n_samples))
    k_total = len(xy)

    # Frame 0 camera -> frame i camera: X_i = M_i X_0 + b_i.
    m = np.einsum("nij,kj->nik", rot, rot[0])  # R_i R_0^T
    b = tr - np.einsum("nij,j->ni", m, tr[0])
    r = m[:, :, 2]  # direction of frame 0's line of sight in frame i
    view_sin = np.hypot(r[:, 0], r[:, 1])
    informative = [i for i in range(1, n_frames) if view_sin[i] >= MIN_VIEW_SIN]
    if len(informative) < n_frames - 1:
        bad = [i for i in range(1, n_frames) if i not in informative]
        warnings.append(
            f"frames {bad} look along nearly the same direction as frame 0 and give no depth"
        )
    if not informative:
        raise _error("no frame views the curve from a different direction than frame 0")

    # Per-frame crossing candidates for every sample: depth, standard error.
    flat = _crossing_candidates(polys, m, b, xy, sigma, informative, view_sin)
    # Unary cost of each candidate: truncated squared reprojection distance over all frames.
    trunc = (3.0 * sigma + 1.0) ** 2
    unary = _unary_costs(polys, m, b, informative, xy, flat, sigma, trunc)
    z_dp, interpolated, zb = _dp_depths(polys, m, b, xy, flat, unary, sigma, trunc, informative)
    b_cam0 = np.array([xy[-1, 0], xy[-1, 1], zb])
    # Refinement: inverse-variance mean of the crossings (one per frame) that agree with the DP.
    z_ref, depth_std, n_used = _refined_depths(
        flat, z_dp, interpolated, k_total, sigma, len(informative)
    )

    # Fill interpolated samples by linear interpolation in arc length.
    known = ~interpolated
    idx = np.arange(k_total)
    if np.any(interpolated):
        z_ref[interpolated] = np.interp(idx[interpolated], idx[known], z_ref[known])
        frac = float(np.mean(interpolated))
        warnings.append(
            f"{int(interpolated.sum())} of {k_total} curve samples ({100 * frac:.0f}%) had no "
            "consistent crossing in any frame; their depth is interpolated"
        )

    points = np.column_stack([xy, z_ref])
    if smooth:
        points[:, 2] = _smooth_column(z_ref, depth_std)
        if noise_level(p0) > 0:
            flat_std = np.ones(k_total)
            for j in range(2):
                points[:, j] = _smooth_column(xy[:, j], flat_std)

    frame_residual = _frame_residuals(
        points, polys, m, b, sigma, trunc, residual_limit, residual_frames, warnings
    )
    cop = _coplanarity_check(b_cam0 - tr[0], polys, rot, tangents, warnings)
    return CurveResult(
        points=points,
        warnings=warnings,
        depth_std=depth_std,
        n_frames_used=n_used,
        interpolated=interpolated,
        coplanarity=cop,
        frame_residual=frame_residual,
    )


def _crossing_candidates(polys, m, b, xy, sigma, informative, view_sin):
    """Every informative frame's crossing candidates of frame 0's samples ``xy`` (cached by
    content, ``_CROSSINGS``), sorted by sample (within a sample in frame order, then the frame's
    own order): (sample, depth, frame, standard error) arrays."""
    lengths = [_length(p) for p in polys]
    # per frame (in frame order) its candidates' sample, depth, standard error
    parts: list[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]] = []
    xy_key = xy.tobytes()
    for i in informative:
        # by content: a trial of the branch search changes one frame's pose, not the others'
        key = (_poly_key(polys[i]), m[i].tobytes(), b[i].tobytes(), xy_key, sigma)
        found = _CROSSINGS.get(key)
        if found is None:
            found = _frame_candidates(polys[i], m[i], b[i], xy, sigma, lengths[i])
            if len(_CROSSINGS) >= _UNARY_MAX:
                _CROSSINGS.clear()
            _CROSSINGS[key] = found
        if found is None:  # no usable crossing in this frame
            continue
        g_k, g_z, g_s = found
        parts.append((g_k, g_z, np.full(len(g_k), i), np.sqrt(2.0) * sigma / (view_sin[i] * g_s)))
    # every candidate, by sample; within a sample in frame order, then the frame's own order
    if parts:
        cat_k, cat_z, cat_f, cat_s = (np.concatenate(v) for v in zip(*parts, strict=True))
    else:
        cat_k, cat_z, cat_f, cat_s = (np.zeros(0) for _ in range(4))
    order = np.argsort(cat_k, kind="stable")
    return (
        cat_k[order].astype(int),
        cat_z[order].astype(float),
        cat_f[order].astype(int),
        cat_s[order].astype(float),
    )


def _unary_costs(polys, m, b, informative, xy, flat, sigma, trunc) -> np.ndarray:
    """Each candidate's unary cost: its truncated squared reprojection distance summed over the
    informative frames (in frame order), in units of sigma^2; blocks cached by content
    (``_UNARY``)."""
    flat_k, flat_z, flat_f, _ = flat
    unary = np.zeros(len(flat_z))
    if len(flat_z):
        pts0 = np.column_stack([xy[flat_k], flat_z])
        # each (frame, source frame) block by content: a trial of the branch search that
        # switches one frame changes only that frame's blocks (its crossings, its distances).
        # The candidates grouped by source frame (each group in the candidates' order): every
        # destination frame's blocks are joined in this order and summed there in frame order
        # (the same sums), then put back once (not one fancy assignment per block)
        by_f = np.argsort(flat_f, kind="stable")
        fs, starts = np.unique(flat_f[by_f], return_index=True)
        ends = np.append(starts[1:], len(by_f))
        pts_f = pts0[by_f]
        src = [pts_f[lo:hi].tobytes() for lo, hi in zip(starts, ends, strict=True)]
        acc = np.zeros(len(flat_z))  # summed over the destination frames in frame order
        for i in informative:
            dest = (_poly_key(polys[i]), m[i].tobytes(), b[i].tobytes(), sigma)
            acc += _unary_blocks(polys[i], m[i], b[i], dest, src, pts_f, starts, ends, trunc)
        unary[by_f] = acc
    unary /= sigma**2
    return unary


def _unary_blocks(poly, mi, bi, dest, src, pts_f, starts, ends, trunc) -> np.ndarray:
    """One destination frame's truncated squared distances of every source frame's block of
    candidates (``pts_f[starts[g]:ends[g]]``), joined in block order; missing blocks measured in
    one query and cached."""
    vals: list = [None] * len(src)
    missing = []
    for g in range(len(src)):
        key = (dest, src[g])
        val = _UNARY.get(key)
        if val is None:
            missing.append((key, g))
        else:
            vals[g] = val
    if missing:
        # every missing block of this frame in one query (each point's distance is its
        # own: the same values as block by block)
        pts_i = _project_xy(
            np.concatenate([pts_f[starts[g] : ends[g]] for _, g in missing]), mi, bi
        )
        # beyond sqrt(trunc) the cost is trunc whatever the distance: the search
        # stops there
        dist = _distances_for_frame(pts_i, poly, bound=np.sqrt(trunc) * 1.0001)
        val_all = np.minimum(dist**2, trunc)
        if len(_UNARY) + len(missing) > _UNARY_MAX:
            _UNARY.clear()
        off = 0
        for key, g in missing:
            cnt = int(ends[g] - starts[g])
            vals[g] = _UNARY[key] = val_all[off : off + cnt]
            off += cnt
    return np.concatenate(vals) if len(vals) > 1 else vals[0]


def _dp_depths(polys, m, b, xy, flat, unary, sigma, trunc, informative):
    """The dynamic programme along the curve (``section4_kernel.depth_path``): (depth per
    sample, whether it was interpolated, B's depth)."""
    flat_k, flat_z = flat[0], flat[1]
    k_total = len(xy)
    # Dynamic programme along the curve. States: candidates, plus a "missing" state per sample.
    # Pairwise cost: continuity of depth relative to the image step between samples.
    step = float(np.hypot(*(xy[1] - xy[0]))) if k_total > 1 else 1.0
    step = max(step, 1e-9)
    miss_cost = len(informative) * trunc / sigma**2  # as bad as a candidate every frame rejects
    jump_w = 0.5  # cost per (depth slope)^2, in units of squared sigmas
    offsets = np.concatenate([[0], np.cumsum(np.bincount(flat_k, minlength=k_total))])
    zs = [flat_z[offsets[k] : offsets[k + 1]] for k in range(k_total)]
    us = [unary[offsets[k] : offsets[k + 1]] for k in range(k_total)]
    # Endpoint A: depth 0 exactly (translations put A at z = 0).
    zs[0] = np.array([0.0])
    us[0] = np.array([0.0])
    # Endpoint B: on frame 0's line of sight through its last point; each informative frame
    # gives the depth whose image is nearest its own last point. Weighted median (weights
    # |r_xy|^2) so that a frame with a wrong pose cannot drag it.
    r = m[:, :, 2]
    z_b = []
    w_b = []
    for i in informative:
        origin_b = m[i] @ np.array([xy[-1, 0], xy[-1, 1], 0.0]) + b[i]
        rxy = r[i, :2]
        z_b.append(float((polys[i][-1] - origin_b[:2]) @ rxy / (rxy @ rxy)))
        w_b.append(float(rxy @ rxy))
    zb = _weighted_median(np.asarray(z_b), np.asarray(w_b))
    zs[-1] = np.array([zb])
    us[-1] = np.array([0.0])

    # the dynamic programme (section4_kernel.depth_path) on every sample's states at once
    zz = np.concatenate(zs)
    uu = np.concatenate(us)
    offs = np.concatenate([[0], np.cumsum([len(v) for v in zs])]).astype(np.int64)
    z_dp, interpolated = depth_path(zz, uu, offs, float(step), jump_w, float(miss_cost))
    return z_dp, interpolated, zb


def _refined_depths(flat, z_dp, interpolated, k_total: int, sigma: float, n_informative: int):
    """Each sample's depth as the inverse-variance mean of the crossings (one per frame) within
    the gate of the DP depth: (depth, its std, crossings used)."""
    flat_k, flat_z, flat_f, flat_s = flat
    z_ref = z_dp.copy()
    depth_std = np.full(k_total, np.inf)
    n_used = np.zeros(k_total, dtype=int)
    depth_std[0] = 0.0
    depth_std[-1] = sigma / max(np.sqrt(n_informative), 1.0)
    if len(flat_z):
        # every sample at once: the crossings within the gate of the DP depth, one per frame
        # (the nearest; the first of equals), summed per sample in frame order
        dz = np.abs(flat_z - z_dp[flat_k])
        inner = (flat_k > 0) & (flat_k < k_total - 1)
        near = inner & ~interpolated[flat_k] & (dz <= np.maximum(3.0 * flat_s, 2.0 * sigma))
        idx = np.flatnonzero(near)
        idx = idx[np.lexsort((idx, dz[idx], flat_f[idx], flat_k[idx]))]
        first = np.ones(len(idx), bool)
        first[1:] = (np.diff(flat_k[idx]) != 0) | (np.diff(flat_f[idx]) != 0)
        sel = idx[first]
        if len(sel):
            ks = flat_k[sel]
            starts = np.flatnonzero(np.concatenate([[True], np.diff(ks) != 0]))
            w = 1.0 / flat_s[sel] ** 2
            sw = np.add.reduceat(w, starts)
            k_sel = ks[starts]
            z_ref[k_sel] = np.add.reduceat(w * flat_z[sel], starts) / sw
            depth_std[k_sel] = 1.0 / np.sqrt(sw)
            n_used[k_sel] = np.diff(np.append(starts, len(sel)))
    return z_ref, depth_std, n_used


def _frame_residuals(
    points, polys, m, b, sigma, trunc, residual_limit, residual_frames, warnings
) -> np.ndarray:
    """Consistency of every frame with the recovered curve: its median reprojection distance
    (inf once the counted frames' running sum exceeds ``residual_limit``); a warning names the
    frames beyond 3 sigma + 1 px."""
    n_frames = len(polys)
    frame_residual = np.zeros(n_frames)
    grid_w = np.sqrt(trunc) * 1.0001  # the unary cost's grids (built already)
    counted = np.ones(n_frames, bool) if residual_frames is None else residual_frames
    # a running sum beyond the limit by more than its rounding (n eps relative; the residuals
    # are >= 0): the search's own sum exceeds the limit too
    stop = residual_limit * (1.0 + 1e-9)
    running = 0.0
    for i in range(n_frames):
        if running > stop:
            frame_residual[i:] = np.inf
            break
        proj_i = points @ m[i].T + b[i]
        frame_residual[i] = _median_distance(proj_i[:, :2], polys[i], grid_w)
        if counted[i]:
            running += frame_residual[i]
    limit = 3.0 * sigma + 1.0
    bad_frames = [
        i for i in range(n_frames) if limit < frame_residual[i] < np.inf
    ]  # (inf: not measured, ``residual_limit``)
    if bad_frames:
        worst = max(frame_residual[i] for i in bad_frames)
        warnings.append(
            f"frames {bad_frames}: the recovered curve reprojects up to {worst:.1f} px (median) "
            f"from their polylines (limit {limit:.1f} px); their poses look inconsistent with "
            "the other frames and were outvoted"
        )
    return frame_residual


def _coplanarity_check(ab_cam0, polys, rot, tangents, warnings) -> float:
    """Coplanarity of A, B and the tangents (the paper's condition for section 4), with a
    warning below ``COPLANAR_THRESHOLD``; nan when a direction is zero."""
    if tangents is not None:
        ta3 = np.asarray(tangents[0], dtype=float)
        tb3 = np.asarray(tangents[1], dtype=float)
    else:
        tans = [pl.end_tangents(p) for p in polys]
        ta_c = triangulate_direction(np.array([t[0] for t in tans]), rot)
        tb_c = triangulate_direction(np.array([t[1] for t in tans]), rot)
        ta3, tb3 = rot[0] @ ta_c, rot[0] @ tb_c
    cop = float("nan")
    if np.linalg.norm(ab_cam0) > 0 and np.linalg.norm(ta3) > 0 and np.linalg.norm(tb3) > 0:
        cop = coplanarity(ab_cam0, ta3, tb3)
        if cop < COPLANAR_THRESHOLD:
            warnings.append(
                f"A, B and the end tangents are nearly coplanar (|det| = {cop:.3f} < "
                f"{COPLANAR_THRESHOLD}): the paper's reconstruction of non-traceable points "
                "needs them non-coplanar; the poses and the curve may be unreliable"
            )
    return cop


def _weighted_median(values: np.ndarray, weights: np.ndarray) -> float:
    order = np.argsort(values)
    cw = np.cumsum(weights[order])
    return float(values[order][np.searchsorted(cw, 0.5 * cw[-1])])


def _smooth_column(z: np.ndarray, std: np.ndarray) -> np.ndarray:
    """Local weighted quadratic regression of one coordinate against sample index.

    Window: +-max(2, 1.5 % of the samples); tricube weights times inverse variances; the two end
    samples (A, B) are kept.  The windows of finite standard errors away from the ends solve
    their 3 x 3 normal equations all at once (the window's weighted moments of the offset; a
    loop of ``lstsq`` per sample was a third of the final section-4 run of the branch search);
    the others - the end samples' weight 1e6 or an unknown depth's 1e-6 in the window make
    those equations ill-conditioned - one by one with ``lstsq`` as before.
    """
    k_total = len(z)
    half = max(2, int(round(0.015 * k_total)))
    if k_total < 2 * half + 3:
        return z
    w_all = np.where(np.isfinite(std) & (std > 0), 1.0 / np.maximum(std, 1e-6) ** 2, 0.0)
    w_all[~np.isfinite(std)] = 1e-6
    w_all[0] = w_all[-1] = 1e6
    out = np.array(z, dtype=float)
    width = 2 * half + 1
    u = np.arange(-half, half + 1, dtype=float)
    tricube = (1 - (np.abs(u) / (half + 1)) ** 3) ** 3
    # windows of samples half+1 .. K-half-2 (neither end sample in them), those of finite std
    ok = np.isfinite(std) & (std > 0)
    whole = sliding_window_view(ok, width)[1:-1].all(axis=1)
    ks = np.arange(half + 1, k_total - half - 1)[whole]
    if len(ks):
        w = sliding_window_view(w_all, width)[ks - half] * tricube
        zw = sliding_window_view(z, width)[ks - half] * w
        mom = [w @ u**p for p in range(5)]
        lhs = np.stack([np.stack(mom[j : j + 3], axis=-1) for j in range(3)], axis=-2)
        rhs = np.stack([zw @ u**p for p in range(3)], axis=-1)
        out[ks] = np.linalg.solve(lhs, rhs[..., None])[:, 0, 0]
    rest = np.setdiff1d(np.arange(1, k_total - 1), ks)
    for k in rest:
        lo, hi = max(0, k - half), min(k_total, k + half + 1)
        uk = np.arange(lo, hi) - k
        v = np.vander(uk.astype(float), 3, increasing=True)
        wk = w_all[lo:hi] * (1 - (np.abs(uk) / (half + 1)) ** 3) ** 3
        a = v * wk[:, None]
        coef, *_ = np.linalg.lstsq(a.T @ v, a.T @ z[lo:hi], rcond=None)
        out[k] = coef[0]
    return out
