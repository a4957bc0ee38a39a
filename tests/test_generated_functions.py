"""Generated NumPy code agrees with the SymPy expressions it came from, and with geometry.

* Every generated function of measurement_model / frame_equations equals its SymPy outputs,
  evaluated independently with mpmath (30 digits), at seeded random points.
* The analytic Jacobians of the measurement model equal central finite differences.
* The measurement model equals an independent NumPy 3-D construction (SciPy rotations).
* Polynomial modules: observable_matrix @ unknown_columns equals the polynomial evaluated exactly
  (Fractions) at random rational points; unknown_columns_jacobian equals finite differences.
* The generated modules import without SymPy.
"""

from __future__ import annotations

import importlib
import subprocess
import sys
from fractions import Fraction
from functools import cache

import mpmath
import numpy as np
import pytest
import sympy as sp
from scipy.spatial.transform import Rotation

from derivations.codegen.generate import REPO_ROOT
from derivations.codegen.spec import FunctionSpec, PolynomialColumns

FUNCTION_MODULES = {
    "measurement_model": "derivations.measurement",
    "frame_equations": "derivations.section3",
}
POLYNOMIAL_MODULES = {
    "lean_polynomial": "derivations.lean",
    "polynomial_12p": "derivations.squaring",
}
N_POINTS = 12


def _generated(name: str):
    """The generated module, or skip if it has not been generated yet."""
    if not (REPO_ROOT / "generated" / f"{name}.py").exists():
        pytest.skip(f"generated/{name}.py does not exist yet")
    return importlib.import_module(f"curverecon.generated.{name}")


@cache
def _function_specs(module: str) -> tuple[FunctionSpec, ...]:
    return tuple(importlib.import_module(module).generated_functions())


@cache
def _polynomial_record(module: str) -> PolynomialColumns:
    return importlib.import_module(module).grouped_columns()


def _sample(name: str, rng: np.random.Generator, n: int) -> np.ndarray:
    """Random argument values in a sensible domain for an argument called ``name``."""
    if name in ("c", "cp"):
        return rng.uniform(0.6, 2.0, n)
    if name == "sin_tau":
        return rng.uniform(-0.9, 0.9, n)
    if name in ("tx", "ty"):
        return rng.uniform(-50.0, 50.0, n)
    return rng.uniform(-1.4, 1.4, n)


def _flat_outputs(spec: FunctionSpec) -> list[sp.Expr]:
    flat: list[sp.Expr] = []
    for value in spec.outputs.values():
        if isinstance(value, (sp.MatrixBase, tuple, list)):
            flat.extend(sp.sympify(v) for v in value)
        else:
            flat.append(sp.sympify(value))
    return flat


def _flat_generated(result: object, n: int) -> np.ndarray:
    arrays = result if isinstance(result, tuple) else (result,)
    return np.concatenate([np.asarray(a).reshape(n, -1) for a in arrays], axis=1)


def _cases() -> list[tuple[str, str]]:
    cases = []
    for generated, module in FUNCTION_MODULES.items():
        try:
            specs = _function_specs(module)
        except (ModuleNotFoundError, AttributeError):
            continue
        cases += [(generated, spec.name) for spec in specs]
    return cases


@pytest.mark.parametrize(("generated", "function"), _cases())
def test_function_matches_sympy(generated: str, function: str) -> None:
    module = _generated(generated)
    spec = next(s for s in _function_specs(FUNCTION_MODULES[generated]) if s.name == function)
    rng = np.random.default_rng(20240611 + sum(map(ord, function)))
    values = {a.name: _sample(a.name, rng, N_POINTS) for a in spec.args}
    got = _flat_generated(getattr(module, function)(**values), N_POINTS)
    flat = _flat_outputs(spec)
    assert got.shape == (N_POINTS, len(flat))
    evaluators = [sp.lambdify(spec.args, e, modules="mpmath") for e in flat]
    checked = 0
    with mpmath.workdps(30):
        for n in range(N_POINTS):
            point = [mpmath.mpf(float(values[a.name][n])) for a in spec.args]
            for k, evaluate in enumerate(evaluators):
                ref = evaluate(*point)
                if not isinstance(ref, (int, float, mpmath.mpf)) or not mpmath.isfinite(ref):
                    continue  # outside the real domain at this random point
                assert got[n, k] == pytest.approx(float(ref), rel=1e-9, abs=1e-9), (
                    f"{function} output {k} at point {n}"
                )
                checked += 1
    assert checked >= N_POINTS * len(flat) // 2


# ---------------------------------------------------------------------------------------------
# Measurement model: geometry and Jacobians
# ---------------------------------------------------------------------------------------------

SHAPE = (100.0, 0.35, 0.8, 2.1)  # c, alpha, beta, phi


def _frames(n: int = 16, seed: int = 7) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    return (
        rng.uniform(-np.pi, np.pi, n),  # delta
        rng.uniform(-1.4, 1.4, n),  # tau
        rng.uniform(-np.pi, np.pi, n),  # theta
        rng.uniform(-80, 80, n),  # tx
        rng.uniform(-80, 80, n),  # ty
    )


def _construction(c, alpha, beta, phi, delta, tau, theta, tx, ty):
    """Independent 3-D construction: SciPy intrinsic z-y-x Euler angles, project, atan2."""
    rot = Rotation.from_euler("ZYX", np.column_stack([theta, tau, delta])).as_matrix()
    t = np.column_stack([tx, ty, np.zeros_like(tx)])
    a3 = rot @ np.zeros(3) + t
    b3 = rot @ np.array([c, 0.0, 0.0]) + t
    tan_a = rot @ np.array([np.cos(beta), np.sin(beta) * np.cos(phi), np.sin(beta) * np.sin(phi)])
    tan_b = rot @ np.array([-np.cos(alpha), np.sin(alpha), 0.0])
    pred = np.column_stack(
        [
            a3[:, 0],
            a3[:, 1],
            b3[:, 0],
            b3[:, 1],
            np.arctan2(tan_a[:, 1], tan_a[:, 0]),
            np.arctan2(tan_b[:, 1], tan_b[:, 0]),
        ]
    )
    return rot, (a3, b3, tan_a, tan_b), pred


def test_measurement_model_constants() -> None:
    mm = _generated("measurement_model")
    assert mm.GLOBAL_PARAMETERS == ("c", "alpha", "beta", "phi")
    assert mm.LOCAL_PARAMETERS == ("delta", "tau", "theta", "tx", "ty")
    assert mm.PREDICTIONS == ("ax", "ay", "bx", "by", "psi_a", "psi_b")


def test_measurement_model_matches_construction() -> None:
    mm = _generated("measurement_model")
    frames = _frames()
    rot, points, pred = _construction(*SHAPE, *frames)
    np.testing.assert_allclose(mm.rotation_matrix(*frames[:3]), rot, atol=1e-14)
    for got, ref in zip(mm.points_3d(*SHAPE, *frames), points, strict=True):
        assert got.shape == (16, 3)
        np.testing.assert_allclose(got, ref, atol=1e-12)
    np.testing.assert_allclose(mm.points_3d(*SHAPE, *frames)[0][:, 2], 0.0)
    np.testing.assert_allclose(mm.predict(*SHAPE, *frames), pred, atol=1e-12)
    p, jg, jl = mm.predict_with_jacobians(*SHAPE, *frames)
    assert p.shape == (16, 6) and jg.shape == (16, 6, 4) and jl.shape == (16, 6, 5)
    np.testing.assert_allclose(p, pred, atol=1e-12)


def test_measurement_model_broadcasting() -> None:
    mm = _generated("measurement_model")
    frames = _frames(n=5)
    assert mm.predict(*SHAPE, frames[0], 0.2, 0.3, 1.0, 2.0).shape == (5, 6)
    assert mm.predict(*SHAPE, 0.1, 0.2, 0.3, 1.0, 2.0).shape == (6,)
    assert mm.rotation_matrix(frames[0], 0.0, 0.0).shape == (5, 3, 3)
    out = mm.predict(*SHAPE, *frames)
    out[0, 0] = 1.0  # outputs are ordinary writable arrays


def test_measurement_jacobians_match_finite_differences() -> None:
    mm = _generated("measurement_model")
    args = [*SHAPE, *_frames(n=10, seed=3)]
    _, jg, jl = mm.predict_with_jacobians(*args)
    jac = np.concatenate([jg, jl], axis=2)
    for k, value in enumerate(args):
        h = 1e-6 * max(1.0, float(np.max(np.abs(value))))
        plus, minus = list(args), list(args)
        plus[k], minus[k] = value + h, value - h
        diff = mm.predict(*plus) - mm.predict(*minus)
        diff[:, 4:] = (diff[:, 4:] + np.pi) % (2 * np.pi) - np.pi  # angles across the cut
        np.testing.assert_allclose(jac[:, :, k], diff / (2 * h), rtol=1e-6, atol=1e-6)


def test_residual_curvature_matches_finite_differences() -> None:
    """sum_k u_k d2 m_k against central differences of J^T u (J checked against the geometry
    above), and exactly symmetric."""
    mm = _generated("measurement_model")
    rng = np.random.default_rng(11)
    frames = _frames(n=8, seed=5)
    u = rng.normal(size=(8, 6)) * np.array([1.0, 1.0, 1.0, 1.0, 40.0, 40.0])
    args = [np.full(8, v) for v in SHAPE] + list(frames)
    curvature = mm.residual_curvature(*args, *u.T)
    assert curvature.shape == (8, 9, 9)
    np.testing.assert_array_equal(curvature, np.swapaxes(curvature, 1, 2))

    def gradient(values: list[np.ndarray]) -> np.ndarray:
        _, jg, jl = mm.predict_with_jacobians(*values)
        return np.einsum("nki,nk->ni", np.concatenate([jg, jl], axis=2), u)

    for k, value in enumerate(args):
        h = 1e-6 * max(1.0, float(np.max(np.abs(value))))
        plus, minus = list(args), list(args)
        plus[k], minus[k] = value + h, value - h
        numeric = (gradient(plus) - gradient(minus)) / (2 * h)
        scale = 1.0 + np.max(np.abs(curvature[:, :, k]))
        np.testing.assert_allclose(curvature[:, :, k], numeric, rtol=0, atol=1e-6 * scale)
    # theta turns every image direction rigidly and tx, ty move only points: those rows vanish
    # when only the angles are weighted
    angles_only = mm.residual_curvature(*args, *(u * [0, 0, 0, 0, 1, 1]).T)
    np.testing.assert_array_equal(angles_only[:, 6:, :], 0.0)


# ---------------------------------------------------------------------------------------------
# Polynomial modules
# ---------------------------------------------------------------------------------------------


def _exact_value(u: object, unknowns: tuple[sp.Symbol, ...], point: tuple[Fraction, ...]):
    """u(point) exactly, as (value, sum of |terms|); u a SymPy expression or a ring element.

    Independent of the code generator: ring elements are evaluated term by term with Fractions,
    expressions by exact substitution of SymPy Rationals into each term of the sum.
    """
    if hasattr(u, "ring") and hasattr(u, "terms"):
        index = [[s.name for s in unknowns].index(str(g)) for g in u.ring.symbols]
        value, size = Fraction(0), Fraction(0)
        for m, cf in u.terms():
            term = Fraction(int(cf.numerator), int(cf.denominator))
            for g, e in enumerate(m):
                term *= point[index[g]] ** int(e)
            value += term
            size += abs(term)
        return value, size
    values = {
        s: sp.Rational(x.numerator, x.denominator) for s, x in zip(unknowns, point, strict=True)
    }
    terms = [term.xreplace(values) for term in sp.Add.make_args(sp.sympify(u))]
    value = sum(terms, sp.Integer(0))
    size = sum((abs(t) for t in terms), sp.Integer(0))
    return Fraction(int(value.p), int(value.q)), Fraction(int(size.p), int(size.q))


@pytest.mark.parametrize("generated", sorted(POLYNOMIAL_MODULES))
def test_polynomial_module_matches_exact_evaluation(generated: str) -> None:
    module = _generated(generated)
    try:
        record = _polynomial_record(POLYNOMIAL_MODULES[generated])
    except (ModuleNotFoundError, AttributeError):
        pytest.skip(f"{POLYNOMIAL_MODULES[generated]}.grouped_columns does not exist yet")
    assert module.UNKNOWNS == tuple(s.name for s in record.unknowns)
    assert module.OBSERVABLE_EXPONENTS == tuple(tuple(e) for e, _ in record.columns)
    rng = np.random.default_rng(11)
    for _ in range(3):
        unknowns = tuple(Fraction(int(rng.integers(5, 20)), 10) for _ in record.unknowns)
        observables = tuple(Fraction(int(rng.integers(5, 20)), 10) for _ in range(3))
        total, size = Fraction(0), Fraction(0)
        columns = []
        for (i, j, k), u in record.columns:
            value, magnitude = _exact_value(u, record.unknowns, unknowns)
            obs = observables[0] ** i * observables[1] ** j * observables[2] ** k
            total += obs * value
            size += abs(obs) * magnitude
            columns.append(value)
        got_columns = module.unknown_columns(*map(float, unknowns))
        scale = max(float(max(abs(c) for c in columns)), 1e-300)
        np.testing.assert_allclose(
            got_columns, np.array([float(c) for c in columns]), rtol=1e-12, atol=1e-12 * scale
        )
        matrix = module.observable_matrix(*(np.array([float(o)]) for o in observables))
        assert matrix.shape == (1, len(record.columns))
        got = float((matrix @ got_columns)[0])
        assert abs(got - float(total)) <= 1e-12 * float(size)


@pytest.mark.parametrize("generated", sorted(POLYNOMIAL_MODULES))
def test_polynomial_jacobian_matches_finite_differences(generated: str) -> None:
    module = _generated(generated)
    point = np.array([1.1, 0.7, 0.9, 0.4])[: len(module.UNKNOWNS)]
    jac = module.unknown_columns_jacobian(*point)
    assert jac.shape == (len(module.OBSERVABLE_EXPONENTS), len(module.UNKNOWNS))
    for v in range(len(point)):
        h = 1e-6
        plus, minus = point.copy(), point.copy()
        plus[v] += h
        minus[v] -= h
        fd = (module.unknown_columns(*plus) - module.unknown_columns(*minus)) / (2 * h)
        scale = np.max(np.abs(jac[:, v])) + 1.0
        np.testing.assert_allclose(jac[:, v], fd, rtol=1e-5, atol=1e-6 * scale)


@pytest.mark.parametrize("generated", sorted(POLYNOMIAL_MODULES))
def test_polynomial_monomial_columns(generated: str) -> None:
    module = _generated(generated)
    point = (1.3, 0.6, 0.8, 0.5)[: len(module.UNKNOWNS)]
    values = module.unknown_columns(*point)
    for column, coefficient, exponents in module.MONOMIAL_COLUMNS:
        expected = coefficient * np.prod([x**e for x, e in zip(point, exponents, strict=True)])
        assert values[column] == pytest.approx(expected, rel=1e-12)


# ---------------------------------------------------------------------------------------------
# Runtime independence from SymPy
# ---------------------------------------------------------------------------------------------


def test_generated_modules_import_without_sympy() -> None:
    names = sorted(p.stem for p in (REPO_ROOT / "generated").glob("*.py") if p.stem != "__init__")
    code = (
        "import sys\n"
        "sys.modules['sympy'] = None\n"
        "sys.modules['jinja2'] = None\n"
        "import importlib\n"
        f"for name in {names!r}:\n"
        "    importlib.import_module('curverecon.generated.' + name)\n"
        "import curverecon.generated.measurement_model as m\n"
        "assert m.predict(100.0, 0.3, 0.4, 1.0, [0.1, 0.2], 0.3, 0.1, 0.0, 0.0).shape == (2, 6)\n"
        "print(m.__file__)\n"
    )
    result = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd="/", check=False
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip().endswith("generated/measurement_model.py")


# ---------------------------------------------------------------------------------------------
# The printer
# ---------------------------------------------------------------------------------------------


def test_printer_style() -> None:
    """Small integer powers as products, ``np.`` prefix, sqrt and atan2 spelled for NumPy."""
    from derivations.codegen.printer import NumPyCodePrinter

    x, y = sp.symbols("x y")
    printer = NumPyCodePrinter()
    assert printer.doprint(x**2) == "x*x"
    assert printer.doprint((x + y) ** 3) == "(x + y)*(x + y)*(x + y)"
    assert printer.doprint(1 / x**2) == "1/(x*x)"
    assert printer.doprint(x**7) == "x**7"
    assert printer.doprint(sp.sqrt(x)) == "np.sqrt(x)"
    assert printer.doprint(sp.sin(x) * sp.cos(y)) == "np.sin(x)*np.cos(y)"
    assert printer.doprint(sp.atan2(y, x)) == "np.arctan2(y, x)"
    assert printer.doprint(sp.Float(0.1) * x) == "0.1*x"


@pytest.mark.parametrize(
    "expr",
    [
        "a/x**2",
        "-a/x**2",
        "-2*a*u*(x + y)/x**2",
        "a*x**2/y**3",
        "-x**2*y/(a**2 + 1)",
        "-x**3",
        "(x + y)**2/(a - x)**2",
        "a*sin(x**2)**2",
    ],
)
def test_printer_powers_in_products_evaluate_correctly(expr: str) -> None:
    """A power printed as a product stays one factor: ``a/(x*x)``, never ``a/x*x``."""
    from derivations.codegen.printer import NumPyCodePrinter

    symbols = sp.symbols("a u x y", real=True)
    e = sp.sympify(expr, locals={s.name: s for s in symbols})
    point = {"a": 1.3, "u": 0.4, "x": 0.7, "y": 2.1}
    code = NumPyCodePrinter().doprint(e)
    value = eval(code, {"np": np}, dict(point))  # noqa: S307 - our own printer's output
    assert value == pytest.approx(float(e.subs({s: point[s.name] for s in symbols})), rel=1e-13)
