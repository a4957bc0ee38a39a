"""Section 4's loops (``curve.section4``) in numba, one core: distances within a bound on a
uniform grid, and the dynamic programme along the curve.

Distances of points to the nearest of many fixed 2-D points within a bound (:class:`Grid`):
a uniform grid of cells one bound wide.

Section 4 scores every crossing candidate by its distance from every frame's densified
polyline, truncated at a bound: a k-d tree query with ``distance_upper_bound`` per (frame,
candidates) pair was most of the branch search's time.  With cells as wide as the bound, the
points within the bound of a query lie in the 3 x 3 cells around it: an exact search of those.
Distances as the tree gives them (the square root of dx^2 + dy^2; inf when no point is within
the bound).
"""

from __future__ import annotations

import math

import numba
import numpy as np

_JIT = {"cache": True, "nogil": True, "fastmath": False}


class Grid:
    """The points sorted by cell: ``order`` holds them cell by cell, cell c's being
    ``pts[order[start[c]:start[c + 1]]]`` (cells row-major, ``nx`` per row)."""

    def __init__(self, pts: np.ndarray, cell: float) -> None:
        pts = np.ascontiguousarray(pts, dtype=float)
        self.cell = float(cell)
        self.x0, self.y0 = float(pts[:, 0].min()), float(pts[:, 1].min())
        self.nx = int((pts[:, 0].max() - self.x0) // self.cell) + 1
        self.ny = int((pts[:, 1].max() - self.y0) // self.cell) + 1
        cx = ((pts[:, 0] - self.x0) // self.cell).astype(np.int64)
        cy = ((pts[:, 1] - self.y0) // self.cell).astype(np.int64)
        cid = cy * self.nx + cx
        order = np.argsort(cid, kind="stable")
        self.sorted = np.ascontiguousarray(pts[order])
        self.start = np.concatenate(
            [[0], np.cumsum(np.bincount(cid, minlength=self.nx * self.ny))]
        ).astype(np.int64)

    def query(self, q: np.ndarray, bound: float) -> np.ndarray:
        """Distance of each point of q (M, 2) to the nearest point, inf beyond ``bound`` (at
        most the cell width)."""
        if not bound <= self.cell:
            raise ValueError("bound wider than the grid's cells")
        return _query(
            self.sorted,
            self.start,
            self.x0,
            self.y0,
            self.cell,
            self.nx,
            self.ny,
            np.ascontiguousarray(q, dtype=float),
            float(bound),
        )

    def nearest(self, q: np.ndarray) -> np.ndarray:
        """Distance of each point of q (M, 2) to the nearest point, however far (rings of
        cells outwards until the next ring cannot hold a nearer point): the distances of
        :meth:`query` where those are finite, and the k-d tree's beyond."""
        return _nearest(
            self.sorted,
            self.start,
            self.x0,
            self.y0,
            self.cell,
            self.nx,
            self.ny,
            np.ascontiguousarray(q, dtype=float),
        )


@numba.njit(**_JIT)
def _scan_cell(pts, start, x0, y0, cell, nx, cx, cy, qx, qy, margin, best):
    """``best`` lowered to the least squared distance from (qx, qy) to cell (cx, cy)'s points,
    unless the cell's rectangle (less ``margin``) is no nearer than ``best``."""
    gx = max(x0 + cx * cell - qx, qx - (x0 + (cx + 1) * cell), 0.0)
    gy = max(y0 + cy * cell - qy, qy - (y0 + (cy + 1) * cell), 0.0)
    gx = max(gx - margin, 0.0)
    gy = max(gy - margin, 0.0)
    if gx * gx + gy * gy > best:
        return best
    c = cy * nx + cx
    for j in range(start[c], start[c + 1]):
        dx = pts[j, 0] - qx
        dy = pts[j, 1] - qy
        d = dx * dx + dy * dy
        if d < best:
            best = d
    return best


@numba.njit(**_JIT)
def _nearest(pts, start, x0, y0, cell, nx, ny, q):
    # ring r: the cells at Chebyshev distance r from the query's cell (clipped to the grid),
    # from the first ring that meets the grid; any point of ring r is at least (r - 1) cells
    # away, so the search stops once that exceeds the best (less a margin for the rounding of
    # a point's cell) or once the rings cover the grid
    out = np.empty(q.shape[0])
    margin = 1e-9 * cell
    for p in range(q.shape[0]):
        qx, qy = q[p, 0], q[p, 1]
        best = np.inf
        if math.isfinite(qx) and math.isfinite(qy):
            fx = int(math.floor((qx - x0) / cell))
            fy = int(math.floor((qy - y0) / cell))
            r = max(0, -fx, fx - (nx - 1), -fy, fy - (ny - 1))
            while True:
                lb = max((r - 1) * cell - margin, 0.0)
                if lb * lb > best:
                    break
                y_lo, y_hi = max(fy - r, 0), min(fy + r, ny - 1)
                x_lo, x_hi = max(fx - r, 0), min(fx + r, nx - 1)
                for cy in range(y_lo, y_hi + 1):
                    if cy == fy - r or cy == fy + r:
                        for cx in range(x_lo, x_hi + 1):
                            best = _scan_cell(
                                pts, start, x0, y0, cell, nx, cx, cy, qx, qy, margin, best
                            )
                    else:
                        if fx - r >= 0:
                            best = _scan_cell(
                                pts, start, x0, y0, cell, nx, fx - r, cy, qx, qy, margin, best
                            )
                        if r > 0 and fx + r <= nx - 1:
                            best = _scan_cell(
                                pts, start, x0, y0, cell, nx, fx + r, cy, qx, qy, margin, best
                            )
                if fx - r <= 0 and fx + r >= nx - 1 and fy - r <= 0 and fy + r >= ny - 1:
                    break
                r += 1
        out[p] = math.sqrt(best)
    return out


@numba.njit(**_JIT)
def _query(pts, start, x0, y0, cell, nx, ny, q, bound):
    # the query's own cell first, then a neighbour only if its rectangle can hold a point
    # nearer than the best so far and within the bound (the rectangle's distance less a margin
    # for the rounding of a point's cell): the minimum over the same points as a scan of all
    # 3 x 3 cells, fewer of them scanned
    out = np.empty(q.shape[0])
    lim = bound * (1.0 + 1e-9)
    lim2 = lim * lim
    margin = 1e-9 * cell
    for p in range(q.shape[0]):
        qx, qy = q[p, 0], q[p, 1]
        best = np.inf
        if math.isfinite(qx) and math.isfinite(qy):
            fx = math.floor((qx - x0) / cell)
            fy = math.floor((qy - y0) / cell)
            for ring in range(2):
                for cy in range(max(fy - 1, 0), min(fy + 1, ny - 1) + 1):
                    for cx in range(max(fx - 1, 0), min(fx + 1, nx - 1) + 1):
                        own = cx == fx and cy == fy
                        if own != (ring == 0):
                            continue
                        if not own:
                            gx = max(x0 + cx * cell - qx, qx - (x0 + (cx + 1) * cell), 0.0)
                            gy = max(y0 + cy * cell - qy, qy - (y0 + (cy + 1) * cell), 0.0)
                            gx = max(gx - margin, 0.0)
                            gy = max(gy - margin, 0.0)
                            lb = gx * gx + gy * gy
                            if lb > best or lb > lim2:
                                continue
                        c = cy * nx + cx
                        for j in range(start[c], start[c + 1]):
                            dx = pts[j, 0] - qx
                            dy = pts[j, 1] - qy
                            d = dx * dx + dy * dy
                            if d < best:
                                best = d
        dist = math.sqrt(best)
        out[p] = dist if dist < bound else np.inf
    return out


@numba.njit(**_JIT)
def depth_path(z, u, offs, step, jump_w, miss_cost):
    """Section 4's dynamic programme along the curve (``section4.reconstruct_curve``): sample k's
    candidates are depths z[offs[k]:offs[k + 1]] with unary costs u[...]; between samples the
    cost ``jump_w`` (depth slope)^2, the slope over the samples since the state's last real
    candidate; every sample but the first and the last also has a "missing" state (the best
    previous state's depth carried on, at ``miss_cost``).  Returns (z per sample, whether the
    sample took the missing state).  Ties: the first state, as ``np.argmin``."""
    kt = offs.shape[0] - 1
    cap = offs[kt] + kt
    st_z = np.empty(cap)
    st_back = np.empty(cap, np.int64)
    st_off = np.empty(kt + 1, np.int64)
    cost = np.empty(cap)
    gap = np.empty(cap)
    # sample 0: its candidates (one, A at depth 0)
    n0 = offs[1] - offs[0]
    st_off[0] = 0
    for a in range(n0):
        st_z[a] = z[offs[0] + a]
        cost[a] = u[offs[0] + a]
        gap[a] = 0.0
        st_back[a] = 0
    st_off[1] = n0
    for k in range(1, kt):
        p0, p1 = st_off[k - 1], st_off[k]
        q = p1
        for c in range(offs[k], offs[k + 1]):
            zk = z[c]
            best = np.inf
            bj = -1
            for p in range(p0, p1):
                s = (zk - st_z[p]) / (step * (gap[p] + 1.0))
                t = cost[p] + jump_w * (s * s)
                if bj < 0 or t < best:
                    best = t
                    bj = p
            st_z[q] = zk
            cost[q] = best + u[c]
            gap[q] = 0.0
            st_back[q] = bj - p0
            q += 1
        if 0 < k < kt - 1:
            jm = p0
            for p in range(p0 + 1, p1):
                if cost[p] < cost[jm]:
                    jm = p
            st_z[q] = st_z[jm]
            cost[q] = cost[jm] + miss_cost
            gap[q] = gap[jm] + 1.0
            st_back[q] = jm - p0
            q += 1
        st_off[k + 1] = q
    # backtrack from the cheapest final state
    z_dp = np.empty(kt)
    missing = np.zeros(kt, np.bool_)
    a0, a1 = st_off[kt - 1], st_off[kt]
    ch = 0
    for p in range(a0 + 1, a1):
        if cost[p] < cost[a0 + ch]:
            ch = p - a0
    for k in range(kt - 1, -1, -1):
        p = st_off[k] + ch
        z_dp[k] = st_z[p]
        missing[k] = ch >= offs[k + 1] - offs[k]
        ch = st_back[p]
    return z_dp, missing
