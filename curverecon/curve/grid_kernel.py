"""Distances of points to the nearest of many fixed 2-D points within a bound: a uniform grid
of cells one bound wide and a numba loop, one core (section 4's unary cost, ``curve.section4``).

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


@numba.njit(**_JIT)
def _query(pts, start, x0, y0, cell, nx, ny, q, bound):
    out = np.empty(q.shape[0])
    for p in range(q.shape[0]):
        qx, qy = q[p, 0], q[p, 1]
        best = np.inf
        if math.isfinite(qx) and math.isfinite(qy):
            fx = math.floor((qx - x0) / cell)
            fy = math.floor((qy - y0) / cell)
            for cy in range(max(fy - 1, 0), min(fy + 1, ny - 1) + 1):
                for cx in range(max(fx - 1, 0), min(fx + 1, nx - 1) + 1):
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
