"""(12'): the paper's "tangentialising and squaring twice", with sparse polynomial arithmetic.

Derivation (conventions of ``docs/CONVENTIONS.md``; lengths in input units):

1. tan^2 of (12): with a_k = arccos(u_k), s_k = tan^2(a_k) and y = tan^2(phi + omega1 + omega2),
   y = tan^2(a2 -/+ a1).  Clearing (1 -/+ t1 t2)^2 and isolating the sign,
   y (1 + s1 s2) - s1 - s2 = +/- 2 t1 t2 (1 + y); squaring gives (12'):
   (y (1 + s1 s2) - s1 - s2)^2 - 4 s1 s2 (1 + y)^2 = 0 (the paper's expanded form).
2. s_k = A_k / D_k: A1 = (d'^2 + c'^2) c^2 tan^2(alpha) - d'^2 c'^2 (tan^2(alpha) + 1),
   D1 = d'^2 c'^2 (likewise A2, D2 with e', beta); y = P/Q with P = (N tan(phi) + M)^2,
   Q = (N - M tan(phi))^2, N = c^2 c'^2 - d'e' c^2 + d'e' c'^2, M = sin(tau)(d' + e') c^2 c'
   (N, M of ``section3.tan_sum_parts`` times c^2 c'^2).  Multiplying (12') by (D1 D2 Q)^2:
   G = (P (D1 D2 + A1 A2) - Q (A1 D2 + A2 D1))^2 - 4 A1 A2 D1 D2 (P + Q)^2 = 0.
3. G is polynomial in sin(tau); sin(tau)^2 = (c^2 - c'^2)/c^2 (times c^2 per power) leaves
   G = E + sin(tau) O, the paper's "polynomial1 = polynomial2 sqrt(1 - c'^2/c^2)".  Squaring:
   H = c^2 E^2 - (c^2 - c'^2) O^2 = 0 (the "raw" twice-squared polynomial).
4. Extraneous factors: H = c^10 X L(cos phi) L(-cos phi) (1 + tan^2 phi)^4 with cos(phi)^2 =
   1/(1 + tan(phi)^2), L the lean polynomial (``derivations.lean``) and X a polynomial in
   (c, c', d', e') alone, checked by exact division (remainder 0).  X is a product of
   (c^2 c'^2 + d'^2 (c^2 - c'^2)) and (c^2 c'^2 + e'^2 (c^2 - c'^2)) powers (positive for c > c'),
   which do not vanish; c^10 does not vanish either.  L(-cos phi) is the other branch
   (phi -> phi + pi, which tan(phi) cannot tell apart): it does not vanish on true frames.
   The reduced (12') is therefore L(cos phi) L(-cos phi) (1 + tan^2 phi)^4, in
   (c, tan alpha, tan beta, tan phi).
"""

from __future__ import annotations

from functools import cache

import sympy as sp
from sympy import ZZ
from sympy.polys.rings import PolyElement, ring

from derivations import lean
from derivations import symbols as s
from derivations.codegen.spec import PolynomialColumns

# working ring with sin(tau); the final ring drops it
_W, _c, _ta, _tb, _tph, _st, _cp, _dp, _ep = ring(
    "c tan_alpha tan_beta tan_phi sin_tau cp dp ep", ZZ
)
SQ_RING, *_ = ring("c tan_alpha tan_beta tan_phi cp dp ep", ZZ)
UNKNOWN_IDX = (0, 1, 2, 3)
OBSERVABLE_IDX = (4, 5, 6)


def s_parts() -> tuple[PolyElement, PolyElement, PolyElement, PolyElement]:
    """(A1, D1, A2, D2) with s1 = A1/D1, s2 = A2/D2 (step 2)."""
    a1 = (_dp**2 + _cp**2) * _c**2 * _ta**2 - _dp**2 * _cp**2 * (_ta**2 + 1)
    a2 = (_ep**2 + _cp**2) * _c**2 * _tb**2 - _ep**2 * _cp**2 * (_tb**2 + 1)
    return a1, _dp**2 * _cp**2, a2, _ep**2 * _cp**2


def y_parts() -> tuple[PolyElement, PolyElement]:
    """(P, Q) with y = P/Q (step 2)."""
    n = _c**2 * _cp**2 - _dp * _ep * _c**2 + _dp * _ep * _cp**2
    m = _st * (_dp + _ep) * _c**2 * _cp
    return (n * _tph + m) ** 2, (n - m * _tph) ** 2


def once_squared() -> PolyElement:
    """G = (12') times (D1 D2 Q)^2 (step 2), still containing sin(tau)."""
    a1, d1, a2, d2 = s_parts()
    p, q = y_parts()
    x = p * (d1 * d2 + a1 * a2) - q * (a1 * d2 + a2 * d1)
    return x**2 - 4 * a1 * a2 * d1 * d2 * (p + q) ** 2


@cache
def raw_polynomial() -> PolyElement:
    """H of step 3 in (c, tan_alpha, tan_beta, tan_phi, cp, dp, ep) (no factor removed)."""
    g = once_squared()
    g = lean.reduce_square(g, 4, _c**2 - _cp**2, _c**2)  # sin(tau)^2 = (c^2 - c'^2)/c^2
    even, odd = lean.split_odd(g, (4,))  # polynomial1 + sqrt(1 - c'^2/c^2) polynomial2
    h = _c**2 * even**2 - (_c**2 - _cp**2) * odd**2
    return SQ_RING({m[:4] + m[5:]: co for m, co in h.terms()})


@cache
def raw_stripped() -> tuple[PolyElement, tuple[int, ...]]:
    """H divided by its monomial content (a power of c only, asserted): (quotient, exponents)."""
    h, content = lean.strip_monomial_content(raw_polynomial())
    assert content[1:] == (0,) * 6, content
    return h, content


@cache
def lean_product() -> PolyElement:
    """L(cos phi) L(-cos phi) (1 + tan(phi)^2)^4 with cos(phi)^2 = 1/(1 + tan(phi)^2).

    L(cos phi) L(-cos phi) is even in cos(phi) (degree 8); each cos(phi)^(2k) becomes
    (1 + tan(phi)^2)^(4 - k) after multiplying by (1 + tan(phi)^2)^4.
    """
    poly = lean.lean_polynomial()
    mirrored = poly.ring({m: co * (-1) ** m[3] for m, co in poly.terms()})
    prod = poly * mirrored
    kmax = prod.degree(3) // 2
    by_k: dict[int, dict[tuple[int, ...], int]] = {}
    for m, co in prod.terms():
        k, r = divmod(m[3], 2)
        assert r == 0  # even in cos(phi)
        by_k.setdefault(k, {})[m[:3] + (0,) + m[4:]] = co
    one_plus = SQ_RING.one + SQ_RING.gens[3] ** 2
    out = SQ_RING.zero
    for k in sorted(by_k):
        out += SQ_RING(by_k[k]) * one_plus ** (kmax - k)
    return out


@cache
def extraneous_factor() -> tuple[PolyElement, tuple[tuple[sp.Expr, int], ...]]:
    """X = H / (c^10 lean_product()), exact (asserted), and its factorisation (factor, power)."""
    h, content = raw_stripped()
    q, r = h.div(lean_product())
    assert r == 0, "the lean product does not divide the raw (12')"
    unk = {m[:4] for m, _ in q.terms()}
    assert unk == {(m[0], 0, 0, 0) for m in unk}, "extraneous factor depends on the angles"
    const, factors = q.factor_list()
    syms = s.SQUARED_UNKNOWNS + s.OBSERVABLES
    out = [(sp.Integer(int(const)), 1)] if const != 1 else []
    out += [(f.as_expr(*syms), e) for f, e in factors]
    return q, tuple(out)


def reduced_polynomial() -> PolyElement:
    """(12') with the extraneous factors removed: ``lean_product()`` (see step 4)."""
    return lean_product()


@cache
def exact_checks(n_frames: int = 6, seed: int = 5) -> dict[str, int]:
    """Exact evaluation at rational noise-free frames (both signs of tau), tan(phi) = sin/cos.

    Counts frames where the reduced (12') vanishes at the true shape and where it does not vanish
    at a perturbed shape (c + 1), evaluated exactly modulo 2**61 - 1 (a nonzero residue proves
    non-vanishing; vanishing follows exactly from reduced = L(cos phi) L(-cos phi) (...)^4 and
    the exact zeros of L, ``lean.exact_checks``).  The raw H is c^10 X times the reduced one
    (exact division), so it vanishes wherever the reduced one does.
    """
    (c, ta, tb, cph, sph), frames = lean.rational_frames(n_frames, seed)
    tph = sph / cph
    red = reduced_polynomial()
    truth, bad = (c, ta, tb, tph), (c + 1, ta, tb, tph)
    return {
        "frames": len(frames),
        "reduced_zero_at_truth": sum(lean.eval_mod_p(red, truth + f) == 0 for f in frames),
        "reduced_nonzero_c_plus_1": sum(lean.eval_mod_p(red, bad + f) != 0 for f in frames),
    }


@cache
def squaring_facts() -> dict[str, object]:
    """Sizes of the raw and reduced (12'), the extraneous factors, for the report."""
    raw = raw_polynomial()
    facts: dict[str, object] = {
        "raw": lean.sizes(raw, UNKNOWN_IDX, OBSERVABLE_IDX),
        "raw_monomial_content": f"c**{raw_stripped()[1][0]}",
    }
    _, factors = extraneous_factor()
    facts["extraneous_factors"] = tuple((str(f), e) for f, e in factors)
    red = reduced_polynomial()
    facts.update(lean.sizes(red, UNKNOWN_IDX, OBSERVABLE_IDX))
    groups = lean.group_terms(red, UNKNOWN_IDX, OBSERVABLE_IDX)
    facts["columns"] = len(groups)
    facts["max_terms_per_column"] = max(len(g) for g in groups.values())
    facts["monomial_columns"] = lean.monomial_columns(groups)
    cols, rank = lean.rank_mod_p(red, UNKNOWN_IDX, OBSERVABLE_IDX, n_frames=240, seed=3)
    facts["rank_mod_p"] = (cols, rank)
    facts["null_space_dimension_exact"] = cols - rank
    facts["exact_checks"] = exact_checks()
    facts["relation_to_lean"] = (
        "raw (12') = c**10 * X * L(cos phi) * L(-cos phi) * (1 + tan(phi)**2)**4, "
        "cos(phi)**2 = 1/(1 + tan(phi)**2), X > 0 free of the angles; exact division"
    )
    return facts


def grouped_columns() -> PolynomialColumns:
    """Reduced (12') grouped by observable monomial, unknowns c, tan alpha, tan beta, tan phi."""
    red = reduced_polynomial()
    cols = lean.group_columns(red, UNKNOWN_IDX, OBSERVABLE_IDX, s.SQUARED_UNKNOWNS)
    return PolynomialColumns(
        name="polynomial_12p",
        unknowns=s.SQUARED_UNKNOWNS,
        observables=s.OBSERVABLES,
        columns=cols,
        doc=(
            "(12') of the paper (tangentialised, squared twice), extraneous factors removed: "
            "L(cos phi) L(-cos phi) (1 + tan(phi)**2)**4 with L the lean polynomial and "
            "cos(phi)**2 = 1/(1 + tan(phi)**2).  Vanishes on noise-free frames for both signs of "
            "tau; cannot tell phi from phi + pi.  Lengths in input units."
        ),
        facts=dict(squaring_facts()),
    )
