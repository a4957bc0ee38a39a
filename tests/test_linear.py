"""The paper's linearisation grouped by observable monomials: rank, minimum frames, exactness."""

from __future__ import annotations

import numpy as np
import pytest
from curverecon.generated import lean_polynomial

from curverecon.errors import CurveReconError
from curverecon.simulate import make_scene
from curverecon.solvers.linear import frame_matrix, min_frames, n_columns, solve_linear


def test_minimum_frames_is_columns_minus_one():
    assert n_columns() == len(lean_polynomial.OBSERVABLE_EXPONENTS)
    assert min_frames() == n_columns() - 1


def test_rank_on_noise_free_frames():
    """One-dimensional null space: rank K - 1; the true unknown columns span it."""
    sc = make_scene(np.random.default_rng(11), 60)
    m, scale = frame_matrix(sc.observations)
    norms = np.linalg.norm(m, axis=0)
    _, sv, vt = np.linalg.svd(m / norms)
    assert sv[-1] / sv[0] < 1e-13  # a null vector...
    assert sv[-2] / sv[0] > 1e3 * sv[-1] / sv[0]  # ... and only one
    c, a, b, p = sc.truth.shape
    u = lean_polynomial.unknown_columns(c / scale, np.tan(a), np.tan(b), np.cos(p)) * norms
    cosang = abs(vt[-1] @ u) / np.linalg.norm(u)
    assert cosang > 1 - 1e-10


def test_fewer_frames_leave_a_larger_null_space():
    sc = make_scene(np.random.default_rng(12), min_frames() - 3)
    m, _ = frame_matrix(sc.observations)
    assert np.linalg.matrix_rank(m / np.linalg.norm(m, axis=0)) <= m.shape[0] < n_columns() - 1


@pytest.mark.parametrize("seed", [0, 2, 4])
def test_exact_from_the_minimum_number_of_frames(seed):
    sc = make_scene(np.random.default_rng(seed), min_frames())
    res = solve_linear(sc.observations)
    truth = sc.truth.shape
    err = np.abs(res.shape - truth) / np.array([truth[0], 1, 1, 1])
    assert np.max(err) < 1e-9, err


def test_exact_with_more_frames():
    sc = make_scene(np.random.default_rng(21), 80)
    res = solve_linear(sc.observations)
    truth = sc.truth.shape
    assert np.max(np.abs(res.shape - truth) / np.array([truth[0], 1, 1, 1])) < 1e-9


def test_too_few_frames_is_a_clear_error():
    sc = make_scene(np.random.default_rng(13), 20)
    with pytest.raises(CurveReconError, match="at least 38 frames"):
        solve_linear(sc.observations)
