"""The generic LO-RANSAC loop on an estimator it knows nothing special about: a 2-D line fitted
to points with gross outliers (the answer checked against the line the inliers were drawn on)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from curverecon.robust.ransac import RansacOptions, lo_ransac, required_iterations


class LineEstimator:
    """Lines n . x = d (|n| = 1) through two points; truncated squared distance as the cost."""

    sample_size = 2

    def __init__(self, points: np.ndarray, threshold: float) -> None:
        self.points = points
        self.num_data = len(points)
        self.threshold = threshold

    def generate_models(self, sample):
        p, q = self.points[sample]
        t = q - p
        if np.hypot(*t) == 0:
            return []
        n = np.array([-t[1], t[0]]) / np.hypot(*t)
        return [(n, float(n @ p))]

    def _dist(self, model):
        n, d = model
        return np.abs(self.points @ n - d)

    def score_model(self, model):
        r = self._dist(model)
        return float(np.sum(np.minimum(r, self.threshold) ** 2)), int(np.sum(r < self.threshold))

    def refine_model(self, model):
        inl = self.points[self._dist(model) < self.threshold]
        c = inl.mean(axis=0)
        _, _, vt = np.linalg.svd(inl - c)
        n = vt[-1]
        return (n, float(n @ c))


def _scene(seed: int, n: int, outlier_ratio: float):
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, np.pi)
    n_true = np.array([np.cos(angle), np.sin(angle)])
    d_true = rng.uniform(-5, 5)
    t = rng.uniform(-50, 50, n)
    pts = d_true * n_true + t[:, None] * np.array([-n_true[1], n_true[0]])
    pts += rng.normal(0, 0.1, pts.shape)
    out = rng.random(n) < outlier_ratio
    pts[out] = rng.uniform(-60, 60, (out.sum(), 2))
    return pts, n_true, d_true, out


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_finds_the_line_among_half_outliers(seed):
    pts, n_true, d_true, out = _scene(seed, 200, 0.5)
    model, stats = lo_ransac(LineEstimator(pts, 0.5), RansacOptions(seed=seed))
    n, d = model
    sign = np.sign(n @ n_true)
    assert math.degrees(math.acos(min(1.0, abs(n @ n_true)))) < 0.2
    assert abs(sign * d - d_true) < 0.05
    assert stats.num_inliers >= 0.95 * np.sum(~out)
    assert stats.refinements >= 1 and stats.iterations < RansacOptions().max_iterations


def test_adaptive_stopping_draws_fewer_samples_with_more_inliers():
    few = lo_ransac(LineEstimator(_scene(4, 200, 0.05)[0], 0.5))[1]
    many = lo_ransac(LineEstimator(_scene(4, 200, 0.6)[0], 0.5))[1]
    assert few.iterations < many.iterations
    assert few.iterations == required_iterations(few.inlier_ratio, 2, RansacOptions())


def test_same_input_same_output_and_too_little_data():
    pts = _scene(5, 100, 0.3)[0]
    a = lo_ransac(LineEstimator(pts, 0.5))
    b = lo_ransac(LineEstimator(pts, 0.5))
    assert np.array_equal(a[0][0], b[0][0]) and a[1].history == b[1].history
    assert lo_ransac(LineEstimator(pts[:1], 0.5)) == (
        None,
        lo_ransac(LineEstimator(pts[:1], 0.5))[1],
    )


def test_required_iterations_formula():
    o = RansacOptions(min_iterations=1, max_iterations=10**9, dyn_num_trials_mult=1.0)
    # (1 - w^m)^k <= 1 - p: w = 0.5, m = 2, p = 0.9999 -> k = ceil(log(1e-4) / log(0.75)) = 33
    assert required_iterations(0.5, 2, o) == 33
    assert required_iterations(0.0, 2, o) == o.max_iterations


class _CountingLines(LineEstimator):
    """LineEstimator that counts refinements and calls every model the same (``same_model``)
    when ``all_same``."""

    def __init__(self, points: np.ndarray, threshold: float, all_same: bool) -> None:
        super().__init__(points, threshold)
        self.refined = 0
        if all_same:
            self.same_model = lambda a, b: True

    def refine_model(self, model):
        self.refined += 1
        return super().refine_model(model)


def test_final_refinements_polish_more_models_and_never_worsen_the_answer():
    """After the loop, ``final_refinements`` more of the best-scoring unrefined models are
    refined (the same samples drawn: same seed); the answer's cost is no higher than without,
    and models the estimator calls the same as one refined before are skipped."""
    pts = _scene(6, 120, 0.6)[0]
    base_est = _CountingLines(pts, 0.5, False)
    base = lo_ransac(base_est, RansacOptions(seed=3, max_iterations=8, min_iterations=8))
    more_est = _CountingLines(pts, 0.5, False)
    o = RansacOptions(seed=3, max_iterations=8, min_iterations=8, final_refinements=3)
    more = lo_ransac(more_est, o)
    assert more[1].cost <= base[1].cost
    assert more_est.refined == base_est.refined + 3
    assert more[1].refinements == base[1].refinements + 3
    same_est = _CountingLines(pts, 0.5, True)
    lo_ransac(same_est, o)
    assert same_est.refined == base_est.refined


def test_an_initial_model_is_scored_and_refined_before_the_samples():
    """``initial_models``: a rough line near the true one (0.5 degrees, 0.3 off), given at
    the start, is refined before any sample (one refinement more, one model more, the same
    number of samples), and with a single sample that has an outlier in it the answer is the
    true line, where without it the answer is that sample's wrong line."""
    pts, n_true, d_true, out = _scene(8, 100, 0.5)
    a = math.atan2(n_true[1], n_true[0]) + math.radians(0.5)
    rough = (np.array([math.cos(a), math.sin(a)]), d_true + 0.3)
    # a seed whose only sample has an outlier in it
    seed = next(
        s
        for s in range(100)
        if out[np.random.default_rng(s).choice(len(pts), size=2, replace=False)].any()
    )
    o = RansacOptions(seed=seed, max_iterations=1, min_iterations=1)
    plain_est = _CountingLines(pts, 0.5, False)
    plain, plain_stats = lo_ransac(plain_est, o)
    est = _CountingLines(pts, 0.5, False)
    model, stats = lo_ransac(est, o, [rough])
    assert stats.iterations == plain_stats.iterations == 1
    assert stats.models == plain_stats.models + 1
    assert est.refined == 1  # the initial model; the sample's line scores worse

    def angle_to_truth(m) -> float:  # type: ignore[no-untyped-def]
        return math.degrees(math.acos(min(1.0, abs(float(m[0] @ n_true)))))

    assert angle_to_truth(plain) > 1.0
    assert angle_to_truth(model) < 0.1
    assert abs(abs(model[1]) - abs(d_true)) < 0.1
