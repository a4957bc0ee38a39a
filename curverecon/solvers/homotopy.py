"""Parameter homotopy continuation for a generated polynomial system (numba, one core).

A generated system module (``generated/minimal_*.py``, emitted by ``make derive`` from a SymPy
system) holds polynomial equations ``F(x; q) = 0`` in unknowns ``x`` (complex vector) whose
coefficients are polynomials in parameters ``q``, as tables:

* ``UNKNOWN_EXPONENTS[k, v]``: exponent of unknown v in unknown-monomial k;
* ``PARAMETER_EXPONENTS[j, w]``: exponent of parameter w in parameter-monomial j;
* ``TERMS[t] = (equation, parameter monomial, unknown monomial)`` with ``COEFFICIENTS[t]``;
* ``START_PARAMETERS`` q0 (generic complex) and ``START_SOLUTIONS``: every solution there.

:func:`track` follows every start solution along ``q(t) = q0 + t (q1 - q0) + t (1 - t) d``,
t from 0 to 1 (``d`` a random complex detour, zero on the first try: the "gamma trick"), with a
Hermite predictor (the interpolant of the path's last points and tangents, extrapolated; no
linear solve of its own: each tangent is a second right-hand side of the corrector's last
elimination) or a fourth-order Runge-Kutta one on ``dx/dt = -F_x^{-1} F_t``
(``HomotopyOptions.predictor``), and a Newton corrector.  The
paths are independent and tracked one after the other in compiled code (each with its own step
size).  A path ends with a status: ``OK``, ``STEP_TOO_SMALL`` (a near-singular point on the path),
``DIVERGED`` (the solution runs off to infinity) or ``TOO_MANY_STEPS``.  The caller retries
failed paths with a fresh detour (:class:`HomotopyOptions` says how often) and never drops one
silently: :class:`TrackResult` counts them.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from types import ModuleType

import numba
import numpy as np

_this = sys.modules[__name__]
"""This module, for compiled code that passes its own kernels as arguments: numba compiles a
bare global function used as a value to its address in this process (so the caller cannot be
cached), a module attribute to a constant resolved while typing (cached)."""

OK, STEP_TOO_SMALL, DIVERGED, TOO_MANY_STEPS, DEGENERATE = 0, 1, 2, 3, 4
STATUS_NAMES = ("ok", "step too small", "diverged", "too many steps", "degenerate")


@dataclass(frozen=True)
class HomotopyOptions:
    """Step control of the path tracker (dimensionless; t runs from 0 to 1).

    Defaults were chosen on the unsquared minimal problem (``generated/minimal_unsquared.py``)
    on noise-free four-frame scenes of seeds 700,000-700,059, one core: a path takes a median of
    63 steps (95th percentile 142), 0.22 s a solve, no path lost; ``bench/minimal.py`` measures
    them on other seeds.  The corrector's tolerance binds the step size: at 1e-9 paths took 91
    steps and the predictor tolerance had no effect above 1e-2 (all with the RK4 predictor;
    ``predictor`` and what follows it give the Hermite predictor's figures).
    """

    initial_step: float = 0.05
    """First step in t.  Paths of a generic parameter homotopy are smooth at t = 0."""
    max_step: float = 0.25
    """Largest step in t: fewer than four steps per path would let the predictor jump paths."""
    min_step: float = 1e-7
    """A path whose step falls below this is declared failed (near-singular) and retried."""
    predictor_tolerance: float = 3e-2
    """Largest first Newton update, relative to 1 + |x|, that accepts a predicted point: a
    larger one means the predictor left the path's neighbourhood (a path jump risk).  RK4: 1e-3
    took the same steps and lost one path in 60 solves, 1e-2 none.  Hermite predictor
    (2026-11-27, one core, interleaved runs): 3e-2 against 1e-2 takes 86 accepted steps a path
    against 95 and 6.7 % less time a minimal solve (median per-scene ratio 0.933 on seeds
    700,000+300, tuned on, and 0.933 on 1,200,000+300), the same real solutions and the same
    retried paths (18 in 300 scenes); 1e-1 only 1.4 % less again."""
    corrector_tolerance: float = 1e-7
    """Newton update, relative to 1 + |x|, at which the corrector has converged.  Along the
    path 1e-7 suffices (the endpoint is polished by Newton's method at t = 1); 1e-9 rejected a
    third of the steps (91 against 63 a path), 1e-6 let paths jump (3 lost in 30 solves)."""
    corrector_iterations: int = 3
    """Newton iterations allowed per step to reach ``corrector_tolerance``."""
    predictor: str = "hermite"
    """``"hermite"``: the predicted point is the Hermite interpolant of the path's last
    ``hermite_points`` accepted points and their tangents, extrapolated to t + h (no linear
    solve: each tangent comes from the corrector's last factorisation, a second right-hand side).
    ``"rk4"``: fourth-order Runge-Kutta on dx/dt = -F_x^-1 F_t, four solves a step (the
    tracker before 2026-11-27; retries use it).  Minimal problem, seeds 700,000 on (30 scenes,
    one core, first pass): RK4 77 accepted steps a path, 114 tries, 6.3 solves and 6.2-6.6 us a
    try, 72 ms a solve's tracking; Hermite on 3 points with ``growth_tolerance`` and
    ``corrector_estimate`` 96 accepted, 120 tries, 2.1 solves and 2.8 us a try, 34 ms; the
    same endpoint on every path."""
    hermite_points: int = 3
    """Past points of the Hermite predictor (a polynomial of degree 2 * points - 1; the first
    step of a path is RK4).  2 points (cubic) took 122 accepted steps a path, 3 points 100."""
    growth_tolerance: float = 1e-3
    """With the Hermite predictor the step doubles after an accepted step whose first Newton
    update, relative to 1 + |x|, is at most this (it stays the same otherwise).  Doubling
    after every accepted step rejected 1 try in 2 (234 tries a path against 150, cubic)."""
    corrector_estimate: bool = True
    """Accept the corrector once the update after the next is estimated below
    ``corrector_tolerance`` (``estimate_order``; k >= 1; a contraction of at
    most 1/2 is still required), not only when an update is below it: 2.1 Newton steps a try
    against 2.6, the same endpoints (Hermite predictor only; RK4 keeps the old test)."""
    estimate_order: float = 2.0
    """The convergence order that estimate assumes up to ``estimate_order_until``: the update
    after the next is estimated as |dx_k| (|dx_k| / |dx_(k-1)|)^order.  Newton's method
    converges quadratically here (|dx_1| is about |dx_0|^2 relative to 1 + |x|: median ratio
    1.2, 10 scenes), so 2; 1 (the linear estimate |dx_k|^2 / |dx_(k-1)|) ran a third
    iteration on 43 % of the accepted steps.  2026-11-27, one core, interleaved: 2 against 1
    on the whole path took 6.7 % less time a minimal solve (median per-scene ratio 0.933,
    seeds 700,000+300, the same real solutions), but on seed 1,200,055 two paths ended on one
    of two near-double roots (phi 0.2 degrees, 1e-5 apart) and its twin was lost: hence
    ``estimate_order_until``."""
    estimate_order_until: float = 0.9
    """Beyond this t the estimate is linear (order 1): paths come close to each other only
    near t = 1, at near-double roots of the real target (seed 1,200,055: with order 2 up to
    t = 1 a path jumped there; with 0.9 the old solutions, on seeds 700,000, 1,200,000 and
    1,500,000 +300 each the same real solutions as order 1 throughout).  Order 2 up to 0.9
    against order 1: median per-scene time ratio 0.944 (seeds 700,000+300, interleaved, one
    core), the same retried and failed paths."""
    max_steps: int = 2000
    """Steps per path before it is declared failed (a generic path needs tens)."""
    divergence: float = 1e8
    """|x| beyond this (in the system's scaled units) is a solution going to infinity."""
    endgame_start: float = 0.99
    """A path stalled beyond this t ends by Newton's method at t = 1 (see ``_endgame``)."""
    endgame_iterations: int = 40
    """Newton iterations of that endgame (linear convergence at a near-double solution)."""
    retries: int = 4
    """Fresh random detours tried for each failed or duplicated path before it is reported
    (each with half the largest step, a tenth of the predictor tolerance and of the smallest
    step of the try before)."""
    full_retries: int = 2
    """Whole second homotopies (every path along one fresh random detour) tried when paths are
    still lost after ``retries``; their new endpoints fill the lost paths' places.  A single
    path retried along a detour is a monodromy loop: it ends at *some* solution, often one
    another path already found, while the lost one can be a path that passes through infinity
    on the straight segment (seed 800,676: careful tracking diverged, and 1 detour in 8 reached
    it).  The union of two complete trackings does not depend on that luck."""
    near_double_twins: bool = True
    """Paths still lost after the retries are looked for as the twins of near-double
    solutions that other paths found (``_recover_near_double``): seed 500,032 of the minimal
    bench lost its true shape, 0.067 from such a twin, to a path jump, and no detour or whole
    second homotopy found it."""
    seed: int = 20261125
    """Seed of the detours: the same input gives the same output."""


@dataclass
class TrackResult:
    """Endpoints of every path at t = 1 and what happened on the way."""

    solutions: np.ndarray
    """(n_paths, n_unknowns) complex endpoints (NaN where a path failed)."""
    status: np.ndarray
    """(n_paths,) status code per path after the retries (``OK`` ...)."""
    steps: np.ndarray
    """(n_paths,) accepted steps of the last try of each path."""
    retried: int = 0
    """Paths that needed at least one fresh detour."""
    recovered: int = 0
    """Paths whose endpoint was found by deflated Newton next to a near-double solution."""
    completed: int = 0
    """Lost paths whose place was filled by a new endpoint of a whole second homotopy."""
    failures: dict[str, int] = field(default_factory=dict)
    """Failed paths by reason, after the retries (a path that jumped onto another's endpoint
    counts as 'duplicate'; its status is -1)."""

    @property
    def n_failed(self) -> int:
        return int(sum(self.failures.values()))


@dataclass(frozen=True)
class PolynomialSystem:
    """A generated system's tables in the layout the compiled tracker reads."""

    n_equations: int
    n_unknowns: int
    n_parameters: int
    umon_start: np.ndarray
    umon_var: np.ndarray
    umon_exp: np.ndarray
    pmon_start: np.ndarray
    pmon_var: np.ndarray
    pmon_exp: np.ndarray
    terms: np.ndarray
    coefficients: np.ndarray
    start_parameters: np.ndarray
    start_solutions: np.ndarray
    column_order: np.ndarray
    """The unknowns in the order the linear solves eliminate them: fewest equations first
    (``_column_order``; ties in the unknowns' order)."""
    elimination: np.ndarray
    """How the linear solves eliminate (``_elimination_plan``): unknowns that occur in two
    equations only, each by one row update, then the others as a dense system in
    ``column_order``.  The compiled trackers and Newton's method take it."""
    tracker: Callable[..., None] | None = field(default=None, compare=False, repr=False)
    """A compiled tracker on the system's generated straight-line kernels (a function of
    ``(q0, q1, detour, x_start, options vector, elimination, x_end, status, steps, t_end)``
    that calls
    :func:`track_generated`), or None: the tracker then reads the tables (slower, any system)."""
    newton: Callable[..., None] | None = field(default=None, compare=False, repr=False)
    """Newton's method on the generated kernels (a compiled function of ``(rows, q, column
    elimination, iterations)`` that calls :func:`newton_generated`), or None (the tables)."""
    nonzero: tuple[int, ...] = ()
    """Unknowns that are nonzero at every counted solution (the saturation of the solution
    count, docs/derivation.md): an endpoint with one of them at zero lies on a spurious
    positive-dimensional component, not among the counted solutions, and is a failed path
    (``DEGENERATE``; see :func:`degenerate`)."""

    @classmethod
    def from_module(
        cls,
        mod: ModuleType,
        tracker: Callable[..., None] | None = None,
        newton: Callable[..., None] | None = None,
        nonzero: tuple[str, ...] = (),
    ) -> PolynomialSystem:
        n_u, n_p = len(mod.UNKNOWNS), len(mod.PARAMETERS)
        uexp = np.asarray(mod.UNKNOWN_EXPONENTS, dtype=np.int64).reshape(-1, n_u)
        pexp = np.asarray(mod.PARAMETER_EXPONENTS, dtype=np.int64).reshape(-1, n_p)
        us, uv, ue = _sparse_rows(uexp)
        ps, pv, pe = _sparse_rows(pexp)
        terms = np.asarray(mod.TERMS, dtype=np.int64).reshape(-1, 3)
        order = _column_order(uexp, terms, len(mod.EQUATIONS))
        return cls(
            n_equations=len(mod.EQUATIONS),
            n_unknowns=uexp.shape[1],
            n_parameters=pexp.shape[1],
            umon_start=us,
            umon_var=uv,
            umon_exp=ue,
            pmon_start=ps,
            pmon_var=pv,
            pmon_exp=pe,
            terms=terms,
            coefficients=np.asarray(mod.COEFFICIENTS, dtype=np.float64),
            start_parameters=np.asarray(mod.START_PARAMETERS, dtype=np.complex128),
            start_solutions=np.asarray(mod.START_SOLUTIONS, dtype=np.complex128),
            column_order=order,
            elimination=_elimination_plan(uexp, terms, len(mod.EQUATIONS), order),
            tracker=tracker,
            newton=newton,
            nonzero=tuple(mod.UNKNOWNS.index(name) for name in nonzero),
        )

    def _args(self) -> tuple:
        return (
            self.n_equations,
            self.umon_start,
            self.umon_var,
            self.umon_exp,
            self.pmon_start,
            self.pmon_var,
            self.pmon_exp,
            self.terms,
            self.coefficients,
        )

    def polish(self, rows: np.ndarray, q: np.ndarray, iterations: int) -> np.ndarray:
        """Newton's method on F(x; q) = 0 from every row (complex arithmetic, compiled): at
        most ``iterations`` steps a row, stopping once every component's step is below 1e-15
        relative to 1 + |x_i|, or before a step that is not finite (singular Jacobian).  Real
        rows at real q stay real.  Returns the polished rows (a new array)."""
        xs = np.array(rows, dtype=np.complex128, order="C").reshape(-1, self.n_unknowns)
        qc = np.ascontiguousarray(q, dtype=np.complex128)
        if self.newton is not None:
            self.newton(xs, qc, self.elimination, iterations)
        else:
            _newton_tables(*self._args(), xs, qc, self.elimination, iterations)
        return xs

    def evaluate(self, x: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """F(x; q) (n_equations,) and its Jacobian in x, at one complex point."""
        x = np.asarray(x, dtype=np.complex128)
        q = np.asarray(q, dtype=np.complex128)
        f = np.empty(self.n_equations, np.complex128)
        jac = np.empty((self.n_equations, self.n_unknowns), np.complex128)
        _evaluate_at(*self._args(), q, x, f, jac)
        return f, jac


def _column_order(unknown_exponents: np.ndarray, terms: np.ndarray, n_equations: int) -> np.ndarray:
    """Unknowns sorted by how many equations they occur in (stable): eliminated in this order,
    an unknown that occurs in two equations only (the minimal system's s_i: its frame's
    unsquared (12*) and its own definition) costs one row update of the linear solve."""
    occurs = np.zeros((n_equations, unknown_exponents.shape[1]), dtype=bool)
    for a, _, k in terms:
        occurs[a] |= unknown_exponents[k] > 0
    return np.argsort(occurs.sum(axis=0), kind="stable").astype(np.int64)


def _elimination_plan(
    unknown_exponents: np.ndarray, terms: np.ndarray, n_equations: int, order: np.ndarray
) -> np.ndarray:
    """The linear solves' plan (``_solve``), an int64 vector: n, the number of pairs p, then
    (unknown, row, row) of each pair, the dense unknowns (n - p, in ``order``) and the rows in
    no pair (n - 2 p).

    A pair is an unknown that occurs in exactly two equations, whose rows no other pair uses:
    then neither row holds another pair's unknown, and one row update (pivoting between the
    two) eliminates it; the other row joins the dense system.  The minimal system's s_i are
    pairs (rows: frame i's unsquared (12*) and s_i's definition), leaving a 5 x 5 dense
    system in (C, A, B, P, m): 0.33 us a solve with two right-hand sides against 0.42 by
    Gaussian elimination on all nine columns in ``order`` (skipping zero rows), and 35 -> 29 ms
    a minimal solve (median, one core, 300 scenes)."""
    n = unknown_exponents.shape[1]
    occurs = np.zeros((n_equations, n), dtype=bool)
    for a, _, k in terms:
        occurs[a] |= unknown_exponents[k] > 0
    pairs: list[tuple[int, int, int]] = []
    used: set[int] = set()
    for v in order:
        rows = [int(r) for r in np.flatnonzero(occurs[:, v])]
        if len(rows) == 2 and not used & set(rows) and n_equations == n:
            pairs.append((int(v), rows[0], rows[1]))
            used |= set(rows)
    paired = {v for v, _, _ in pairs}
    dense = [int(v) for v in order if int(v) not in paired]
    free = [r for r in range(n_equations) if r not in used]
    flat = [k for pair in pairs for k in pair]
    return np.array([n, len(pairs), *flat, *dense, *free], dtype=np.int64)


def _sparse_rows(exponents: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CSR form of an exponent table: row k's nonzero (variable, exponent) pairs."""
    starts = [0]
    var: list[int] = []
    exp: list[int] = []
    for row in exponents:
        for v, e in enumerate(row):
            if e:
                var.append(v)
                exp.append(int(e))
        starts.append(len(var))
    return (
        np.array(starts, dtype=np.int64),
        np.array(var, dtype=np.int64),
        np.array(exp, dtype=np.int64),
    )


# ----------------------------------------------------------------------------------------------
# compiled kernels
# ----------------------------------------------------------------------------------------------

# No "reassoc": with it LLVM vectorised the reductions (norms, the back substitution) with a
# prologue that depends on the arrays' addresses, so one input gave endpoints differing at 1e-16
# from process to process, and on a scene with a near-double root (seed 600,125) a different
# set of solutions.
_JIT = {"cache": True, "nogil": True, "fastmath": {"contract", "arcp", "nsz"}}
_JIT_STEP = {**_JIT, "_nrt": False}
"""The tracker's steps (``_track_path`` and what it calls for each try): no reference counting
of their array arguments (they allocate nothing; ``_track_core`` owns every array).  With it,
a call per try cost 20 % more time a minimal solve than the single kernel they were cut from
(median per-scene 27 against 23 ms, process time, seeds 700,000-700,039); without it the
same time within 2 % and the same endpoints bit for bit.  Not numba's ``inline="always"``:
inlined, the steps changed the endpoints in the last bits on every scene."""


@numba.njit(**_JIT)
def _coefficient_matrix(n_eq, ps, pv, pe, terms, coef, q, dq, n_umon, w, wt, want_t, pm, pmt):
    """W[eq, umon] = sum over terms of coef * pmon(q); Wt the same with d pmon/dt (q' = dq).

    ``pm``, ``pmt``: scratch of one entry per parameter monomial (no allocation per call)."""
    n_pmon = ps.shape[0] - 1
    for j in range(n_pmon):
        val = 1.0 + 0.0j
        der = 0.0 + 0.0j
        for i in range(ps[j], ps[j + 1]):
            base = q[pv[i]]
            e = pe[i]
            p = 1.0 + 0.0j
            for _ in range(e - 1):
                p *= base
            # d/dt (val * base**e) = der * base**e + val * e * base**(e-1) * dq
            der = der * (p * base) + val * (e * p * dq[pv[i]])
            val = val * (p * base)
        pm[j] = val
        pmt[j] = der
    for a in range(n_eq):
        for k in range(n_umon):
            w[a, k] = 0.0
            wt[a, k] = 0.0
    for t in range(terms.shape[0]):
        a = terms[t, 0]
        j = terms[t, 1]
        k = terms[t, 2]
        w[a, k] += coef[t] * pm[j]
        if want_t:
            wt[a, k] += coef[t] * pmt[j]


@numba.njit(**_JIT)
def _residual_jacobian(us, uv, ue, x, w, f, jac, pw, ks, keq):
    """F = W u(x) and F_x = W du/dx."""
    _residual_jacobian_t(us, uv, ue, x, w, w, f, jac, f, False, pw, ks, keq)


@numba.njit(**_JIT)
def _monomial_equations(terms, n_umon):
    """CSR of the equations each unknown monomial occurs in: (starts (n_umon + 1), equations);
    W[a, k] is zero for every other equation a, so the loops skip it."""
    n_eq = 0
    for t in range(terms.shape[0]):
        if terms[t, 0] + 1 > n_eq:
            n_eq = terms[t, 0] + 1
    used = np.zeros((n_umon, n_eq), np.bool_)
    for t in range(terms.shape[0]):
        used[terms[t, 2], terms[t, 0]] = True
    starts = np.zeros(n_umon + 1, np.int64)
    for k in range(n_umon):
        starts[k + 1] = starts[k] + np.sum(used[k])
    eqs = np.empty(starts[n_umon], np.int64)
    for k in range(n_umon):
        j = starts[k]
        for a in range(n_eq):
            if used[k, a]:
                eqs[j] = a
                j += 1
    return starts, eqs


@numba.njit(**_JIT)
def _residual_jacobian_t(us, uv, ue, x, w, wt, f, jac, ft, want_t, pw, ks, keq):
    """F = W u(x), F_x = W du/dx and (``want_t``) F_t = Wt u(x).

    Powers of every unknown come from one table (``pw``, scratch of shape (n_unknowns, largest
    exponent + 1)); each monomial's partial derivative in x_v is e_v x_v^(e_v - 1) times the
    other factors.  ``ks``, ``keq``: the equations each monomial occurs in
    (:func:`_monomial_equations`).
    """
    n_eq, n_umon = w.shape
    n_var = x.shape[0]
    max_e = pw.shape[1] - 1
    for v in range(n_var):
        pw[v, 0] = 1.0
        for e in range(1, max_e + 1):
            pw[v, e] = pw[v, e - 1] * x[v]
    for a in range(n_eq):
        f[a] = 0.0
        if want_t:
            ft[a] = 0.0
        for v in range(n_var):
            jac[a, v] = 0.0
    for k in range(n_umon):
        val = 1.0 + 0.0j
        for i in range(us[k], us[k + 1]):
            val *= pw[uv[i], ue[i]]
        for j in range(ks[k], ks[k + 1]):
            a = keq[j]
            f[a] += w[a, k] * val
            if want_t:
                ft[a] += wt[a, k] * val
        for i in range(us[k], us[k + 1]):
            d = 1.0 * ue[i] + 0.0j
            for i2 in range(us[k], us[k + 1]):
                if i2 == i:
                    d *= pw[uv[i2], ue[i2] - 1]
                else:
                    d *= pw[uv[i2], ue[i2]]
            v = uv[i]
            for j in range(ks[k], ks[k + 1]):
                a = keq[j]
                jac[a, v] += w[a, k] * d


@numba.njit(**_JIT)
def _reciprocal(z):
    """1 / z for a nonzero finite complex z: conj(z) / |z|^2 by one real division (numba's
    complex division scales against overflow with branches, several times slower; the
    tracker's entries stay far below 1e150)."""
    d = 1.0 / (z.real * z.real + z.imag * z.imag)
    return complex(z.real * d, -z.imag * d)


@numba.njit(**_JIT)
def _solve(a, b, out, m, r, plan):
    """out = a^-1 b by Gaussian elimination with partial pivoting; False if a is singular.

    ``plan`` is ``PolynomialSystem.elimination``: first the unknowns that occur in two
    equations only (the minimal system's s_i: its frame's unsquared (12*) and its own
    definition), each eliminated by one row update, pivoting between its two rows; then the
    rest, a dense system, by partial pivoting over its rows (in the plan's column order; rows
    whose entry in the pivot column is zero are skipped).  ``m``, ``r``: scratch of the shapes
    of ``a`` and ``b`` (``out`` must not be ``b``).  Pivots by |Re| + |Im| (within a factor
    sqrt(2) of the modulus, without its square root); one complex division per pivot."""
    return _solve_pair(a, b, b, out, out, m, r, r, plan, False)


@numba.njit(**_JIT)
def _solve_pair(a, b, c, out, out2, m, r, r2, plan, two):
    """``_solve`` for one right-hand side b, or (``two``) also out2 = a^-1 c with the same
    elimination (``r2``: scratch like ``r``; ``out2`` must not be ``c``).

    Layout of the scratch: ``m[:nd, :nd]`` the dense system (nd = n - pairs) and
    ``m[nd + p, :nd]`` pair p's pivot row on the dense unknowns, ``m[nd + p, nd]`` the
    inverse of its pivot; ``r[:nd]``, ``r[nd + p]`` the right-hand sides alike."""
    n = b.shape[0]
    n2 = plan[1]
    nd = n - n2
    cols = 2 + 3 * n2  # the dense unknowns' columns, then the rows in no pair
    free = cols + nd
    n_free = n - 2 * n2
    for i in range(n_free):
        row = plan[free + i]
        r[i] = b[row]
        if two:
            r2[i] = c[row]
        for k in range(nd):
            m[i, k] = a[row, plan[cols + k]]
    for p in range(n2):
        col = plan[2 + 3 * p]
        piv = plan[3 + 3 * p]
        oth = plan[4 + 3 * p]
        va = a[piv, col]
        vb = a[oth, col]
        mag_a = abs(va.real) + abs(va.imag)
        mag_b = abs(vb.real) + abs(vb.imag)
        if mag_b > mag_a:
            piv, oth, va, vb, mag_a = oth, piv, vb, va, mag_b
        if mag_a == 0.0 or not np.isfinite(mag_a):
            return False
        inv = _reciprocal(va)
        fac = vb * inv
        i = n_free + p
        j = nd + p
        m[j, nd] = inv
        r[j] = b[piv]
        r[i] = b[oth] - fac * b[piv]
        if two:
            r2[j] = c[piv]
            r2[i] = c[oth] - fac * c[piv]
        for k in range(nd):
            cc = plan[cols + k]
            m[j, k] = a[piv, cc]
            m[i, k] = a[oth, cc] - fac * a[piv, cc]
    for col in range(nd):
        piv = col
        best = abs(m[col, col].real) + abs(m[col, col].imag)
        for row in range(col + 1, nd):
            mag = abs(m[row, col].real) + abs(m[row, col].imag)
            if mag > best:
                best = mag
                piv = row
        if best == 0.0 or not np.isfinite(best):
            return False
        if piv != col:
            for k in range(col, nd):
                tmp = m[col, k]
                m[col, k] = m[piv, k]
                m[piv, k] = tmp
            tmp = r[col]
            r[col] = r[piv]
            r[piv] = tmp
            if two:
                tmp = r2[col]
                r2[col] = r2[piv]
                r2[piv] = tmp
        inv = _reciprocal(m[col, col])
        out[col] = inv  # the pivots' inverses, until the solution overwrites them
        for row in range(col + 1, nd):
            if m[row, col] != 0.0:
                fac = m[row, col] * inv
                for k in range(col + 1, nd):
                    m[row, k] -= fac * m[col, k]
                r[row] -= fac * r[col]
                if two:
                    r2[row] -= fac * r2[col]
    for row in range(nd - 1, -1, -1):
        s = r[row]
        for k in range(row + 1, nd):
            s -= m[row, k] * r[k]
        r[row] = s * out[row]
        if two:
            s2 = r2[row]
            for k in range(row + 1, nd):
                s2 -= m[row, k] * r2[k]
            r2[row] = s2 * out[row]
    for p in range(n2):  # each pair's unknown from its pivot row
        j = nd + p
        s = r[j]
        for k in range(nd):
            s -= m[j, k] * r[k]
        r[j] = s * m[j, nd]
        if two:
            s2 = r2[j]
            for k in range(nd):
                s2 -= m[j, k] * r2[k]
            r2[j] = s2 * m[j, nd]
    for k in range(nd):
        out[plan[cols + k]] = r[k]
        if two:
            out2[plan[cols + k]] = r2[k]
    for p in range(n2):
        out[plan[2 + 3 * p]] = r[nd + p]
        if two:
            out2[plan[2 + 3 * p]] = r2[nd + p]
    return True


loop_solve_pair = _solve_pair
"""The tracker's own loop solve (``_solve_pair``), for a solver whose generated kernels carry
no written-out solve (``track_generated``'s ``solve_pair`` argument)."""


@numba.njit(**_JIT)
def _hermite_weights(th, npts, tt, wts, z, col):
    """Weights of the Hermite interpolant of ``npts`` points at ``tt``: the polynomial of degree
    2 npts - 1 through values x_j and derivatives v_j at the (distinct, real) ``th[j]`` is
    sum_j wts[2j] x_j + wts[2j + 1] v_j there.  Confluent divided differences (each node twice)
    of each unit datum, real scalars: the paths' unknowns are combined once, with these.

    ``z``: scratch of ``hermite_scratch(npts)`` entries (the nodes, then the reciprocals of
    their differences, shared by every datum: one division each instead of one per datum);
    ``col``: scratch of 2 npts.  The tracker keeps :func:`_hermite_table` (what depends on the
    nodes only) from one try to the next and calls :func:`_hermite_at` alone: the same
    arithmetic, 5.7 % less time a minimal solve (median per-scene ratio 0.943, seeds
    700,000+300, one core, interleaved; the same solutions)."""
    n = 2 * npts
    _hermite_nodes(th, npts, z)
    for b in range(n):
        _hermite_column(z, n, b, col)
        wts[b] = _hermite_horner(col, z, n, tt)


@numba.njit(**_JIT)
def _hermite_nodes(th, npts, z):
    """``z``: each node twice, then the reciprocals of their differences at every level (0 for
    a repeated node)."""
    n = 2 * npts
    for j in range(npts):
        z[2 * j] = th[j]
        z[2 * j + 1] = th[j]
    idx = n
    for lev in range(1, n):
        for k in range(n - 1, lev - 1, -1):
            dz = z[k] - z[k - lev]
            z[idx] = 1.0 / dz if dz != 0.0 else 0.0  # 0: a repeated node (derivative datum)
            idx += 1


@numba.njit(**_JIT)
def _hermite_column(z, n, b, col):
    """The Newton-form coefficients (confluent divided differences) of unit datum ``b`` (a
    value if even, a derivative if odd) into ``col`` (n entries)."""
    for k in range(n):
        col[k] = 1.0 if (b % 2 == 0 and (k == b or k == b + 1)) else 0.0  # values
    idx = n
    for k in range(n - 1, 0, -1):  # first differences: derivative data at repeated nodes
        if k % 2 == 1:
            col[k] = 1.0 if b == k else 0.0
        else:
            col[k] = (col[k] - col[k - 1]) * z[idx]
        idx += 1
    for lev in range(2, n):
        for k in range(n - 1, lev - 1, -1):
            col[k] = (col[k] - col[k - 1]) * z[idx]
            idx += 1


@numba.njit(**_JIT)
def _hermite_horner(col, z, n, tt):
    """The Newton form with coefficients ``col`` and nodes ``z`` at ``tt``."""
    acc = col[n - 1]
    for k in range(n - 2, -1, -1):
        acc = acc * (tt - z[k]) + col[k]
    return acc


@numba.njit(**_JIT)
def _hermite_table(th, npts, z, table):
    """What ``_hermite_weights`` computes from the nodes alone: ``z`` and every unit datum's
    Newton coefficients (row b of ``table``, (2 npts, 2 npts) at least)."""
    n = 2 * npts
    _hermite_nodes(th, npts, z)
    for b in range(n):
        _hermite_column(z, n, b, table[b])


@numba.njit(**_JIT)
def _hermite_at(npts, tt, z, table, wts):
    """``_hermite_weights`` at ``tt`` from ``_hermite_table``'s ``z`` and ``table``."""
    n = 2 * npts
    for b in range(n):
        wts[b] = _hermite_horner(table[b], z, n, tt)


def hermite_scratch(npts: int) -> int:
    """Entries of ``_hermite_weights``' scratch ``z``: 2 npts nodes and the reciprocals of
    their differences at every level."""
    n = 2 * npts
    return n + n * (n - 1) // 2


@numba.njit(**_JIT)
def _norm(x):
    s = 0.0
    for i in range(x.shape[0]):
        s += x[i].real * x[i].real + x[i].imag * x[i].imag
    return np.sqrt(s)


@numba.njit(**_JIT)
def _power_table(ue, n_var):
    """Scratch for the powers of every unknown: (n_var, largest exponent + 1)."""
    max_e = 0
    for i in range(ue.shape[0]):
        if ue[i] > max_e:
            max_e = ue[i]
    return np.empty((n_var, max_e + 1), np.complex128)


@numba.njit(**_JIT)
def _evaluate_at(n_eq, us, uv, ue, ps, pv, pe, terms, coef, q, x, f, jac):
    n_umon = us.shape[0] - 1
    w = np.empty((n_eq, n_umon), np.complex128)
    wt = np.empty((n_eq, n_umon), np.complex128)
    dq = np.zeros(q.shape[0], np.complex128)
    pm = np.empty(ps.shape[0] - 1, np.complex128)
    pmt = np.empty(ps.shape[0] - 1, np.complex128)
    _coefficient_matrix(n_eq, ps, pv, pe, terms, coef, q, dq, n_umon, w, wt, False, pm, pmt)
    ks, keq = _monomial_equations(terms, n_umon)
    _residual_jacobian(us, uv, ue, x, w, f, jac, _power_table(ue, x.shape[0]), ks, keq)


@numba.njit(**_JIT)
def _params_at(q0, q1, d, t, q, dq):
    for i in range(q0.shape[0]):
        q[i] = q0[i] + t * (q1[i] - q0[i]) + t * (1.0 - t) * d[i]
        dq[i] = (q1[i] - q0[i]) + (1.0 - 2.0 * t) * d[i]


@numba.njit(**_JIT)
def _table_coefficients(q, w):
    """W at q from the tables; ``w`` is the workspace tuple of ``_track_paths``."""
    wm, n_eq, ps, pv, pe, terms, coef, pm, pmt, us, uv, ue, pw, ks, keq = w
    _coefficient_matrix(n_eq, ps, pv, pe, terms, coef, q, q, wm.shape[1], wm, wm, False, pm, pmt)


@numba.njit(**_JIT)
def _table_coefficients_t(q, dq, w, wt):
    """W at q and Wt = dW/dt along dq from the tables; ``wt`` is the pair (Wt, the workspace
    tuple) of ``_track_paths``."""
    wm, n_eq, ps, pv, pe, terms, coef, pm, pmt, us, uv, ue, pw, ks, keq = w
    _coefficient_matrix(n_eq, ps, pv, pe, terms, coef, q, dq, wm.shape[1], wm, wt[0], True, pm, pmt)


@numba.njit(**_JIT)
def _table_coefficient_rates(q, dq, wt):
    """Wt = dW/dt along dq at q from the tables (``wt`` as in ``_table_coefficients_t``; W in
    the workspace is written again at q: called where it already holds W at q)."""
    _table_coefficients_t(q, dq, wt[1], wt)


@numba.njit(**_JIT)
def _table_residual_jacobian(x, w, f, jac):
    """F, F_x at x from W (in the workspace tuple ``w``) and the tables."""
    wm, n_eq, ps, pv, pe, terms, coef, pm, pmt, us, uv, ue, pw, ks, keq = w
    _residual_jacobian(us, uv, ue, x, wm, f, jac, pw, ks, keq)


@numba.njit(**_JIT)
def _table_residual_jacobian_t(x, w, wt, f, jac, ft):
    """F, F_x and F_t at x from W, Wt and the tables."""
    wm, n_eq, ps, pv, pe, terms, coef, pm, pmt, us, uv, ue, pw, ks, keq = w
    _residual_jacobian_t(us, uv, ue, x, wm, wt[0], f, jac, ft, True, pw, ks, keq)


@numba.njit(**_JIT)
def _table_workspace(n_eq, us, uv, ue, ps, pv, pe, terms, coef, n_var):
    """The table evaluators' shared arguments and scratch (``_table_*``): W, the tables, the
    parameter monomials' values and t-derivatives, the unknowns' power table and the equations
    each unknown monomial occurs in."""
    n_umon = us.shape[0] - 1
    ks, keq = _monomial_equations(terms, n_umon)
    return (
        np.empty((n_eq, n_umon), np.complex128),
        n_eq,
        ps,
        pv,
        pe,
        terms,
        coef,
        np.empty(ps.shape[0] - 1, np.complex128),
        np.empty(ps.shape[0] - 1, np.complex128),
        us,
        uv,
        ue,
        _power_table(ue, n_var),
        ks,
        keq,
    )


@numba.njit(**_JIT)
def _track_paths(
    n_eq,
    us,
    uv,
    ue,
    ps,
    pv,
    pe,
    terms,
    coef,
    q0,
    q1,
    d,
    x_start,
    opts,
    plan,
    x_end,
    status,
    steps,
    t_end,
):
    """Track every row of ``x_start`` from t = 0 to 1 on the tables (see the module docstring)."""
    n_umon = us.shape[0] - 1
    workspace = _table_workspace(n_eq, us, uv, ue, ps, pv, pe, terms, coef, x_start.shape[1])
    _track_core(
        _this._table_coefficients,
        _this._table_coefficients_t,
        _this._table_coefficient_rates,
        _this._table_residual_jacobian,
        _this._table_residual_jacobian_t,
        _this._solve_pair,
        workspace,
        (np.empty((n_eq, n_umon), np.complex128), workspace),
        n_eq,
        q0,
        q1,
        d,
        x_start,
        opts,
        plan,
        x_end,
        status,
        steps,
        t_end,
    )


@numba.njit(**_JIT)
def track_generated(
    coefficients,
    coefficients_t,
    coefficient_rates,
    residual_jacobian,
    residual_jacobian_t,
    solve_pair,
    n_coefficients,
    q0,
    q1,
    d,
    x_start,
    opts,
    plan,
    x_end,
    status,
    steps,
    t_end,
):
    """Track every row of ``x_start`` from t = 0 to 1 (see the module docstring) with a
    system's generated straight-line kernels: the functions ``coefficients``,
    ``coefficients_t``, ``coefficient_rates``, ``residual_jacobian``, ``residual_jacobian_t``
    and ``solve_pair`` of a module that
    ``derivations.codegen.generate.system_kernels`` wrote, ``n_coefficients`` its
    ``N_COEFFICIENTS`` (``plan`` must be that module's ``ELIMINATION``).

    Call it from a compiled function of your own that names the module's kernels (numba caches
    that function; one called from Python with kernels as arguments would be compiled again in
    every process): see ``curverecon.solvers.minimal``."""
    _track_core(
        coefficients,
        coefficients_t,
        coefficient_rates,
        residual_jacobian,
        residual_jacobian_t,
        solve_pair,
        np.empty(n_coefficients, np.complex128),
        np.empty(n_coefficients, np.complex128),
        x_start.shape[1],
        q0,
        q1,
        d,
        x_start,
        opts,
        plan,
        x_end,
        status,
        steps,
        t_end,
    )


@numba.njit(**_JIT)
def track_workspace(
    coefficients,
    coefficients_t,
    coefficient_rates,
    residual_jacobian,
    residual_jacobian_t,
    solve_pair,
    w,
    wt,
    q0,
    q1,
    d,
    x_start,
    opts,
    plan,
    x_end,
    status,
    steps,
    t_end,
):
    """``track_generated`` on the caller's coefficient workspaces ``w`` and ``wt``, for kernels
    that keep data of their own beyond W's entries (``persp_fixed_axis_3pt``: W as a polynomial
    in t, its coefficients after the entries)."""
    _track_core(
        coefficients,
        coefficients_t,
        coefficient_rates,
        residual_jacobian,
        residual_jacobian_t,
        solve_pair,
        w,
        wt,
        x_start.shape[1],
        q0,
        q1,
        d,
        x_start,
        opts,
        plan,
        x_end,
        status,
        steps,
        t_end,
    )


@numba.njit(**_JIT)
def _track_core(
    coefficients,
    coefficients_t,
    coefficient_rates,
    residual_jacobian,
    residual_jacobian_t,
    solve_pair,
    w,
    wt,
    n_eq,
    q0,
    q1,
    d,
    x_start,
    opts,
    plan,
    x_end,
    status,
    steps,
    t_end,
):
    """The tracker on any evaluation of the system, with the generated kernels' signatures:
    ``coefficients(q, w)`` and ``coefficients_t(q, dq, w, wt)`` fill the coefficient workspace
    ``w`` at q (and ``wt``, its derivative along dq), ``coefficient_rates(q, dq, wt)`` that
    derivative alone, ``residual_jacobian(x, w, f, jac)`` and
    ``residual_jacobian_t(x, w, wt, f, jac, ft)`` give F, F_x (and F_t) at x from them;
    ``solve_pair(a, b, c, out, out2, m, r, r2, plan, two)`` is the linear solve
    (:func:`_solve_pair`, or a system's generated one: the loops written out for its plan,
    0.24 against 0.38 us with two right-hand sides, 0.19 against 0.31 with one; with the
    Horner-form dW/dt about 19 % less time a minimal solve: median per-scene ratio 0.755 with
    the quadratic corrector estimate, which alone gave 0.933, one core, interleaved, seeds
    700,000+300).

    With the Hermite predictor a try evaluates W alone, and its first Newton iteration F and
    F_x alone (one right-hand side): most rejected tries end there.  dW/dt and F_t, for the
    tangent, come from the second iteration on (the last iteration's tangent is the accepted
    point's): 0.1 + 0.8 x 0.25 us against 0.37 for W with dW/dt, and 0.15 against 0.22 for the
    first iteration's F, F_x.

    Each path: :func:`_track_path` (predictor, corrector, step control) from t = 0 to 1, then
    :func:`_polish_end` at t = 1; ``s`` is the scratch all of them share
    (:func:`_tracker_scratch`, allocated once)."""
    s = _tracker_scratch(n_eq, x_start.shape[1], q0.shape[0], int(opts[8]))
    for p in range(x_start.shape[0]):
        x = x_start[p].copy()
        st, n_steps, t = _track_path(
            coefficients,
            coefficients_t,
            coefficient_rates,
            residual_jacobian,
            residual_jacobian_t,
            solve_pair,
            w,
            wt,
            q0,
            q1,
            d,
            x,
            opts,
            plan,
            s,
        )
        if st == OK:
            _polish_end(coefficients, residual_jacobian, solve_pair, w, q0, q1, d, x, plan, s)
        for i in range(x.shape[0]):
            x_end[p, i] = x[i]
        status[p] = st
        steps[p] = n_steps
        t_end[p] = t


@numba.njit(**_JIT)
def _tracker_scratch(n_eq, n_var, n_par, n_hermite):
    """The tracker's scratch, one tuple for every path: q, dq, F, F_t, F_x, the RK4 stages
    k1-k4, the predicted point y, the Newton update dx, the tangent, the linear solve's
    scratch (lu, rhs, rhs2), and the Hermite predictor's history: the last accepted points
    (t, x, dx/dt), oldest first, the interpolant's weights and the divided differences of
    its nodes (``hermite_scratch``, ``_hermite_table``)."""
    n_hist = max(n_hermite, 1)
    return (
        np.empty(n_par, np.complex128),
        np.empty(n_par, np.complex128),
        np.empty(n_eq, np.complex128),
        np.empty(n_eq, np.complex128),
        np.empty((n_eq, n_var), np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty(n_var, np.complex128),
        np.empty((n_eq, n_var), np.complex128),
        np.empty(n_eq, np.complex128),
        np.empty(n_eq, np.complex128),
        np.empty(n_hist),
        np.empty((n_hist, n_var), np.complex128),
        np.empty((n_hist, n_var), np.complex128),
        np.empty(2 * n_hist),
        np.empty(2 * n_hist + n_hist * (2 * n_hist - 1)),
        np.empty((2 * n_hist, 2 * n_hist)),
    )


@numba.njit(**_JIT_STEP)
def _track_path(
    coefficients,
    coefficients_t,
    coefficient_rates,
    residual_jacobian,
    residual_jacobian_t,
    solve_pair,
    w,
    wt,
    q0,
    q1,
    d,
    x,
    opts,
    plan,
    s,
):
    """One path from ``x`` (updated in place) at t = 0 to t = 1: predicted (Hermite once the
    history holds two points, RK4 before and with ``opts[8]`` = 0), corrected by Newton's method
    and accepted, or the step halved.  Returns (status, accepted steps, t reached).

    ``w_at``, ``wt_at``: the t at which W and Wt in ``w``, ``wt`` were last evaluated (-1: not
    yet); ``nh`` the Hermite history's points, ``tabled`` whether its divided differences are
    up to date."""
    h, hmax, hmin = opts[0], opts[1], opts[2]
    max_steps, divergence = int(opts[5]), opts[6]
    n_hermite = int(opts[8])  # 0: RK4 predictor; else Hermite on this many past points
    tol_grow = opts[9]
    q, dq, f, ft, jac, k1, k2, k3, k4, y, dx, tangent, lu, rhs, rhs2 = s[:15]
    th, xh, vh, wts, z, col = s[15:]
    w_at = -1.0
    wt_at = -1.0
    t = 0.0
    n_ok = 0
    n_steps = 0
    nh = 0
    tabled = False
    while t < 1.0:
        if n_steps >= max_steps:
            return TOO_MANY_STEPS, n_steps, t
        if h > 1.0 - t:
            h = 1.0 - t
        good = True
        if n_hermite > 0 and nh >= 2:
            if not tabled:  # the history changed: its nodes' divided differences
                _hermite_table(th, nh, z, col)
                tabled = True
            w_at = _predict_hermite(
                coefficients, w, q0, q1, d, t, h, nh, w_at, q, dq, y, xh, vh, wts, z, col
            )
        else:
            good, w_at, wt_at = _predict_rk4(
                coefficients_t,
                residual_jacobian_t,
                solve_pair,
                w,
                wt,
                q0,
                q1,
                d,
                x,
                t,
                h,
                w_at,
                wt_at,
                plan,
                q,
                dq,
                f,
                ft,
                jac,
                k1,
                k2,
                k3,
                k4,
                y,
                lu,
                rhs,
            )
        first = 0.0
        scale = 0.0
        if good:
            good, first, scale, wt_at = _correct(
                coefficient_rates,
                residual_jacobian,
                residual_jacobian_t,
                solve_pair,
                w,
                wt,
                t + h,
                w_at,
                wt_at,
                opts,
                plan,
                q,
                dq,
                f,
                ft,
                jac,
                y,
                dx,
                tangent,
                lu,
                rhs,
                rhs2,
            )
        if good:
            if n_hermite > 0:
                nh = _push_history(t, h, x, nh, n_hermite, k1, y, tangent, th, xh, vh)
                tabled = False
            for i in range(x.shape[0]):
                x[i] = y[i]
            t = t + h
            n_steps += 1
            if n_hermite > 0:
                if first <= tol_grow * scale:
                    h = min(2.0 * h, hmax)
            else:
                n_ok += 1
                if n_ok >= 2:
                    h = min(2.0 * h, hmax)
                    n_ok = 0
            if _norm(x) > divergence:
                return DIVERGED, n_steps, t
        else:
            h *= 0.5
            n_ok = 0
            if h < hmin:
                return STEP_TOO_SMALL, n_steps, t
    return OK, n_steps, t


@numba.njit(**_JIT_STEP)
def _predict_hermite(coefficients, w, q0, q1, d, t, h, nh, w_at, q, dq, y, xh, vh, wts, z, col):
    """Hermite predictor: y is the interpolant at t + h of the history's ``nh`` points (xh,
    tangents vh; ``z``, ``col`` their ``_hermite_table``, ``wts`` scratch); W at t + h for the
    corrector (q, dq: the parameters there).  Returns the t at which ``w`` holds W."""
    _hermite_at(nh, t + h, z, col, wts)
    for i in range(y.shape[0]):
        acc = 0.0 + 0.0j
        for j in range(nh):
            acc += wts[2 * j] * xh[j, i] + wts[2 * j + 1] * vh[j, i]
        y[i] = acc
    if t + h != w_at:  # the corrector's W at t + h (Wt when a tangent is needed)
        _params_at(q0, q1, d, t + h, q, dq)
        coefficients(q, w)
        w_at = t + h
    return w_at


@numba.njit(**_JIT_STEP)
def _predict_rk4(
    coefficients_t,
    residual_jacobian_t,
    solve_pair,
    w,
    wt,
    q0,
    q1,
    d,
    x,
    t,
    h,
    w_at,
    wt_at,
    plan,
    q,
    dq,
    f,
    ft,
    jac,
    k1,
    k2,
    k3,
    k4,
    y,
    lu,
    rhs,
):
    """RK4 predictor on dx/dt = -F_x^-1 F_t from x at t: y at t + h, the stages in k1-k4 (k1,
    the tangent at x, starts the Hermite history); q, dq, f, ft, jac, lu, rhs scratch.
    Returns (whether every stage's solve succeeded, the t of W in ``w``, the t of Wt in
    ``wt``)."""
    n_var = x.shape[0]
    for stage in range(4):
        if stage == 0:
            ts = t
            for i in range(n_var):
                y[i] = x[i]
        elif stage == 1:
            ts = t + 0.5 * h
            for i in range(n_var):
                y[i] = x[i] + 0.5 * h * k1[i]
        elif stage == 2:
            ts = t + 0.5 * h
            for i in range(n_var):
                y[i] = x[i] + 0.5 * h * k2[i]
        else:
            ts = t + h
            for i in range(n_var):
                y[i] = x[i] + h * k3[i]
        if ts != w_at:  # W and Wt at ts (stages 2 and 3 share one; stage 1
            # reuses the last accepted step's stage 4)
            _params_at(q0, q1, d, ts, q, dq)
            coefficients_t(q, dq, w, wt)
            w_at = ts
            wt_at = ts
        residual_jacobian_t(y, w, wt, f, jac, ft)
        kk = k1 if stage == 0 else (k2 if stage == 1 else (k3 if stage == 2 else k4))
        if not solve_pair(jac, ft, ft, kk, kk, lu, rhs, rhs, plan, False):
            return False, w_at, wt_at
        for i in range(n_var):
            kk[i] = -kk[i]
    for i in range(n_var):
        y[i] = x[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    return True, w_at, wt_at


@numba.njit(**_JIT_STEP)
def _correct(
    coefficient_rates,
    residual_jacobian,
    residual_jacobian_t,
    solve_pair,
    w,
    wt,
    t_next,
    w_at,
    wt_at,
    opts,
    plan,
    q,
    dq,
    f,
    ft,
    jac,
    y,
    dx,
    tangent,
    lu,
    rhs,
    rhs2,
):
    """Newton corrector of y at t + h = ``t_next`` (W there is already in ``w``; q, dq are at
    ``w_at``; f, ft, jac, dx, lu, rhs, rhs2 scratch).  With the Hermite predictor each
    iteration also solves for the tangent dx/dt = -F_x^-1 F_t with the same elimination: the
    last one is the accepted point's tangent (``tangent``).  Returns (converged, the first
    update's norm, 1 + |y| before the corrector, the t of Wt in ``wt``)."""
    tol_pred, tol_corr, n_corr = opts[3], opts[4], int(opts[7])
    n_hermite = int(opts[8])
    estimate = opts[10] > 0.0 and n_hermite > 0
    order = opts[11]  # the order the estimate assumes (1: linear, 2: quadratic convergence)
    quad_until = opts[12]  # ... up to this t (linear beyond: near-double roots at t = 1)
    first = 0.0
    scale = 1.0 + _norm(y)
    good = False
    prev = 0.0
    fresh = False  # has an iteration given the tangent?
    for it in range(n_corr):
        if n_hermite > 0 and it > 0:
            if wt_at != w_at:  # q, dq are at w_at
                coefficient_rates(q, dq, wt)
                wt_at = w_at
            residual_jacobian_t(y, w, wt, f, jac, ft)
            if not solve_pair(jac, f, ft, dx, tangent, lu, rhs, rhs2, plan, True):
                break
            fresh = True
        else:
            residual_jacobian(y, w, f, jac)
            if not solve_pair(jac, f, f, dx, dx, lu, rhs, rhs, plan, False):
                break
        nd = _norm(dx)
        if it == 0:
            first = nd
            if nd > tol_pred * scale:
                break
        if it > 0 and nd > 0.5 * prev:
            break
        for i in range(y.shape[0]):
            y[i] -= dx[i]
        if it > 0:  # the update after this one, estimated
            nxt = nd * (nd / prev) ** (order if t_next <= quad_until else 1.0)
        if nd <= tol_corr * scale or (estimate and it > 0 and nxt <= tol_corr * scale):
            good = True
            break
        prev = nd
    if good and n_hermite > 0 and not fresh:  # converged in one iteration (rare)
        if wt_at != w_at:
            coefficient_rates(q, dq, wt)
            wt_at = w_at
        residual_jacobian_t(y, w, wt, f, jac, ft)
        good = solve_pair(jac, f, ft, dx, tangent, lu, rhs, rhs2, plan, True)
    return good, first, scale, wt_at


@numba.njit(**_JIT_STEP)
def _push_history(t, h, x, nh, n_hermite, k1, y, tangent, th, xh, vh):
    """The accepted point y at t + h and its tangent join the Hermite history (the oldest of
    ``n_hermite`` points leaves it); the path's first step first enters its start x at t with
    the RK4 step's k1.  Returns the history's new number of points."""
    n_var = x.shape[0]
    if nh == 0:  # the path's start and its tangent (the RK4 step's k1)
        th[0] = t
        for i in range(n_var):
            xh[0, i] = x[i]
            vh[0, i] = k1[i]
        nh = 1
    if nh == n_hermite:
        for j in range(nh - 1):
            th[j] = th[j + 1]
            for i in range(n_var):
                xh[j, i] = xh[j + 1, i]
                vh[j, i] = vh[j + 1, i]
        nh -= 1
    th[nh] = t + h
    for i in range(n_var):
        xh[nh, i] = y[i]
        vh[nh, i] = -tangent[i]
    return nh + 1


@numba.njit(**_JIT_STEP)
def _polish_end(coefficients, residual_jacobian, solve_pair, w, q0, q1, d, x, plan, s):
    """Final Newton polish of a path's endpoint x at t = 1 (at most three iterations)."""
    q, dq, f, jac, dx, lu, rhs = s[0], s[1], s[2], s[4], s[10], s[12], s[13]
    _params_at(q0, q1, d, 1.0, q, dq)
    coefficients(q, w)
    for _ in range(3):
        residual_jacobian(x, w, f, jac)
        if not solve_pair(jac, f, f, dx, dx, lu, rhs, rhs, plan, False):
            break
        for i in range(x.shape[0]):
            x[i] -= dx[i]
        if _norm(dx) <= 1e-15 * (1.0 + _norm(x)):
            break


@numba.njit(**_JIT)
def _newton_core(coefficients, residual_jacobian, w, xs, q, plan, iterations):
    """Newton's method from every row of ``xs`` in place (``PolynomialSystem.polish``), on any
    evaluation of the system (the signatures of ``_track_core``)."""
    n = xs.shape[1]
    f = np.empty(n, np.complex128)
    jac = np.empty((n, n), np.complex128)
    dx = np.empty(n, np.complex128)
    lu = np.empty((n, n), np.complex128)
    rhs = np.empty(n, np.complex128)
    coefficients(q, w)
    for p in range(xs.shape[0]):
        for _ in range(iterations):
            residual_jacobian(xs[p], w, f, jac)
            if not _solve(jac, f, dx, lu, rhs, plan):
                break
            finite = True
            for i in range(n):
                if not (np.isfinite(dx[i].real) and np.isfinite(dx[i].imag)):
                    finite = False
            if not finite:
                break
            small = True
            for i in range(n):
                xs[p, i] -= dx[i]
                if abs(dx[i]) >= 1e-15 * (1.0 + abs(xs[p, i])):
                    small = False
            if small:
                break


@numba.njit(**_JIT)
def _newton_tables(n_eq, us, uv, ue, ps, pv, pe, terms, coef, xs, q, plan, iterations):
    """``_newton_core`` on the tables (a system without generated kernels)."""
    workspace = _table_workspace(n_eq, us, uv, ue, ps, pv, pe, terms, coef, xs.shape[1])
    _newton_core(
        _this._table_coefficients,
        _this._table_residual_jacobian,
        workspace,
        xs,
        q,
        plan,
        iterations,
    )


@numba.njit(**_JIT)
def newton_generated(coefficients, residual_jacobian, n_coefficients, xs, q, plan, iterations):
    """Newton's method from every row of ``xs`` in place, on a system's generated kernels
    (``coefficients``, ``residual_jacobian`` and ``N_COEFFICIENTS`` of its kernel module; see
    :func:`track_generated` for why the caller is a compiled function naming them)."""
    w = np.empty(n_coefficients, np.complex128)
    _newton_core(coefficients, residual_jacobian, w, xs, q, plan, iterations)


def _options_vector(o: HomotopyOptions) -> np.ndarray:
    if o.predictor not in ("hermite", "rk4"):
        raise ValueError(f"HomotopyOptions.predictor: 'hermite' or 'rk4', got {o.predictor!r}")
    if o.predictor == "hermite" and o.hermite_points < 2:
        raise ValueError("HomotopyOptions.hermite_points: at least 2")
    return np.array(
        [
            o.initial_step,
            o.max_step,
            o.min_step,
            o.predictor_tolerance,
            o.corrector_tolerance,
            float(o.max_steps),
            o.divergence,
            float(o.corrector_iterations),
            float(o.hermite_points if o.predictor == "hermite" else 0),
            o.growth_tolerance,
            1.0 if o.corrector_estimate else 0.0,
            o.estimate_order,
            o.estimate_order_until,
        ]
    )


def track_once(
    system: PolynomialSystem,
    start_parameters: np.ndarray,
    target_parameters: np.ndarray,
    start_solutions: np.ndarray,
    detour: np.ndarray | None = None,
    options: HomotopyOptions | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One try over the given paths: (endpoints, status, steps)."""
    o = options or HomotopyOptions()
    q0 = np.ascontiguousarray(start_parameters, dtype=np.complex128)
    q1 = np.ascontiguousarray(target_parameters, dtype=np.complex128)
    d = np.zeros_like(q0) if detour is None else np.ascontiguousarray(detour, np.complex128)
    xs = np.ascontiguousarray(start_solutions, dtype=np.complex128)
    x_end = np.empty_like(xs)
    status = np.empty(xs.shape[0], np.int64)
    steps = np.empty(xs.shape[0], np.int64)
    t_end = np.empty(xs.shape[0], np.float64)
    if system.tracker is not None:
        plan = system.elimination
        system.tracker(q0, q1, d, xs, _options_vector(o), plan, x_end, status, steps, t_end)
    else:
        _track_paths(
            *system._args(),
            q0,
            q1,
            d,
            xs,
            _options_vector(o),
            system.elimination,
            x_end,
            status,
            steps,
            t_end,
        )
    _endgame(system, q1, x_end, status, t_end, o)
    return x_end, status, steps


def _endgame(
    system: PolynomialSystem,
    q1: np.ndarray,
    x: np.ndarray,
    status: np.ndarray,
    t_end: np.ndarray,
    o: HomotopyOptions,
) -> None:
    """Paths that stalled close to t = 1 (a near-double solution there: phi near 0 or 180
    degrees, c' near c) finish by Newton's method at t = 1, which converges there, if slowly."""
    for p in np.flatnonzero((status == STEP_TOO_SMALL) & (t_end >= o.endgame_start)):
        y = x[p].copy()
        for _ in range(o.endgame_iterations):
            f, jac = system.evaluate(y, q1)
            try:
                dx = np.linalg.solve(jac, f)
            except np.linalg.LinAlgError:
                break
            y = y - dx
            if not np.all(np.isfinite(y)):
                break
            if np.linalg.norm(dx) <= 1e-12 * (1 + np.linalg.norm(y)):
                break
        if np.all(np.isfinite(y)) and np.linalg.norm(y - x[p]) <= 1e-2 * (1 + np.linalg.norm(y)):
            f, _ = system.evaluate(y, q1)
            fy = np.linalg.norm(f)
            if fy <= 1e-10 * (1 + np.linalg.norm(y)) ** 8:
                x[p] = y
                status[p] = OK


DEGENERATE_TOLERANCE = 1e-10
"""An unknown of ``PolynomialSystem.nonzero`` below this, relative to 1 + |x|, is zero.  Seed
600,125 of the minimal bench, in one process of two: a whole second homotopy ended at tan^2
alpha, tan^2 beta about 1e-12 with cos^2 phi about 6e4 (the spurious component tan alpha =
tan beta = 0, where the lean polynomial vanishes identically) and that point took the place
of a real solution (tan^2 alpha = 289).  At 1e-10 a real shape is refused only with alpha or
beta below 1e-5 radians, a tangent along AB, which ``minimal.check_four_frames`` refuses."""


def degenerate(system: PolynomialSystem, x: np.ndarray) -> np.ndarray:
    """For each row of ``x`` (or the one vector): is one of the system's ``nonzero`` unknowns
    zero there (relative to 1 + |x|)?  Non-finite rows count as degenerate."""
    rows = np.atleast_2d(x)
    out = ~np.all(np.isfinite(rows), axis=1)
    if system.nonzero:
        with np.errstate(invalid="ignore"):
            size = 1.0 + np.linalg.norm(np.where(np.isfinite(rows), rows, 0), axis=1)
            small = np.abs(rows[:, list(system.nonzero)]) <= DEGENERATE_TOLERANCE * size[:, None]
        out |= np.any(small, axis=1)
    return out if np.ndim(x) == 2 else out[:1]


def _mark_degenerate(system: PolynomialSystem, x: np.ndarray, status: np.ndarray) -> None:
    """Paths that ended OK on a degenerate point (``degenerate``) failed: ``DEGENERATE``."""
    ok = np.flatnonzero(status == OK)
    if ok.size and system.nonzero:
        status[ok[degenerate(system, x[ok])]] = DEGENERATE


def _close_pairs(ends: np.ndarray, tol: float) -> np.ndarray:
    """(n, n) matrix: are rows i and j of ``ends`` within ``tol`` (1 + the smaller norm)?

    Full distances only for the pairs whose first coordinates are that close (a distance is at
    least that difference): the full (104, 104, 9) difference cost 2.1 ms a solve, this 0.1."""
    size = np.linalg.norm(ends, axis=1)
    limit = tol * (1.0 + np.minimum(size[:, None], size[None, :]))
    i, j = np.nonzero(np.abs(ends[:, None, 0] - ends[None, :, 0]) <= limit)
    close = np.zeros(limit.shape, dtype=bool)
    close[i, j] = np.linalg.norm(ends[i] - ends[j], axis=1) <= limit[i, j]
    return close


def _coincide(x: np.ndarray, rows: np.ndarray, others: np.ndarray, tol: float) -> np.ndarray:
    """For each index in ``rows``: does x[row] coincide with x[k] for some k in ``others``?"""
    out = np.zeros(rows.size, dtype=bool)
    if rows.size == 0 or others.size == 0:
        return out
    a, b = x[rows], x[others]
    dist = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    scale = 1.0 + np.minimum(np.linalg.norm(a, axis=1)[:, None], np.linalg.norm(b, axis=1)[None, :])
    same = rows[:, None] == others[None, :]
    return np.any((dist <= tol * scale) & ~same, axis=1)


def _deflated_newton(
    system: PolynomialSystem,
    q: np.ndarray,
    x: np.ndarray,
    roots: np.ndarray,
    a: np.ndarray,
    iterations: int = 60,
) -> np.ndarray | None:
    """Newton's method on F(x) / prod_r a.(x - r): it cannot converge to a known root r.

    The deflated step is the plain Newton step u = F_x^-1 F scaled by 1 / (1 - sum_r
    a.u / a.(x - r)) (Sherman-Morrison; Farrell, Birkisson and Funke 2015, with a holomorphic
    deflation factor so that it applies to complex solutions).  Returns the new root or None.
    """
    for _ in range(iterations):
        f, jac = system.evaluate(x, q)
        try:
            u = np.linalg.solve(jac, f)
        except np.linalg.LinAlgError:
            return None
        denom = 1.0 - np.sum((a @ u) / ((x - roots) @ a))
        step = u / denom
        x = x - step
        if not np.all(np.isfinite(x)):
            return None
        if np.linalg.norm(step) <= 1e-13 * (1 + np.linalg.norm(x)):
            return x
    f, jac = system.evaluate(x, q)
    try:
        ok = np.linalg.norm(np.linalg.solve(jac, f)) <= 1e-9 * (1 + np.linalg.norm(x))
    except np.linalg.LinAlgError:  # a singular end point is no regular root
        return None
    return x if ok else None


def _recover_twins(
    system: PolynomialSystem,
    q1: np.ndarray,
    x: np.ndarray,
    status: np.ndarray,
    rng: np.random.Generator,
    tol: float,
) -> int:
    """Paths that kept landing on another path's endpoint r: r is usually one of two nearly
    coincident solutions (a near-double root), and the path belongs to the other.  Deflated
    Newton, with r and every other known endpoint nearby deflated, finds it: first from the
    twin's predicted place (``_twin_start``), then from a random point next to r.  Accepted
    only if it is a new solution.  Returns how many were recovered."""
    recovered = 0
    for p in np.flatnonzero(status == -1):
        ok = np.flatnonzero(status == OK)
        if ok.size == 0:
            break
        r = x[p]
        near = ok[np.argmin(np.linalg.norm(x[ok] - r, axis=1))]
        scale = 1.0 + np.linalg.norm(x[near])
        a = rng.normal(size=r.shape) + 1j * rng.normal(size=r.shape)
        jitter = 1e-3 * scale * (rng.normal(size=r.shape) + 1j * rng.normal(size=r.shape))
        close = ok[np.linalg.norm(x[ok] - x[near], axis=1) <= 0.1 * scale]
        for start in (_twin_start(system, q1, x[near]), x[near] + jitter):
            if start is None:
                continue
            y = _deflated_newton(system, q1, start, x[close], a)
            if y is None:
                continue
            dist = np.linalg.norm(x[ok] - y, axis=1) / (1.0 + np.linalg.norm(y))
            if dist.min() > tol and not degenerate(system, y)[0]:
                x[p] = y
                status[p] = OK
                recovered += 1
                break
    return recovered


def _recover_near_double(
    system: PolynomialSystem, q1: np.ndarray, x: np.ndarray, status: np.ndarray, tol: float
) -> int:
    """Paths still lost after every retry: the missing solutions are most often twins of
    near-double roots found by other paths (a path jumped between the two close solutions
    and the jump surfaced elsewhere as a duplicate).  Every found solution's twin is predicted
    (``_twin_start``), nearest first, and Newton's method from there fills a lost path's place
    with each new solution it reaches.  Seed 500,032 of the minimal bench: the duplicate was
    6.3 from the lost solution, whose twin was 0.067 from it.  Returns how many were found."""
    lost = list(np.flatnonzero(status != OK))
    ok = np.flatnonzero(status == OK)
    if not lost or ok.size == 0:
        return 0
    starts = [(k, _twin_start(system, q1, x[k])) for k in ok]
    starts = [(np.linalg.norm(y - x[k]), k, y) for k, y in starts if y is not None]
    found = 0
    for _, k, y0 in sorted(starts, key=lambda item: item[0]):
        known = np.flatnonzero(status == OK)
        y = _deflated_newton(system, q1, y0, x[k : k + 1], np.conj(y0 - x[k]))
        if y is None:
            continue
        dist = np.linalg.norm(x[known] - y, axis=1) / (1.0 + np.linalg.norm(y))
        if dist.min() > tol and not degenerate(system, y)[0]:
            slot = lost.pop(0)
            x[slot], status[slot] = y, OK
            found += 1
            if not lost:
                break
    return found


def _twin_start(system: PolynomialSystem, q: np.ndarray, r: np.ndarray) -> np.ndarray | None:
    """Where the twin of a near-double root r lies, to second order.

    Near r the system is nearly singular along one direction: the Jacobian's right and left
    singular vectors v, u of its smallest singular value.  Along the line r + h v the residual's
    component g(h) = u^H F(r + h v) = g'(0) h + g''(0) h^2 / 2 + ... vanishes at h = 0 (r) and
    at h = -2 g'(0) / g''(0): the twin (g'' by a central difference of u^H F_x v).  Seed
    500,032 of the minimal bench: the twin 0.067 from r (smallest singular value 1e-10 of the
    largest), predicted to 4.5e-4, where Newton's method converges to it and a random start
    1e-3 from r reached a complex solution instead."""
    f, jac = system.evaluate(r, q)
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(jac))):
        return None
    left, _, right_h = np.linalg.svd(jac)
    u, v = left[:, -1], right_h[-1].conj()
    eps = 1e-6 * (1.0 + np.linalg.norm(r))

    def slope(h: float) -> complex:
        return complex(np.vdot(u, system.evaluate(r + h * v, q)[1] @ v))

    curvature = (slope(eps) - slope(-eps)) / (2.0 * eps)
    if curvature == 0 or not np.isfinite(curvature):
        return None
    h = -2.0 * complex(np.vdot(u, jac @ v)) / curvature
    if not np.isfinite(h) or abs(h) > 0.1 * (1.0 + np.linalg.norm(r)):
        return None  # not a near-double root: its twin would not be near
    return r + h * v


def track(
    system: PolynomialSystem,
    target_parameters: np.ndarray,
    options: HomotopyOptions | None = None,
    duplicate_tolerance: float = 1e-8,
) -> TrackResult:
    """Every start solution of ``system`` tracked to ``target_parameters``, failures retried.

    Two paths cannot end at one regular solution, so when two endpoints coincide one path
    jumped: the endpoint is kept once (it is a solution) and the other path tracked again.
    A retried path follows a fresh random complex detour (the gamma trick) with more careful
    step control at each try (``HomotopyOptions.retries``); its endpoint is accepted only if
    no other path ended there.  Paths that stall just before t = 1 finish by Newton's method
    there (``_endgame``).  Paths still lost then are filled from whole second homotopies
    (``options.full_retries``: every path along a fresh detour, new endpoints only).  What
    still fails after that is reported in ``TrackResult.failures`` (a jump as 'duplicate')
    and its endpoint set to NaN: never dropped silently.
    """
    o = options or HomotopyOptions()
    q0 = system.start_parameters
    q1 = np.asarray(target_parameters, dtype=np.complex128)
    x, status, steps = track_once(system, q0, q1, system.start_solutions, None, o)
    _mark_degenerate(system, x, status)
    everyone = np.arange(x.shape[0])
    ok = np.flatnonzero(status == OK)
    # of endpoints that coincide, the first stays (it is a solution either way); the others
    # jumped and are tracked again
    # (one distance matrix: each path's _coincide with the earlier ones cost 70 us, 7 ms a
    # solve, as much as 5 % of it)
    close = _close_pairs(x[ok], duplicate_tolerance)
    kept = np.ones(ok.size, dtype=bool)
    # only rows close to an earlier one can be dropped (most solves have none: 104 np.any
    # calls cost 0.2 ms a solve)
    for k in np.flatnonzero(np.tril(close, -1).any(axis=1)):
        kept[k] = not np.any(close[k, :k] & kept[:k])
    status[ok[~kept]] = -1
    rng = np.random.default_rng(o.seed)
    retried = np.zeros(x.shape[0], dtype=bool)
    span = np.linalg.norm(q1 - q0) + 1e-300
    for attempt in range(1, o.retries + 1):
        bad = np.flatnonzero(status != OK)
        if bad.size == 0:
            break
        retried[bad] = True
        # each retry more careful than the last: smaller steps, tighter predictor, and a
        # smaller smallest step, so that a path near a singular point can still pass it
        careful = replace(
            o,
            predictor="rk4",
            max_step=o.max_step / 2**attempt,
            predictor_tolerance=o.predictor_tolerance / 10**attempt,
            min_step=o.min_step / 10**attempt,
            max_steps=o.max_steps * 2**attempt,
        )
        detour = rng.normal(size=q0.shape) + 1j * rng.normal(size=q0.shape)
        detour *= 0.25 * span / np.linalg.norm(detour)
        xi, si, ni = track_once(system, q0, q1, system.start_solutions[bad], detour, careful)
        x[bad], status[bad], steps[bad] = xi, si, ni
        _mark_degenerate(system, x, status)
        new_ok = bad[status[bad] == OK]
        others = everyone[status == OK]
        status[new_ok[_coincide(x, new_ok, others, duplicate_tolerance)]] = -1
    with np.errstate(all="ignore"):  # deflated Newton may overflow on a path it then rejects
        twins = _recover_twins(system, q1, x, status, rng, duplicate_tolerance)
    completed = 0
    for _ in range(o.full_retries):
        bad = np.flatnonzero(status != OK)
        if bad.size == 0:
            break
        detour = rng.normal(size=q0.shape) + 1j * rng.normal(size=q0.shape)
        detour *= 0.25 * span / np.linalg.norm(detour)
        xa, sa, _ = track_once(system, q0, q1, system.start_solutions, detour, o)
        sa[(sa == OK) & degenerate(system, xa)] = DEGENERATE
        for y in xa[sa == OK]:
            known = np.flatnonzero(status == OK)
            dist = np.linalg.norm(x[known] - y, axis=1)
            scale = 1.0 + np.minimum(np.linalg.norm(x[known], axis=1), np.linalg.norm(y))
            if known.size and np.any(dist <= duplicate_tolerance * scale):
                continue
            slot, bad = bad[0], bad[1:]
            x[slot], status[slot] = y, OK
            completed += 1
            if bad.size == 0:
                break
    if o.near_double_twins:
        with np.errstate(all="ignore"):
            twins += _recover_near_double(system, q1, x, status, duplicate_tolerance)
    failures: dict[str, int] = {}
    for code, name in ((-1, "duplicate"), *enumerate(STATUS_NAMES)):
        n = int(np.sum(status == code))
        if n and code != OK:
            failures[name] = n
    out = x.copy()
    out[status != OK] = np.nan
    return TrackResult(
        solutions=out,
        status=status,
        steps=steps,
        retried=int(retried.sum()),
        recovered=twins,
        completed=completed,
        failures=failures,
    )
