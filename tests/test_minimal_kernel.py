"""The generated straight-line kernels of a parametric polynomial system (the minimal solver).

``make derive`` writes ``generated/minimal_unsquared_kernel.py`` from the same SymPy system as
the tables of ``generated/minimal_unsquared.py``: F(x; q) = W(q) u(x), F_x and F_t written out
after one CSE pass.  They are checked against the table-driven evaluation
(``PolynomialSystem.evaluate``), F_t against the derivative of that evaluation along the
parameter path (a Cauchy integral over a circle in t: exact for a polynomial in t up to
rounding), and the code generator on a small system against SymPy directly.
"""

from __future__ import annotations

import importlib.util
from dataclasses import replace

import numpy as np
import pytest
import sympy as sp
from curverecon.generated import minimal_unsquared_kernel as kernel

from curverecon.simulate import make_scene
from curverecon.solvers import homotopy, minimal
from derivations.codegen.generate import render_system_kernel_module
from derivations.codegen.spec import PolynomialSystem as SystemRecord


def _crandn(rng: np.random.Generator, n: int) -> np.ndarray:
    return rng.normal(size=n) + 1j * rng.normal(size=n)


def _kernel_eval(mod, x: np.ndarray, q: np.ndarray, dq: np.ndarray):  # type: ignore[no-untyped-def]
    n_eq, n_u = len(mod.EQUATIONS), len(mod.UNKNOWNS)
    w = np.empty(mod.N_COEFFICIENTS, np.complex128)
    wt = np.empty_like(w)
    f = np.empty(n_eq, np.complex128)
    ft = np.empty_like(f)
    jac = np.empty((n_eq, n_u), np.complex128)
    mod.coefficients_t(q, dq, w, wt)
    mod.residual_jacobian_t(x, w, wt, f, jac, ft)
    # the kernels without t give the same F and F_x
    w0, f0, jac0 = np.empty_like(w), np.empty_like(f), np.empty_like(jac)
    mod.coefficients(q, w0)
    mod.residual_jacobian(x, w0, f0, jac0)
    # and dW/dt alone (the tracker's second Newton iteration on) the same dW/dt
    wt0 = np.empty_like(wt)
    mod.coefficient_rates(q, dq, wt0)
    for got, want in ((w0, w), (f0, f), (jac0, jac), (wt0, wt)):
        assert np.abs(got - want).max() <= 1e-13 * np.abs(want).max()
    return f, jac, ft


def test_generated_kernels_agree_with_the_tables() -> None:
    """F, F_x equal the table-driven evaluation to 1e-12 relative at random complex points, and
    F_t = dF(x; q + t dq)/dt at t = 0: the mean of F(x; q + r e^(i theta) dq) e^(-i theta) / r
    over 32 points of a circle (exact for the polynomial of degree < 32 in t)."""
    system = minimal._system()
    assert kernel.UNKNOWNS == minimal.minimal_unsquared.UNKNOWNS
    rng = np.random.default_rng(5)
    n_points, radius = 32, 0.5
    roots = np.exp(2j * np.pi * np.arange(n_points) / n_points)
    for _ in range(6):
        x = _crandn(rng, system.n_unknowns)
        q = _crandn(rng, system.n_parameters)
        dq = _crandn(rng, system.n_parameters)
        f, jac, ft = _kernel_eval(kernel, x, q, dq)
        f_ref, jac_ref = system.evaluate(x, q)
        assert np.abs(f - f_ref).max() <= 1e-12 * np.abs(f_ref).max()
        assert np.abs(jac - jac_ref).max() <= 1e-12 * np.abs(jac_ref).max()
        on_circle = np.array([system.evaluate(x, q + radius * z * dq)[0] for z in roots])
        ft_ref = (on_circle * roots.conj()[:, None]).mean(axis=0) / radius
        scale = np.abs(on_circle).max() / radius
        assert np.abs(ft - ft_ref).max() <= 1e-12 * scale
        assert np.abs(ft_ref).max() > 1e-3 * scale  # a derivative that could be wrong


def test_the_code_generator_on_a_small_system(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """Any SymPy system in, kernels out: a 2 x 2 system with a constant coefficient, checked
    against SymPy's own F, F_x and F_t = F_q . dq."""
    x, y, a, b = sp.symbols("x y a b")
    eqs = (a * x**2 + b * x * y - 3, x * y**2 + a * b * y + b**2 - x)
    record = SystemRecord(
        name="toy",
        unknowns=(x, y),
        parameters=(a, b),
        equations=eqs,
        equation_names=("first", "second"),
        start_parameters=(1j, 2.0),
        start_solutions=((1.0, 2.0),),
        doc="A toy system.",
    )
    path = tmp_path / "toy_kernel.py"
    path.write_text(render_system_kernel_module(source="tests", doc="Toy.", system=record))
    spec = importlib.util.spec_from_file_location("toy_kernel", path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    assert mod.UNKNOWNS == ("x", "y") and mod.PARAMETERS == ("a", "b")
    da, db = sp.symbols("da db")
    jac_s = sp.Matrix(eqs).jacobian([x, y])
    ft_s = [sp.diff(e, a) * da + sp.diff(e, b) * db for e in eqs]
    ref = sp.lambdify((x, y, a, b, da, db), (list(eqs), jac_s, ft_s))
    rng = np.random.default_rng(3)
    for _ in range(4):
        xv, qv, dqv = _crandn(rng, 2), _crandn(rng, 2), _crandn(rng, 2)
        f, jac, ft = _kernel_eval(mod, xv, qv, dqv)
        f_ref, jac_ref, ft_ref = ref(*xv, *qv, *dqv)
        np.testing.assert_allclose(f, np.array(f_ref, complex), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(jac, np.array(jac_ref, complex), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(ft, np.array(ft_ref, complex), rtol=1e-13, atol=1e-13)


def test_the_kernel_tracker_follows_the_same_paths_as_the_tables() -> None:
    """One four-frame scene from the 3-D generator: every path tracked on the generated kernels
    ends where the table-driven tracker's does (same status, same endpoint up to rounding)."""
    system = minimal._system()
    assert system.tracker is not None
    tables = replace(system, tracker=None)
    obs = make_scene(np.random.default_rng(600_003), 4).observations
    scale = float(np.mean(obs.cp))
    target = np.column_stack([obs.cp, obs.dp, obs.ep]).ravel() / scale
    q0, xs = system.start_parameters, system.start_solutions
    xk, sk, _ = homotopy.track_once(system, q0, target, xs)
    xt, st, _ = homotopy.track_once(tables, q0, target, xs)
    assert np.array_equal(sk, st) and np.sum(sk == homotopy.OK) >= 100
    ok = sk == homotopy.OK
    rel = np.linalg.norm(xk[ok] - xt[ok], axis=1) / (1 + np.linalg.norm(xt[ok], axis=1))
    assert rel.max() < 1e-8


def test_the_linear_solves_eliminate_each_frames_own_unknown_first() -> None:
    """s_i occurs in two equations only (its frame's unsquared (12*) and its definition), so
    the column order puts s0..s3 first; the other unknowns occur in five or more."""
    system = minimal._system()
    names = [minimal.minimal_unsquared.UNKNOWNS[k] for k in system.column_order]
    assert names[:4] == ["s0", "s1", "s2", "s3"]


def test_the_elimination_plan_pairs_each_s_with_its_two_equations() -> None:
    """The plan (``PolynomialSystem.elimination``): s_i occurs in its frame's unsquared (12*)
    (row i) and its definition (row 4 + i) only, so each is one pair; (C, A, B, P, m) are left
    dense with m**2 - A B P (row 8) the one row in no pair."""
    system = minimal._system()
    names = minimal.minimal_unsquared.UNKNOWNS
    plan = system.elimination
    assert plan[0] == 9 and plan[1] == 4
    pairs = plan[2:14].reshape(4, 3)
    assert [names[v] for v in pairs[:, 0]] == ["s0", "s1", "s2", "s3"]
    assert [tuple(r) for r in pairs[:, 1:]] == [(0, 4), (1, 5), (2, 6), (3, 7)]
    assert sorted(names[v] for v in plan[14:19]) == ["A", "B", "C", "P", "m"]
    assert list(plan[19:]) == [8]


@pytest.mark.parametrize("seed", [600_003, 700_011])
def test_the_paired_elimination_solves_like_lapack(seed) -> None:
    """The tracker's linear solves (``homotopy._solve_pair``, two right-hand sides) on the
    minimal system's Jacobian along a scene's paths (3-D generator; points tracked part of the
    way) against numpy's LAPACK solve: the paired plan, and all nine columns dense.  Then with
    a pair's two rows scaled apart by 1e8 either way (the pivot is the other row)."""
    system = minimal._system()
    obs = make_scene(np.random.default_rng(seed), 4).observations
    scale = float(np.mean(obs.cp))
    target = np.column_stack([obs.cp, obs.dp, obs.ep]).ravel() / scale
    q0, xs = system.start_parameters, system.start_solutions[::10]
    qh = q0 + 0.6 * (target - q0)
    xh, st, _ = homotopy.track_once(system, q0, qh, xs)
    assert np.all(st == homotopy.OK)
    n = system.n_unknowns
    dense = np.array([n, 0, *system.column_order, *range(n)], dtype=np.int64)
    rng = np.random.default_rng(seed)
    m, r, r2 = np.empty((n, n), complex), np.empty(n, complex), np.empty(n, complex)
    for x in xh:
        _, jac = system.evaluate(x, qh)
        b, c = _crandn(rng, n), _crandn(rng, n)
        for factor in (1.0, 1e8, 1e-8):
            a = jac.copy()
            a[4] *= factor  # s0's definition: the pivot row of pair s0 changes
            want = np.linalg.solve(a, np.column_stack([b, c]))
            for plan in (system.elimination, dense):
                out, out2 = np.empty(n, complex), np.empty(n, complex)
                assert homotopy._solve_pair(a, b, c, out, out2, m, r, r2, plan, True)
                got = np.column_stack([out, out2])
                resid = np.abs(a @ got - np.column_stack([b, c])).max()
                assert resid < 1e-12 * np.abs(a).max() * (1 + np.abs(got).max())
                err = np.abs(got - want).max() / np.abs(want).max()
                assert err < 1e-9
    singular = np.zeros((n, n), complex)
    assert not homotopy._solve_pair(singular, b, c, out, out2, m, r, r2, system.elimination, True)


def test_newton_on_the_kernels_and_on_the_tables_reach_the_same_solutions() -> None:
    """Real solutions of a four-frame scene, moved by 1e-6: Newton's method on the generated
    kernels and on the tables brings each back to the same point, where F vanishes (1e-12
    of the Jacobian's scale) and the rows stay real."""
    system = minimal._system()
    assert system.newton is not None
    tables = replace(system, tracker=None, newton=None)
    obs = make_scene(np.random.default_rng(600_007), 4).observations
    scale = float(np.mean(obs.cp))
    target = np.column_stack([obs.cp, obs.dp, obs.ep]).ravel() / scale
    x = homotopy.track(system, target).solutions
    real = np.all(np.isfinite(x), axis=1) & np.all(np.abs(x.imag) < 1e-8 * (1 + np.abs(x)), axis=1)
    assert real.sum() >= 2
    rng = np.random.default_rng(0)
    start = x[real].real * (1 + 1e-6 * rng.normal(size=x[real].shape))
    by_kernels = system.polish(start, target, 8)
    by_tables = tables.polish(start, target, 8)
    assert np.array_equal(
        start, x[real].real * (1 + 1e-6 * np.random.default_rng(0).normal(size=x[real].shape))
    )  # the input is not modified
    rel = np.abs(by_kernels - by_tables) / (1 + np.abs(by_tables))
    assert rel.max() < 1e-10 and np.abs(by_kernels.imag).max() == 0
    for row in by_kernels:
        f, jac = system.evaluate(row, target)
        assert np.abs(f).max() < 1e-12 * np.abs(jac).max() * (1 + np.abs(row).max())
    assert np.abs(start - by_kernels).max() > 1e-9  # Newton moved them


def test_the_hermite_weights_reproduce_a_quintic() -> None:
    """The Hermite predictor's weights on three points (values and derivatives) give a
    polynomial of degree 5 exactly, inside and outside the points (the extrapolation)."""
    rng = np.random.default_rng(3)
    coef = rng.normal(size=6) + 1j * rng.normal(size=6)
    poly, deriv = np.polynomial.Polynomial(coef), np.polynomial.Polynomial(coef).deriv()
    th = np.array([0.1, 0.17, 0.3])
    wts, z, col = np.empty(6), np.empty(homotopy.hermite_scratch(3)), np.empty(6)
    for tt in (0.12, 0.3, 0.45, 0.6):
        homotopy._hermite_weights(th, 3, tt, wts, z, col)
        got = sum(wts[2 * j] * poly(th[j]) + wts[2 * j + 1] * deriv(th[j]) for j in range(3))
        assert abs(got - poly(tt)) < 1e-11 * np.abs(coef).sum()
    homotopy._hermite_weights(th, 2, 0.5, wts, z, col)  # two points: a cubic
    cubic = np.polynomial.Polynomial(coef[:4])
    got = sum(wts[2 * j] * cubic(th[j]) + wts[2 * j + 1] * cubic.deriv()(th[j]) for j in range(2))
    assert abs(got - cubic(0.5)) < 1e-11 * np.abs(coef).sum()


def test_the_hermite_table_gives_the_same_weights() -> None:
    """The tracker's split of the weights (``_hermite_table`` once a history, ``_hermite_at``
    each try) gives ``_hermite_weights``' numbers exactly, for two and three points."""
    th = np.array([0.1, 0.17, 0.3])
    for npts in (2, 3):
        z1, z2 = np.empty(homotopy.hermite_scratch(3)), np.empty(homotopy.hermite_scratch(3))
        w1, w2, col, table = np.empty(6), np.empty(6), np.empty(6), np.empty((6, 6))
        homotopy._hermite_table(th, npts, z2, table)
        for tt in (0.12, 0.3, 0.45, 0.6):
            homotopy._hermite_weights(th, npts, tt, w1, z1, col)
            homotopy._hermite_at(npts, tt, z2, table, w2)
            assert np.array_equal(w1[: 2 * npts], w2[: 2 * npts])


def _solve_both(a: np.ndarray, b: np.ndarray, c: np.ndarray, plan: np.ndarray):  # type: ignore[no-untyped-def]
    n = b.shape[0]
    out = []
    for solve in (kernel.solve_pair, homotopy._solve_pair):
        x, y = np.empty(n, complex), np.empty(n, complex)
        scratch = (np.empty((n, n), complex), np.empty(n, complex), np.empty(n, complex))
        ok = solve(a, b, c, x, y, *scratch, plan, True)
        x1 = np.empty(n, complex)
        ok1 = solve(a, b, b, x1, x1, *scratch, plan, False)
        out.append((ok, x, y, ok1, x1))
    return out


def test_the_generated_linear_solve_agrees_with_numpy() -> None:
    """The generated straight-line ``solve_pair`` (the elimination plan written out) on the
    system's Jacobians at random complex points, with rows scaled over six decades so that
    the pivoting branches are taken (a pair's second row larger or not): both right-hand
    sides equal numpy's solve (LAPACK) to 1e-10 relative and the tracker's loop solve to
    1e-12; a singular matrix (a zero column, a zero pair column) is refused."""
    system = minimal._system()
    plan = system.elimination
    assert tuple(kernel.ELIMINATION) == tuple(plan)
    assert system.tracker is not None  # the kernels are used
    rng = np.random.default_rng(11)
    q = np.asarray(minimal.minimal_unsquared.START_PARAMETERS, complex)
    n = len(kernel.UNKNOWNS)
    w = np.empty(kernel.N_COEFFICIENTS, complex)
    kernel.coefficients(q, w)
    swapped = []
    for _ in range(40):
        x = _crandn(rng, n)
        f, jac = np.empty(n, complex), np.empty((n, n), complex)
        kernel.residual_jacobian(x, w, f, jac)
        jac = jac * (10.0 ** rng.uniform(-3, 3, size=n))[:, None]  # rows of any size
        col, piv, oth = plan[2:5]
        swapped.append(abs(jac[oth, col]) > abs(jac[piv, col]))  # pair 0 pivots on its 2nd row
        b, c = _crandn(rng, n), _crandn(rng, n)
        (ok, x_gen, y_gen, ok1, x1_gen), (okl, x_loop, y_loop, _, _) = _solve_both(jac, b, c, plan)
        assert ok and ok1 and okl
        want_x, want_y = np.linalg.solve(jac, b), np.linalg.solve(jac, c)
        for got, want in ((x_gen, want_x), (y_gen, want_y), (x1_gen, want_x)):
            assert np.abs(got - want).max() <= 1e-10 * np.abs(want).max()
        cond = np.linalg.cond(jac)
        for got, loop in ((x_gen, x_loop), (y_gen, y_loop)):
            assert np.abs(got - loop).max() <= 1e-15 * cond * np.abs(loop).max()
    assert 0 < sum(swapped) < len(swapped)  # both of a pair's branches were taken
    for column in (0, int(plan[2])):  # C (dense) and s0 (a pair's unknown)
        singular = jac.copy()
        singular[:, column] = 0.0
        assert not _solve_both(singular, b, c, plan)[0][0]
        assert not _solve_both(singular, b, c, plan)[0][3]


@pytest.mark.parametrize("seed", [600_003, 700_011])
def test_the_hermite_predictor_follows_the_same_paths_as_rk4(seed) -> None:
    """The default Hermite predictor (``HomotopyOptions.predictor``) against the RK4 one on the
    same paths of a four-frame scene from the 3-D generator: every path ends OK, each at RK4's
    endpoint (1e-8 relative), with fewer linear solves (RK4: at least 5 a step; Hermite: about
    2, counted here as steps of each, which are at most 1.6 times RK4's)."""
    system = minimal._system()
    obs = make_scene(np.random.default_rng(seed), 4).observations
    scale = float(np.mean(obs.cp))
    target = np.column_stack([obs.cp, obs.dp, obs.ep]).ravel() / scale
    q0, xs = system.start_parameters, system.start_solutions
    rk4 = replace(homotopy.HomotopyOptions(), predictor="rk4")
    assert homotopy.HomotopyOptions().predictor == "hermite"
    xh, sh, nh = homotopy.track_once(system, q0, target, xs)
    xr, sr, nr = homotopy.track_once(system, q0, target, xs, None, rk4)
    assert np.all(sh == homotopy.OK) and np.all(sr == homotopy.OK)
    rel = np.linalg.norm(xh - xr, axis=1) / (1 + np.linalg.norm(xr, axis=1))
    assert rel.max() < 1e-8
    assert nh.sum() <= 1.6 * nr.sum()


def test_a_predictor_that_is_not_known_raises() -> None:
    system = minimal._system()
    with pytest.raises(ValueError, match="predictor"):
        homotopy.track_once(
            system,
            system.start_parameters,
            system.start_parameters,
            system.start_solutions[:1],
            None,
            homotopy.HomotopyOptions(predictor="pade"),
        )


def test_close_pairs_equal_the_full_distance_matrix() -> None:
    """The duplicate test's prefiltered distances (``homotopy._close_pairs``) give the same
    matrix as every distance, with rows that agree in their first coordinate but not elsewhere
    and near-duplicates on both sides of the tolerance."""
    rng = np.random.default_rng(8)
    ends = _crandn(rng, 60 * 9).reshape(60, 9) * 10.0 ** rng.integers(-2, 3, size=(60, 1))
    ends[1] = ends[0] * (1 + 1e-10)  # a duplicate
    ends[2] = ends[0] + 1e-5  # near, not within 1e-8
    ends[3, 0] = ends[4, 0]  # same first coordinate only
    ends[5] = ends[6] + 0.5e-8  # within 1e-8 (1 + |x|)
    size = np.linalg.norm(ends, axis=1)
    full = np.linalg.norm(ends[:, None, :] - ends[None, :, :], axis=2) <= 1e-8 * (
        1.0 + np.minimum(size[:, None], size[None, :])
    )
    got = homotopy._close_pairs(ends, 1e-8)
    assert np.array_equal(got, full)
    assert got[0, 1] and got[5, 6] and not got[0, 2] and not got[3, 4]
    assert homotopy._close_pairs(ends[:0], 1e-8).shape == (0, 0)


def test_poses_of_many_shapes_equal_the_poses_of_each() -> None:
    """``poses_from_shapes`` (every shape at once, as the minimal solver calls it) gives each
    shape's ``poses_from_shape`` exactly: the truth and random shapes, 4 to 8 frames."""
    from curverecon.solvers.pose import poses_from_shape, poses_from_shapes

    for seed in range(4):
        sc = make_scene(np.random.default_rng(seed), 4 + seed)
        rng = np.random.default_rng(seed)
        t = sc.truth
        shapes = np.array(
            [[t.c, t.alpha, t.beta, abs(t.phi)]]
            + [[t.c * rng.uniform(0.8, 3), *rng.uniform(0, 1.5, 2), rng.uniform(0, 3.1)]]
            + [[t.c * rng.uniform(0.8, 3), *rng.uniform(0, 1.5, 2), rng.uniform(0, 3.1)]]
        )
        poses, misfit = poses_from_shapes(sc.observations, shapes)
        assert poses.shape == (3, 4 + seed, 5) and misfit.shape == (3, 4 + seed)
        for k, shape in enumerate(shapes):
            one_pose, one_misfit = poses_from_shape(sc.observations, shape)
            assert np.array_equal(one_pose, poses[k]) and np.array_equal(one_misfit, misfit[k])
        assert misfit[0].max() < 1e-7  # the truth fits
    empty = poses_from_shapes(
        make_scene(np.random.default_rng(0), 4).observations, np.zeros((0, 4))
    )
    assert empty[0].shape == (0, 4, 5) and empty[1].shape == (0, 4)


def test_deflated_newton_gives_up_at_a_singular_end_point() -> None:
    """An end point whose Jacobian is singular is no regular root: None, not an exception."""
    from curverecon.solvers import homotopy

    class Flat:
        def evaluate(self, x, q):
            return np.ones(2, complex), np.zeros((2, 2), complex)

    x = np.array([1.0 + 0j, 2.0 + 0j])
    roots = np.array([[0.0 + 0j, 0.0 + 0j]])
    a = np.array([1.0 + 0.5j, -0.3 + 1j])
    assert homotopy._deflated_newton(Flat(), None, x, roots, a, iterations=0) is None
