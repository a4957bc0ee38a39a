"""The maximum-likelihood shape's bias correction (``curverecon.refine.bias``).

The bias is measured independently: many noisy copies of one scene (the measurements predicted
from the simulator's 3-D geometry, ``test_conventions.canonical_parameters``), each fitted by
maximum likelihood; the mean error of those fits is the bias the correction should remove.
"""

from __future__ import annotations

import numpy as np
from curverecon.generated import measurement_model
from test_conventions import canonical_parameters

from curverecon.model.observations import wrap_angle
from curverecon.model.pose import normalise
from curverecon.simulate import make_scene


def test_the_correction_removes_the_bias_of_a_monte_carlo_mean():
    """12 noisy copies of a 100-frame scene at 2 px / 2 deg (where the bias is about two
    standard deviations of c): the fits' mean error in c is significant, the correction has its
    sign and leaves a significantly smaller one, and every corrected fit is within 3 of its
    standard deviations (the fit's covariance plus the correction's)."""
    from curverecon.refine.bias import ml_bias
    from curverecon.refine.ml import refine

    sigma = 2.0
    sc = make_scene(np.random.default_rng(3), 100, sigma, sigma)
    shape, poses = canonical_parameters(sc.truth)
    pred = measurement_model.predict(*shape, *poses.T)
    w8 = np.array([1 / sigma] * 4 + [1 / np.radians(sigma)] * 2)
    rng = np.random.default_rng(0)
    errors, corrections, variances = [], [], []
    for _ in range(12):
        meas = pred + rng.standard_normal(pred.shape) / w8
        meas[:, 4:6] = wrap_angle(meas[:, 4:6])
        fit = refine(meas, shape, poses, sigma, np.radians(sigma), frame_search=True)
        bc = ml_bias(
            meas, fit.shape, fit.poses, sigma, np.radians(sigma), fit.frame_chi2, fit.covariance
        )
        err = fit.shape - shape
        err[1:] = wrap_angle(err[1:])
        errors.append(err)
        corrections.append(bc.bias)
        variances.append(np.diag(fit.covariance + bc.covariance))
    errors, corrections, variances = map(np.array, (errors, corrections, variances))
    se = errors.std(axis=0, ddof=1) / np.sqrt(len(errors))
    bias = errors.mean(axis=0)
    assert bias[0] > 4 * se[0]  # c comes out long: a bias to remove
    corrected = (errors - corrections).mean(axis=0)
    mean_correction = corrections.mean(axis=0)
    assert 0 < mean_correction[0] < 2 * bias[0]  # the right sign, not overdone
    assert abs(corrected[0]) < bias[0] - 2 * se[0]  # the mean error significantly smaller
    # the error bar: each corrected fit within 3 of its standard deviations (the fit's and the
    # correction's covariance together)
    assert np.all(np.abs(errors - corrections) <= 3 * np.sqrt(variances))


def test_a_long_noise_free_sequence_still_gives_the_truth():
    """1,200 noise-free frames (the bias-corrected estimator's range): no noise, no bias to
    remove; the answer is the truth to 1e-9 (relative c, angles in radians)."""
    from curverecon.pipeline import reconstruct
    from curverecon.refine.bias import BIAS_CORRECTED_FRAMES

    n = BIAS_CORRECTED_FRAMES + 200
    sc = make_scene(np.random.default_rng(21), n, 0.0, 0.0)
    shape = normalise(*canonical_parameters(sc.truth))[0]  # the answer's conventions
    rec = reconstruct(sc.observations)
    assert rec.inliers.all()
    err = rec.shape - shape
    err[1:] = wrap_angle(err[1:])
    assert abs(err[0]) / shape[0] < 1e-9 and np.max(np.abs(err[1:])) < 1e-9


def test_from_bias_corrected_frames_the_answer_is_corrected_and_its_std_widened():
    """A noisy 1,200-frame scene: the default answer is the maximum-likelihood shape minus the
    correction (named so), its std at least the maximum-likelihood one; ``estimator="ml"``
    keeps the uncorrected fit."""
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct

    obs = make_scene(np.random.default_rng(22), 1200, 1.0, 1.0).observations
    rec = reconstruct(obs)
    ml = reconstruct(obs, options=ReconstructOptions(estimator="ml"))
    assert rec.estimator == "ml-bias-corrected" and ml.estimator == "ml"
    assert not np.allclose(rec.shape, ml.shape, rtol=1e-9, atol=0.0)
    assert np.all(np.asarray(rec.std) >= np.asarray(ml.std))
    assert not any("precision, not the accuracy" in w for w in rec.warnings)


def test_the_correction_needs_noise_and_five_frames():
    """No correction (None) for fewer than 5 frames or noise-free residuals."""
    from curverecon.refine.bias import ml_bias

    meas = np.zeros((4, 6))
    assert ml_bias(meas, np.ones(4), np.zeros((4, 5)), 1.0, 0.1, np.ones(4), np.eye(4)) is None
    meas = np.zeros((10, 6))
    assert ml_bias(meas, np.ones(4), np.zeros((10, 5)), 1.0, 0.1, np.zeros(10), np.eye(4)) is None


def test_the_fold_gain_is_the_inverse_slope_of_the_biased_map():
    """Independent construction: a bias that is linear in the shape, b(g) = b0 + K (g - g_fit),
    and the fit g_fit = g* + b(g*) solved for g* directly.  Changing b by e moves g* by
    (I + K)^-1 e; along the correction that is e / lambda, and ``_fold_gain`` (from b at the fit
    and at the fit minus it, as ``ml_bias`` evaluates it) returns 1 / lambda."""
    from curverecon.refine.bias import MIN_SLOPE, _fold_gain

    sd = np.array([0.5, 0.01, 0.02, 0.005])
    g_fit = np.array([150.0, 0.7, 0.4, 0.06])
    b0 = np.array([0.4, -0.004, 0.002, 0.012])
    direction = b0 / sd / np.linalg.norm(b0 / sd)
    for s in (-0.4, -0.7, 0.0):  # slope of the bias along the correction (standardised)
        k = np.diag(sd) @ (s * np.outer(direction, direction)) @ np.diag(1 / sd)

        def bias(g, e=0.0, k=k):
            return b0 + k @ (g - g_fit) + e * b0

        def solve(e, k=k):  # g* with g* + bias(g*) = g_fit
            return np.linalg.solve(np.eye(4) + k, g_fit - b0 - e * b0 + k @ g_fit)

        moved = solve(1e-3) - solve(0.0)
        assert np.allclose(moved, -1e-3 * b0 / (1 + s), rtol=1e-9, atol=0.0)
        gain = _fold_gain(bias(g_fit), bias(g_fit - b0), sd)
        assert np.isclose(gain, 1 / max(1 + s, MIN_SLOPE), rtol=1e-9)
    # a bias that shrinks along the correction keeps the gain at 1; no bias, no gain
    assert _fold_gain(b0, 0.5 * b0, sd) == 1.0
    assert _fold_gain(np.zeros(4), b0, sd) == 1.0


def test_phi_near_zero_keeps_an_honest_error_bar():
    """phi of 0.003 rad (the fold of the mirror phi -> -phi: the maximum-likelihood phi comes
    out about 3 degrees at 1 deg noise, whatever the frames, and the simulated bias, flat in phi
    there, finds a fraction of it).  2,000 frames at 1 px / 1 deg: the answer's phi within 3 of
    its std, which the fold's gain widened (without it phi's error was 4.2 std)."""
    import curverecon.refine.answer as answer
    from curverecon.pipeline import reconstruct

    sc = make_scene(np.random.default_rng(1382), 2000, 1.0, 1.0)
    truth = normalise(sc.truth.shape, np.zeros((1, 5)))[0]
    assert truth[3] < 0.005
    seen = []
    original = answer.ml_bias

    def ml_bias(*args, **kwargs):
        seen.append(original(*args, **kwargs))
        return seen[-1]

    answer.ml_bias = ml_bias
    try:
        rec = reconstruct(sc.observations)
    finally:
        answer.ml_bias = original
    assert rec.estimator == "ml-bias-corrected"
    assert seen[-1].gain > 1.3
    err = rec.shape - truth
    err[1:] = wrap_angle(err[1:])
    assert np.all(np.abs(err) <= 3 * np.asarray(rec.std))
