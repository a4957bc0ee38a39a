"""The placement sweep of ``curve.labels`` (which end is A, judged by a polyline): numba loops.

For each of K rigid placements of a 3-D curve (rotations, the curve's A on the polyline's first
point) the mean square of the polyline's samples' distances to the nearest projected curve
sample and of the projected curve's samples' distances to the nearest dense polyline sample.
The same figure as the array form it replaces (a (K, P, M) table of complex distances per
sweep, and the Python overhead of building it: 3-4 ms a placement of 16-frame polylines, the
largest cost of the labelling stage after the pipeline runs).

Compiled with ``cache=True`` (numba's on-disk cache: the first import compiles once).
"""

from __future__ import annotations

import numba
import numpy as np

_JIT = {"cache": True, "nogil": True, "fastmath": False}


@numba.njit(**_JIT)
def _nearest_sq(x: float, y: float, px: np.ndarray, py: np.ndarray) -> float:
    """Squared distance of (x, y) to the nearest of the points (px, py)."""
    best = np.inf
    for j in range(px.shape[0]):
        dx = px[j] - x
        dy = py[j] - y
        d = dx * dx + dy * dy
        if d < best:
            best = d
    return best


@numba.njit(**_JIT)
def placement_mean_squares(
    rots: np.ndarray,
    body: np.ndarray,
    origin: np.ndarray,
    poly: np.ndarray,
    dense: np.ndarray,
    back_stride: int,
) -> np.ndarray:
    """(K,) mean squares (px^2) of the placements ``rots`` (K, 3, 3; the first two rows
    project) of the curve ``body`` (M, 3; A at the origin) moved to ``origin`` (2,): the
    distances of ``poly``'s points (P, 2) to the nearest projected curve point, and of every
    ``back_stride``-th projected curve point to the nearest of ``dense`` (Q, 2)."""
    k_rots = rots.shape[0]
    m = body.shape[0]
    out = np.empty(k_rots)
    qx = np.empty(m)
    qy = np.empty(m)
    dx = dense[:, 0].copy()
    dy = dense[:, 1].copy()
    for k in range(k_rots):
        for i in range(m):
            qx[i] = rots[k, 0, 0] * body[i, 0] + rots[k, 0, 1] * body[i, 1]
            qx[i] += rots[k, 0, 2] * body[i, 2] + origin[0]
            qy[i] = rots[k, 1, 0] * body[i, 0] + rots[k, 1, 1] * body[i, 1]
            qy[i] += rots[k, 1, 2] * body[i, 2] + origin[1]
        total = 0.0
        count = 0
        for p in range(poly.shape[0]):
            total += _nearest_sq(poly[p, 0], poly[p, 1], qx, qy)
            count += 1
        for i in range(0, m, back_stride):
            total += _nearest_sq(qx[i], qy[i], dx, dy)
            count += 1
        out[k] = total / count
    return out
