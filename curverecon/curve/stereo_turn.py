"""Each stereo frame's turn about the chord AB, fixed by its triangulated curve.

With only A and B traced, a rigid frame's pose is known up to a turn about the chord AB (A and
B stay where they are whatever the turn); the curve, triangulated in every frame, is not
symmetric about the chord and fixes it.  Conventions as in ``curverecon.curve.stereo``: frame
poses (3, 4) [R_f | T_f] with X_f = R_f X_0 + T_f (frame 0's camera-0 coordinates to frame f's),
lengths in the units of the rig's t, angles in radians.
"""

from __future__ import annotations

import numpy as np

#: Turns tried in the global search of a frame's turn (then refined by closest points).
_TURN_GRID = 90

#: Cap on a point's squared distance / variance in the global search (a robust cost: a point
#: far from the reference, e.g. where its std is small but its match wrong, counts no more).
_CAP = 25.0

#: Points of a curve and of the reference in the global search (every k-th; the refinement
#: takes them all).
_SEARCH_POINTS = 60

#: Most closest-point refinements of the turn after the global search (each gains a fixed
#: fraction where the turn slides the curve along itself; stopped when the turn stays within
#: ``_TOLERANCE`` radians).
_REFINE = 60
_TOLERANCE = 1e-10


def _axis_frame(points: np.ndarray, a0: np.ndarray, axis: np.ndarray):
    """(along the axis (K,), across it (K, 3), the across part turned a quarter (K, 3))."""
    rel = points - a0
    h = rel @ axis
    perp = rel - h[:, None] * axis
    return h, perp, np.cross(axis, perp)


def rotation_about(axis: np.ndarray, angle: float) -> np.ndarray:
    """(3, 3) rotation by ``angle`` (radians, right-handed) about the unit ``axis``."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def _feet(points: np.ndarray, curve: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(nearest points on the polyline ``curve`` (..., K, 3), squared distances (..., K))."""
    seg0, seg = curve[:-1], np.diff(curve, axis=0)
    len2 = np.maximum((seg * seg).sum(1), 1e-300)
    rel = points[..., :, None, :] - seg0
    u = np.clip((rel * seg).sum(-1) / len2, 0.0, 1.0)
    foot = seg0 + u[..., None] * seg
    d2 = ((points[..., :, None, :] - foot) ** 2).sum(-1)
    k = np.argmin(d2, axis=-1)
    near = np.take_along_axis(foot, k[..., None, None], axis=-2)[..., 0, :]
    return near, np.take_along_axis(d2, k[..., None], axis=-1)[..., 0]


def _thinned(points: np.ndarray, most: int) -> np.ndarray:
    """Every k-th point (and the last) so that at most about ``most`` remain."""
    step = max(1, -(-len(points) // most))
    keep = np.unique(np.r_[np.arange(0, len(points), step), len(points) - 1])
    return points[keep]


def _search(h, perp, quarter, w, reference, a0, axis) -> float:
    """The turn of least capped cost sum min(d^2 w, ``_CAP``) among ``_TURN_GRID`` turns (on
    at most ``_SEARCH_POINTS`` points and reference points)."""
    step = max(1, -(-len(h) // _SEARCH_POINTS))
    h, perp, quarter, w = h[::step], perp[::step], quarter[::step], w[::step]
    grid = np.linspace(-np.pi, np.pi, _TURN_GRID, endpoint=False)
    turned = (
        a0
        + h[None, :, None] * axis
        + np.cos(grid)[:, None, None] * perp
        + np.sin(grid)[:, None, None] * quarter
    )
    d2 = _feet(turned, _thinned(reference, _SEARCH_POINTS))[1]
    return float(grid[int(np.argmin(np.minimum(d2 * w, _CAP).sum(1)))])


def best_turn(points, std, reference, a0, axis, search: bool = True) -> float:
    """The turn (radians) about the axis through ``a0`` along the unit ``axis`` that brings
    ``points`` (K, 3; std (K,)) closest to the polyline ``reference``: a global search over
    ``_TURN_GRID`` turns of the capped cost sum min(d^2 / std^2, ``_CAP``) (``search``; else
    from no turn), then closest-point refinements, each the weighted least-squares turn in
    closed form (until it stays put)."""
    h, perp, quarter = _axis_frame(points, a0, axis)
    w = 1.0 / np.maximum(std, 1e-300) ** 2
    angle = _search(h, perp, quarter, w, reference, a0, axis) if search else 0.0
    for _ in range(_REFINE):
        now = a0 + h[:, None] * axis + np.cos(angle) * perp + np.sin(angle) * quarter
        near, d2 = _feet(now, reference)
        keep = d2 * w <= _CAP
        target = (near - a0)[keep]
        q = target - (target @ axis)[:, None] * axis
        num = (w[keep] * (q * quarter[keep]).sum(1)).sum()
        den = (w[keep] * (q * perp[keep]).sum(1)).sum()
        angle, last = float(np.arctan2(num, den)), angle
        if abs(angle - last) < _TOLERANCE:
            break
    return angle


def turned_pose(pose: np.ndarray, a0: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """The pose under which frame f's points, moved to frame 0, come out turned by ``angle``
    about the axis through ``a0`` (Q = ``rotation_about(axis, angle)``):
    [R_f Q^T | T_f + R_f (a0 - Q^T a0)].  A point on the axis keeps its place in frame f."""
    qt = rotation_about(axis, -angle)
    rot, tr = pose[:, :3], pose[:, 3]
    return np.column_stack([rot @ qt, tr + rot @ (a0 - qt @ a0)])


__all__ = ["best_turn", "rotation_about", "turned_pose"]
