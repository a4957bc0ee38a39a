"""The global start: (10) solved per frame, the pose-free cost, and the search without truth."""

from __future__ import annotations

import numpy as np
from curverecon.generated import frame_equations
from test_conventions import canonical_parameters

from curverecon.robust.search import (
    branch_candidates,
    frame_terms,
    poses_from_branches,
    reduced_cost,
    robust_start,
)
from curverecon.simulate import make_scene


def test_branches_solve_equation_10():
    sc = make_scene(np.random.default_rng(51), 15)
    obs = sc.observations
    t = frame_terms(obs)
    c, ta = sc.truth.c * 1.1, np.tan(sc.truth.alpha)
    cos_d, sin_d, s, r_b = branch_candidates(t["cp"], t["ub"], np.array(c), np.array(ta))
    feasible = r_b == 0
    assert feasible.any()
    delta = np.arctan2(sin_d, cos_d)
    r10 = frame_equations.residual_10(c, ta, obs.cp[:, None], obs.dp[:, None], delta, s)
    scale = np.abs(obs.dp * obs.cp)[:, None] + obs.cp[:, None] * c * ta
    assert np.max(np.abs(r10[feasible]) / np.broadcast_to(scale, r10.shape)[feasible]) < 1e-9
    # sign of sin(tau): two candidates each
    assert np.all(s[:, :2] >= 0) and np.all(s[:, 2:] <= 0)


def test_reduced_cost_vanishes_at_the_truth_only():
    sc = make_scene(np.random.default_rng(52), 12)
    obs = sc.observations
    c, a, b, p = sc.truth.shape
    gamma = np.arccos(np.max(obs.cp) / c)
    x = np.array([[gamma, a, b, p], [gamma, a + 0.05, b, p], [gamma, a, b, p + 0.1]])
    cost = reduced_cost(frame_terms(obs), x, 1.0)
    assert cost[0] < 1e-20
    assert cost[1] > 1e-6 and cost[2] > 1e-6


def test_poses_from_branches_at_the_truth():
    sc = make_scene(np.random.default_rng(53), 10)
    shape, poses = canonical_parameters(sc.truth)
    from curverecon.model.pose import normalise

    shape_n, poses_n = normalise(shape, poses)
    p = poses_from_branches(sc.observations, shape_n)
    assert np.allclose(np.cos(p[:, 0]), np.cos(poses_n[:, 0]), atol=1e-7)
    assert np.allclose(p[:, 1], poses_n[:, 1], atol=1e-7)


def test_start_finds_the_noise_free_shape_without_truth():
    sc = make_scene(np.random.default_rng(54), 10)
    cands = robust_start(sc.observations)
    best = cands[0].result
    assert best.chi2 < 1e-12
    assert np.allclose(best.shape, sc.truth.shape, rtol=1e-8, atol=1e-8)


def test_start_with_noise_and_an_outlier_frame():
    sc = make_scene(np.random.default_rng(55), 20, 1.0, 1.0, outlier_fraction=0.05)
    cands = robust_start(sc.observations, 1.0, np.radians(1.0))
    err = np.degrees(np.abs(cands[0].result.shape[1:] - sc.truth.shape[1:]))
    assert np.max(err) < 5.0
    assert abs(cands[0].result.shape[0] / sc.truth.c - 1) < 0.05
