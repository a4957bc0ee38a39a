"""The triangulated stereo curve smoothed along itself, with the std the smoothing leaves.

The paper's curve is smooth; triangulated points scatter about it (mostly along camera 0's
rays).  Each coordinate is a cubic smoothing spline of the point's arc position (0 at A, 1 at
B), weighted by 1 / std^2, one smoothing parameter for all three coordinates chosen by two-fold
cross-validation: the spline through the even points predicts the odd ones and the other way
round (generalised cross-validation, tried first, chose no smoothing at all on the scenes of
bench/stereo_curve.py, where the stds, capped at the depth where the curve runs along the
epipolar lines, span three decades).  The smoother is linear, x_hat = H x, so a point's std
after it is sqrt(sum_j H_ij^2 std_j^2) (noise only; the smoothing's bias is what the
cross-validation keeps small).  Units: those of the points (the rig's t).
"""

from __future__ import annotations

import numpy as np

#: Smoothing parameters tried (the spline's curvature penalty against the squared residuals
#: weighted by 1 / std^2 over their mean, on the unit parameter range), log-spaced; the range
#: holds the choices on the scenes of bench/stereo_curve.py (1e-6 to 1e-3) well inside.
_LAMBDAS = np.logspace(-8.0, -1.0, 22)

#: Fewest points smoothed (fewer are returned as they are).
_MIN_POINTS = 8


def _hat(u: np.ndarray, w: np.ndarray, lam: float) -> np.ndarray:
    """(K, K) matrix H of the weighted smoothing spline at its own abscissas (x_hat = H x)."""
    from scipy.interpolate import make_smoothing_spline

    return make_smoothing_spline(u, np.eye(len(u)), w=w, lam=lam)(u)


def _cv_score(u: np.ndarray, points: np.ndarray, w: np.ndarray, lam: float) -> float:
    """Weighted squared error of the even points' spline at the odd points and back."""
    from scipy.interpolate import make_smoothing_spline

    score = 0.0
    for half in (0, 1):
        fit = np.arange(len(u)) % 2 == half
        spline = make_smoothing_spline(u[fit], points[fit], w=w[fit], lam=lam)
        score += float((w[~fit, None] * (points[~fit] - spline(u[~fit])) ** 2).sum())
    return score


def smooth_curve(
    u: np.ndarray, points: np.ndarray, std: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(points (K, 3), std (K,)) smoothed along the arc positions ``u`` (K,) (increasing, 0 to
    1) with weights 1 / ``std``^2; the smoothing parameter of least two-fold cross-validation
    error over ``_LAMBDAS``.  Fewer than ``_MIN_POINTS`` points, or positions not strictly
    increasing: returned as they are."""
    u = np.asarray(u, float)
    if len(u) < _MIN_POINTS or np.any(np.diff(u) <= 0):
        return points, std
    w = 1.0 / np.maximum(std, 1e-300) ** 2
    w = w / w.mean()
    scores = [_cv_score(u, points, w, float(lam)) for lam in _LAMBDAS]
    h = _hat(u, w, float(_LAMBDAS[int(np.argmin(scores))]))
    return h @ points, np.sqrt((h**2) @ (std**2))


__all__ = ["smooth_curve"]
