"""The lean polynomial and (12') against noise-free frames built here with NumPy.

Frames: one random shape per test, per frame R = R_y(tau) R_x(delta) (both signs of tau),
c' = x of R B, d' = -c' u_y/u_x and e' = c' u_y/u_x from the projected tangent directions.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy as sp

from derivations import lean, squaring
from derivations import symbols as s


def frames(seed: int, n: int = 40) -> tuple[tuple[float, float, float, float], np.ndarray]:
    """(c, tan alpha, tan beta, phi) and an (n, 3) array of noise-free (c', d', e')."""
    rng = np.random.default_rng(seed)
    c = rng.uniform(40, 250)
    alpha, beta = np.radians(rng.uniform(10, 80, 2))
    phi = np.radians(rng.uniform(-170, 170))
    rows = []
    while len(rows) < n:
        delta = np.radians(rng.uniform(-180, 180))
        tau = np.radians(rng.uniform(5, 80)) * (1 if len(rows) % 2 else -1)
        cd, sd, ct, st = np.cos(delta), np.sin(delta), np.cos(tau), np.sin(tau)
        r = np.array([[ct, 0, st], [0, 1, 0], [-st, 0, ct]]) @ np.array(
            [[1, 0, 0], [0, cd, -sd], [0, sd, cd]]
        )
        t_b = r @ np.array([-np.cos(alpha), np.sin(alpha), 0])
        t_a = r @ np.array([np.cos(beta), np.sin(beta) * np.cos(phi), np.sin(beta) * np.sin(phi)])
        if min(abs(t_a[0]), abs(t_b[0])) < 1e-2:
            continue
        cp = (r @ np.array([c, 0, 0]))[0]
        rows.append((cp, -cp * t_b[1] / t_b[0], cp * t_a[1] / t_a[0]))
    return (c, np.tan(alpha), np.tan(beta), phi), np.array(rows)


def relative_value(poly: object, values: list[float]) -> float:
    """|poly| / sum |terms| at ``values`` (mpmath 40 digits; inputs are float64)."""
    return lean.evaluate_relative(poly, values, dps=40)  # type: ignore[arg-type]


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_lean_vanishes_on_true_frames_only(seed: int) -> None:
    (c, ta, tb, phi), obs = frames(seed)
    poly = lean.lean_polynomial()
    true = [relative_value(poly, [c, ta, tb, np.cos(phi), *o]) for o in obs]
    assert max(true) < 1e-12
    wrong_c = [relative_value(poly, [1.02 * c, ta, tb, np.cos(phi), *o]) for o in obs]
    wrong_phi = [relative_value(poly, [c, ta, tb, np.cos(phi + 0.05), *o]) for o in obs]
    assert np.median(wrong_c) > 1e-6
    assert np.median(wrong_phi) > 1e-6


def test_reduced_12p_vanishes_on_true_frames_only() -> None:
    (c, ta, tb, phi), obs = frames(4, n=6)
    poly = squaring.reduced_polynomial()
    true = [relative_value(poly, [c, ta, tb, np.tan(phi), *o]) for o in obs]
    assert max(true) < 1e-12
    wrong = [relative_value(poly, [c, 1.05 * ta, tb, np.tan(phi), *o]) for o in obs]
    assert np.median(wrong) > 1e-6
    # tan(phi) cannot tell phi from phi + pi: the other branch vanishes too
    other = [relative_value(poly, [c, ta, tb, np.tan(phi + np.pi), *o]) for o in obs]
    assert max(other) < 1e-12


def test_raw_12p_vanishes_on_true_frames() -> None:
    """Exact rational frames (both signs of tau), evaluated modulo 2**61 - 1."""
    (c, ta, tb, cph, sph), obs = lean.rational_frames(3, seed=21)
    raw = squaring.raw_polynomial()
    assert all(lean.eval_mod_p(raw, (c, ta, tb, sph / cph) + o) == 0 for o in obs)
    assert all(lean.eval_mod_p(raw, (c + 1, ta, tb, sph / cph) + o) != 0 for o in obs)


def test_lean_depends_on_cos_phi_only_and_mirror() -> None:
    """The mirror (phi -> -phi) cannot be seen: the lean polynomial has no sin(phi)."""
    names = tuple(str(g) for g in lean.lean_polynomial().ring.symbols)
    assert names == ("c", "tan_alpha", "tan_beta", "cos_phi", "cp", "dp", "ep")


def test_lean_and_12p_relation() -> None:
    """raw (12') = c^k X L(cos phi) L(-cos phi) (1 + tan^2 phi)^4, X free of the angles."""
    quotient, factors = squaring.extraneous_factor()  # asserts an exact division
    for m in quotient.itermonoms():
        assert m[1:4] == (0, 0, 0)
    # the extraneous factors never vanish for c > c' > 0
    for f, _ in factors:
        fn = sp.lambdify((s.c, s.cp, s.dp, s.ep), f)
        (_, _, _, _), obs = frames(6, n=5)
        for o in obs:
            assert abs(fn(200.0, *o)) > 0
    # and only the factor L(cos phi) vanishes on the true frames
    (c, ta, tb, phi), obs = frames(7, n=10)
    poly = lean.lean_polynomial()
    mirror = [relative_value(poly, [c, ta, tb, -np.cos(phi), *o]) for o in obs]
    assert np.median(mirror) > 1e-6


def test_sizes() -> None:
    f = lean.lean_facts()
    assert (f["terms"], f["unknown_monomials"], f["columns"]) == (221, 57, 39)
    g = squaring.squaring_facts()
    assert g["raw"]["terms"] == 52208  # type: ignore[index]
    assert g["raw"]["unknown_monomials"] == 1014  # type: ignore[index]
    assert (g["terms"], g["columns"]) == (4048, 205)


def test_lean_null_space_dimension_is_one() -> None:
    cols, rank = lean.rank_mod_p(lean.lean_polynomial(), lean.UNKNOWN_IDX, lean.OBSERVABLE_IDX,
                                 n_frames=50, seed=11)  # fmt: skip
    assert cols - rank == 1
    assert lean.lean_facts()["null_space_dimension"] == 1


def test_lean_null_space_float_frames_mpmath() -> None:
    """SVD of the grouped frame matrix of NumPy-built noise-free frames, 30 digits."""
    poly = lean.lean_polynomial()
    keys = sorted(lean.group_terms(poly, lean.UNKNOWN_IDX, lean.OBSERVABLE_IDX))
    (c, _, _, _), obs = frames(8, n=50)
    with mpmath.workdps(30):
        m = lean.frame_matrix(lean.group_terms(poly, lean.UNKNOWN_IDX, lean.OBSERVABLE_IDX),
                              obs, c)  # fmt: skip
        sv = sorted(mpmath.svd_r(m, compute_uv=False), reverse=True)
        rel = [float(v / sv[0]) for v in sv]
    assert len(keys) == 39
    assert rel[-1] < 1e-6 * rel[-2]  # one singular value far below the others
    assert rel[-2] > 1e-14


def test_12p_grouped_null_space_is_39() -> None:
    cols, rank = lean.rank_mod_p(squaring.reduced_polynomial(), squaring.UNKNOWN_IDX,
                                 squaring.OBSERVABLE_IDX, n_frames=230, seed=12)  # fmt: skip
    assert (cols, cols - rank) == (205, 39)


def test_grouped_columns_reassemble_the_polynomial() -> None:
    rec = lean.grouped_columns()
    assert rec.unknowns == s.LEAN_UNKNOWNS and rec.observables == s.OBSERVABLES
    assert [k for k, _ in rec.columns] == sorted(k for k, _ in rec.columns)
    total = sum(s.cp**i * s.dp**j * s.ep**k * u for (i, j, k), u in rec.columns)
    assert sp.expand(total - lean.lean_expr()) == 0
    rec2 = squaring.grouped_columns()
    assert rec2.unknowns == s.SQUARED_UNKNOWNS and len(rec2.columns) == 205
    (c, ta, tb, phi), obs = frames(9, n=3)
    f = sp.lambdify(s.SQUARED_UNKNOWNS, [u for _, u in rec2.columns])
    u = np.array(f(c, ta, tb, np.tan(phi)), dtype=float)
    for o in obs:
        row = np.array([o[0] ** i * o[1] ** j * o[2] ** k for (i, j, k), _ in rec2.columns])
        assert abs(row @ u) / np.sum(np.abs(row * u)) < 1e-9


def test_shape_from_null_vector() -> None:
    (c, ta, tb, phi), obs = frames(10, n=80)
    poly = lean.lean_polynomial()
    cols = lean.column_values(poly, (c, ta, tb, np.cos(phi)))
    got = lean.shape_from_null_vector({k: -2.5 * v for k, v in cols.items()})
    assert np.allclose(got, (c, ta, tb, np.cos(phi)), rtol=1e-8)
    # from the SVD null vector of the noise-free frames
    keys = sorted(cols)
    mat = np.array([[(o[0] / c) ** i * (o[1] / c) ** j * (o[2] / c) ** k for i, j, k in keys]
                    for o in obs])  # fmt: skip
    nrm = np.linalg.norm(mat, axis=0)
    vec = np.linalg.svd(mat / nrm)[2][-1] / nrm
    got = lean.shape_from_null_vector({k: vec[n] * c ** (-sum(k)) for n, k in enumerate(keys)})
    assert np.allclose(got, (c, ta, tb, np.cos(phi)), rtol=1e-3)


def test_monomial_columns() -> None:
    mono = lean.lean_facts()["monomial_columns"]
    assert [m[2] for m in mono] == [(8, 4, 4, 4), (8, 4, 4, 2), (8, 4, 4, 2), (8, 4, 4, 4)]
