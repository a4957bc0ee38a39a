"""The lean elimination of delta and tau (NOTES item 4): one squaring instead of the paper's two.

Derivation (conventions of ``docs/CONVENTIONS.md``; lengths in input units):

1. (10) and (11) are linear in (cos(delta), sin(delta)):
   q1 cos(delta) + p1 sin(delta) = d'c',  a cos(delta) + b sin(delta) = e'c',
   a = q2 cos(phi) - p2 sin(phi), b = -q2 sin(phi) - p2 cos(phi).
2. Cramer's rule and cos^2 + sin^2 = 1 give, with r_k^2 = p_k^2 + q_k^2 and
   K = cos(phi)(q1 q2 - p1 p2) - sin(phi)(p1 q2 + q1 p2) = r1 r2 cos(phi + omega1 + omega2),
   (K - d'e'c'^2)^2 - (r1^2 - d'^2 c'^2)(r2^2 - e'^2 c'^2) = 0,
   which is the branch-free (12*) times r1^2 r2^2 (``section3.residual_12_expr``).
3. Every p_k carries one sin(tau); sin(tau)^2 = (c^2 - c'^2)/c^2 (4') and
   sin(phi)^2 = 1 - cos(phi)^2 leave E + sin(phi) sin(tau) O = 0 with E, O free of both sines
   (the mirror (phi, tau) -> (-phi, -tau) leaves the equation unchanged, so sin(phi) and sin(tau)
   only occur together).
4. Squaring once: c^2 E^2 - (1 - cos(phi)^2)(c^2 - c'^2) O^2 = 0.  It has the factor c^10, which
   does not vanish (c > 0) and is divided out.  What remains is irreducible over the rationals
   (``sympy`` factor_list) and depends on cos(phi) only.

The polynomial is homogeneous in the lengths (c, c', d', e').
"""

from __future__ import annotations

import random
from collections import defaultdict
from fractions import Fraction
from functools import cache

import mpmath
import numpy as np
import sympy as sp
from sympy import ZZ
from sympy.polys.rings import PolyElement, ring

from derivations import symbols as s
from derivations.codegen.spec import PolynomialColumns

# ------------------------------------------------------------------------------------------
# sparse-polynomial helpers (also used by derivations.squaring)
# ------------------------------------------------------------------------------------------


def reduce_square(poly: PolyElement, index: int, num: PolyElement, den: PolyElement) -> PolyElement:
    """Replace x**2 by num/den in ``poly`` (x = generator ``index``) and clear the denominator.

    Every x**(2k + r) (r in {0, 1}) becomes x**r num**k den**(K - k), K the largest k: the result
    is ``poly`` times den**K with x of degree at most 1.
    """
    rng = poly.ring
    terms = poly.terms()
    kmax = max(m[index] // 2 for m, _ in terms)
    out = rng.zero
    powers: dict[int, PolyElement] = {}
    for m, co in terms:
        k, r = divmod(m[index], 2)
        mm = list(m)
        mm[index] = r
        if k not in powers:
            powers[k] = num**k * den ** (kmax - k)
        out += rng({tuple(mm): co}) * powers[k]
    return out


def split_odd(poly: PolyElement, indices: tuple[int, ...]) -> tuple[PolyElement, PolyElement]:
    """poly = even + prod(x_i) * odd, for generators x_i (i in ``indices``) of degree <= 1.

    Raises ``ValueError`` when a term has some but not all of the x_i.
    """
    rng = poly.ring
    even: dict[tuple[int, ...], object] = {}
    odd: dict[tuple[int, ...], object] = {}
    for m, co in poly.terms():
        flags = {m[i] for i in indices}
        if len(flags) != 1 or max(flags) > 1:
            raise ValueError("poly is not of the form even + product * odd")
        mm = list(m)
        for i in indices:
            mm[i] = 0
        (odd if flags == {1} else even)[tuple(mm)] = co
    return rng(even), rng(odd)


def strip_monomial_content(poly: PolyElement) -> tuple[PolyElement, tuple[int, ...]]:
    """Divide ``poly`` by the largest monomial dividing all its terms: (quotient, exponents)."""
    terms = poly.terms()
    mins = tuple(min(m[i] for m, _ in terms) for i in range(poly.ring.ngens))
    out = poly.ring({tuple(a - b for a, b in zip(m, mins, strict=True)): co for m, co in terms})
    return out, mins


def sizes(
    poly: PolyElement, unknown_idx: tuple[int, ...], observable_idx: tuple[int, ...]
) -> dict[str, object]:
    """Degrees and term counts of ``poly`` (total, in the unknowns, in the observables)."""
    ngens = poly.ring.ngens
    deg = [0] * ngens
    total = du = do = 0
    unk: set[tuple[int, ...]] = set()
    obs: set[tuple[int, ...]] = set()
    for m in poly.itermonoms():
        total = max(total, sum(m))
        du = max(du, sum(m[i] for i in unknown_idx))
        do = max(do, sum(m[i] for i in observable_idx))
        deg = [max(a, b) for a, b in zip(deg, m, strict=True)]
        unk.add(tuple(m[i] for i in unknown_idx))
        obs.add(tuple(m[i] for i in observable_idx))
    return {
        "terms": len(poly),
        "total_degree": total,
        "degree_in_unknowns": du,
        "degree_in_observables": do,
        "degrees": {str(g): deg[k] for k, g in enumerate(poly.ring.gens)},
        "unknown_monomials": len(unk),
        "observable_monomials": len(obs),
    }


def group_terms(
    poly: PolyElement, unknown_idx: tuple[int, ...], observable_idx: tuple[int, ...]
) -> dict[tuple[int, ...], dict[tuple[int, ...], int]]:
    """{observable exponents: {unknown exponents: integer coefficient}}."""
    groups: dict[tuple[int, ...], dict[tuple[int, ...], int]] = defaultdict(dict)
    for m, co in poly.terms():
        groups[tuple(m[i] for i in observable_idx)][tuple(m[i] for i in unknown_idx)] = int(co)
    return dict(groups)


def group_columns(
    poly: PolyElement,
    unknown_idx: tuple[int, ...],
    observable_idx: tuple[int, ...],
    unknowns: tuple[sp.Symbol, ...],
) -> tuple[tuple[tuple[int, int, int], sp.Expr], ...]:
    """Group ``poly`` by its monomial in the observables; columns sorted by exponent tuple.

    Each column's unknown part goes through a ring in ``unknowns`` (fixed symbol order) and
    ``as_expr``, so the SymPy expression is deterministic.
    """
    uring = ring(list(unknowns), ZZ)[0]
    groups = group_terms(poly, unknown_idx, observable_idx)
    return tuple((k, uring(groups[k]).as_expr()) for k in sorted(groups))  # type: ignore[misc]


def monomial_columns(
    groups: dict[tuple[int, ...], dict[tuple[int, ...], int]],
) -> tuple[tuple[int, int, tuple[int, ...]], ...]:
    """(column, coefficient, unknown exponents) of the columns whose unknown part is a monomial."""
    keys = sorted(groups)
    out = []
    for k, key in enumerate(keys):
        g = groups[key]
        if len(g) == 1:
            ((e, co),) = g.items()
            out.append((k, co, e))
    return tuple(out)


# ------------------------------------------------------------------------------------------
# the lean polynomial
# ------------------------------------------------------------------------------------------

# working ring: sin(phi) and sin(tau) are eliminated; the final ring drops them
_W, _c, _ta, _tb, _cph, _sph, _st, _cp, _dp, _ep = ring(
    "c tan_alpha tan_beta cos_phi sin_phi sin_tau cp dp ep", ZZ
)
LEAN_RING, *_ = ring("c tan_alpha tan_beta cos_phi cp dp ep", ZZ)
UNKNOWN_IDX = (0, 1, 2, 3)
OBSERVABLE_IDX = (4, 5, 6)


def residual_12_numerator() -> PolyElement:
    """(12*) times r1^2 r2^2 in the working ring (step 2 of the module docstring)."""
    p1 = _dp * _c * _ta * _st
    q1 = _cp * _c * _ta
    p2 = _ep * _c * _tb * _st
    q2 = _cp * _c * _tb
    k = _cph * (q1 * q2 - p1 * p2) - _sph * (p1 * q2 + q1 * p2)
    dc = _dp * _cp
    ec = _ep * _cp
    return (k - dc * ec) ** 2 - (p1**2 + q1**2 - dc**2) * (p2**2 + q2**2 - ec**2)


@cache
def unsquared_parts() -> tuple[PolyElement, PolyElement]:
    """(E, O) of step 3: (12*) r1^2 r2^2 c^2K = E + sin(phi) sin(tau) O, in the working ring.

    Neither contains sin(phi) or sin(tau); the minimal solver's system (``derivations.minimal``)
    keeps this unsquared form, with sin(phi) sin(tau) as an unknown of its own.
    """
    num = residual_12_numerator()
    # step 3: sin(phi)^2 = 1 - cos(phi)^2; sin(tau)^2 = (c^2 - c'^2)/c^2 (times c^2 per power)
    num = reduce_square(num, 4, 1 - _cph**2, _W.one)
    num = reduce_square(num, 5, _c**2 - _cp**2, _c**2)
    return split_odd(num, (4, 5))  # num = even + sin(phi) sin(tau) odd


@cache
def lean_polynomial() -> PolyElement:
    """The lean polynomial in (c, tan_alpha, tan_beta, cos_phi, cp, dp, ep) (steps 3 and 4)."""
    even, odd = unsquared_parts()
    # step 4: even^2 = sin(phi)^2 sin(tau)^2 odd^2, times c^2
    sq = _c**2 * even**2 - (1 - _cph**2) * (_c**2 - _cp**2) * odd**2
    sq, content = strip_monomial_content(sq)
    assert content == (10, 0, 0, 0, 0, 0, 0, 0, 0), content  # the factor c^10 (c > 0)
    # drop the sine slots (they no longer occur)
    return LEAN_RING({m[:4] + m[6:]: co for m, co in sq.terms()})


def lean_expr() -> sp.Expr:
    """The lean polynomial as a SymPy expression in symbols.c, tan_alpha, ..., cp, dp, ep."""
    syms = s.LEAN_UNKNOWNS + s.OBSERVABLES
    return lean_polynomial().as_expr(*syms)


@cache
def is_irreducible() -> bool:
    """True when the lean polynomial is irreducible over the rationals (sympy factor_list)."""
    _, factors = lean_polynomial().factor_list()
    return len(factors) == 1 and factors[0][1] == 1


# ------------------------------------------------------------------------------------------
# numeric checks on noise-free frames
# ------------------------------------------------------------------------------------------


def true_frames(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Shape and noise-free observables of ``n`` frames: ((c, ta, tb, phi), (n, 3) of (cp, dp, ep)).

    The shape is drawn once (c in [50, 200], alpha, beta in [10, 80] deg, phi in (-180, 180)
    deg); per frame delta in (-180, 180) deg and |tau| in [5, 80] deg with alternating sign.
    Observables follow the construction: c' = c cos(tau), d', e' from
    ``section3.predicted_exprs``.
    """
    rng = np.random.default_rng(seed)
    deg = np.pi / 180
    c = rng.uniform(50, 200)
    ta = np.tan(rng.uniform(10, 80) * deg)
    tb = np.tan(rng.uniform(10, 80) * deg)
    phi = rng.uniform(-180, 180) * deg
    delta = rng.uniform(-180, 180, n) * deg
    tau = rng.uniform(5, 80, n) * deg * np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    st = np.sin(tau)
    cp = c * np.cos(tau)
    dp = cp * c * ta * np.cos(delta) / (cp - c * ta * st * np.sin(delta))
    dph = delta + phi
    ep = cp * c * tb * np.cos(dph) / (cp + c * tb * st * np.sin(dph))
    return np.array([c, ta, tb, phi]), np.column_stack([cp, dp, ep])


def evaluate_relative(poly: PolyElement, values: list[float], dps: int = 50) -> float:
    """|poly(values)| / sum |terms| at ``values`` (mpmath, ``dps`` digits)."""
    with mpmath.workdps(dps):
        tables = _power_tables(poly, [mpmath.mpf(v) for v in values], lambda a, b: a * b)
        tot = mpmath.mpf(0)
        mag = mpmath.mpf(0)
        for m, co in poly.terms():
            t = mpmath.mpf(int(co))
            for row, e in zip(tables, m, strict=True):
                if e:
                    t *= row[e]
            tot += t
            mag += abs(t)
        return float(abs(tot) / mag)


def frame_matrix(
    groups: dict[tuple[int, ...], dict[tuple[int, ...], int]], obs: np.ndarray, scale: float
) -> mpmath.matrix:
    """Rows: frames; columns: observable monomials (sorted), of observables / ``scale``."""
    keys = sorted(groups)
    m = mpmath.matrix(len(obs), len(keys))
    for i, (a, b, d) in enumerate(obs):
        x = [
            mpmath.mpf(float(a)) / scale,
            mpmath.mpf(float(b)) / scale,
            mpmath.mpf(float(d)) / scale,
        ]
        for k, (i1, i2, i3) in enumerate(keys):
            m[i, k] = x[0] ** i1 * x[1] ** i2 * x[2] ** i3
    return m


def singular_values(
    poly: PolyElement,
    observable_idx: tuple[int, ...],
    unknown_idx: tuple[int, ...],
    n_frames: int,
    seed: int,
    dps: int = 40,
) -> list[float]:
    """Singular values (descending, relative to the largest) of the frame matrix, mpmath.

    Observables are divided by the shape's c, which leaves the null space's dimension unchanged
    (each column is multiplied by a constant) and balances the columns.
    """
    groups = group_terms(poly, unknown_idx, observable_idx)
    shape, obs = true_frames(n_frames, seed)
    with mpmath.workdps(dps):
        m = frame_matrix(groups, obs, float(shape[0]))
        # column-normalise: does not change the rank
        for k in range(m.cols):
            nrm = mpmath.sqrt(sum(m[i, k] ** 2 for i in range(m.rows)))
            for i in range(m.rows):
                m[i, k] /= nrm
        sv = mpmath.svd_r(m, compute_uv=False)
        vals = sorted((sv[i] for i in range(len(sv))), reverse=True)
        return [float(v / vals[0]) for v in vals]


def null_space_dimension(sv: list[float], tol: float = 1e-18) -> int:
    """Number of relative singular values below ``tol`` (noise-free frames, 30-digit arithmetic)."""
    return sum(1 for v in sv if v < tol)


def rational_frames(
    n: int, seed: int
) -> tuple[tuple[Fraction, ...], list[tuple[Fraction, Fraction, Fraction]]]:
    """Exact noise-free frames: rational shape and pose, rational (c', d', e').

    cos/sin pairs come from the half-angle parametrisation ((1 - t^2)/(1 + t^2), 2t/(1 + t^2)),
    t rational; cos(tau) > 0 and sin(tau) of either sign.  Returns ((c, tan alpha, tan beta,
    cos phi, sin phi), [(c', d', e')]).
    """
    rnd = random.Random(seed)

    def cos_sin() -> tuple[Fraction, Fraction]:
        t = Fraction(rnd.randint(-60, 60), rnd.randint(1, 60))
        return (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)

    c = Fraction(rnd.randint(50, 200))
    ta = Fraction(rnd.randint(1, 40), rnd.randint(1, 40))
    tb = Fraction(rnd.randint(1, 40), rnd.randint(1, 40))
    cph, sph = cos_sin()
    frames = []
    while len(frames) < n:
        ct, st = cos_sin()
        st = abs(st) if len(frames) % 2 == 0 else -abs(st)  # both signs of sin(tau)
        cd, sd = cos_sin()
        cdp, sdp = cd * cph - sd * sph, sd * cph + cd * sph  # cos, sin of delta + phi
        cp = c * abs(ct)
        den_d = cp - c * ta * st * sd
        den_e = cp + c * tb * st * sdp
        if ct == 0 or den_d == 0 or den_e == 0:
            continue
        frames.append((cp, cp * c * ta * cd / den_d, cp * c * tb * cdp / den_e))
    return (c, ta, tb, cph, sph), frames


def rank_mod_p(
    poly: PolyElement,
    unknown_idx: tuple[int, ...],
    observable_idx: tuple[int, ...],
    n_frames: int,
    seed: int,
    prime: int = 2**31 - 1,
) -> tuple[int, int]:
    """(columns, rank) of the grouped frame matrix of exact frames, reduced modulo ``prime``.

    The rows are the observable monomials of :func:`rational_frames`; reduction mod p is a ring
    homomorphism, so the rank over GF(p) is a lower bound of the rank over the rationals and
    ``columns - rank`` an upper bound of the null-space dimension.  The true unknown columns
    lie in the null space, so a bound of 1 makes the dimension exactly 1.
    """
    keys = sorted(group_terms(poly, unknown_idx, observable_idx))
    _, frames = rational_frames(n_frames, seed)

    def mod(x: Fraction) -> int:
        return x.numerator % prime * pow(x.denominator % prime, -1, prime) % prime

    mat = np.empty((len(frames), len(keys)), dtype=np.int64)
    for r, frame in enumerate(frames):
        a, b, d = (mod(x) for x in frame)
        mat[r] = [
            pow(a, i, prime) * pow(b, j, prime) * pow(d, k, prime) % prime for i, j, k in keys
        ]
    return len(keys), _rank_mod(mat, prime)


def _rank_mod(mat: np.ndarray, prime: int) -> int:
    """Rank of an integer matrix over GF(prime), prime < 2**31 (Gaussian elimination, int64)."""
    a = mat % prime
    rank = 0
    rows, cols = a.shape
    for col in range(cols):
        nz = np.nonzero(a[rank:, col])[0]
        if nz.size == 0:
            continue
        piv = rank + int(nz[0])
        a[[rank, piv]] = a[[piv, rank]]
        inv = pow(int(a[rank, col]), -1, prime)
        a[rank] = a[rank] * inv % prime
        others = np.nonzero(a[:, col])[0]
        others = others[others != rank]
        if others.size:
            a[others] = (a[others] - np.outer(a[others, col], a[rank]) % prime) % prime
        rank += 1
        if rank == rows:
            break
    return rank


def shape_from_null_vector(v: dict[tuple[int, int, int], float]) -> tuple[float, ...]:
    """(c, tan alpha, tan beta, cos phi) from a null vector of the lean frame matrix (any scale).

    ``v`` maps the observable exponents (i, j, k) of cp**i dp**j ep**k to the null vector's
    entry.  With k = cos(phi)^2 and lambda the unknown scale, the columns used are
    (4,0,4): lambda c^8 ta^4 tb^4 k^2,  (4,1,3): 4 lambda c^8 ta^4 tb^4 k   -> k = 4 v404 / v413;
    (6,0,4): -2 lambda c^6 k ta^4 tb^2 (k tb^2 + 1),
    (8,0,2): -2 lambda c^6 ta^4 tb^2 (k - 1)(k tb^2 - 1)   -> with w = c^2 tb^2, z = tb^2:
    R1 = v604/v404 = -2 (k z + 1)/(k w), R2 = v802/v404 = -2 (k - 1)(k z - 1)/(k^2 w), so
    w = -4 / (k (R1 - R2 k/(k - 1))) and z = (-R1 k w/2 - 1)/k;
    the same with (4,4,0), (6,4,0), (8,2,0) gives tan(alpha)^2 and c^2 again;
    (8,1,1): -4 lambda c^6 ta^3 tb^3 (k - 1)(cos phi + ta tb) gives cos(phi) with its sign.
    tan(alpha), tan(beta) > 0 (the normalisation alpha, beta in [0, 90] deg).  Degenerate for
    cos(phi) in {0, +1, -1}.
    """

    def tan2_and_c2(mono: float, r1: float, r2: float, k: float) -> tuple[float, float]:
        rr1, rr2 = r1 / mono, r2 / mono
        w = -4.0 / (k * (rr1 - rr2 * k / (k - 1.0)))
        z = (-rr1 * k * w / 2.0 - 1.0) / k
        return z, w / z

    k = 4.0 * v[(4, 0, 4)] / v[(4, 1, 3)]
    tb2, c2_b = tan2_and_c2(v[(4, 0, 4)], v[(6, 0, 4)], v[(8, 0, 2)], k)
    ta2, c2_a = tan2_and_c2(v[(4, 4, 0)], v[(6, 4, 0)], v[(8, 2, 0)], k)
    c2 = 0.5 * (c2_a + c2_b)
    ta, tb = float(np.sqrt(ta2)), float(np.sqrt(tb2))
    ratio = v[(8, 1, 1)] / v[(4, 0, 4)]  # -4 (k - 1)(cos phi + ta tb) / (c^2 ta tb k^2)
    cos_phi = -ratio * c2 * ta * tb * k * k / (4.0 * (k - 1.0)) - ta * tb
    return float(np.sqrt(c2)), ta, tb, float(cos_phi)


def _power_tables(poly: PolyElement, values: list, mul) -> list[list]:  # type: ignore[type-arg]
    """powers[i][e] = values[i]**e for e up to poly's degree in generator i."""
    tables = []
    for i, v in enumerate(values):
        row = [type(v)(1)]
        for _ in range(poly.degree(i)):
            row.append(mul(row[-1], v))
        tables.append(row)
    return tables


def eval_exact(poly: PolyElement, values: tuple[Fraction, ...]) -> Fraction:
    """poly at rational ``values`` (one per generator), exactly."""
    tables = _power_tables(poly, list(values), lambda a, b: a * b)
    total = Fraction(0)
    for m, co in poly.terms():
        term = Fraction(int(co))
        for row, e in zip(tables, m, strict=True):
            if e:
                term *= row[e]
        total += term
    return total


def eval_mod_p(poly: PolyElement, values: tuple[Fraction, ...], prime: int = 2**61 - 1) -> int:
    """poly at rational ``values`` reduced modulo ``prime`` (a nonzero result proves poly != 0)."""
    vals = [v.numerator % prime * pow(v.denominator % prime, -1, prime) % prime for v in values]
    tables = _power_tables(poly, vals, lambda a, b: a * b % prime)
    total = 0
    for m, co in poly.terms():
        term = int(co)
        for row, e in zip(tables, m, strict=True):
            if e:
                term = term * row[e] % prime
        total += term
    return total % prime


@cache
def exact_checks(n_frames: int = 12, seed: int = 5) -> dict[str, object]:
    """Exact evaluation of the lean polynomial at rational noise-free frames (both signs of tau).

    ``zero_at_truth``: number of frames where L(true shape) == 0 exactly; ``nonzero_*``: number
    of frames where L does not vanish at a perturbed shape (c + 1, tan alpha * 11/10, or the
    other branch cos(phi) -> -cos(phi)).
    """
    (c, ta, tb, cph, _), frames = rational_frames(n_frames, seed)
    poly = lean_polynomial()
    out: dict[str, object] = {"frames": len(frames)}
    variants = {
        "zero_at_truth": (c, ta, tb, cph),
        "nonzero_c_plus_1": (c + 1, ta, tb, cph),
        "nonzero_tan_alpha_times_1.1": (c, ta * Fraction(11, 10), tb, cph),
        "nonzero_other_branch_cos_phi": (c, ta, tb, -cph),
    }
    for key, shape in variants.items():
        vals = [eval_exact(poly, shape + f) for f in frames]
        out[key] = sum(1 for v in vals if (v == 0) == key.startswith("zero"))
    return out


def column_values(
    poly: PolyElement,
    shape: tuple[float, ...],
    unknown_idx: tuple[int, ...] = UNKNOWN_IDX,
    observable_idx: tuple[int, ...] = OBSERVABLE_IDX,
) -> dict[tuple[int, ...], float]:
    """The grouped unknown columns u_k at ``shape`` (floats), keyed by observable exponents."""
    groups = group_terms(poly, unknown_idx, observable_idx)
    out = {}
    for key, g in groups.items():
        out[key] = float(
            sum(co * np.prod([x**e for x, e in zip(shape, m, strict=True)]) for m, co in g.items())
        )
    return out


@cache
def recovery_checks() -> dict[str, float]:
    """Max relative error of :func:`shape_from_null_vector` (a) on exact columns at 20 seeded
    shapes (times a random scale), (b) on the float64 SVD null vector of 80 noise-free frames."""
    poly = lean_polynomial()
    rng = np.random.default_rng(99)
    worst_exact = 0.0
    for _ in range(20):
        deg = np.pi / 180
        shape = (
            rng.uniform(50, 200),
            np.tan(rng.uniform(10, 80) * deg),
            np.tan(rng.uniform(10, 80) * deg),
            np.cos(rng.uniform(10, 170) * deg),
        )
        scale = rng.uniform(-2, 2)
        cols = {k: v * scale for k, v in column_values(poly, shape).items()}
        got = shape_from_null_vector(cols)
        worst_exact = max(
            worst_exact, max(abs(g - w) / abs(w) for g, w in zip(got, shape, strict=True))
        )
    keys = sorted(group_terms(poly, UNKNOWN_IDX, OBSERVABLE_IDX))
    truth, obs = true_frames(80, 11)
    sc = truth[0]
    mat = np.array(
        [[(o[0] / sc) ** i * (o[1] / sc) ** j * (o[2] / sc) ** k for i, j, k in keys] for o in obs]
    )
    nrm = np.linalg.norm(mat, axis=0)
    vt = np.linalg.svd(mat / nrm)[2]
    vec = vt[-1] / nrm
    got = shape_from_null_vector({k: vec[n] * sc ** (-sum(k)) for n, k in enumerate(keys)})
    want = (truth[0], truth[1], truth[2], np.cos(truth[3]))
    worst_svd = max(abs(g - w) / abs(w) for g, w in zip(got, want, strict=True))
    return {"exact_columns": float(worst_exact), "svd_noise_free_80_frames": float(worst_svd)}


@cache
def lean_facts() -> dict[str, object]:
    """Sizes, irreducibility, null-space dimension and vanishing checks for the report."""
    poly = lean_polynomial()
    facts: dict[str, object] = sizes(poly, UNKNOWN_IDX, OBSERVABLE_IDX)
    facts["irreducible"] = is_irreducible()
    facts["divided_out"] = "c**10"
    groups = group_terms(poly, UNKNOWN_IDX, OBSERVABLE_IDX)
    facts["columns"] = len(groups)
    facts["monomial_columns"] = monomial_columns(groups)
    sv = singular_values(poly, OBSERVABLE_IDX, UNKNOWN_IDX, n_frames=45, seed=7, dps=30)
    facts["null_space_dimension"] = null_space_dimension(sv)
    # bounds only (the float inputs may differ in the last bit between NumPy builds)
    facts["svd_smallest_below_1e-18"] = sv[-1] < 1e-18
    facts["svd_second_smallest_above_1e-16"] = sv[-2] > 1e-16
    cols, rank = rank_mod_p(poly, UNKNOWN_IDX, OBSERVABLE_IDX, n_frames=60, seed=3)
    facts["rank_mod_p"] = (cols, rank)
    facts["null_space_dimension_exact"] = cols - rank
    facts["exact_checks"] = exact_checks()
    rec = recovery_checks()
    facts["ratio_recovery_exact_columns_below_1e-9"] = rec["exact_columns"] < 1e-9
    facts["ratio_recovery_svd_80_frames_below_1e-4"] = rec["svd_noise_free_80_frames"] < 1e-4
    return facts


def grouped_columns() -> PolynomialColumns:
    """The lean polynomial grouped by observable monomial (cp**i dp**j ep**k), for codegen."""
    poly = lean_polynomial()
    cols = group_columns(poly, UNKNOWN_IDX, OBSERVABLE_IDX, s.LEAN_UNKNOWNS)
    return PolynomialColumns(
        name="lean_polynomial",
        unknowns=s.LEAN_UNKNOWNS,
        observables=s.OBSERVABLES,
        columns=cols,
        doc=(
            "Lean elimination of delta and tau (NOTES item 4): (10), (11) solved for cos(delta), "
            "sin(delta), cos^2 + sin^2 = 1, squared once to remove sin(phi) sin(tau), the factor "
            "c**10 divided out.  Vanishes on noise-free frames for both signs of tau; depends on "
            "cos(phi) only.  Lengths in input units."
        ),
        facts=dict(lean_facts()),
    )
