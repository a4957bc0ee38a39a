"""Long sequences: the per-frame computations in chunks and on the frames still moving give the
answer of the plain computation; the refinement from one shape on all frames; the outlier test's
one-round path for many frames."""

from __future__ import annotations

import numpy as np
import pytest
from test_conventions import canonical_parameters

from curverecon.model.pose import normalise
from curverecon.options import OutlierOptions
from curverecon.refine import marginal, ml
from curverecon.refine.ml import frame_leverages, optimise_poses, refine
from curverecon.refine.start import refine_hypothesis
from curverecon.robust.outliers import find_outlier_frames
from curverecon.simulate import make_scene
from curverecon.solvers.pose import poses_from_shape

TS = np.radians(1.0)
W8 = np.array([1.0] * 4 + [1.0 / TS] * 2)


def _scene(seed: int, n: int, noise: float = 1.0, outliers: float = 0.0):
    return make_scene(np.random.default_rng(seed), n, noise, noise, outlier_fraction=outliers)


def test_pose_optimisation_reaches_the_true_poses_in_chunks_as_in_one_piece(monkeypatch):
    sc = _scene(3, 300, noise=0.0)
    shape, truth = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    start = truth + np.random.default_rng(4).normal(scale=0.02, size=truth.shape)
    start[:, 2:] = truth[:, 2:]
    whole = optimise_poses(shape, start, meas, W8, 20)
    # noise-free: every frame back at its true pose (independent: the simulated geometry)
    assert np.max(np.abs(whole[0][:, :2] - truth[:, :2])) < 1e-7
    monkeypatch.setattr(ml, "FRAME_CHUNK", 64)
    chunked = optimise_poses(shape, start, meas, W8, 20)
    assert np.array_equal(whole[0], chunked[0]) and np.array_equal(whole[1], chunked[1])


def test_refinement_and_leverages_in_chunks_are_those_in_one_piece(monkeypatch):
    sc = _scene(5, 400)
    shape, poses = canonical_parameters(sc.truth)
    g0 = shape * 1.002
    p0, _ = poses_from_shape(sc.observations, g0)
    meas = sc.observations.measurements()
    weights = np.random.default_rng(6).uniform(0.5, 1.0, 400)
    whole = refine(meas, g0, p0, 1.0, TS, frame_weights=weights)
    lev = frame_leverages(whole.shape, whole.poses, meas, W8)
    monkeypatch.setattr(ml, "FRAME_CHUNK", 50)
    chunked = refine(meas, g0, p0, 1.0, TS, frame_weights=weights)
    assert np.array_equal(whole.shape, chunked.shape)
    assert np.array_equal(whole.poses, chunked.poses)
    assert np.array_equal(whole.covariance, chunked.covariance)
    assert np.array_equal(lev, frame_leverages(whole.shape, whole.poses, meas, W8))


def test_marginal_step_in_chunks_is_the_one_in_one_piece(monkeypatch):
    sc = _scene(7, 260)
    meas = sc.observations.measurements()
    shape, poses = canonical_parameters(sc.truth)
    fit = refine(meas, shape, poses, 1.0, TS, covariance=False)
    whole = marginal.refine_marginal(meas, fit.shape, fit.poses, 1.0, TS, fit.chi2)
    monkeypatch.setattr(marginal, "FRAME_CHUNK", 40)
    monkeypatch.setattr(ml, "FRAME_CHUNK", 40)
    chunked = marginal.refine_marginal(meas, fit.shape, fit.poses, 1.0, TS, fit.chi2)
    assert np.array_equal(whole.shape, chunked.shape)
    assert np.array_equal(whole.poses, chunked.poses)
    assert whole.value == chunked.value


def test_refinement_from_one_shape_finds_the_truth_on_all_frames():
    sc = _scene(9, 600, noise=0.0)
    truth, _ = normalise(sc.truth.shape, np.zeros((1, 5)))
    start = sc.truth.shape * np.array([1.02, 0.98, 1.03, 0.97])
    fit = refine_hypothesis(sc.observations, start, 1.0, TS)
    assert fit.chi2 < 1e-12
    assert np.max(np.abs(fit.shape - truth) / np.r_[truth[0], 1, 1, 1]) < 1e-7
    assert fit.poses.shape == (600, 5)


@pytest.mark.parametrize("seed", [12, 13])
def test_long_sequence_outliers_are_dropped_in_one_round(seed):
    """With ``batch_frames`` low, the one-round path flags simulated outlier frames only (the
    simulation's truth; one of the six fits by chance), the same as the one-at-a-time path."""
    sc = _scene(seed, 120, outliers=0.05)
    obs = sc.observations
    shape, poses = canonical_parameters(sc.truth)
    fit = refine(obs, shape, poses, 1.0, TS, covariance=False)
    true_out = ~sc.truth.inliers
    assert true_out.sum() >= 3
    one_round = find_outlier_frames(obs, fit, 1.0, TS, OutlierOptions(batch_frames=50))
    one_by_one = find_outlier_frames(obs, fit, 1.0, TS, OutlierOptions(batch_frames=10**9))
    flagged = ~one_round[0]
    assert flagged.sum() >= true_out.sum() - 1 and not np.any(flagged & ~true_out)
    assert np.array_equal(one_round[0], one_by_one[0])
    assert np.allclose(one_round[1].shape, one_by_one[1].shape, rtol=1e-6, atol=1e-8)


def test_many_frames_warn_that_the_std_is_the_precision_not_the_accuracy():
    """From ``BIAS_WARNING_FRAMES`` inlier frames on the uncorrected maximum-likelihood answer
    (``estimator="ml"``) says its standard deviations understate its error; below, it does
    not."""
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct
    from curverecon.refine.answer import BIAS_WARNING_FRAMES

    ml = ReconstructOptions(estimator="ml")
    many = reconstruct(_scene(13, BIAS_WARNING_FRAMES + 50).observations, options=ml)
    few = reconstruct(_scene(13, 300).observations, options=ml)
    assert any("precision, not the accuracy" in w for w in many.warnings)
    assert not any("precision, not the accuracy" in w for w in few.warnings)


def test_beyond_marginal_max_frames_the_answer_is_maximum_likelihood_and_says_so():
    """From ``marginal_max_frames`` inlier frames on, ``estimator="marginal"`` gives the answer
    of ``estimator="ml"`` (the same shape and std) with a warning naming the option; below, the
    marginal step runs (it moves the shape on a noisy scene)."""
    from curverecon.options import ReconstructOptions
    from curverecon.pipeline import reconstruct

    obs = _scene(14, 280).observations  # below BIAS_CORRECTED_FRAMES
    capped = reconstruct(obs, options=ReconstructOptions(marginal_max_frames=250))
    ml_answer = reconstruct(obs, options=ReconstructOptions(estimator="ml"))
    default = reconstruct(obs)
    assert capped.estimator == "ml" and default.estimator == "marginal"
    assert np.array_equal(capped.shape, ml_answer.shape)
    assert np.array_equal(capped.std, ml_answer.std)
    assert any("marginal_max_frames" in w for w in capped.warnings)
    assert not any("marginal_max_frames" in w for w in default.warnings + ml_answer.warnings)
    assert not np.allclose(default.shape, ml_answer.shape, rtol=1e-9, atol=0.0)


def _start(sc, factor):
    """A start shape off the truth by ``factor``, with the true poses."""
    shape, poses = canonical_parameters(sc.truth)
    return shape * np.asarray(factor), poses


def test_profile_iteration_reaches_the_exact_shape_without_noise(monkeypatch):
    """The profile iteration (the fit from ``PROFILE_FRAMES`` frames on, here lowered to 300)
    from a start 0.2-0.3 % off with the true poses: the simulated shape to 1e-7 (independent:
    the 3-D construction).  (From 2-3 % off, frames near a fold take other pose basins on the
    way, for the joint iteration too: a local minimum, chi2 83 and 295.)"""
    monkeypatch.setattr(ml, "PROFILE_FRAMES", 300)
    sc = _scene(21, 400, noise=0.0)
    truth, _ = canonical_parameters(sc.truth)
    start, poses = _start(sc, [1.002, 0.998, 1.003, 0.997])
    g, p, r, chi2, iters, conv = ml.refine_batch(sc.observations, start[None], poses[None])
    shape = g[0]
    assert conv[0] and chi2[0] < 1e-12 and iters[0] <= 15
    assert np.max(np.abs(shape - truth) / np.r_[truth[0], 1, 1, 1]) < 1e-7
    assert np.isclose(chi2[0], np.sum(r * r))


@pytest.mark.parametrize("seed", [22, 23])
def test_profile_iteration_ends_at_a_stationary_point_of_the_profile(monkeypatch, seed):
    """1 px / 1 deg noise: the profile fit ends where central differences of the profile chi2
    (every pose re-optimised for each shifted shape: no Newton algebra) are flat, below 0.05
    per standard deviation, and no worse than the joint damped iteration (another algorithm;
    it may end in another pose basin of a frame near a fold: within 0.2 standard deviations
    and 0.1 of chi2, or lower)."""
    sc = _scene(seed, 500)
    start, poses = _start(sc, [1.01, 0.99, 1.01, 0.99])
    joint = refine(sc.observations, start, poses, 1.0, TS, xtol=1e-13, ftol=1e-14)
    monkeypatch.setattr(ml, "PROFILE_FRAMES", 300)
    g, p, r, chi2, iters, conv = ml.refine_batch(sc.observations, start[None], poses[None])
    std = np.sqrt(np.diag(joint.covariance))
    meas = sc.observations.measurements()
    assert conv[0]
    for i in range(4):
        h = np.zeros(4)
        h[i] = 0.1 * std[i]
        up = np.sum(optimise_poses(g[0] + h, p[0], meas, W8, 20)[1] ** 2)
        down = np.sum(optimise_poses(g[0] - h, p[0], meas, W8, 20)[1] ** 2)
        assert abs(up - down) / 0.2 < 0.05
    assert np.max(np.abs(g[0] - joint.shape) / std) < 0.2
    assert chi2[0] <= joint.chi2 + 0.1
