"""The minimal problem: four frames of the lean polynomial, every solution (issue 12).

Four frames give four lean equations (``derivations.lean``, NOTES item 4) in the four unknowns
(c, tan(alpha), tan(beta), cos(phi)).  This module turns them into the system the runtime's
minimal solver tracks, and solves its start system once, here, by monodromy.

Reduction (each step a fact checked below, on the lean polynomial's terms):

1. c occurs in even powers only, so C = c^2 is the unknown (c > 0 is recovered as sqrt(C)).
2. In every term the exponents of a = tan(alpha), b = tan(beta), p = cos(phi) are all even or
   all odd.  So (a, b, p) -> (-a, -b, p) and (a, b, p) -> (-a, b, -p) map solutions to
   solutions: orbits of four.  With A = a^2, B = b^2, P = p^2 and m = a b p, a term is
   A^i B^j P^k or m A^i B^j P^k, and each frame's equation reads F0(C, A, B, P) + m F1 = 0.
   Adding m^2 - A B P = 0 gives a system in (C, A, B, P, m) whose solutions are the orbits.
   Geometrically an orbit is one curve (checked on the construction by
   ``derivations.minimal_count``): (a, -b, -p) is (tan beta, phi) -> (-tan beta, phi + pi),
   the same tangent line; (-a, b, -p) is the curve turned by pi about AB; so a real orbit has
   exactly one member with a, b > 0, one candidate shape.  The mirror image (phi, delta, tau)
   -> (-phi, -delta, -tau) leaves a, b and cos(phi) unchanged: it is the same solution.
3. Lengths are homogeneous (degree 16 in c, c', d', e'), so the runtime divides all of them by
   one length before solving; C is then dimensionless.

The start system: random complex parameters (cp_i, dp_i, ep_i) for the four frames (seeded).
One solution is made by construction (random complex C, A, B, P, m = sqrt(A B P); then each
frame's cp_i, dp_i random and ep_i a root of that frame's equation, a quartic in ep_i).
Monodromy then loops the parameters around random triangles, tracking every known solution with
the runtime's own tracker (``curverecon.solvers.homotopy``); endpoints not seen before are added
until the count reaches the independent Groebner-basis count of ``derivations.minimal_count``
(msolve) and one more loop adds nothing, or, without that tool, until ``STABLE_LOOPS`` loops
add nothing.  The facts record whether the two counts agree.
Every solution is then polished by Newton's method in mpmath at 30 digits and printed to 17,
so the emitted data are the same on every machine.
"""

from __future__ import annotations

from functools import cache
from types import SimpleNamespace

import mpmath
import numpy as np
import sympy as sp

from derivations import lean
from derivations.codegen.generate import system_terms
from derivations.codegen.spec import PolynomialSystem

FRAMES = 4
SEED = 2026_11_25
STABLE_LOOPS = 3
MAX_LOOPS = 60
POLISH_DPS = 30

C, A, B, P, M = sp.symbols("C A B P m")
UNKNOWNS = (C, A, B, P, M)
PARAMETERS = tuple(sp.Symbol(f"{name}{i}") for i in range(FRAMES) for name in ("cp", "dp", "ep"))


def reduced_term(
    exponents: tuple[int, ...],
) -> tuple[int, int, int, int, int]:
    """Exponents of (C, A, B, P, m) for a lean term c^i a^j b^k p^l (step 1 and 2)."""
    i, j, k, n = exponents
    if i % 2:
        raise ValueError("odd power of c in the lean polynomial")
    parity = {j % 2, k % 2, n % 2}
    if len(parity) != 1:
        raise ValueError("mixed parity of tan(alpha), tan(beta), cos(phi) exponents")
    odd = parity.pop()
    return (i // 2, (j - odd) // 2, (k - odd) // 2, (n - odd) // 2, odd)


@cache
def frame_equation() -> sp.Expr:
    """The lean polynomial of one frame in (C, A, B, P, m) and symbols cp, dp, ep."""
    cp, dp, ep = sp.symbols("cp dp ep")
    expr = sp.Integer(0)
    for mono, coeff in lean.lean_polynomial().terms():
        red = reduced_term(mono[:4])
        o = mono[4:]
        expr += (
            int(coeff)
            * C ** red[0]
            * A ** red[1]
            * B ** red[2]
            * P ** red[3]
            * M ** red[4]
            * cp ** o[0]
            * dp ** o[1]
            * ep ** o[2]
        )
    return expr


def equations() -> tuple[sp.Expr, ...]:
    """Four frame equations (parameters cp_i, dp_i, ep_i) and m^2 - A B P."""
    cp, dp, ep = sp.symbols("cp dp ep")
    base = frame_equation()
    pa = PARAMETERS
    eqs = [base.subs({cp: pa[3 * i], dp: pa[3 * i + 1], ep: pa[3 * i + 2]}) for i in range(FRAMES)]
    eqs.append(M**2 - A * B * P)
    return tuple(eqs)


def _tables(eqs: tuple[sp.Expr, ...]) -> SimpleNamespace:
    """The generated module's tables, built here the same way (for monodromy before emitting)."""
    umons, pmons, terms = system_terms(eqs, UNKNOWNS, PARAMETERS)
    return SimpleNamespace(
        UNKNOWNS=tuple(s.name for s in UNKNOWNS),
        PARAMETERS=tuple(s.name for s in PARAMETERS),
        EQUATIONS=tuple(range(len(eqs))),
        UNKNOWN_EXPONENTS=np.array(umons, dtype=np.int64),
        PARAMETER_EXPONENTS=np.array(pmons, dtype=np.int64),
        TERMS=np.array([t[:3] for t in terms], dtype=np.int64),
        COEFFICIENTS=np.array([t[3] for t in terms], dtype=np.float64),
        START_PARAMETERS=np.zeros(len(PARAMETERS), complex),
        START_SOLUTIONS=np.zeros((1, 5), complex),
    )


def _round(z: complex, digits: int = 15) -> complex:
    """A complex number rounded to ``digits`` significant digits (a short exact decimal)."""
    return complex(float(f"{z.real:.{digits}g}"), float(f"{z.imag:.{digits}g}"))


def _first_solution(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Parameters q0 and one solution x0 there, by construction (module docstring)."""
    cp, dp, ep = sp.symbols("cp dp ep")
    base = frame_equation()

    def crandn(*shape: int) -> np.ndarray:
        return (rng.normal(size=shape) + 1j * rng.normal(size=shape)) / np.sqrt(2)

    x = crandn(4) + np.array([1.5, 1.0, 1.0, 0.5])
    x0 = np.array([x[0], x[1], x[2], x[3], np.sqrt(x[1] * x[2] * x[3])])
    x0 = np.array([_round(z) for z in x0])
    subs = dict(zip(UNKNOWNS, (sp.Float(0) + sp.sympify(complex(z)) for z in x0), strict=True))
    q = []
    for _ in range(FRAMES):
        cpv, dpv = (_round(z) for z in crandn(2) + 1.0)
        quartic = sp.Poly(sp.expand(base.subs(subs).subs({cp: complex(cpv), dp: complex(dpv)})), ep)
        roots = np.roots([complex(c) for c in quartic.all_coeffs()])
        q += [cpv, dpv, _round(roots[np.argmin(np.abs(roots - 1.0))])]
    return np.array(q), x0


def _newton_float(sys_, x: np.ndarray, q: np.ndarray, iters: int = 8) -> np.ndarray:
    for _ in range(iters):
        f, jac = sys_.evaluate(x, q)
        x = x - np.linalg.solve(jac, f)
    return x


def _new_points(known: np.ndarray, pts: np.ndarray, tol: float = 1e-6) -> np.ndarray:
    """Rows of ``pts`` (finite) not within ``tol`` (relative) of a known row or of each other."""
    out: list[np.ndarray] = []
    for p in pts:
        if not np.all(np.isfinite(p)):
            continue
        ref = np.vstack([known.reshape(-1, pts.shape[1]), np.array(out).reshape(-1, pts.shape[1])])
        if ref.size:
            d = np.linalg.norm(ref - p, axis=1) / (1 + np.linalg.norm(p))
            if d.min() < tol:
                continue
        out.append(p)
    return np.array(out).reshape(-1, known.shape[1] if known.size else pts.shape[1])


def monodromy(seed: int = SEED) -> tuple[np.ndarray, np.ndarray, dict[str, object]]:
    """Every solution of the start system: (q0, solutions, facts)."""
    from curverecon.solvers import homotopy

    rng = np.random.default_rng(seed)
    tables = _tables(equations())
    sys_ = homotopy.PolynomialSystem.from_module(tables)
    q0, x0 = _first_solution(rng)
    x0 = _newton_float(sys_, x0, q0)
    sols = x0[None, :]
    stable = 0
    loops = 0
    opts = homotopy.HomotopyOptions(max_step=0.1, predictor_tolerance=1e-4)
    expected = _expected_count()
    while loops < MAX_LOOPS and stable < (1 if len(sols) == expected else STABLE_LOOPS):
        loops += 1
        q1 = q0 + (rng.normal(size=q0.shape) + 1j * rng.normal(size=q0.shape))
        q2 = q0 + (rng.normal(size=q0.shape) + 1j * rng.normal(size=q0.shape))
        x = sols
        ok = np.ones(len(x), bool)
        for qa, qb in ((q0, q1), (q1, q2), (q2, q0)):
            x, st, _ = homotopy.track_once(sys_, qa, qb, x, None, opts)
            ok &= st == homotopy.OK
        new = _new_points(sols, x[ok])
        if len(new):
            sols = np.vstack([sols, new])
            stable = 0
        else:
            stable += 1
    facts = {
        "monodromy_loops": loops,
        "monodromy_count_equals_msolve": len(sols) == expected if expected else None,
    }
    return q0, sols, facts


def _expected_count() -> int | None:
    """The reduced system's solution count from msolve (derivations.minimal_count), if installed."""
    from derivations import minimal_count

    try:
        return int(minimal_count.minimal_facts()["orbits"])  # type: ignore[index]
    except (ImportError, minimal_count.MsolveMissingError):
        return None


def _mp_system(eqs: tuple[sp.Expr, ...], q0: np.ndarray):  # type: ignore[no-untyped-def]
    """F and its Jacobian in mpmath at the start parameters (exact binary values of q0)."""
    subs = {
        p: sp.Float(z.real, 40) + sp.I * sp.Float(z.imag, 40)
        for p, z in zip(PARAMETERS, q0, strict=True)
    }
    polys = [sp.Poly(sp.expand(e.subs(subs)), *UNKNOWNS) for e in eqs]
    mp_terms = [
        [(m, mpmath.mpc(str(sp.re(c).evalf(40)), str(sp.im(c).evalf(40)))) for m, c in p.terms()]
        for p in polys
    ]

    def evaluate(x: list) -> tuple[list, list]:
        pw = [[mpmath.mpc(1)] for _ in x]
        for v, xv in enumerate(x):
            for _ in range(8):
                pw[v].append(pw[v][-1] * xv)
        f, jac = [], []
        for ts in mp_terms:
            fv = mpmath.mpc(0)
            row = [mpmath.mpc(0)] * len(x)
            for m, c in ts:
                val = c
                for v, e in enumerate(m):
                    val *= pw[v][e]
                fv += val
                for v, e in enumerate(m):
                    if e:
                        d = c * e
                        for w, e2 in enumerate(m):
                            d *= pw[w][e2 - 1] if w == v else pw[w][e2]
                        row[v] += d
            f.append(fv)
            jac.append(row)
        return f, jac

    return evaluate


def polish(eqs: tuple[sp.Expr, ...], q0: np.ndarray, sols: np.ndarray) -> np.ndarray:
    """Newton's method at POLISH_DPS digits; rows sorted by (Re, Im) of each unknown."""
    evaluate = _mp_system(eqs, q0)
    out = []
    with mpmath.workdps(POLISH_DPS):
        for row in sols:
            x = [mpmath.mpc(complex(z)) for z in row]
            for _ in range(3):
                f, jac = evaluate(x)
                dx = mpmath.lu_solve(mpmath.matrix(jac), mpmath.matrix(f))
                x = [xi - dx[i] for i, xi in enumerate(x)]
            out.append([complex(float(z.real), float(z.imag)) for z in x])
    arr = np.array(out)
    # sort by Re C, then Im C, Re A, ... (rounded, so that rounding noise cannot reorder rows)
    order = np.lexsort(
        [np.round(arr[:, k].imag, 9) for k in range(4, -1, -1)]
        + [np.round(arr[:, k].real, 9) for k in range(4, -1, -1)]
    )
    return arr[order]


@cache
def minimal_system() -> PolynomialSystem:
    """The four-frame minimal problem with its start system solved (module docstring)."""
    eqs = equations()
    q0, sols, facts = monodromy()
    sols = polish(eqs, q0, sols)
    n_terms = len(lean.lean_polynomial().terms())
    facts = dict(facts)
    facts.update(
        {
            "solutions": len(sols),
            "solutions_original_variables": 4 * len(sols),
            "frames": FRAMES,
            "lean_terms_per_frame": n_terms,
            "seed": SEED,
        }
    )
    return PolynomialSystem(
        name="minimal_lean",
        unknowns=UNKNOWNS,
        parameters=PARAMETERS,
        equations=eqs,
        equation_names=tuple(f"lean polynomial, frame {i}" for i in range(FRAMES))
        + ("m**2 - A*B*P",),
        start_parameters=tuple(complex(z) for z in q0),
        start_solutions=tuple(tuple(complex(z) for z in row) for row in sols),
        doc=(
            "The four-frame minimal problem of the lean polynomial (issue 12), reduced by its "
            "symmetry: unknowns C = c^2, A = tan(alpha)^2, B = tan(beta)^2, P = cos(phi)^2, "
            "m = tan(alpha) tan(beta) cos(phi) (one unknown vector per orbit of four solutions "
            "in (tan alpha, tan beta, cos phi)); parameters (cp, dp, ep) of each frame, all "
            "lengths divided by one common length.  START_SOLUTIONS are every solution at "
            "START_PARAMETERS, found by monodromy; curverecon.solvers.homotopy tracks them to "
            "any frames' parameters."
        ),
        facts=facts,
    )
