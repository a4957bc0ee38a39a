"""Which end is A in a frame, judged by its polyline (``"ends_identified": false`` with curves).

The end points and tangents of a frame decide its labelling only weakly where the two
labellings' predictions differ little (a quarter of the frames at 1 degree of tangent noise fit
both within chi2 4), and traced tangents misfit by 5-30 degrees.  A polyline runs from A to B
along the whole curve: the 3-D curve of a reconstruction, turned to the frame's pose in either
labelling (A on the polyline's first point, or on its last) and that pose refitted to the
polyline (rotation and image translation, :func:`polyline_misfits`), fits one direction at the
noise level and the other, for a curve whose two ends differ, by pixels.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from curverecon.curve.polyline import resample
from curverecon.model.observations import Observations
from curverecon.model.pose import rotations, translations
from curverecon.model.reconstruction import Reconstruction

CURVE_SAMPLES = 60
"""Points of the 3-D curve projected in the fit."""

POLYLINE_SAMPLES = 24
"""Points of the polyline (equal arc length) whose distance to the projected curve is fitted."""

MAX_EVALUATIONS = 20
"""Residual evaluations of each pose fit (5 parameters)."""


def _distances(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point to the nearest sample of ``curve`` (both dense enough)."""
    dx = points[:, 0:1] - curve[:, 0]
    dy = points[:, 1:2] - curve[:, 1]
    return np.sqrt((dx * dx + dy * dy).min(axis=1))


def _fit_rms(body: np.ndarray, polyline: np.ndarray, pose: np.ndarray) -> float:
    """RMS (px) of the curve ``body`` (curve frame, A first) projected at ``pose`` refitted to
    ``polyline`` (from the frame's A to its B): both ends' offsets and the distances of the
    polyline's samples to the projected curve and back."""
    rot0 = rotations(pose[None])[0]
    t0 = translations(pose[None])[0][:2]
    poly, _ = resample(polyline, POLYLINE_SAMPLES)
    dense, _ = resample(polyline, CURVE_SAMPLES)

    def residuals(p: np.ndarray) -> np.ndarray:
        rot = Rotation.from_rotvec(p[:3]).as_matrix() @ rot0
        proj = body @ rot[:2].T + t0 + p[3:5]
        ends = np.concatenate([proj[0] - polyline[0], proj[-1] - polyline[-1]])
        return np.concatenate([ends, _distances(poly, proj), _distances(proj[::3], dense)])

    with np.errstate(all="ignore"):
        fit = least_squares(residuals, np.zeros(5), max_nfev=MAX_EVALUATIONS, x_scale="jac")
    return float(np.sqrt(np.mean(fit.fun**2)))


def polyline_misfits(
    rec: Reconstruction,
    obs: Observations,
    same_poses: np.ndarray,
    other_poses: np.ndarray,
    frames: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Per frame the RMS (px) of ``rec.curve3d`` fitted to the frame's polyline as labelled in
    ``obs`` and reversed (labels exchanged), starting from ``same_poses`` and ``other_poses``
    (each frame's pose for ``rec.shape`` in either labelling): (N,), (N,), NaN outside the
    mask ``frames``."""
    rot0 = rotations(rec.poses[:1])[0]
    t0 = translations(rec.poses[:1])[0]
    curve = np.asarray(rec.curve3d, float)
    arc = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))]
    t = np.linspace(0.0, arc[-1], CURVE_SAMPLES)
    curve = np.column_stack([np.interp(t, arc, curve[:, k]) for k in range(3)])
    body = (curve - t0) @ rot0  # frame 0's camera coordinates to the curve frame
    same = np.full(obs.n_frames, np.nan)
    other = np.full(obs.n_frames, np.nan)
    for i in np.flatnonzero(frames):
        polyline = obs.curves[i]
        same[i] = _fit_rms(body, polyline, same_poses[i])
        other[i] = _fit_rms(body, polyline[::-1], other_poses[i])
    return same, other
