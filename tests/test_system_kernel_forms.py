"""The code generator's faster forms of a system's kernels: F, F_x and F_t nested in Horner
form (``PolynomialSystem.horner``) and the unrolled linear solve without the arithmetic on
entries of F_x that are always zero (``PolynomialSystem.sparse_solve``), as the perspective
fixed-axis kernels use them.  Checked on a small system shaped like that one (two unknowns
that occur in three equations each, the others in all six) against SymPy's own F, F_x, F_t
and against numpy's dense solve.
"""

from __future__ import annotations

import importlib.util
from dataclasses import replace
from pathlib import Path
from types import ModuleType

import numpy as np
import sympy as sp

from derivations.codegen.generate import render_system_kernel_module
from derivations.codegen.spec import PolynomialSystem as SystemRecord

B, C, N1, N2, M1, M2 = sp.symbols("b c n1 n2 m1 m2")
A, D = sp.symbols("a d")


def _equations() -> tuple[sp.Expr, ...]:
    """Per m in (m1, m2) three equations in (b or c or both, n1, n2, m), quadratic in m and in
    n, as the fixed axis's edge planes are."""
    out = []
    for k, m in enumerate((M1, M2)):
        s = k + 1
        out += [
            A * B * m**2 * N1**2 + s * m * N2 + D * B * m * N1 * N2 - m**2 + B - A,
            D * C * m**2 * N2**2 + A * m * N1 + s * C * m**2 * N1 - D + 2 * C * m,
            A * B * C * m**2 * N1 * N2 + D * m * N2**2 * m + B * m - C * N1 * m + s,
        ]
    return tuple(out)


def _module(tmp_path: Path, record: SystemRecord, name: str) -> ModuleType:
    path = tmp_path / f"{name}.py"
    path.write_text(render_system_kernel_module(source="tests", doc="Toy.", system=record))
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _evaluate(mod: ModuleType, x: np.ndarray, q: np.ndarray, dq: np.ndarray) -> tuple:
    w = np.empty(mod.N_COEFFICIENTS, np.complex128)
    wt = np.empty_like(w)
    f, ft = np.empty(6, np.complex128), np.empty(6, np.complex128)
    jac = np.empty((6, 6), np.complex128)
    mod.coefficients_t(q, dq, w, wt)
    mod.residual_jacobian_t(x, w, wt, f, jac, ft)
    f1, jac1 = np.empty_like(f), np.empty_like(jac)
    mod.residual_jacobian(x, w, f1, jac1)
    np.testing.assert_allclose(f1, f, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(jac1, jac, rtol=1e-14, atol=1e-14)
    return f, jac, ft


def test_horner_form_and_sparse_solve_agree_with_sympy_and_numpy(tmp_path: Path) -> None:
    eqs = _equations()
    plain = SystemRecord(
        name="toy",
        unknowns=(B, C, N1, N2, M1, M2),
        parameters=(A, D),
        equations=eqs,
        equation_names=tuple(f"e{i}" for i in range(6)),
        start_parameters=(1j, 2.0),
        start_solutions=((1.0,) * 6,),
        doc="A toy system.",
    )
    fast = replace(plain, horner=(B, C, M1, M2, N1, N2), sparse_solve=True)
    mod_plain = _module(tmp_path, plain, "toy_plain")
    mod_fast = _module(tmp_path, fast, "toy_fast")
    source_plain = (tmp_path / "toy_plain.py").read_text()
    source_fast = (tmp_path / "toy_fast.py").read_text()
    # the forms did change the code: fewer products in the residuals and in the solve
    assert source_fast.count("*") < 0.9 * source_plain.count("*")
    assert source_fast.count("fac = ") < source_plain.count("fac = ")

    da, dd = sp.symbols("da dd")
    jac_s = sp.Matrix(eqs).jacobian([B, C, N1, N2, M1, M2])
    ft_s = [sp.diff(e, A) * da + sp.diff(e, D) * dd for e in eqs]
    ref = sp.lambdify((B, C, N1, N2, M1, M2, A, D, da, dd), (list(eqs), jac_s, ft_s))
    rng = np.random.default_rng(11)
    plan = np.asarray(mod_fast.ELIMINATION, np.int64)
    for _ in range(6):
        x = rng.normal(size=6) + 1j * rng.normal(size=6)
        q = rng.normal(size=2) + 1j * rng.normal(size=2)
        dq = rng.normal(size=2) + 1j * rng.normal(size=2)
        f_ref, jac_ref, ft_ref = (np.array(v, complex) for v in ref(*x, *q, *dq))
        for mod in (mod_plain, mod_fast):
            f, jac, ft = _evaluate(mod, x, q, dq)
            scale = np.abs(f_ref).max() + np.abs(jac_ref).max()
            assert np.abs(f - f_ref).max() <= 1e-13 * scale
            assert np.abs(jac - jac_ref).max() <= 1e-13 * scale
            assert np.abs(ft - np.array(ft_ref, complex)).max() <= 1e-13 * np.abs(ft_ref).max()
        assert np.all(jac_ref[:3, 5] == 0) and np.all(jac_ref[3:, 4] == 0)  # the structure
        want, want2 = np.linalg.solve(jac_ref, f_ref), np.linalg.solve(jac_ref, ft_ref)
        for mod in (mod_plain, mod_fast):
            out, out2 = np.empty(6, complex), np.empty(6, complex)
            scratch = (np.empty((6, 6), complex), np.empty(6, complex), np.empty(6, complex))
            m, r, r2 = scratch
            assert mod.solve_pair(jac_ref, f_ref, ft_ref, out, out2, m, r, r2, plan, True)
            np.testing.assert_allclose(out, want, rtol=1e-10, atol=1e-12 * np.abs(want).max())
            np.testing.assert_allclose(out2, want2, rtol=1e-10, atol=1e-12 * np.abs(want2).max())
            one = np.empty(6, complex)
            assert mod.solve_pair(jac_ref, f_ref, f_ref, one, one, m, r, r, plan, False)
            np.testing.assert_allclose(one, want, rtol=1e-10, atol=1e-12 * np.abs(want).max())
