"""The minimal problem: four frames, every solution, as an unsquared system.

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
4. The system tracked is not the lean polynomial itself but its unsquared form.  The lean
   polynomial is c^2 E^2 - sin(phi)^2 sin(tau)^2 c^2 O^2 over c^10 (``lean.unsquared_parts``):
   a product (E~ - cp s O~)(E~ + cp s O~) with E = c^4 E~, O = c^6 a b cp O~ and
   s = C tan(alpha) tan(beta) sin(phi) sin(tau).  E~ and O~ are polynomials in
   (C, A, B, P, m) (their terms have the parity of step 2, checked below), so s_i =
   -E~_i / (cp_i O~_i) is unchanged by the sign moves of step 2 and each frame contributes an
   unknown s_i with

       E~_i + cp_i s_i O~_i = 0,    s_i^2 = C A B (1 - P)(C - cp_i^2)        (unsquared (12*))

   and the lean equation is their product (checked below: E~^2 - cp^2 s^2 O~^2 equals the
   reduced lean polynomial modulo m^2 - A B P).  A solution of the lean system fixes every s_i
   (s_i = -E~_i / (cp_i O~_i)), so the counts agree (104 = msolve's count; the facts record it).
   Why: the squared equation has a double root wherever s_i = 0, a near-double one where the
   curve is nearly flat (phi near 0 or 180 degrees) or AB nearly parallel to the image
   (c' near c), and there the lean system's Jacobian at the truth is singular to 1e-9 relative
   and paths merged or stalled.  The unsquared system is regular there (its derivative in s_i
   is cp_i O~_i): on fresh noise-free scenes it lists the truth where the lean system did not
   (docs/accuracy.md, "Four frames: the complete minimal solver").  Its equations are also of lower
   degree (C^2 and degree 1 in A, B, P, m, against C^4 A^2 B^2 P^2), so a step costs less.

The start system: random complex parameters (cp_i, dp_i, ep_i) for the four frames (seeded).
One solution is made by construction (random complex C, A, B, P, m = sqrt(A B P),
s_i = sqrt(C A B (1 - P)(C - cp_i^2)); then each frame's cp_i, dp_i random and ep_i a root of
that frame's first equation, a quadratic in ep_i).
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
S = tuple(sp.Symbol(f"s{i}") for i in range(FRAMES))
REDUCED = (C, A, B, P, M)
"""The lean system's unknowns after step 2 (one per orbit)."""
UNKNOWNS = REDUCED + S
"""The tracked system's unknowns (step 4): s_i = C tan(alpha) tan(beta) sin(phi) sin(tau_i)."""
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


def _reduce(poly, shift: tuple[int, int, int, int]) -> sp.Expr:  # type: ignore[no-untyped-def]
    """A working-ring polynomial divided by c^i a^j b^k cp^l (``shift``), in (C, A, B, P, m)
    and symbols cp, dp, ep (steps 1 and 2); raises if a term does not reduce."""
    cp, dp, ep = sp.symbols("cp dp ep")
    n = len(poly.ring.gens)
    expr = sp.Integer(0)
    for mono, coeff in poly.terms():
        # working ring of lean.unsquared_parts: (c, ta, tb, cos_phi, sin_phi, sin_tau, cp,
        # dp, ep); the lean ring drops the two sines
        unk, obs = mono[:4], mono[n - 3 :]
        unk = (unk[0] - shift[0], unk[1] - shift[1], unk[2] - shift[2], unk[3])
        obs = (obs[0] - shift[3], obs[1], obs[2])
        if min(unk) < 0 or min(obs) < 0:
            raise ValueError("the shift does not divide every term")
        red = reduced_term(unk)
        expr += (
            int(coeff)
            * C ** red[0]
            * A ** red[1]
            * B ** red[2]
            * P ** red[3]
            * M ** red[4]
            * cp ** obs[0]
            * dp ** obs[1]
            * ep ** obs[2]
        )
    return expr


@cache
def frame_equation() -> sp.Expr:
    """The lean polynomial of one frame in (C, A, B, P, m) and symbols cp, dp, ep."""
    return _reduce(lean.lean_polynomial(), (0, 0, 0, 0))


@cache
def frame_parts() -> tuple[sp.Expr, sp.Expr]:
    """(E~, O~) of step 4: E = c^4 E~ and O = c^6 tan(alpha) tan(beta) cp O~, reduced.

    The powers divided out are the monomial content of E and O (``lean.strip_monomial_content``
    finds exactly these, checked in ``unsquared_facts``).
    """
    even, odd = lean.unsquared_parts()
    return _reduce(even, (4, 0, 0, 0)), _reduce(odd, (6, 1, 1, 1))


def frame_system(i: int) -> tuple[sp.Expr, sp.Expr]:
    """Frame i's two equations of step 4 (unsquared (12*) and the definition of s_i)."""
    cp, dp, ep = sp.symbols("cp dp ep")
    e_t, o_t = frame_parts()
    pa = PARAMETERS[3 * i : 3 * i + 3]
    sub = {cp: pa[0], dp: pa[1], ep: pa[2]}
    unsquared = sp.expand((e_t + cp * S[i] * o_t).subs(sub))
    definition = sp.expand(S[i] ** 2 - C * A * B * (1 - P) * (C - pa[0] ** 2))
    return unsquared, definition


@cache
def unsquared_facts() -> dict[str, object]:
    """Checks of step 4 on the polynomials (exact, SymPy)."""
    cp = sp.Symbol("cp")
    even, odd = lean.unsquared_parts()
    e_t, o_t = frame_parts()
    s_sq = C * A * B * (1 - P) * (C - cp**2)
    product = sp.expand(e_t**2 - cp**2 * s_sq * o_t**2)
    # modulo m^2 - A B P: reduce every power of m above 1
    diff = sp.rem(sp.Poly(product - frame_equation(), M), sp.Poly(M**2 - A * B * P, M))
    return {
        "unsquared_content_E": lean.strip_monomial_content(even)[1][:4],
        "unsquared_content_O": lean.strip_monomial_content(odd)[1][:4]
        + lean.strip_monomial_content(odd)[1][6:7],
        "unsquared_product_is_lean": diff.is_zero,
        "unsquared_terms_E": len(sp.Add.make_args(e_t)),
        "unsquared_terms_O": len(sp.Add.make_args(o_t)),
    }


def equations() -> tuple[sp.Expr, ...]:
    """Step 4's system: per frame the unsquared (12*) (parameters cp_i, dp_i, ep_i), per frame
    the definition of s_i, and m^2 - A B P."""
    frames = [frame_system(i) for i in range(FRAMES)]
    eqs = [f[0] for f in frames] + [f[1] for f in frames]
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
        START_SOLUTIONS=np.zeros((1, len(UNKNOWNS)), complex),
    )


def _round(z: complex, digits: int = 15) -> complex:
    """A complex number rounded to ``digits`` significant digits (a short exact decimal)."""
    return complex(float(f"{z.real:.{digits}g}"), float(f"{z.imag:.{digits}g}"))


def _first_solution(rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """Parameters q0 and one solution x0 there, by construction (module docstring)."""
    cp, dp, ep = sp.symbols("cp dp ep")
    e_t, o_t = frame_parts()

    def crandn(*shape: int) -> np.ndarray:
        return (rng.normal(size=shape) + 1j * rng.normal(size=shape)) / np.sqrt(2)

    x = crandn(4) + np.array([1.5, 1.0, 1.0, 0.5])
    x0 = np.array([_round(z) for z in (x[0], x[1], x[2], x[3], np.sqrt(x[1] * x[2] * x[3]))])
    subs = dict(zip(REDUCED, (sp.Float(0) + sp.sympify(complex(z)) for z in x0), strict=True))
    q: list[complex] = []
    s_values: list[complex] = []
    for _ in range(FRAMES):
        cpv, dpv = (_round(z) for z in crandn(2) + 1.0)
        s_i = _round(np.sqrt(x0[0] * x0[1] * x0[2] * (1 - x0[3]) * (x0[0] - cpv**2)))
        unsquared = (e_t + cp * sp.sympify(s_i) * o_t).subs(subs)
        quadratic = sp.Poly(sp.expand(unsquared.subs({cp: cpv, dp: dpv})), ep)
        roots = np.roots([complex(c) for c in quadratic.all_coeffs()])
        q += [cpv, dpv, _round(roots[np.argmin(np.abs(roots - 1.0))])]
        s_values.append(s_i)
    return np.array(q), np.concatenate([x0, s_values])


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
    # sort by Re C, then Re A, ..., then Im C, ... (rounded, so that rounding noise cannot
    # reorder rows)
    last = arr.shape[1] - 1
    order = np.lexsort(
        [np.round(arr[:, k].imag, 9) for k in range(last, -1, -1)]
        + [np.round(arr[:, k].real, 9) for k in range(last, -1, -1)]
    )
    return arr[order]


@cache
def minimal_system() -> PolynomialSystem:
    """The four-frame minimal problem with its start system solved (module docstring)."""
    eqs = equations()
    q0, sols, facts = monodromy()
    sols = polish(eqs, q0, sols)
    facts = dict(facts)
    checks = unsquared_facts()
    if not checks["unsquared_product_is_lean"]:
        raise AssertionError("step 4: E~^2 - cp^2 s^2 O~^2 is not the reduced lean polynomial")
    facts.update(checks)
    facts.update(
        {
            "solutions": len(sols),
            "solutions_original_variables": 4 * len(sols),
            "frames": FRAMES,
            "lean_terms_per_frame": len(lean.lean_polynomial().terms()),
            "seed": SEED,
        }
    )
    return PolynomialSystem(
        name="minimal_unsquared",
        unknowns=UNKNOWNS,
        parameters=PARAMETERS,
        equations=eqs,
        equation_names=tuple(f"unsquared (12*), frame {i}" for i in range(FRAMES))
        + tuple(f"s{i}**2 - C*A*B*(1 - P)*(C - cp{i}**2)" for i in range(FRAMES))
        + ("m**2 - A*B*P",),
        start_parameters=tuple(complex(z) for z in q0),
        start_solutions=tuple(tuple(complex(z) for z in row) for row in sols),
        doc=(
            "The four-frame minimal problem in its unsquared form, reduced by the "
            "lean polynomial's symmetry: unknowns C = c^2, A = tan(alpha)^2, B = tan(beta)^2, "
            "P = cos(phi)^2, m = tan(alpha) tan(beta) cos(phi) (one unknown vector per orbit of "
            "four solutions in (tan alpha, tan beta, cos phi)) and per frame s_i = C tan(alpha) "
            "tan(beta) sin(phi) sin(tau_i); parameters (cp, dp, ep) of each frame, all lengths "
            "divided by one common length.  START_SOLUTIONS are every solution at "
            "START_PARAMETERS, found by monodromy; curverecon.solvers.homotopy tracks them to "
            "any frames' parameters."
        ),
        facts=facts,
    )
