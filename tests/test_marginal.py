"""Marginal-likelihood refinement (poses integrated out by Laplace's method, Haar prior)."""

from __future__ import annotations

import numpy as np
import pytest
from curverecon.generated import measurement_model
from test_conventions import canonical_parameters

from curverecon.model.observations import wrap_line_angle
from curverecon.model.pose import normalise
from curverecon.options import BranchOptions
from curverecon.refine import marginal
from curverecon.refine.marginal import refine_marginal, shape_information, solve_poses, volume_terms
from curverecon.refine.ml import crlb, refine
from curverecon.simulate import make_scene

TS = np.radians(1.0)
W8 = np.array([1.0] * 4 + [1.0 / TS] * 2)


def _errors(est: np.ndarray, truth: np.ndarray) -> np.ndarray:
    d = np.angle(np.exp(1j * (est[1:] - truth[1:])))
    return np.concatenate([[(est[0] - truth[0]) / truth[0]], d])


def _fits(seed: int, n_frames: int = 20, noise: float = 1.0):
    sc = make_scene(np.random.default_rng(seed), n_frames, noise, noise)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    ml = refine(meas, shape, poses, noise, np.radians(noise), covariance=False)
    mg = refine_marginal(meas, ml.shape, ml.poses, noise, np.radians(noise), ml.chi2)
    return sc, shape, poses, meas, ml, mg


def _frame_chi2_gradient(g, p, meas):
    """(N, 5) gradient of each frame's chi2 / 2 over its pose (analytic Jacobian)."""
    pred, _, jl = measurement_model.predict_with_jacobians(*g, *p.T)
    r = pred - meas
    r[:, 4:6] = wrap_line_angle(r[:, 4:6])
    return np.einsum("nki,nk->ni", jl * W8[None, :, None], r * W8), r * W8


def _pose_hessian_fd(g, p, meas):
    """(N, 5, 5) Hessian of each frame's chi2 / 2 over its pose, by central differences of the
    analytic gradient (independent of the module's second-derivative formulas)."""
    h = np.empty((p.shape[0], 5, 5))
    for k in range(5):
        e = np.zeros_like(p)
        e[:, k] = 1e-6
        h[:, :, k] = (
            _frame_chi2_gradient(g, p + e, meas)[0] - _frame_chi2_gradient(g, p - e, meas)[0]
        ) / 2e-6
    return 0.5 * (h + np.swapaxes(h, 1, 2))


def _frame_terms(g, p, meas, kappa):
    """Each frame's term of F (module docstring) with its pose re-solved from p, written out
    directly; and those poses."""
    p = solve_poses(g[None], p[None], meas, W8, 30)[0][0]
    _, r = _frame_chi2_gradient(g, p, meas)
    h = _pose_hessian_fd(g, p, meas)
    sign, logdet = np.linalg.slogdet(h)
    assert np.all(sign > 0)
    prior = -2.0 * np.log(np.abs(np.cos(p[:, 1])))
    return np.sum(r * r, axis=1) / kappa + logdet + prior, p


def _f(g, p, meas, kappa):
    """F (module docstring) with every frame's pose re-solved from p, written out directly."""
    return float(np.sum(_frame_terms(g, p, meas, kappa)[0]))


def _f_mixture(g, p, alt, meas, kappa):
    """F with the frames of a finite row in ``alt`` (their other branch) as two-component
    mixtures, -2 log(exp(-F_a / 2) + exp(-F_b / 2)), written out directly."""
    if alt is None:
        return _f(g, p, meas, kappa)
    fa, pa = _frame_terms(g, p, meas, kappa)
    two = np.flatnonzero(np.all(np.isfinite(alt), axis=1))
    fb, pb = _frame_terms(g, alt[two], meas[two], kappa)
    d = np.abs(np.angle(np.exp(1j * (pb[:, :2] - pa[two, :2]))))
    fb = np.where(np.max(d, axis=1) < 1e-3, np.inf, fb)
    fa[two] = -2.0 * np.logaddexp(-fa[two] / 2.0, -fb / 2.0)
    return float(np.sum(fa))


def test_noise_free_data_keep_the_exact_answer():
    sc = make_scene(np.random.default_rng(7), 8)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    ml = refine(meas, shape, poses, 1.0, TS)
    assert ml.chi2 < 1e-18
    # no noise to measure: the correction (proportional to the noise scale) is not applied
    assert refine_marginal(meas, ml.shape, ml.poses, 1.0, TS, ml.chi2) is None


def test_too_few_frames_to_measure_the_noise():
    sc = make_scene(np.random.default_rng(8), 4, 1.0, 1.0)
    shape, poses = canonical_parameters(sc.truth)
    meas = sc.observations.measurements()
    assert refine_marginal(meas, shape, poses, 1.0, TS, 3.0) is None


@pytest.mark.parametrize("seed", [3, 11])
def test_answer_is_a_local_minimum_of_f(seed):
    _, _, _, meas, ml, mg = _fits(seed)
    assert mg is not None and mg.converged
    f_ml = _f(ml.shape, ml.poses, meas, mg.kappa)
    f_mg = _f(mg.shape, mg.poses, meas, mg.kappa)
    assert f_mg < f_ml - 1e-3  # the correction moved the shape, downhill
    assert abs(f_mg - mg.value) < 1e-5 * abs(f_mg)
    # steps of a tenth of a standard deviation along each axis of the shape do not go lower
    std = np.sqrt(np.diag(np.linalg.inv(shape_information(mg.shape, mg.poses, W8))))
    for k in range(4):
        for sgn in (-1.0, 1.0):
            g = mg.shape.copy()
            g[k] += sgn * 0.1 * std[k] * np.sqrt(mg.kappa)
            assert _f(g, mg.poses, meas, mg.kappa) > f_mg - 1e-6


@pytest.mark.parametrize("seed", [3, 11])
def test_mixture_answer_is_a_local_minimum_of_the_mixture_f(seed):
    """With each frame's other branch of (10) as a second mixture component (the pipeline's
    default): the value reported is the mixture F written out directly, and steps of a tenth
    of a standard deviation along each axis of the shape do not go lower."""
    from curverecon.robust.branches import second_branches

    sc, _, _, meas, ml, _ = _fits(seed)
    kappa = ml.chi2 / (meas.shape[0] - 4)
    alt = second_branches(sc.observations, ml, W8, kappa, BranchOptions())
    assert np.isfinite(alt).all(axis=1).sum() >= 3  # frames with a competing branch
    mg = refine_marginal(meas, ml.shape, ml.poses, 1.0, TS, ml.chi2, alt)
    assert mg is not None and mg.converged
    p_alt = mg.other_poses
    f_mg = _f_mixture(mg.shape, mg.poses, p_alt, meas, kappa)
    # (within 0.05: the module's pose solves stop at 4 Newton steps, these at 30; on seed 3
    # one single-branch frame's term differs by 0.008)
    assert abs(f_mg - mg.value) < 0.05
    assert f_mg < _f_mixture(ml.shape, ml.poses, alt, meas, kappa) - 1e-3
    std = np.sqrt(np.diag(np.linalg.inv(shape_information(mg.shape, mg.poses, W8))) * kappa)
    for k in range(4):
        for sgn in (-1.0, 1.0):
            g = mg.shape.copy()
            g[k] += sgn * 0.1 * std[k]
            assert _f_mixture(g, mg.poses, p_alt, meas, kappa) > f_mg - 1e-6


@pytest.mark.parametrize("seed", [3, 13])
def test_analytic_gradient_matches_finite_differences_of_f(seed):
    """F's gradient (chi2 part exact, dp/dg from the full Hessian, volume part by differences
    at first-order poses) against central differences of F with every pose re-solved."""
    _, _, _, meas, ml, _ = _fits(seed)
    kappa = ml.chi2 / (meas.shape[0] - 4)
    std = np.sqrt(np.diag(np.linalg.inv(shape_information(ml.shape, ml.poses, W8))) * kappa)
    dirs = np.diag(std)  # one standard deviation of each parameter

    def f_and_poses(g):
        p, r, _, jl, _ = marginal._solve(g[None], ml.poses[None], meas, W8, 30, 1e-15 * kappa)
        return float(np.sum(r * r) / kappa + np.sum(volume_terms(g[None], p, r, jl, W8))), p[0]

    for offset in ([0.0, 0.0, 0.0, 0.0], [0.6, -0.4, 0.3, 0.2]):
        g = ml.shape + dirs @ np.array(offset)
        p, *lin = marginal._solve(g[None], ml.poses[None], meas, W8, 30, 1e-15 * kappa)
        grad, dpdx = marginal._gradient(g, p[0], [a[0] for a in lin], meas, W8, kappa, dirs)
        h = 1e-3  # smaller steps see the pose solves' rounding (1e-4: errors of 1e-3)
        want, dp_want = np.empty(4), np.empty((meas.shape[0], 5, 4))
        for k in range(4):
            f_plus, p_plus = f_and_poses(g + h * dirs[:, k])
            f_minus, p_minus = f_and_poses(g - h * dirs[:, k])
            want[k] = (f_plus - f_minus) / (2 * h)
            dp_want[:, :, k] = (p_plus - p_minus) / (2 * h)
        assert np.max(np.abs(want)) > 0.1  # not a trivial check at a flat point
        assert np.allclose(grad, want, rtol=1e-3, atol=1e-3)
        # the poses follow the shape as the full Hessian says (Gauss-Newton's would not)
        assert np.allclose(dpdx, dp_want, rtol=1e-3, atol=1e-4 * np.max(np.abs(dp_want)))


def test_only_the_ratio_of_the_sigmas_matters():
    _, _, _, meas, ml, mg = _fits(5)
    mg3 = refine_marginal(meas, ml.shape, ml.poses, 3.0, 3.0 * TS, ml.chi2 / 9.0)
    assert mg3 is not None
    assert np.allclose(mg3.shape, mg.shape, rtol=1e-5, atol=1e-7)


def test_volume_term_is_the_log_det_of_the_pose_hessian_and_the_haar_prior():
    # Laplace: the integral over p of exp(-chi2(p) / 2) is about (2 pi)^(5/2) det(H)^(-1/2)
    # exp(-chi2_min / 2), H the Hessian of chi2 / 2 at the mode; -2 log of it is chi2_min +
    # log det H + const.  The Haar density of R_z(theta) R_y(tau) R_x(delta) is |cos tau|.
    _, _, _, meas, ml, _ = _fits(13)
    g, p = ml.shape, ml.poses
    pred, _, jl = measurement_model.predict_with_jacobians(*g, *p.T)
    _, r = _frame_chi2_gradient(g, p, meas)
    got = volume_terms(g[None], p[None], r[None], (jl * W8[None, :, None])[None], W8)[0]
    h = _pose_hessian_fd(g, p, meas)
    want = np.linalg.slogdet(h)[1] - 2.0 * np.log(np.abs(np.cos(p[:, 1])))
    assert np.allclose(got, want, atol=1e-5)
    # the second-order part matters: J^T J alone is off on some frame by more than 0.01
    v = np.einsum("nki,nkj->nij", jl * W8[None, :, None], jl * W8[None, :, None])
    gn = np.linalg.slogdet(v)[1] - 2.0 * np.log(np.abs(np.cos(p[:, 1])))
    assert np.max(np.abs(gn - want)) > 1e-2


def test_less_biased_than_maximum_likelihood_at_1px_20_frames():
    """Over seeded scenes of the independent simulator, the maximum-likelihood chord c is long
    (incidental poses: Neyman-Scott); the marginal estimate of c is not, and its angles are
    about as good.  Errors in units of each scene's Cramer-Rao bound."""
    z_ml, z_mg = [], []
    for seed in range(300, 316):
        sc, shape, poses, meas, ml, mg = _fits(seed)
        truth, _ = normalise(shape, poses)
        bound = crlb(shape, poses, 1.0, TS) / [shape[0], 1, 1, 1]
        z_ml.append(_errors(normalise(ml.shape, ml.poses)[0], truth) / bound)
        z_mg.append(_errors(normalise(mg.shape, mg.poses)[0], truth) / bound)
    z_ml, z_mg = np.array(z_ml), np.array(z_mg)
    rms_ml = np.sqrt(np.mean(z_ml**2, axis=0))
    rms_mg = np.sqrt(np.mean(z_mg**2, axis=0))
    assert np.mean(z_ml[:, 0]) > 0.5  # the bias this corrects
    assert abs(np.mean(z_mg[:, 0])) < 0.5 * np.mean(z_ml[:, 0])
    assert rms_mg[0] < 0.5 * rms_ml[0]
    assert np.mean(rms_mg[1:]) < 1.2 * np.mean(rms_ml[1:])


def test_pipeline_uses_the_marginal_estimate_and_says_so():
    from curverecon.pipeline import reconstruct

    sc = make_scene(np.random.default_rng(21), 20, 1.0, 1.0)
    ml = reconstruct(sc.observations, estimator="ml")
    mg = reconstruct(sc.observations)
    assert ml.estimator == "ml" and mg.estimator == "marginal"
    assert mg.to_json_dict()["estimator"] == "marginal"
    assert not np.allclose(ml.shape, mg.shape, rtol=1e-6)
    # the marginal answer is not the chi2 optimum, but near it: here it fits better than the
    # maximum-likelihood answer (its mixture over each frame's two branches led it to a
    # branch pattern the ML search had not reached: 10.1 against 11.1) ...
    assert abs(mg.chi2 - ml.chi2) < 10.0
    # ... and every frame sits on its best branch of (10) for that shape
    assert np.all(mg.branch_alternative_chi2 >= mg.frame_chi2 - 1e-6)


def test_pipeline_noise_free_answer_is_the_exact_one():
    from curverecon.pipeline import reconstruct

    sc = make_scene(np.random.default_rng(22), 8)
    shape, poses = canonical_parameters(sc.truth)
    rec = reconstruct(sc.observations)
    assert rec.estimator == "ml"  # nothing to integrate: no noise
    assert np.allclose(rec.shape, normalise(shape, poses)[0], rtol=1e-9, atol=1e-9)


def test_unknown_estimator_is_refused():
    from curverecon.errors import CurveReconError
    from curverecon.pipeline import reconstruct

    sc = make_scene(np.random.default_rng(23), 6, 1.0, 1.0)
    with pytest.raises(CurveReconError, match="unknown estimator"):
        reconstruct(sc.observations, estimator="bayes")


def test_pipeline_takes_the_basin_whose_marginal_optimum_is_highest():
    """Among fits about as good by chi2, the answer is the basin with the best marginal optimum.

    A headline-cell scene of the benchmark (1 px, 1 deg, 20 frames, phi near 15 degrees, so a
    frame's other branch sees nearly the mirror shape) with two such fits.  With one branch per
    frame, F at the two fits' maximum-likelihood points preferred the wrong one (alpha 4
    standard deviations off) and at their marginal optima the truth's.  Checked against the
    simulator's truth and against the mixture F (each frame's two branches) computed directly
    (``_f_mixture``: finite-difference pose Hessians) at every alternative's optimum.
    """
    from bench.common import make, true_poses
    from bench.config import full
    from curverecon.pipeline import reconstruct
    from curverecon.robust.branches import second_branches

    cfg = full()
    sc = make(cfg.seed, "accuracy", (13, 196), 20, point_sigma=1.0, tangent_sigma_deg=1.0)
    truth, truth_poses = true_poses(sc)
    meas = sc.observations.measurements()
    ml = reconstruct(sc.observations, estimator="ml")
    rec = reconstruct(sc.observations)
    assert rec.estimator == "marginal" and ml.alternatives
    sd = crlb(truth, truth_poses, 1.0, TS)
    z = np.abs(_errors(rec.shape, truth)) / (sd / np.array([truth[0], 1.0, 1.0, 1.0]))
    assert np.all(z < 2.0), z
    kappa = ml.chi2 / (sc.observations.n_frames - 4)

    def second(shape, poses):  # each frame's other branch, as the pipeline takes it
        fit = refine(sc.observations, shape, poses, 1.0, TS, max_iter=0, covariance=False)
        return second_branches(sc.observations, fit, W8, kappa, BranchOptions())

    f_answer = _f_mixture(rec.shape, rec.poses, second(rec.shape, rec.poses), meas, kappa)
    for alt in ml.alternatives:
        opt = refine_marginal(
            meas, alt.shape, alt.poses, 1.0, TS, ml.chi2, second(alt.shape, alt.poses)
        )
        if opt is not None and np.max(np.abs(_errors(opt.shape, rec.shape))) > 1e-3:
            assert f_answer < _f_mixture(opt.shape, opt.poses, opt.other_poses, meas, kappa)
