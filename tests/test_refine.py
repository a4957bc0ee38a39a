"""Maximum-likelihood refinement (Schur-complement LM) and the Cramer-Rao bound."""

from __future__ import annotations

import numpy as np
import pytest
from curverecon.generated import measurement_model
from test_conventions import canonical_parameters

from curverecon.refine.ml import crlb, crlb_covariance, refine, refine_batch
from curverecon.simulate import make_scene


def _perturb(shape, poses, rng, scale=1.0):
    s = shape + scale * np.array([0.03 * shape[0], 0.05, 0.05, 0.05]) * rng.normal(size=4)
    p = poses + scale * np.array([0.05, 0.03, 0.01, 1.0, 1.0]) * rng.normal(size=poses.shape)
    return s, p


def test_refinement_recovers_noise_free_truth_from_a_perturbed_start():
    sc = make_scene(np.random.default_rng(41), 10)
    shape, poses = canonical_parameters(sc.truth)
    s0, p0 = _perturb(shape, poses, np.random.default_rng(0))
    res = refine(sc.observations, s0, p0)
    assert res.converged
    assert res.chi2 < 1e-16
    assert np.allclose(res.shape, shape, rtol=1e-10, atol=1e-10)
    start_err = np.max(np.abs(s0 - shape) / [shape[0], 1, 1, 1])
    assert start_err > 1e-3  # the start really was off


def test_refinement_improves_a_noisy_start():
    sc = make_scene(np.random.default_rng(42), 20, 1.0, 1.0)
    shape, poses = canonical_parameters(sc.truth)
    s0, p0 = _perturb(shape, poses, np.random.default_rng(1))
    res = refine(sc.observations, s0, p0, 1.0, np.radians(1.0))
    from curverecon.refine.ml import standardised_residuals

    w8 = np.array([1.0] * 4 + [1 / np.radians(1.0)] * 2)
    chi2_start = np.sum(standardised_residuals(s0, p0, sc.observations.measurements(), w8) ** 2)
    assert res.chi2 < 0.1 * chi2_start
    assert res.std is not None
    err = np.abs(res.shape - shape)
    assert np.all(err < 5 * res.std + 1e-9), (err, res.std)
    assert np.all(res.frame_chi2 >= 0) and np.isclose(res.frame_chi2.sum(), res.chi2)


def test_batch_equals_single():
    sc = make_scene(np.random.default_rng(43), 8, 0.5, 0.5)
    shape, poses = canonical_parameters(sc.truth)
    rng = np.random.default_rng(2)
    starts = [_perturb(shape, poses, rng, 0.3) for _ in range(3)]
    g, p, r, chi2, _, _ = refine_batch(
        sc.observations, np.array([s for s, _ in starts]), np.array([q for _, q in starts])
    )
    for k, (s0, p0) in enumerate(starts):
        single = refine(sc.observations, s0, p0, covariance=False)
        assert np.allclose(single.shape, g[k]) and np.isclose(single.chi2, chi2[k])


def test_schur_covariance_equals_dense_inverse():
    sc = make_scene(np.random.default_rng(44), 7)
    shape, poses = canonical_parameters(sc.truth)
    ps, ts = 0.7, np.radians(2.0)
    _, jg, jl = measurement_model.predict_with_jacobians(*shape, *poses.T)
    w = np.array([1 / ps] * 4 + [1 / ts] * 2)
    n = len(poses)
    dense = np.zeros((6 * n, 4 + 5 * n))
    for i in range(n):
        dense[6 * i : 6 * i + 6, :4] = jg[i] * w[:, None]
        dense[6 * i : 6 * i + 6, 4 + 5 * i : 9 + 5 * i] = jl[i] * w[:, None]
    cov = np.linalg.inv(dense.T @ dense)[:4, :4]
    assert np.allclose(crlb_covariance(shape, poses, ps, ts), cov, rtol=1e-6)
    assert np.allclose(crlb(shape, poses, ps, ts), np.sqrt(np.diag(cov)), rtol=1e-6)


@pytest.mark.parametrize("n", [20, 60])
def test_crlb_shrinks_with_frames(n):
    sc = make_scene(np.random.default_rng(45), n)
    shape, poses = canonical_parameters(sc.truth)
    b = crlb(shape, poses, 1.0, np.radians(1.0))
    assert np.all(np.isfinite(b)) and np.all(b > 0)
    if n == 60:
        b20 = crlb(shape, poses[:20], 1.0, np.radians(1.0))
        assert np.all(b < b20)


def test_damping_decreases_on_good_steps_near_degenerate_frame():
    """Noise-free, a frame with c' close to c (tau ~ 7 deg, B'x flat in tau): LM must shrink its
    damping after successful steps and converge quadratically, not creep to the iteration limit."""
    sc = make_scene(np.random.default_rng(1086), 6)
    shape, poses = canonical_parameters(sc.truth)
    assert np.max(sc.observations.cp / shape[0]) > 0.99
    s0, p0 = _perturb(shape, poses, np.random.default_rng(3), 0.2)
    res = refine(sc.observations, s0, p0)
    assert res.converged and res.iterations < 60
    assert res.chi2 < 1e-18
    assert np.allclose(res.shape, shape, rtol=1e-10, atol=1e-10)


def test_frame_leverages_predict_the_deleted_fit():
    """Leverage l_i: frame i's residual at the fit without it is its residual at the full fit
    divided by 1 - l_i (linearised).  Checked against real refits with frame i left out (its
    pose then re-fitted alone), at small noise where the linearisation holds; the leverages add
    up to the four shape parameters."""
    from curverecon.refine.ml import frame_leverages, optimise_poses

    sc = make_scene(np.random.default_rng(31), 12, 0.05, 0.05)
    obs, ts = sc.observations, np.radians(0.05)
    shape, poses = canonical_parameters(sc.truth)
    w8 = np.array([1 / 0.05] * 4 + [1 / ts] * 2)
    fit = refine(obs, shape, poses, 0.05, ts, covariance=False)
    lev = frame_leverages(fit.shape, fit.poses, obs.measurements(), w8)
    assert abs(np.sum(lev) - 4.0) < 1e-6 and np.all((lev > 0) & (lev < 1))
    for i in np.argsort(-lev)[:3]:  # the frames that pin the shape most
        keep = np.arange(obs.n_frames) != i
        rest = refine(obs.subset(keep), fit.shape, fit.poses[keep], 0.05, ts, covariance=False)
        _, r = optimise_poses(
            rest.shape, fit.poses[i : i + 1], obs.measurements()[i : i + 1], w8, 20
        )
        deleted = float(np.sum(r * r))
        predicted = fit.frame_chi2[i] / (1.0 - lev[i]) ** 2
        # (with 1 - l_i instead of its square the prediction is 5 to 40 times too small here)
        assert abs(deleted - predicted) < 0.15 * predicted, (i, lev[i], deleted, predicted)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_pose_solve_reaches_the_pose_from_a_start_degrees_off(seed):
    """``optimise_poses`` with step halving: from every frame's true pose with delta 12 degrees
    off, (nearly) every frame reaches the minimum found from the true pose itself; without the
    halving (``halvings=0``) a full Gauss-Newton step that overshoots left 6-13 % of the frames
    where they were.  Then ``switch_branches(..., rescue=True)`` brings every frame still
    misfitting by more than ``RESCUE_CHI2`` to that minimum or below."""
    from test_conventions import canonical_parameters

    from curverecon.options import SearchOptions
    from curverecon.refine.ml import optimise_poses
    from curverecon.robust.search import switch_branches

    RESCUE_CHI2 = SearchOptions().rescue_chi2

    sc = make_scene(np.random.default_rng(seed), 400, point_sigma=1.0, tangent_sigma_deg=1.0)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    _, r0 = optimise_poses(shape, poses.copy(), meas, w8, 20)
    f0 = np.sum(r0 * r0, axis=1)
    start = poses.copy()
    start[:, 0] += np.radians(12.0)
    p1, r1 = optimise_poses(shape, start.copy(), meas, w8, 20)
    _, r2 = optimise_poses(shape, start.copy(), meas, w8, 20, halvings=0)
    missed = np.sum(r1 * r1, axis=1) > f0 + 1e-6
    missed_plain = np.sum(r2 * r2, axis=1) > f0 + 1e-6
    assert missed.sum() <= 8 < missed_plain.sum()
    p3 = switch_branches(sc.observations, shape, p1, w8, rescue=True)
    _, r3 = optimise_poses(shape, p3, meas, w8, 0)
    f3 = np.sum(r3 * r3, axis=1)
    assert not np.any((f3 > RESCUE_CHI2) & (f3 > f0 + 1e-6))


def test_schur_information_stays_exact_with_a_measurement_seen_end_on():
    """A frame whose one measurement row is huge (a tangent seen nearly end-on: its angle's
    derivatives ~1e9) makes U - W V^-1 W^T cancel to noise in double precision.  With that row
    scaled by 1e9 (V's condition number far beyond ``SCHUR_COND_MAX``, so the row-sorted QR
    handles the frame) the frame's information must match the same formula evaluated with 60
    digits (mpmath), the total must stay positive definite, and on well-conditioned frames the
    QR must match the normal equations."""
    import mpmath
    from test_conventions import canonical_parameters

    from curverecon.refine.ml import (
        SCHUR_COND_MAX,
        _frame_schur_qr,
        _ill_conditioned,
        frame_information,
        schur_information,
    )

    sc = make_scene(np.random.default_rng(4), 12, point_sigma=1.0, tangent_sigma_deg=1.0)
    shape, poses = canonical_parameters(sc.truth)
    w8 = np.array([1.0] * 4 + [1.0 / np.radians(1.0)] * 2)
    _, jg, jl = measurement_model.predict_with_jacobians(*shape, *poses.T)
    jg, jl = jg * w8[None, :, None], jl * w8[None, :, None]
    assert not _ill_conditioned(np.einsum("nki,nkj->nij", jl, jl)).any()
    plain = frame_information(shape, poses, sc.observations.measurements(), w8)
    scale = np.abs(plain).max()
    assert np.allclose(_frame_schur_qr(jg, jl), plain, rtol=1e-8, atol=1e-8 * scale)

    jg[3, 5] *= 1e9
    jl[3, 5] *= 1e9
    assert np.linalg.cond(jl[3].T @ jl[3]) > SCHUR_COND_MAX
    mpmath.mp.dps = 60
    g3, l3 = mpmath.matrix(jg[3].tolist()), mpmath.matrix(jl[3].tolist())
    exact = g3.T * g3 - (g3.T * l3) * mpmath.inverse(l3.T * l3) * (l3.T * g3)
    exact = np.array(exact.tolist(), dtype=float)
    got = _frame_schur_qr(jg[3:4], jl[3:4])[0]
    assert np.allclose(got, exact, rtol=1e-10, atol=1e-10 * np.abs(exact).max())
    total = schur_information(jg, jl)
    assert np.linalg.eigvalsh(total)[0] > 0
