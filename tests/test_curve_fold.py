"""The curve bundle does not keep a spline folded over itself (honest curve3d
uncertainty).

With each polyline point's foot the nearest point of the projected curve, a spline that runs
forward, back and forward again along one stretch fits every polyline as well as the single
curve and, its strands spread over the noise band, better: random seed 1206 (12 frames, 1 px,
1 degree, ``simulate.make_scene``) folded near B, ``curve3d`` 1.42 times the true curve's
length and up to 12 of its own std off.  The truth here is the 3-D curve ``make_scene`` drew.
"""

from __future__ import annotations

import numpy as np

from curverecon.curve import fixed_poses, residuals, spline
from curverecon.pipeline import reconstruct
from curverecon.simulate import make_scene


def _scene(n_points: int = 150):
    return make_scene(
        np.random.default_rng(1206),
        12,
        1.0,
        1.0,
        with_curve=True,
        curve_family="random",
        n_curve_points=n_points,
    )


def _length(p: np.ndarray) -> float:
    return float(np.sum(np.linalg.norm(np.diff(p, axis=0), axis=1)))


def _problem(sc):
    """The bundle's problem on the scene's polylines, with the true poses (frame 0 -> i)."""
    rot, tr = sc.truth.rotations, sc.truth.A3
    m = np.einsum("nij,kj->nik", rot, rot[0])
    b = tr - np.einsum("nij,j->ni", m, tr[0])
    prob = residuals.Problem(list(sc.observations.curves), 1.0, 12, None, None, 1.0, 1.0)
    return prob, m, b


def test_fold_test_tells_a_folded_spline_from_the_true_curve() -> None:
    sc = _scene()
    prob, m, b = _problem(sc)
    true = sc.curve_3d
    assert not fixed_poses.is_folded(prob, spline.fit_spline(true, 12), m, b, 8.0)
    # forward to B, back over the last fifth of the curve, forward to B again: every image of
    # it lies on the polyline
    n = len(true)
    back = true[int(0.8 * n) : -1][::-1]
    folded = np.vstack([true, back, true[int(0.8 * n) + 1 :]])
    assert _length(folded) > 1.3 * _length(true)
    assert fixed_poses.is_folded(prob, spline.fit_spline(folded, 12), m, b, 8.0)


def test_bundle_on_a_scene_that_folded_is_one_curve_within_its_std() -> None:
    sc = _scene()
    on = reconstruct(sc.observations)
    assert on.curve3d is not None and on.curve3d_normal_std is not None
    dense = _scene(5000).curve_3d
    assert abs(_length(on.curve3d) / _length(dense) - 1.0) < 0.02  # folded: 1.42
    d = min(
        (
            np.array([np.min(np.linalg.norm(q - p, axis=1)) for p in on.curve3d])
            for q in (dense, dense * [1.0, 1.0, -1.0])
        ),
        key=np.mean,
    )
    assert np.max(d / on.curve3d_normal_std) < 3.0  # folded: 12.4
