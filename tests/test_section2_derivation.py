"""The Section 2 derivation (derivations/section2.py): counts, closed forms and the construction.

msolve's counts (``section2.facts``) are checked by an independent route on random *complex*
instances: the closed forms (resultants in SymPy, numpy roots) give every solution, each is
verified on the row's equations and they are distinct; their number must equal msolve's.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp

pytest.importorskip("sympy")
from derivations import section2 as s2  # noqa: E402


def _complex_values(symbols: list, seed: int) -> dict:
    rng = np.random.default_rng(seed)
    return {x: complex(*rng.normal(size=2)) for x in symbols}


def _distinct(solutions: list[np.ndarray]) -> int:
    kept: list[np.ndarray] = []
    for x in solutions:
        if all(np.abs(x - y).max() > 1e-6 * (1 + np.abs(x).max()) for y in kept):
            kept.append(x)
    return len(kept)


def _verified(unknowns: list, eqs: list, values: dict, candidates: list[np.ndarray]) -> list:
    f = sp.lambdify(unknowns, [e.xreplace(values) for e in eqs], "numpy")
    return [x for x in candidates if np.abs(np.array(f(*x), complex)).max() < 1e-7]


def _flat(pairs: list) -> list:
    return [x for pair in pairs for x in pair]


def test_fixed_axis_count_on_a_random_complex_instance() -> None:
    z, v, eqs = s2.fixed_axis_system(4)
    values = _complex_values(_flat(v), 3)
    cof, k = s2.fixed_axis_cofactors(v)
    subs = dict(zip(sp.symbols("C1:4", real=True), cof, strict=True))
    subs.update(zip(sp.symbols("k1:4", real=True), k, strict=True))
    coeffs = [
        complex(c.xreplace(subs).xreplace(values)) for c in s2.fixed_axis_cubic_in_cofactors()
    ]
    kk = np.array([complex(x.xreplace(values)) for x in k])
    candidates = []
    for w in np.roots(coeffs):
        for signs in itertools.product((1, -1), repeat=4):
            r = np.sqrt(w + np.concatenate([[0], kk]))
            candidates.append(np.array(signs) * r)
    found = _distinct(_verified(z, eqs, values, candidates))
    assert found == s2.facts()["fixed_axis"]["random"][0] == 6


def test_free_3pt_count_on_a_random_complex_instance() -> None:
    unknowns, data, eqs = s2.free_3pt_system(3)
    values = _complex_values(_flat(data), 4)
    q = s2.free_3pt_quadratic()
    num = [complex(sp.sympify(x).xreplace(values)) for x in q["quadratic"]]
    pm, p0, qm, q0, det = (complex(sp.sympify(x).xreplace(values)) for x in q["linear"])
    abc = np.array([complex(sp.sympify(x).xreplace(values)) for x in q["abc"]])
    candidates = []
    for m in np.roots(num):
        p = (pm * m + p0) / det
        for signs in itertools.product((1, -1), repeat=3):
            z = np.array(signs) * np.sqrt(p + np.concatenate([[0], abc[0:2]]))
            e = (m + np.concatenate([[0], abc[4:6]])) / z
            candidates.append(np.concatenate([z, e]))
    found = _distinct(_verified(unknowns, eqs, values, candidates))
    assert found == s2.facts()["free_3pt"]["random"][0] == 16


def test_uniform_rotation_count_on_a_random_complex_instance() -> None:
    """Equally spaced times: eliminate z2 (linear in the equal-steps equation) and z1 by a
    resultant; the roots in z0 with their back-substitutions are every solution."""
    z, v, eqs = s2.uniform_rotation_system(3)
    rng = np.random.default_rng(5)
    pairs = rng.integers(-9, 10, (6, 2))
    values = {x: int(a) + sp.I * int(b) for x, (a, b) in zip(_flat(v), pairs, strict=True)}
    e1, e2, e3 = (e.xreplace(values) for e in eqs)
    slope = sp.diff(e3, z[2])  # e3 is linear in z2
    r = sp.resultant(sp.resultant(e2, e3, z[2]), e1, z[1])
    roots = np.roots([complex(c) for c in sp.Poly(sp.expand(r), z[0]).all_coeffs()])
    candidates = []
    for z0 in roots:
        for s in (1, -1):
            z1 = s * np.sqrt(complex(sp.sympify(e1 - z[1] ** 2).xreplace({z[0]: z0})) * -1)
            at = {z[0]: z0, z[1]: z1, z[2]: 0}
            z2 = -complex(e3.xreplace(at)) / complex(slope.xreplace(at))
            candidates.append(np.array([z0, z1, z2]))
    found = _distinct(_verified(z, eqs, values, candidates))
    assert found == s2.facts()["uniform_rotation"]["random"][0] == 4


def test_force_field_count_on_another_random_instance() -> None:
    """msolve at a third random instance (the report used two others): 778 again."""
    got = s2.count_force_field(s2.force_field_random_frames(9, 7))
    assert got.dimension == 0
    assert got.degree == s2.force_field_facts()["random"][0] == 778


def test_equations_vanish_at_the_3d_construction() -> None:
    assert max(s2.checks().values()) < 1e-10
    closed = s2.closed_form_checks()
    assert closed["fixed_axis_cubic"][0] < 1e-10  # median; the max is the cubic's cancellation
    assert closed["fixed_axis_cubic"][1] < 1e-4
    assert closed["free_3pt_quadratic"][1] < 1e-8
    assert closed["uniform_rotation_angles"][1] < 1e-10


def test_force_field_needs_nine_frames() -> None:
    ranks = s2.force_field_jacobian_ranks()
    assert ranks[8][0] == 8 and ranks[9][0] == 9


def test_uniqueness_and_degenerate_axes() -> None:
    facts = s2.facts()
    assert facts["fixed_axis"]["noise_free_one_more"] == 2  # the mirror pair
    assert facts["uniform_rotation"]["noise_free_one_more"] == 2
    assert facts["free_3pt"]["noise_free_one_more"] == 16  # per-frame flips of 4 frames
    assert all(f["below_dimension"] == 1 for f in facts.values())
    deg = s2.degenerate_axes()
    assert deg["fixed_axis"] == {"along the viewing direction": 1, "in the image plane": 1}
    assert deg["uniform_rotation"]["in the image plane"] == 0


def test_generated_closed_forms_match_sympy() -> None:
    """generated/section2_minimal.py evaluates the derivation's expressions (real data)."""
    from curverecon.generated import section2_minimal as gen

    rng = np.random.default_rng(6)
    v4 = s2.v_symbols(4)
    data = rng.normal(size=8)
    values = dict(zip(_flat(v4), data, strict=True))
    cof, k = s2.fixed_axis_cofactors(v4)
    subs = dict(zip(sp.symbols("C1:4", real=True), cof, strict=True))
    subs.update(zip(sp.symbols("k1:4", real=True), k, strict=True))
    want = [float(c.xreplace(subs).xreplace(values)) for c in s2.fixed_axis_cubic_in_cofactors()]
    got, _, _ = gen.fixed_axis_cubic(*data)
    assert np.allclose(got, want, rtol=1e-12, atol=0)
