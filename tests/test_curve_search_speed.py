"""The speed-ups of the branch search by the curve and of the curve bundle (issue 13, item 6)
give the values of the constructions they replace: section 4's grid distances with pruned
cells against a scan of all 3 x 3 cells, the median of the frame residuals without the far
points' tree queries, the batched local quadratic smoothing against one ``lstsq`` per sample,
the cache of validated polylines, the batched pose increments of the bundle's LM, and the
duplicate joint refits scored once (``CurveOptions.refit_same_tol``).
"""

from __future__ import annotations

import numpy as np
import pytest

from curverecon.curve import bundle as bd
from curverecon.curve import polyline as pl
from curverecon.curve import section4 as s4
from curverecon.curve.branches import _distinct_optima
from curverecon.curve.section4_kernel import Grid
from curverecon.errors import CurveReconError


def _scan_all_cells(grid: Grid, q: np.ndarray, bound: float) -> np.ndarray:
    """Nearest-point distance over every point of the 3 x 3 cells around each query."""
    out = np.empty(len(q))
    for p, (qx, qy) in enumerate(q):
        fx = int(np.floor((qx - grid.x0) / grid.cell))
        fy = int(np.floor((qy - grid.y0) / grid.cell))
        best = np.inf
        for cy in range(max(fy - 1, 0), min(fy + 1, grid.ny - 1) + 1):
            for cx in range(max(fx - 1, 0), min(fx + 1, grid.nx - 1) + 1):
                c = cy * grid.nx + cx
                pts = grid.sorted[grid.start[c] : grid.start[c + 1]]
                if len(pts):
                    best = min(best, float(((pts[:, 0] - qx) ** 2 + (pts[:, 1] - qy) ** 2).min()))
        d = np.sqrt(best)
        out[p] = d if d < bound else np.inf
    return out


@pytest.mark.parametrize("seed", range(6))
def test_grid_query_prunes_cells_without_changing_distances(seed):
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, 1.0, 3000)
    pts = np.column_stack([250.0 * t, 80.0 * np.sin(3.0 * t * rng.uniform(1, 3))])
    cell = rng.uniform(1.0, 6.0)
    grid = Grid(pts, cell)
    q = np.vstack(
        [
            pts[rng.integers(0, len(pts), 400)] + rng.normal(size=(400, 2)) * cell,
            # on cell corners and edges, and outside the grid
            np.column_stack(
                [
                    grid.x0 + rng.integers(-2, grid.nx + 2, 100) * cell,
                    grid.y0 + rng.integers(-2, grid.ny + 2, 100) * cell,
                ]
            ),
            pts[:50],
        ]
    )
    for bound in (cell, 0.4 * cell):
        np.testing.assert_array_equal(grid.query(q, bound), _scan_all_cells(grid, q, bound))


@pytest.mark.parametrize("far_fraction", [0.0, 0.3, 0.5, 0.51, 0.8, 1.0])
def test_median_distance_equals_median_of_all_distances(far_fraction):
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, 200)
    poly = np.column_stack([200.0 * t, 40.0 * np.sin(5.0 * t)])
    for n in (59, 60):
        near = poly[rng.integers(0, 200, n)] + rng.normal(size=(n, 2))
        far = poly[rng.integers(0, 200, n)] + [0.0, 30.0] + rng.normal(size=(n, 2)) * 5
        pts = np.where((rng.random(n) < far_fraction)[:, None], far, near)
        full = np.median(s4._distances_for_frame(pts, poly))
        assert s4._median_distance(pts, poly, 4.0) == full


def _smooth_one_by_one(z: np.ndarray, std: np.ndarray) -> np.ndarray:
    """Section 4's smoothing as it was written: one ``lstsq`` per sample."""
    k_total = len(z)
    half = max(2, int(round(0.015 * k_total)))
    if k_total < 2 * half + 3:
        return z
    w_all = np.where(np.isfinite(std) & (std > 0), 1.0 / np.maximum(std, 1e-6) ** 2, 0.0)
    w_all[~np.isfinite(std)] = 1e-6
    w_all[0] = w_all[-1] = 1e6
    out = z.copy()
    for k in range(1, k_total - 1):
        lo, hi = max(0, k - half), min(k_total, k + half + 1)
        u = np.arange(lo, hi) - k
        v = np.vander(u.astype(float), 3, increasing=True)
        w = w_all[lo:hi] * (1 - (np.abs(u) / (half + 1)) ** 3) ** 3
        a = v * w[:, None]
        coef, *_ = np.linalg.lstsq(a.T @ v, a.T @ z[lo:hi], rcond=None)
        out[k] = coef[0]
    return out


@pytest.mark.parametrize("k_total", [7, 60, 200, 331])
def test_batched_smoothing_equals_one_lstsq_per_sample(k_total):
    rng = np.random.default_rng(k_total)
    z = np.cumsum(rng.normal(size=k_total)) * 10.0
    std = np.abs(rng.normal(size=k_total)) + 0.2
    std[0] = 0.0
    scale = np.abs(z).max() + 1.0
    np.testing.assert_allclose(
        s4._smooth_column(z, std), _smooth_one_by_one(z, std), rtol=0, atol=1e-8 * scale
    )
    ones = np.ones(k_total)
    np.testing.assert_allclose(
        s4._smooth_column(z, ones), _smooth_one_by_one(z, ones), rtol=0, atol=1e-9 * scale
    )


def test_validated_polylines_are_cached_read_only_and_still_checked():
    rng = np.random.default_rng(3)
    poly = np.cumsum(rng.normal(size=(50, 2)), axis=0)
    poly[10] = poly[9]  # a repeated point: removed
    first = s4._valid_polyline(poly, "frame 0 curve")
    np.testing.assert_array_equal(first, pl.as_polyline(poly))
    assert s4._valid_polyline(poly.copy(), "frame 0 curve") is first
    assert not first.flags.writeable
    bad = poly.copy()
    bad[5, 0] = np.nan
    with pytest.raises(CurveReconError, match="frame 3 curve"):
        s4._valid_polyline(bad, "frame 3 curve")
    assert s4._valid_polyline(poly.tolist(), "x").flags.writeable  # not an array: not cached


def test_batched_pose_increments_equal_frame_by_frame():
    rng = np.random.default_rng(5)
    n, k = 9, 12
    t = np.linspace(0.0, 1.0, 120)
    polys = [np.column_stack([100.0 * t, 20.0 * np.sin(3.0 * t + i)]) for i in range(n)]
    prob = bd._Problem(polys, 1.0, k, None, None, 1.0, 1.0)
    ctrl = rng.normal(size=(k, 3))
    m = np.linalg.qr(rng.normal(size=(n, 3, 3)))[0]
    b = rng.normal(size=(n, 3))
    for scale in (1e-14, 1e-3, 0.5):
        dx = rng.normal(size=prob.n_par) * scale
        c2, m2, b2 = prob.apply(ctrl, m, b, dx)
        for i in range(1, n):
            off = prob.n_curve + 5 * (i - 1)
            np.testing.assert_allclose(
                m2[i], bd._expm_so3(dx[off : off + 3]) @ m[i], rtol=0, atol=1e-14
            )
            np.testing.assert_array_equal(b2[i, :2], b[i, :2] + dx[off + 3 : off + 5])
        np.testing.assert_array_equal(m2[0], m[0])
        np.testing.assert_array_equal(b2[0], b[0])


def test_duplicate_refits_scored_once():
    rng = np.random.default_rng(11)
    shapes = rng.normal(size=(6, 4))
    poses = rng.normal(size=(6, 8, 5))
    # 2 and 4 repeat 0 within the refinement's tolerance; 5 differs from 1 by 1e-3
    shapes[2], poses[2] = shapes[0] + 2e-5, poses[0] - 2e-5
    shapes[4], poses[4] = shapes[0], poses[0]
    shapes[5], poses[5] = shapes[1], poses[1] + 1e-3
    assert _distinct_optima([0, 1, 2, 3, 4, 5], shapes, poses, 1e-4) == [0, 1, 3, 5]
    assert _distinct_optima([2, 0, 4], shapes, poses, 1e-4) == [2]
    assert _distinct_optima([0, 1, 2, 3, 4, 5], shapes, poses, 0.0) == [0, 1, 2, 3, 4, 5]
