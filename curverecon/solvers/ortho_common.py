"""Shared pieces of the orthographic minimal solvers (``ortho_<row>.py``).

Input checks with one-line :class:`~curverecon.errors.CurveReconError` messages, rotations about
an axis, the rotation taking two vectors to two others, and the assembly of a
:class:`~curverecon.solvers.rigid_solutions.RigidSolutions` from the depths of B (and C) relative
to A.  Conventions: ``points`` (F, P, 2) image positions in input units, A first; depths are
orthographic camera z relative to A; rotations act on differences, X_f - A_f = R_f (X_0 - A_0).
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.solvers.rigid_solutions import RigidSolutions

MIRROR = np.diag([1.0, 1.0, -1.0])
"""The orthographic mirror z -> -z."""


def check_input(
    points: object, times: object, frames: int, names: tuple[str, ...], row: str
) -> tuple[np.ndarray, np.ndarray]:
    """``points`` as (frames, len(names), 2) float64 and ``times`` as (frames,), or a
    CurveReconError naming what is wrong (shape, non-finite values, times not increasing)."""
    pts = np.asarray(points, dtype=float)
    t = np.asarray(times, dtype=float)
    want = (frames, len(names), 2)
    if pts.shape != want:
        raise CurveReconError(
            f"{row}: the minimal solver needs points of shape {want} ({frames} frames of "
            f"{', '.join(names)}), got {pts.shape}"
        )
    if t.shape != (frames,):
        raise CurveReconError(
            f"{row}: the minimal solver needs {frames} times, got shape {t.shape}"
        )
    if not (np.all(np.isfinite(pts)) and np.all(np.isfinite(t))):
        raise CurveReconError(f"{row}: points and times must be finite numbers")
    if np.any(np.diff(t) <= 0):
        raise CurveReconError(f"{row}: times must be strictly increasing, got {t.tolist()}")
    return pts, t


def scale_of(diffs: np.ndarray, row: str) -> float:
    """RMS length of the image differences (the solvers work on differences / this scale)."""
    scale = float(np.sqrt(np.mean(np.sum(diffs**2, axis=-1))))
    if not scale > 0:
        raise CurveReconError(f"{row}: the traceable points coincide in every frame")
    return scale


def rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rot(axis, angle), right-handed, ``axis`` a unit vector, ``angle`` in radians."""
    n = np.asarray(axis, dtype=float)
    k = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    c, s = np.cos(angle), np.sin(angle)
    return c * np.eye(3) + s * k + (1.0 - c) * np.outer(n, n)


def angle_about(axis: np.ndarray, d0: np.ndarray, d1: np.ndarray) -> float:
    """Signed angle (radians) of the rotation about unit ``axis`` taking d0's component
    perpendicular to the axis to d1's."""
    p0 = d0 - (d0 @ axis) * axis
    p1 = d1 - (d1 @ axis) * axis
    return float(np.arctan2(axis @ np.cross(p0, p1), p0 @ p1))


def rotation_from_pairs(
    d0: np.ndarray, e0: np.ndarray, d1: np.ndarray, e1: np.ndarray
) -> np.ndarray:
    """The rotation R with R d0 = d1 and R e0 = e1 (equal Gram matrices, non-collinear)."""
    f0 = np.column_stack([d0, e0, np.cross(d0, e0)])
    f1 = np.column_stack([d1, e1, np.cross(d1, e1)])
    return f1 @ np.linalg.inv(f0)


def assemble(
    points: np.ndarray,
    depths: list[np.ndarray],
    rotations: list[np.ndarray],
    motion: list[dict],
    n_paths: int,
    n_failed_paths: int = 0,
) -> RigidSolutions:
    """RigidSolutions from per-solution depths (F, P - 1) of B (and C) relative to A."""
    frames, npts, _ = points.shape
    if not depths:
        out = RigidSolutions.empty(frames, npts)
        out.n_paths, out.n_complex, out.n_failed_paths = n_paths, n_paths, n_failed_paths
        return out
    p3 = np.zeros((len(depths), frames, npts, 3))
    p3[:, :, :, :2] = points[None]
    p3[:, :, 1:, 2] = np.array(depths)
    return RigidSolutions(
        points3=p3,
        rotations=np.array(rotations),
        motion=motion,
        n_paths=n_paths,
        n_complex=n_paths - len(depths) - n_failed_paths,
        n_failed_paths=n_failed_paths,
    )
