"""What limits the curve bundle's ``curve3d`` at half a pixel.

Scenes: ``simulate.make_scene`` with 3-D curves of ``curve_families`` moved and projected by the
simulator (no project code in the geometry), 12 frames, end points and tangents given.

- What limits ``curve3d`` at 0.5 px is not the flexibility: a Fourier scene whose ``curve3d``
  is about 0.5 % of the length off has the right shape (within 0.1 % after the best
  rotation about A) and is tilted as a whole in frame 0's camera, which only frame 0's own view
  fixes; the reported ``curve3d_std`` covers that tilt.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import make_lsq_spline
from scipy.spatial.transform import Rotation

from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene


def _length(curve: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(curve, axis=0), axis=1).sum())


def _arc(curve: np.ndarray) -> np.ndarray:
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(curve, axis=0), axis=1))])
    return s / s[-1]


def _mean_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Mean distance of the points of ``a`` from the polyline ``b``."""
    seg0, seg = b[:-1], np.diff(b, axis=0)
    t = np.clip(((a[:, None] - seg0[None]) * seg[None]).sum(2) / (seg * seg).sum(1), 0.0, 1.0)
    return float(
        np.linalg.norm(a[:, None] - (seg0[None] + t[..., None] * seg[None]), axis=2).min(1).mean()
    )


def _spline_miss(curve: np.ndarray, k: int) -> float:
    """Mean distance (/ length) of a dense true curve from its least-squares clamped cubic
    spline of ``k`` control points (scipy, arc-length parameter): how wiggly the curve is."""
    u = _arc(curve)
    knots = np.concatenate([[0.0] * 3, np.linspace(0.0, 1.0, k - 2), [1.0] * 3])
    spl = make_lsq_spline(u, curve, knots, k=3)
    return _mean_distance(spl(np.linspace(0.0, 1.0, 400)), curve) / _length(curve)


def _scene(family: str, seed: int, noise: float, n_points: int = 150):
    return make_scene(
        np.random.default_rng(seed),
        12,
        noise,
        noise,
        with_curve=True,
        curve_family=family,
        n_curve_points=n_points,
    )


def test_curve3d_error_at_half_a_pixel_is_the_tilt_in_frame_0_not_the_shape():
    scene = _scene("fourier", 6003, 0.5)
    rec = reconstruct(scene.observations)
    truth = scene.curve_3d
    length = _length(truth)
    mirror = min((truth, truth * [1.0, 1.0, -1.0]), key=lambda q: _mean_distance(rec.curve3d, q))
    err = _mean_distance(rec.curve3d, mirror) / length
    # the raw error in frame 0's camera: about the 0.5 % target or more (0.8 %; 0.48 % with the
    # coarse stage on thinned polylines, joint.COARSE_POINTS = 40, a lower-cost fit)
    assert err > 0.004
    # the same points in arc length, the best rotation about A
    u = np.linspace(0.0, 1.0, 200)
    p = np.column_stack([np.interp(u, _arc(rec.curve3d), rec.curve3d[:, j]) for j in range(3)])
    q = np.column_stack([np.interp(u, _arc(mirror), mirror[:, j]) for j in range(3)])
    rot, _ = Rotation.align_vectors(q - q[0], p - p[0])
    aligned = rot.apply(rec.curve3d - rec.curve3d[0]) + mirror[0]
    aligned_err = _mean_distance(aligned, mirror) / length
    assert aligned_err < 0.001
    assert err > 5.0 * aligned_err  # the raw error is the tilt
    tilt_deg = np.degrees(np.linalg.norm(rot.as_rotvec()))
    assert tilt_deg > 0.5
    # the reported std covers the raw error
    assert err * length < 3.0 * float(np.mean(rec.curve3d_std))
