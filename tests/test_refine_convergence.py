"""Convergence of the maximum-likelihood refinement (Newton-type LM with embedded pose steps)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from curverecon.generated import measurement_model
from test_conventions import canonical_parameters

from bench.common import make, true_poses
from curverecon.refine.ml import _lin_batch, _weights, curvature, refine, standardised_residuals
from curverecon.simulate import make_scene

TS = math.radians(1.0)


def _headline(idx: int):
    """A headline benchmark scene (1 px, 1 degree, 20 frames) and its true parameters."""
    sc = make(20260521, "accuracy", (13, idx), 20, point_sigma=1.0, tangent_sigma_deg=1.0)
    shape, poses = true_poses(sc)
    return sc.observations, shape, poses


@pytest.mark.parametrize("idx", [2, 9, 106, 194])
def test_converges_quickly_from_the_truth_on_hard_scenes(idx):
    # Plain Gauss-Newton LM took 133, 42, 83, 74 iterations here (frames with c' close to c:
    # the fold tau = 0 of B' = c cos(tau), where Gauss-Newton overshoots in tau and zig-zags).
    obs, shape, poses = _headline(idx)
    res = refine(obs, shape, poses, 1.0, TS, covariance=False)
    assert res.converged
    assert res.iterations <= 55, res.iterations
    # a minimum: the gradient J^T r vanishes (relative to its size at the start)
    meas = obs.measurements()
    w8 = _weights(1.0, TS)
    g0 = _gradient(shape, poses, meas, w8)
    g1 = _gradient(res.shape, res.poses, meas, w8)
    assert np.linalg.norm(g1) < 1e-5 * np.linalg.norm(g0)


def _gradient(shape, poses, meas, w8):
    r, jg, jl = _lin_batch(np.asarray(shape)[None], np.asarray(poses)[None], meas, w8)
    eg = np.einsum("knai,kna->i", jg, r)
    el = np.einsum("knai,kna->ni", jl, r)
    return np.concatenate([eg, el.ravel()])


def test_1000_frames_converge_from_the_truth():
    sc = make(20260521, "speed", (3, 1000), 1000, point_sigma=1.0, tangent_sigma_deg=1.0)
    shape, poses = true_poses(sc)
    res = refine(sc.observations, shape, poses, 1.0, TS)
    assert res.converged and res.iterations <= 40, res.iterations
    assert res.std is not None and np.all(np.isfinite(res.std))


def test_chi2_matches_scipy_least_squares():
    """Same residual function, independent optimiser (MINPACK LM, finite differences)."""
    from scipy.optimize import least_squares

    sc = make_scene(np.random.default_rng(7), 8, 1.0, 1.0)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    w8 = _weights(1.0, TS)
    n = len(poses)

    def fun(x):
        return standardised_residuals(x[:4], x[4:].reshape(n, 5), meas, w8).ravel()

    x0 = np.concatenate([shape, poses.ravel()])
    sol = least_squares(fun, x0, method="lm", xtol=1e-12, ftol=1e-12, gtol=1e-12)
    ref = float(np.sum(sol.fun**2))
    res = refine(sc.observations, shape, poses, 1.0, TS, covariance=False)
    assert res.converged
    assert res.chi2 <= ref * (1 + 1e-8) + 1e-12, (res.chi2, ref)
    # started at scipy's answer refine stays there (it is a minimum of the same objective)
    again = refine(sc.observations, sol.x[:4], sol.x[4:].reshape(n, 5), 1.0, TS, covariance=False)
    assert abs(again.chi2 - ref) <= 1e-8 * ref
    assert np.allclose(again.shape, sol.x[:4], rtol=1e-6, atol=1e-8)


@pytest.mark.parametrize("n_frames,seed", [(6, 51), (6, 52), (20, 53)])
def test_noise_free_data_converge_to_the_truth_exactly(n_frames, seed):
    sc = make_scene(np.random.default_rng(seed), n_frames)
    shape, poses = canonical_parameters(sc.truth)
    rng = np.random.default_rng(seed + 100)
    s0 = shape + np.array([0.01 * shape[0], 0.01, 0.01, 0.01]) * rng.normal(size=4)
    p0 = poses + np.array([0.01, 0.01, 0.003, 0.3, 0.3]) * rng.normal(size=poses.shape)
    res = refine(sc.observations, s0, p0)
    assert res.converged
    assert res.chi2 < 1e-18
    err = np.abs(res.shape - shape) / np.array([shape[0], 1.0, 1.0, 1.0])
    assert np.max(err) < 1e-10, err


def test_second_order_term_matches_finite_differences():
    """curvature is sum_k r_k d2 r_k: J^T J + it is the Hessian of chi2 / 2."""
    sc = make_scene(np.random.default_rng(8), 3, 2.0, 3.0)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    w8 = _weights(1.0, TS)
    x = np.concatenate([shape, poses.ravel()]) + 0.02 * np.random.default_rng(1).normal(
        size=4 + poses.size
    )
    n = len(poses)

    def lin(x):
        r, jg, jl = _lin_batch(x[None, :4], x[4:].reshape(1, n, 5), meas, w8)
        jac = np.zeros((6 * n, 4 + 5 * n))
        for i in range(n):
            jac[6 * i : 6 * i + 6, :4] = jg[0, i]
            jac[6 * i : 6 * i + 6, 4 + 5 * i : 9 + 5 * i] = jl[0, i]
        return r, jac

    r, jac = lin(x)
    hess = np.zeros((x.size, x.size))
    for j in range(x.size):
        e = np.zeros(x.size)
        e[j] = 1e-6 * max(1.0, abs(x[j]))
        rp, jp = lin(x + e)
        rm, jm = lin(x - e)
        hess[:, j] = (jp.T @ rp.ravel() - jm.T @ rm.ravel()) / (2 * e[j])
    hess = 0.5 * (hess + hess.T)
    model = jac.T @ jac
    s = curvature(x[None, :4], x[4:].reshape(1, n, 5), r, w8)[0]
    for i in range(n):
        idx = np.r_[0:4, 4 + 5 * i : 9 + 5 * i]
        model[np.ix_(idx, idx)] += s[i]
    gn_error = np.max(np.abs(hess - jac.T @ jac))
    assert gn_error > 1e-3  # the second-order term matters here
    assert np.max(np.abs(hess - model)) < 1e-6 * gn_error + 1e-7
    assert measurement_model.GLOBAL_PARAMETERS == ("c", "alpha", "beta", "phi")


@pytest.mark.parametrize("idx", [9, 90])
def test_frame_search_finds_lower_minima(idx):
    """From the truth the local fit keeps frames in worse pose basins (tau against -tau near
    the fold, other delta); ``frame_search`` moves them (9: 9.28 -> 5.30, 90: 10.53 -> 4.55)."""
    obs, shape, poses = _headline(idx)
    local = refine(obs, shape, poses, 1.0, TS, covariance=False)
    found = refine(obs, shape, poses, 1.0, TS, covariance=False, frame_search=True)
    assert found.converged
    assert found.chi2 < 0.8 * local.chi2, (found.chi2, local.chi2)
    assert np.isclose(found.frame_chi2.sum(), found.chi2)


def test_normal_blocks_are_those_of_the_plain_formulation():
    """The fused blocks of the iteration (one J^T J product per frame, the second-order term
    added entry by entry) equal, to the bit, the separate products plus :func:`curvature`."""
    from curverecon.refine.ml import _lin_aug, _normal_blocks

    obs, shape, poses = _headline(9)
    meas = obs.measurements()
    rng = np.random.default_rng(4)
    g = shape[None] * (1 + 0.02 * rng.normal(size=(3, 4)))
    p = poses[None] + 0.05 * rng.normal(size=(3, *poses.shape))
    for w8 in (_weights(1.0, TS), _weights(1.0, TS) * rng.uniform(0.5, 1.5, (len(poses), 1))):
        r, jg, jl = _lin_batch(g, p, meas, w8)
        jg, jl = np.ascontiguousarray(jg), np.ascontiguousarray(jl)
        for newton in (np.zeros(3, bool), np.ones(3, bool), np.array([True, False, True])):
            r2, ja = _lin_aug(g, p, meas, w8)
            h, u, el, eg, dv, du, _, _ = _normal_blocks(g, p, r2, ja, w8, newton)
            jgt, jlt = np.swapaxes(jg, -1, -2), np.swapaxes(jl, -1, -2)
            u0, v0, w0 = np.sum(jgt @ jg, axis=1), jlt @ jl, jgt @ jl
            np.testing.assert_array_equal(dv, np.einsum("knii->kni", v0))
            np.testing.assert_array_equal(du, np.einsum("kii->ki", u0))
            s = curvature(g, p, r, w8)
            s[~newton] = 0.0
            v0 += s[..., 4:, 4:]
            w0 += s[..., :4, 4:]
            u0 += np.sum(s[..., :4, :4], axis=-3)
            np.testing.assert_array_equal(h[..., :5, :5], v0)
            np.testing.assert_array_equal(h[..., 5:, :5], w0)
            np.testing.assert_array_equal(u, u0)
            np.testing.assert_array_equal(el, (jlt @ r[..., None])[..., 0])
            np.testing.assert_array_equal(eg, np.sum(jgt @ r[..., None], axis=1)[..., 0])


def test_linearisation_residuals_are_the_wrapped_residuals():
    """_lin_aug inlines wrap_line_angle: same residuals, to the bit (and the Jacobians)."""
    from curverecon.model.observations import wrap_line_angle
    from curverecon.refine.ml import _lin_aug

    obs, shape, poses = _headline(2)
    meas = obs.measurements()
    w8 = _weights(1.0, TS)
    rng = np.random.default_rng(5)
    for scale in (0.0, 0.3, 3.0):  # also angles far outside (-pi/2, pi/2]
        p = poses + scale * rng.normal(size=poses.shape)
        r, ja = _lin_aug(shape[None], p[None], meas, w8)
        pred, jg, jl = measurement_model.predict_with_jacobians(*shape, *p.T)
        r0 = pred - meas
        r0[:, 4:6] = wrap_line_angle(r0[:, 4:6])
        np.testing.assert_array_equal(r[0], r0 * w8)
        np.testing.assert_array_equal(ja[0], np.concatenate([jl, jg], -1) * w8[:, None])
        np.testing.assert_allclose(r[0], standardised_residuals(shape, p, meas, w8), atol=1e-9)
