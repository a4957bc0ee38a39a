"""Turn FunctionSpec / PolynomialColumns records into formatted NumPy modules.

The pipeline (after SymForce's ``Codegen``): flatten the outputs of one function, run one
``sympy.cse`` pass over all of them (temporaries ``_tmp0, _tmp1, ...`` from
``sympy.numbered_symbols``, canonical order), print every expression with
:class:`~derivations.codegen.printer.NumPyCodePrinter`, render ``templates/module.py.jinja``,
and pipe the text through the venv's pinned ``ruff format``.  Polynomials are not printed as
expressions at all: they become integer tables evaluated by a small vectorised routine.

The output depends only on the inputs: no timestamps, no absolute paths, no set/dict order
(everything iterated is sorted or comes in a fixed order).
"""

from __future__ import annotations

import difflib
import keyword
import shutil
import subprocess
import sys
import textwrap
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import jinja2
import numpy as np
import sympy as sp

from derivations.codegen.config import TEMPLATE_DIR, NumPyConfig
from derivations.codegen.printer import NumPyCodePrinter, ScalarCodePrinter
from derivations.codegen.spec import FunctionSpec, PolynomialColumns, PolynomialSystem

TEMPLATE_NAME = "module.py.jinja"
TEMPLATE_PATH = "derivations/codegen/templates/" + TEMPLATE_NAME
KERNEL_TEMPLATE_NAME = "kernel.py.jinja"
SYSTEM_KERNEL_TEMPLATE_NAME = "system_kernel.py.jinja"
REPO_ROOT = Path(__file__).resolve().parents[2]


# ---------------------------------------------------------------------------------------------
# Functions
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Output:
    """One output of a function: its flat components and the trailing shape they stack into."""

    name: str
    components: tuple[sp.Expr, ...]
    shape: tuple[int, ...]  # () scalar, (n,) tuple, (r, k) matrix


@dataclass(frozen=True)
class FunctionCode:
    """A printed function, ready for the ``function`` macro."""

    name: str
    args: tuple[str, ...]
    doc: str
    temporaries: tuple[tuple[str, str], ...]
    output_lines: tuple[str, ...]
    return_expr: str
    return_annotation: str


def _normalise_output(name: str, value: object) -> _Output:
    """Scalar expr -> shape (); tuple/list -> (n,); Matrix r x k -> (r, k)."""
    if isinstance(value, sp.MatrixBase):
        rows, cols = value.shape
        return _Output(name, tuple(sp.sympify(v) for v in value), (rows, cols))
    if isinstance(value, (tuple, list)):
        return _Output(name, tuple(sp.sympify(v) for v in value), (len(value),))
    return _Output(name, (sp.sympify(value),), ())


def _cse(spec: FunctionSpec, config: NumPyConfig) -> tuple[list[_Output], list, list]:
    """The outputs of ``spec`` and one ``sympy.cse`` pass over all their components."""
    outputs = [_normalise_output(name, value) for name, value in spec.outputs.items()]
    flat: list[sp.Expr] = [e for out in outputs for e in out.components]
    replacements, reduced = sp.cse(
        flat,
        symbols=sp.numbered_symbols("_tmp"),
        optimizations=config.cse_optimizations,
        order="canonical",
    )
    return outputs, replacements, reduced


def print_function(spec: FunctionSpec, config: NumPyConfig) -> FunctionCode:
    """One CSE pass over all outputs of ``spec`` and print it."""
    printer = NumPyCodePrinter(config)
    outputs = [_normalise_output(name, value) for name, value in spec.outputs.items()]
    flat: list[sp.Expr] = [e for out in outputs for e in out.components]
    arg_names = tuple(a.name for a in spec.args)
    free = set().union(*(e.free_symbols for e in flat)) if flat else set()
    unknown = sorted(s.name for s in free if s.name not in arg_names)
    if unknown:
        raise ValueError(f"{spec.name}: outputs use symbols that are not arguments: {unknown}")
    clashes = sorted(
        n for n in spec.outputs if n in arg_names or n.startswith("_") or not n.isidentifier()
    )
    if clashes:
        raise ValueError(f"{spec.name}: output names must be new identifiers: {clashes}")
    _, replacements, reduced = _cse(spec, config)
    temporaries = tuple((sym.name, printer.doprint(expr)) for sym, expr in replacements)
    lines: list[str] = []
    position = 0
    for out in outputs:
        parts = [printer.doprint(e) for e in reduced[position : position + len(out.components)]]
        position += len(out.components)
        if out.shape == ():
            lines.append(f"{out.name} = _full({parts[0]}, _shape)")
        elif any(e == 0 for e in reduced[position - len(out.components) : position]):
            # sparse (Jacobians, second derivatives): zeros first, then only the nonzero entries
            entries = [
                f"({k}, {part})"
                for k, (part, e) in enumerate(
                    zip(parts, reduced[position - len(out.components) : position], strict=True)
                )
                if e != 0
            ]
            stacked = f"_scatter(({', '.join(entries)},), {len(parts)}, _shape)"
            if len(out.shape) == 2:
                rows, cols = out.shape
                stacked += f".reshape((*_shape, {rows}, {cols}))"
            lines.append(f"{out.name} = {stacked}")
        else:
            stacked = f"_stack(({', '.join(parts)},), _shape)"
            if len(out.shape) == 2:
                rows, cols = out.shape
                stacked += f".reshape((*_shape, {rows}, {cols}))"
            lines.append(f"{out.name} = {stacked}")
    names = [out.name for out in outputs]
    if len(names) == 1:
        return_expr, annotation = names[0], "np.ndarray"
    else:
        return_expr = ", ".join(names)
        annotation = "tuple[" + ", ".join(["np.ndarray"] * len(names)) + "]"
    return FunctionCode(
        name=spec.name,
        args=arg_names,
        doc=wrap_doc(spec.doc, config.line_length - 8),
        temporaries=temporaries,
        output_lines=tuple(lines),
        return_expr=return_expr,
        return_annotation=annotation,
    )


@dataclass(frozen=True)
class KernelCode:
    """A printed scalar kernel, ready for ``templates/kernel.py.jinja``."""

    name: str
    args: tuple[str, ...]
    outputs: tuple[tuple[str, str], ...]  # (name, shape as text)
    doc: str
    temporaries: tuple[tuple[str, str], ...]
    output_lines: tuple[str, ...]


def print_kernel(spec: FunctionSpec, config: NumPyConfig) -> KernelCode:
    """``spec`` as a scalar numba kernel: float arguments, the outputs written into arrays the
    caller passes (after the arguments, in the order of ``spec.outputs``).  Every entry is
    written, zeros included, so the arrays need no initialisation.  One CSE pass over all
    outputs, as :func:`print_function`, printed by ``ScalarCodePrinter`` (``math``)."""
    printer = ScalarCodePrinter(config)
    outputs, replacements, reduced = _cse(spec, config)
    temporaries = tuple((sym.name, printer.doprint(expr)) for sym, expr in replacements)
    lines: list[str] = []
    position = 0
    shapes: list[tuple[str, str]] = []
    for out in outputs:
        parts = [printer.doprint(e) for e in reduced[position : position + len(out.components)]]
        position += len(out.components)
        shape = out.shape or (1,)
        shapes.append((out.name, "(" + ", ".join(str(d) for d in shape) + ",)"))
        for k, part in enumerate(parts):
            if len(shape) == 2:
                index = f"{k // shape[1]}, {k % shape[1]}"
            else:
                index = str(k)
            value = "0.0" if part == "0" else part
            lines.append(f"{out.name}[{index}] = {value}")
    return KernelCode(
        name=spec.name,
        args=tuple(a.name for a in spec.args),
        outputs=tuple(shapes),
        doc=wrap_doc(spec.doc, config.line_length - 8),
        temporaries=temporaries,
        output_lines=tuple(lines),
    )


# ---------------------------------------------------------------------------------------------
# Polynomials
# ---------------------------------------------------------------------------------------------


def _coefficient(value: object) -> int | Fraction:
    """A ring/SymPy coefficient as an exact Python int or Fraction."""
    if isinstance(value, int):
        return value
    if isinstance(value, sp.Rational):
        return Fraction(int(value.p), int(value.q))
    numerator = getattr(value, "numerator", None)
    denominator = getattr(value, "denominator", None)
    if numerator is not None and denominator is not None:
        # gmpy2 mpz/mpq, PythonMPQ and Fraction all expose these (as attributes or methods).
        num = numerator() if callable(numerator) else numerator
        den = denominator() if callable(denominator) else denominator
        return Fraction(int(num), int(den))
    rational = sp.Rational(sp.sympify(value))
    return Fraction(int(rational.p), int(rational.q))


def polynomial_terms(
    u: object, unknowns: Sequence[sp.Symbol]
) -> list[tuple[tuple[int, ...], int | Fraction]]:
    """Terms (exponents in ``unknowns`` order, exact coefficient) of u, sorted by exponents.

    ``u`` may be a SymPy expression, a ``Poly`` or a ``sympy.polys.rings.PolyElement`` (the
    latter is much faster for the 50,000-term (12') and is used when the derivation hands it
    over).  Generators of a ring that are not among ``unknowns`` must not occur.
    """
    names = [s.name for s in unknowns]
    if hasattr(u, "ring") and hasattr(u, "terms"):
        gens = [str(g) for g in u.ring.symbols]
        index = []
        for g in gens:
            index.append(names.index(g) if g in names else None)
        result: dict[tuple[int, ...], int | Fraction] = {}
        for monom, coeff in u.terms():
            exps = [0] * len(names)
            for g, e in enumerate(monom):
                if e:
                    if index[g] is None:
                        raise ValueError(f"generator {gens[g]} is not an unknown")
                    exps[index[g]] = int(e)
            result[tuple(exps)] = _coefficient(coeff)
        items = result.items()
    elif isinstance(u, sp.Poly):
        poly = u if [str(g) for g in u.gens] == names else sp.Poly(u.as_expr(), *unknowns)
        items = ((tuple(int(e) for e in m), _coefficient(cf)) for m, cf in poly.terms())
    else:
        items = _expanded_terms(sp.sympify(u), unknowns).items()
    return sorted(((m, c) for m, c in items if c != 0), key=lambda t: t[0])


def _expanded_terms(
    expr: sp.Expr, unknowns: Sequence[sp.Symbol]
) -> dict[tuple[int, ...], int | Fraction]:
    """Terms of an expanded polynomial expression, read off its Add/Mul/Pow tree directly.

    ``sympy.Poly(expr)`` takes tens of seconds on the 50,000 terms of (12'); this walk is linear.
    Expressions that are not already expanded sums of monomials fall back to ``sympy.Poly``.
    """
    position = {s: i for i, s in enumerate(unknowns)}
    result: dict[tuple[int, ...], int | Fraction] = {}
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_coeff_Mul()
        exps = [0] * len(unknowns)
        for factor in sp.Mul.make_args(rest):
            if factor == 1:
                continue
            base, e = factor.as_base_exp()
            if base not in position or not (e.is_Integer and e >= 0):
                poly = sp.Poly(expr, *unknowns)
                return {tuple(int(x) for x in m): _coefficient(cf) for m, cf in poly.terms()}
            exps[position[base]] += int(e)
        key = tuple(exps)
        result[key] = result.get(key, 0) + _coefficient(coeff)
    return result


def _literal(value: int | Fraction, config: NumPyConfig) -> str:
    if isinstance(value, Fraction) and value.denominator != 1:
        return config.format_float(float(value))
    return str(int(value))


def _pack(items: Iterable[str], width: int) -> list[str]:
    """Greedy packing of ``item,`` tokens into lines of at most ``width`` characters.

    An item may be a group (``"0, 2, 6, 8"``, one monomial); groups are never split across lines.
    """
    lines: list[str] = []
    current = ""
    for item in items:
        token = item + ","
        if current and len(current) + 1 + len(token) > width:
            lines.append(current)
            current = token
        else:
            current = f"{current} {token}" if current else token
    if current:
        lines.append(current)
    return lines


@dataclass(frozen=True)
class PolynomialCode:
    """A PolynomialColumns record as tables, ready for ``polynomial.py.jinja``."""

    unknowns: tuple[str, ...]
    observables: tuple[str, ...]
    unknowns_repr: str
    observables_repr: str
    facts_repr: str
    observable_exponents: tuple[str, ...]
    monomial_columns: tuple[str, ...]
    n_columns: int
    n_monomials: int
    n_terms: int
    length_degree: int | None  # total degree in (c, observables) if homogeneous, else None
    unknown_degrees: str
    observable_degrees: str
    monomial_rows: tuple[str, ...]
    term_rows: tuple[str, ...]
    coefficient_rows: tuple[str, ...]


def _plain_literal(value: object) -> str:
    """A deterministic Python literal of plain data (dicts with sorted keys, tuples, scalars)."""
    if isinstance(value, (bool, int, str)) or value is None:
        return repr(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, Fraction):
        return repr(float(value)) if value.denominator != 1 else repr(int(value))
    if isinstance(value, (tuple, list)):
        items = [_plain_literal(v) for v in value]
        return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"
    if isinstance(value, dict):
        keys = sorted(value, key=str)
        return (
            "{" + ", ".join(f"{_plain_literal(k)}: {_plain_literal(value[k])}" for k in keys) + "}"
        )
    if isinstance(value, sp.Integer):
        return repr(int(value))
    return repr(str(value))


def _repr_facts(facts: dict[str, object]) -> str:
    """A deterministic literal of the derivation's facts (sorted keys, plain values only)."""
    return _plain_literal(dict(facts))


def wrap_doc(text: str, width: int) -> str:
    """Re-wrap only the lines of ``text`` longer than ``width`` (lists and layout are kept)."""
    lines: list[str] = []
    for line in text.strip().split("\n"):
        if len(line) <= width:
            lines.append(line.rstrip())
            continue
        indent = line[: len(line) - len(line.lstrip())]
        lines += textwrap.wrap(
            line.strip(),
            width=width,
            initial_indent=indent,
            subsequent_indent=indent,
            break_on_hyphens=False,
        )
    return "\n".join(lines)


def print_polynomial(record: PolynomialColumns, config: NumPyConfig) -> PolynomialCode:
    """Tables of a grouped polynomial: distinct unknown monomials, terms, coefficients."""
    unknowns = tuple(s.name for s in record.unknowns)
    observables = tuple(s.name for s in record.observables)
    if len(observables) != 3:
        raise ValueError("PolynomialColumns expects three observables (cp, dp, ep)")
    column_terms = [polynomial_terms(u, record.unknowns) for _, u in record.columns]
    monomials = sorted({m for terms in column_terms for m, _ in terms})
    monomial_index = {m: i for i, m in enumerate(monomials)}
    term_items: list[str] = []
    coefficient_items: list[str] = []
    monomial_columns: list[str] = []
    for k, terms in enumerate(column_terms):
        for m, coeff in terms:
            term_items.append(f"{k}, {monomial_index[m]}")
            coefficient_items.append(_literal(coeff, config))
        if len(terms) == 1:
            m, coeff = terms[0]
            monomial_columns.append(f"({k}, {_literal(coeff, config)}, {tuple(m)!r})")
    width = config.line_length - len(config.indent) - 4
    # Homogeneity in the lengths: the unknown "c" and the three observables carry a length.
    c_index = unknowns.index("c") if "c" in unknowns else None
    length_degrees = {
        sum(int(x) for x in e) + (m[c_index] if c_index is not None else 0)
        for (e, _), terms in zip(record.columns, column_terms, strict=True)
        for m, _ in terms
    }
    n_u = len(unknowns)
    unknown_degrees = tuple(max((m[v] for m in monomials), default=0) for v in range(n_u))
    observable_degrees = tuple(
        max((int(e[v]) for e, _ in record.columns), default=0) for v in range(3)
    )
    return PolynomialCode(
        unknowns=unknowns,
        observables=observables,
        unknowns_repr=repr(unknowns),
        observables_repr=repr(observables),
        facts_repr=_repr_facts(dict(record.facts)),
        observable_exponents=tuple(repr(tuple(int(x) for x in e)) for e, _ in record.columns),
        monomial_columns=tuple(monomial_columns),
        n_columns=len(record.columns),
        n_monomials=len(monomials),
        n_terms=len(coefficient_items),
        length_degree=next(iter(length_degrees)) if len(length_degrees) == 1 else None,
        unknown_degrees=repr(unknown_degrees),
        observable_degrees=repr(observable_degrees),
        monomial_rows=tuple(_pack((", ".join(map(str, m)) for m in monomials), width)),
        term_rows=tuple(_pack(term_items, width)),
        coefficient_rows=tuple(_pack(coefficient_items, width)),
    )


@dataclass(frozen=True)
class SystemCode:
    """A PolynomialSystem record as tables, ready for ``system.py.jinja``."""

    unknowns_repr: str
    parameters_repr: str
    equations_repr: str
    facts_repr: str
    n_unknowns: int
    n_parameters: int
    n_unknown_monomials: int
    n_parameter_monomials: int
    n_terms: int
    n_solutions: int
    unknown_rows: tuple[str, ...]
    parameter_rows: tuple[str, ...]
    term_rows: tuple[str, ...]
    coefficient_rows: tuple[str, ...]
    start_parameter_rows: tuple[str, ...]
    start_solution_rows: tuple[str, ...]


def complex_literal(value: complex, digits: int = 17) -> str:
    """``complex(re, im)`` with both parts printed to ``digits`` significant digits."""
    z = complex(value)
    return f"complex({z.real:.{digits}g}, {z.imag:.{digits}g})"


def system_terms(
    equations: Sequence[sp.Expr],
    unknowns: Sequence[sp.Symbol],
    parameters: Sequence[sp.Symbol],
) -> tuple[list[tuple[int, ...]], list[tuple[int, ...]], list[tuple[int, int, int, int]]]:
    """A parametric system as tables: the sorted unknown monomials, the sorted parameter
    monomials, and every term as (equation, parameter monomial, unknown monomial, integer
    coefficient), in a fixed order.  The generated module's tables and the derivation's own
    monodromy (``derivations.minimal``) both come from here."""
    gens = tuple(unknowns) + tuple(parameters)
    n_u = len(unknowns)
    per_equation = [sp.Poly(sp.expand(e), *gens).terms() for e in equations]
    umons = sorted({m[:n_u] for ts in per_equation for m, _ in ts})
    pmons = sorted({m[n_u:] for ts in per_equation for m, _ in ts})
    u_index = {m: i for i, m in enumerate(umons)}
    p_index = {m: i for i, m in enumerate(pmons)}
    terms: list[tuple[int, int, int, int]] = []
    for a, ts in enumerate(per_equation):
        for m, coeff in sorted(ts):
            if not coeff.is_Integer:
                raise ValueError(f"non-integer coefficient {coeff} in equation {a}")
            terms.append((a, p_index[m[n_u:]], u_index[m[:n_u]], int(coeff)))
    return umons, pmons, terms


def print_system(record: PolynomialSystem, config: NumPyConfig) -> SystemCode:
    """Tables of a parametric polynomial system: every term as (equation, parameter monomial,
    unknown monomial) with its integer coefficient; monomials sorted, so the order is fixed."""
    n_u = len(record.unknowns)
    umons, pmons, terms = system_terms(record.equations, record.unknowns, record.parameters)
    term_items = [f"{a}, {j}, {k}" for a, j, k, _ in terms]
    coefficient_items = [str(c) for *_, c in terms]
    width = config.line_length - len(config.indent) - 4
    return SystemCode(
        unknowns_repr=repr(tuple(s.name for s in record.unknowns)),
        parameters_repr=repr(tuple(s.name for s in record.parameters)),
        equations_repr=repr(tuple(record.equation_names)),
        facts_repr=_repr_facts(dict(record.facts)),
        n_unknowns=n_u,
        n_parameters=len(record.parameters),
        n_unknown_monomials=len(umons),
        n_parameter_monomials=len(pmons),
        n_terms=len(term_items),
        n_solutions=len(record.start_solutions),
        unknown_rows=tuple(_pack((", ".join(map(str, m)) for m in umons), width)),
        parameter_rows=tuple(_pack((", ".join(map(str, m)) for m in pmons), width)),
        term_rows=tuple(_pack(term_items, width)),
        coefficient_rows=tuple(_pack(coefficient_items, width)),
        start_parameter_rows=tuple(complex_literal(z) for z in record.start_parameters),
        start_solution_rows=tuple(
            "(" + ", ".join(complex_literal(z) for z in row) + ")" for row in record.start_solutions
        ),
    )


@dataclass(frozen=True)
class ArrayKernelCode:
    """A printed straight-line kernel on arrays, ready for ``templates/system_kernel.py.jinja``.

    ``loads`` read the scalar inputs out of the argument arrays (``C = x[0]``), ``temporaries``
    are the common subexpressions, ``stores`` write every output entry (zeros included)."""

    name: str
    args: tuple[str, ...]
    outputs: tuple[str, ...]
    doc: str
    loads: tuple[tuple[str, str], ...]
    temporaries: tuple[tuple[str, str], ...]
    stores: tuple[tuple[str, str], ...]


def print_array_kernel(
    name: str,
    inputs: Sequence[tuple[str, Sequence[sp.Symbol]]],
    outputs: Sequence[tuple[str, sp.Expr | sp.MatrixBase | Sequence[sp.Expr]]],
    doc: str,
    config: NumPyConfig,
) -> ArrayKernelCode:
    """A straight-line numba kernel: scalar symbols read from input arrays (``inputs``: (array
    name, its symbols in index order)), one ``sympy.cse`` pass over every output component
    (temporaries ``_tmp0, _tmp1, ...``), every output entry written into the output arrays
    (``outputs``: (array name, expressions); a Matrix is written as a 2-D array).  The
    arithmetic is whatever the arguments hold (complex128 for a homotopy)."""
    printer = ScalarCodePrinter(config)
    # Each input symbol becomes a local variable of its own name, unless that name is taken
    # (an array argument, a module name, a keyword, another input, a temporary): then
    # ``_<array>_<index>``.
    reserved = {a for a, _ in inputs} | {a for a, _ in outputs} | {"math", "np", "numba"}
    local: dict[sp.Symbol, sp.Symbol] = {}
    loads: list[tuple[str, str]] = []
    for array, symbols in inputs:
        for k, sym in enumerate(symbols):
            if sym in local:
                raise ValueError(f"{name}: {sym.name!r} is read from two inputs")
            text = sym.name
            if (
                not text.isidentifier()
                or keyword.iskeyword(text)
                or text in reserved
                or text.startswith("_")
            ):
                text = f"_{array}_{k}"
            reserved.add(text)
            local[sym] = sp.Symbol(text)
            loads.append((text, f"{array}[{k}]"))
    flat: list[sp.Expr] = []
    index: list[tuple[str, str]] = []
    for out_name, value in outputs:
        if isinstance(value, sp.MatrixBase):
            rows, cols = value.shape
            for r in range(rows):
                for c in range(cols):
                    flat.append(sp.sympify(value[r, c]).xreplace(local))
                    index.append((out_name, f"{r}, {c}"))
        else:
            for k, e in enumerate(value):  # type: ignore[arg-type]
                flat.append(sp.sympify(e).xreplace(local))
                index.append((out_name, str(k)))
    used = set().union(*(e.free_symbols for e in flat)) if flat else set()
    unknown = sorted(s.name for s in used if s not in set(local.values()))
    if unknown:
        raise ValueError(f"{name}: outputs use symbols that are not inputs: {unknown}")
    loads = [(text, where) for text, where in loads if sp.Symbol(text) in used]
    replacements, reduced = sp.cse(
        flat,
        symbols=sp.numbered_symbols("_tmp"),
        optimizations=config.cse_optimizations,
        order="canonical",
    )
    temporaries = tuple((sym.name, printer.doprint(expr)) for sym, expr in replacements)
    stores = []
    for (array, idx), e in zip(index, reduced, strict=True):
        text = printer.doprint(e)
        stores.append((f"{array}[{idx}]", "0.0" if text == "0" else text))
    args = tuple(a for a, _ in inputs) + tuple(a for a, _ in outputs)
    return ArrayKernelCode(
        name=name,
        args=args,
        outputs=tuple(a for a, _ in outputs),
        doc=wrap_doc(doc, config.line_length - 8),
        loads=tuple(loads),
        temporaries=temporaries,
        stores=tuple(stores),
    )


@dataclass(frozen=True)
class SystemKernelCode:
    """A PolynomialSystem's straight-line kernels, ready for ``system_kernel.py.jinja``."""

    unknowns_repr: str
    parameters_repr: str
    equations_repr: str
    n_coefficients: int
    coefficient_rows: tuple[str, ...]
    kernels: tuple[ArrayKernelCode, ...]
    elimination_repr: str
    """The linear solves' elimination plan (``curverecon.solvers.homotopy._elimination_plan``)."""
    solver_lines: tuple[str, ...]
    """The body of ``solve_pair``, that plan written out (:func:`print_linear_solver`)."""
    solver_one_lines: tuple[str, ...]
    """The body of ``solve_one``, the same for one right-hand side."""
    dense_unknowns: int = 0
    """Unknowns of the plan's dense system; when the solve is not unrolled (``solver_lines``
    empty) the tracker's own loop solve is used and the module says so."""


def print_linear_solver(
    plan: Sequence[int], two: bool, structure: np.ndarray | None = None
) -> tuple[str, ...]:
    """The body of a straight-line ``solve_pair(a, b, c, out, out2, m, r, r2, plan, two)``:
    ``out = a^-1 b`` and (``two``) ``out2 = a^-1 c`` for one elimination plan, the arithmetic
    of ``curverecon.solvers.homotopy._solve_pair`` with the plan's loops unrolled and every
    entry a local variable (``m``, ``r``, ``r2``, ``plan`` are not read; they keep that
    function's signature).

    Plan layout (``_elimination_plan``): n, the number of pairs, (unknown, row, row) of each
    pair, the dense unknowns, the rows in no pair.  Each pair's unknown is eliminated by one
    row update, pivoting between its two rows by |Re| + |Im|; the dense system by partial
    pivoting: for each column, every lower row whose entry is larger than the pivot row's is
    swapped with it in turn, which leaves the largest (the first of equal ones) as the pivot,
    as the loop's search does; the other rows' order does not change the result (each row's
    update reads the pivot row only).  Returns False if a pivot is zero or not finite.

    ``two``: the body of the two right-hand sides' solve (``e``, ``y`` the second's entries);
    otherwise of ``solve_one(a, b, out)``, the first alone.

    ``structure``: (equations, unknowns) booleans, the entries of ``a`` that can be nonzero
    (the others are exact zeros); the dense system's arithmetic on entries that stay zero is
    left out (each row keeps the union of the rows a pivot search can swap into it): the same
    results, fewer operations (the fixed-axis system's m_f occur in three rows each, so its
    first two columns eliminate from two and three rows instead of five and four)."""
    plan = [int(v) for v in plan]
    n, n_pairs = plan[0], plan[1]
    pairs = [tuple(plan[2 + 3 * p : 5 + 3 * p]) for p in range(n_pairs)]
    nd = n - n_pairs
    cols = 2 + 3 * n_pairs
    dense = plan[cols : cols + nd]
    free = plan[cols + nd : cols + nd + n - 2 * n_pairs]
    lines: list[str] = []
    emit = lines.append
    # columns (of the dense unknowns) each dense row can hold nonzero: all without a structure
    nz = [set(range(nd)) for _ in range(nd)]
    if structure is not None:
        for i, row in enumerate(free):
            nz[i] = {k for k, col in enumerate(dense) if structure[row, col]}
        for p, (_, piv, oth) in enumerate(pairs):
            nz[len(free) + p] = {
                k for k, col in enumerate(dense) if structure[piv, col] or structure[oth, col]
            }
    for i, row in enumerate(free):  # the dense system's rows: rows in no pair first
        for k, col in enumerate(dense):
            emit(f"m{i}_{k} = a[{row}, {col}]")
        emit(f"g{i} = b[{row}]")
        if two:
            emit(f"e{i} = c[{row}]")
    for p, (col, piv, oth) in enumerate(pairs):  # then each pair's other row, updated
        i = len(free) + p
        emit(f"va = a[{piv}, {col}]")
        emit(f"vb = a[{oth}, {col}]")
        emit("mag_a = abs(va.real) + abs(va.imag)")
        emit("mag_b = abs(vb.real) + abs(vb.imag)")
        emit("if mag_b > mag_a:")
        emit(f"    ip, io = {oth}, {piv}")
        emit("    va, vb, mag_a = vb, va, mag_b")
        emit("else:")
        emit(f"    ip, io = {piv}, {oth}")
        emit("if mag_a == 0.0 or not np.isfinite(mag_a):")
        emit("    return False")
        emit("dd = 1.0 / (va.real * va.real + va.imag * va.imag)")
        emit(f"v{p} = complex(va.real * dd, -va.imag * dd)")
        emit(f"fac = vb * v{p}")
        for k, cc in enumerate(dense):
            emit(f"p{p}_{k} = a[ip, {cc}]")
            emit(f"m{i}_{k} = a[io, {cc}] - fac * p{p}_{k}")
        emit(f"pr{p} = b[ip]")
        emit(f"g{i} = b[io] - fac * pr{p}")
        if two:
            emit(f"pt{p} = c[ip]")
            emit(f"e{i} = c[io] - fac * pt{p}")
    for j in range(nd):
        emit(f"best = abs(m{j}_{j}.real) + abs(m{j}_{j}.imag)")
        swap = [row for row in range(j + 1, nd) if j in nz[row]]  # the others hold a zero
        union = set().union(nz[j], *(nz[row] for row in swap))
        for row in [j, *swap]:
            nz[row] = set(union)
        for row in swap:
            emit(f"mag = abs(m{row}_{j}.real) + abs(m{row}_{j}.imag)")
            emit("if mag > best:")
            emit("    best = mag")
            top = [f"m{j}_{k}" for k in range(j, nd)] + [f"g{j}"] + ([f"e{j}"] if two else [])
            low = [f"m{row}_{k}" for k in range(j, nd)] + [f"g{row}"] + ([f"e{row}"] if two else [])
            emit(f"    {', '.join(top)}, {', '.join(low)} = {', '.join(low)}, {', '.join(top)}")
        emit("if best == 0.0 or not np.isfinite(best):")
        emit("    return False")
        emit(f"dd = 1.0 / (m{j}_{j}.real * m{j}_{j}.real + m{j}_{j}.imag * m{j}_{j}.imag)")
        emit(f"u{j} = complex(m{j}_{j}.real * dd, -m{j}_{j}.imag * dd)")
        for row in swap:
            emit(f"fac = m{row}_{j} * u{j}")
            for k in range(j + 1, nd):
                if k in nz[j]:
                    emit(f"m{row}_{k} = m{row}_{k} - fac * m{j}_{k}")
                    nz[row].add(k)
            emit(f"g{row} = g{row} - fac * g{j}")
            if two:
                emit(f"e{row} = e{row} - fac * e{j}")
    for j in range(nd - 1, -1, -1):  # back substitution
        upper = [k for k in range(j + 1, nd) if k in nz[j]]
        terms = " - ".join([f"g{j}"] + [f"m{j}_{k} * x{k}" for k in upper])
        emit(f"x{j} = ({terms}) * u{j}")
        if two:
            terms = " - ".join([f"e{j}"] + [f"m{j}_{k} * y{k}" for k in upper])
            emit(f"y{j} = ({terms}) * u{j}")
    for p, (col, _, _) in enumerate(pairs):  # each pair's unknown from its pivot row
        terms = " - ".join([f"pr{p}"] + [f"p{p}_{k} * x{k}" for k in range(nd)])
        emit(f"out[{col}] = ({terms}) * v{p}")
    for k, cc in enumerate(dense):
        emit(f"out[{cc}] = x{k}")
    if two:
        for p, (col, _, _) in enumerate(pairs):
            terms = " - ".join([f"pt{p}"] + [f"p{p}_{k} * y{k}" for k in range(nd)])
            emit(f"out2[{col}] = ({terms}) * v{p}")
        for k, cc in enumerate(dense):
            emit(f"out2[{cc}] = y{k}")
    emit("return True")
    return tuple(lines)


def system_kernels(
    record: PolynomialSystem, config: NumPyConfig, unroll_solver: bool = True
) -> SystemKernelCode:
    """Straight-line kernels of a parametric system F(x; q) = W(q) u(x) (``u`` the unknown
    monomials, ``W`` the coefficient matrix, a polynomial in the parameters):

    * ``coefficients(q, w)``: the nonzero entries of W(q), in (equation, unknown monomial) order;
    * ``coefficients_t(q, dq, w, wt)``: those and their derivative along dq, dW/dt = W_q . dq;
    * ``coefficient_rates(q, dq, wt)``: that derivative alone;
    * ``residual_jacobian(x, w, f, jac)``: F and F_x at x from the entries w;
    * ``residual_jacobian_t(x, w, wt, f, jac, ft)``: those and F_t = (dW/dt) u(x).

    The split lets a tracker evaluate W once per t and reuse it for every Newton iteration
    there.  Entries that do not depend on q are written into the residual kernels as numbers.
    Terms come from :func:`system_terms`, so the entries are the same sums as the table-driven
    module's.  ``unroll_solver``: also ``solve_one`` and ``solve_pair``, the plan's linear solve
    unrolled (its length grows as the cube of the dense unknowns: 15 of them wrote 15,000
    lines; without it the tracker's loop solve serves)."""
    n_u = len(record.unknowns)
    umons, pmons, terms = system_terms(record.equations, record.unknowns, record.parameters)
    params = tuple(record.parameters)
    rates = tuple(sp.Symbol(f"d_{p.name}") for p in params)
    entries: dict[tuple[int, int], sp.Expr] = {}
    for a, j, k, coeff in terms:
        pmon = sp.Mul(*(p**e for p, e in zip(params, pmons[j], strict=True)))
        entries[(a, k)] = entries.get((a, k), sp.Integer(0)) + coeff * pmon
    keys = sorted(entries)
    values = [sp.expand(entries[key]) for key in keys]
    # dW/dt = sum_p (dW/dq_p) dq_p with each partial derivative in Horner form, not expanded:
    # one CSE pass then shares the partials' factors (minimal system: 128 temporaries and
    # 0.20 us a call against 176 and 0.25 us expanded; the same values to 1e-11 relative)
    rate_values = [
        sum(
            (
                sp.horner(sp.diff(v, p)) * r
                for p, r in zip(params, rates, strict=True)
                if sp.diff(v, p) != 0
            ),
            start=sp.Integer(0),
        )
        for v in values
    ]
    w_syms = tuple(sp.Symbol(f"w{i}") for i in range(len(keys)))
    wt_syms = tuple(sp.Symbol(f"wt{i}") for i in range(len(keys)))
    unknowns = tuple(record.unknowns)

    def umon(k: int) -> sp.Expr:
        return sp.Mul(*(x**e for x, e in zip(unknowns, umons[k], strict=True)))

    n_eq = len(record.equations)
    f = [sp.Integer(0)] * n_eq
    ft = [sp.Integer(0)] * n_eq
    for i, (a, k) in enumerate(keys):
        if values[i].is_Number:  # a constant entry is written into the code, not read from w
            f[a] += values[i] * umon(k)
        else:
            f[a] += w_syms[i] * umon(k)
            ft[a] += wt_syms[i] * umon(k)
    jac = sp.Matrix(n_eq, n_u, lambda a, v: sp.expand(sp.diff(f[a], unknowns[v])))
    if record.horner:  # nested in the record's order of unknowns (see its ``horner``)
        gens = record.horner
        f = [sp.horner(e, *gens) if e.free_symbols & set(gens) else e for e in f]
        ft = [sp.horner(e, *gens) if e.free_symbols & set(gens) else e for e in ft]
        jac = jac.applyfunc(lambda e: sp.horner(e, *gens) if e.free_symbols & set(gens) else e)
    kernels = (
        print_array_kernel(
            "coefficients",
            [("q", params)],
            [("w", values)],
            "The nonzero entries of the coefficient matrix W(q) (COEFFICIENT_ENTRIES order).",
            config,
        ),
        print_array_kernel(
            "coefficients_t",
            [("q", params), ("dq", rates)],
            [("w", values), ("wt", rate_values)],
            "W(q) as ``coefficients`` and its derivative dW/dt = W_q . dq along dq = dq/dt.",
            config,
        ),
        print_array_kernel(
            "coefficient_rates",
            [("q", params), ("dq", rates)],
            [("wt", rate_values)],
            "dW/dt = W_q . dq alone (``coefficients_t`` without W): a tracker needs it only "
            "where it keeps a tangent.",
            config,
        ),
        print_array_kernel(
            "residual_jacobian",
            [("x", unknowns), ("w", w_syms)],
            [("f", f), ("jac", jac)],
            "F(x; q) = W(q) u(x) and its Jacobian F_x, from W's entries w.",
            config,
        ),
        print_array_kernel(
            "residual_jacobian_t",
            [("x", unknowns), ("w", w_syms), ("wt", wt_syms)],
            [("f", f), ("jac", jac), ("ft", ft)],
            "F and F_x as ``residual_jacobian``, and F_t = (dW/dt) u(x) from dW/dt's entries wt.",
            config,
        ),
    )
    width = config.line_length - len(config.indent) - 4
    rows = [f"({a}, {tuple(umons[k])!r})" for a, k in keys]
    from curverecon.solvers import homotopy  # the runtime's own plan, so that they agree

    exponents = np.array(umons, dtype=np.int64).reshape(-1, n_u)
    table = np.array([(a, j, k) for a, j, k, _ in terms], dtype=np.int64).reshape(-1, 3)
    order = homotopy._column_order(exponents, table, n_eq)
    plan = homotopy._elimination_plan(exponents, table, n_eq, order)
    structure = None
    if record.sparse_solve:
        structure = np.array([[jac[a, v] != 0 for v in range(n_u)] for a in range(n_eq)])
    return SystemKernelCode(
        unknowns_repr=repr(tuple(s.name for s in record.unknowns)),
        parameters_repr=repr(tuple(s.name for s in record.parameters)),
        equations_repr=repr(tuple(record.equation_names)),
        n_coefficients=len(keys),
        coefficient_rows=tuple(_pack(rows, width)),
        kernels=kernels,
        elimination_repr=repr(tuple(int(v) for v in plan)),
        solver_lines=print_linear_solver(plan, True, structure) if unroll_solver else (),
        solver_one_lines=print_linear_solver(plan, False, structure) if unroll_solver else (),
        dense_unknowns=int(plan[0] - plan[1]),
    )


# ---------------------------------------------------------------------------------------------
# Rendering and formatting
# ---------------------------------------------------------------------------------------------


def _environment() -> jinja2.Environment:
    return jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(TEMPLATE_DIR)),
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
        autoescape=False,
    )


def ruff_executable() -> str:
    """The pinned ruff next to the running interpreter (the venv), else the one on PATH."""
    candidate = Path(sys.executable).parent / "ruff"
    if candidate.exists():
        return str(candidate)
    found = shutil.which("ruff")
    if found is None:
        raise RuntimeError("ruff not found: install the dev extras (make setup)")
    return found


def format_python(text: str, filename: str = "generated/module.py") -> str:
    """Format ``text`` with ``ruff format`` using the repository configuration."""
    result = subprocess.run(
        [ruff_executable(), "format", "--stdin-filename", filename, "-"],
        input=text,
        capture_output=True,
        text=True,
        cwd=REPO_ROOT,
        check=False,
    )
    if result.returncode != 0:
        raise RuntimeError(f"ruff format failed on {filename}:\n{result.stderr}")
    return result.stdout


def render_module(
    *,
    source: str,
    doc: str,
    functions: Sequence[FunctionSpec] = (),
    constants: dict[str, object] | None = None,
    polynomial: PolynomialColumns | None = None,
    system: PolynomialSystem | None = None,
    filename: str = "generated/module.py",
    config: NumPyConfig | None = None,
) -> str:
    """The formatted text of one generated module.

    ``source`` is the repository-relative path of the derivation script named in the preamble.
    """
    config = config or NumPyConfig()
    return _render(
        TEMPLATE_NAME,
        source,
        doc,
        filename,
        config,
        dtype=config.dtype,
        constants=[(k, repr(v)) for k, v in (constants or {}).items()],
        functions=[print_function(f, config) for f in functions],
        polynomial=polynomial is not None,
        poly=print_polynomial(polynomial, config) if polynomial is not None else None,
        system=print_system(system, config) if system is not None else None,
    )


def _render(
    name: str, source: str, doc: str, filename: str, config: NumPyConfig, **fields: object
) -> str:
    """Template ``name`` rendered with the preamble's fields and ``fields``, then formatted."""
    text = (
        _environment()
        .get_template(name)
        .render(
            source=source,
            template="derivations/codegen/templates/" + name,
            sympy_version=sp.__version__,
            doc=wrap_doc(doc, config.line_length - 4),
            **fields,
        )
    )
    if config.run_ruff_format:
        text = format_python(text, filename)
    return text


def render_kernel_module(
    *,
    source: str,
    doc: str,
    kernels: Sequence[FunctionSpec],
    filename: str = "generated/kernel.py",
    config: NumPyConfig | None = None,
) -> str:
    """The formatted text of one module of scalar numba kernels (``templates/kernel.py.jinja``)."""
    config = config or NumPyConfig()
    kernel_code = [print_kernel(f, config) for f in kernels]
    return _render(KERNEL_TEMPLATE_NAME, source, doc, filename, config, kernels=kernel_code)


def render_system_kernel_module(
    *,
    source: str,
    doc: str,
    system: PolynomialSystem,
    filename: str = "generated/system_kernel.py",
    config: NumPyConfig | None = None,
    unroll_solver: bool = True,
) -> str:
    """The formatted text of a module of straight-line numba kernels of a parametric polynomial
    system (``templates/system_kernel.py.jinja``, :func:`system_kernels`)."""
    config = config or NumPyConfig()
    code = system_kernels(system, config, unroll_solver)
    return _render(SYSTEM_KERNEL_TEMPLATE_NAME, source, doc, filename, config, kernel=code)


def render_init(modules: Sequence[tuple[str, str]], source: str) -> str:
    """generated/__init__.py: the preamble and a docstring listing the generated modules."""
    lines = [
        "# " + "-" * 97,
        "# Generated, do not edit / do not modify: change derivations/ and run `make derive`.",
        "#",
        f"# Derivation: {source}",
        f"# SymPy:      {sp.__version__}",
        "# " + "-" * 97,
        '"""Code generated from derivations/ (NumPy only; imported as curverecon.generated).',
        "",
    ]
    for name, summary in modules:
        lines += textwrap.wrap(f"- ``{name}``: {summary}", width=100, subsequent_indent="  ")
    lines += ['"""', "", "__all__ = " + repr(tuple(name for name, _ in modules)), ""]
    return format_python("\n".join(lines), "generated/__init__.py")


# ---------------------------------------------------------------------------------------------
# Writing (SymForce's compare_or_update)
# ---------------------------------------------------------------------------------------------


def unified_diff(old: str, new: str, path: str) -> str:
    """A unified diff of the committed text ``old`` against the regenerated ``new``."""
    return "".join(
        difflib.unified_diff(
            old.splitlines(keepends=True),
            new.splitlines(keepends=True),
            fromfile=f"{path} (committed)",
            tofile=f"{path} (regenerated)",
            n=2,
        )
    )


def compare_or_update(path: Path, text: str, update: bool) -> str | None:
    """Write ``text`` to ``path`` if ``update``, else return a diff (None if they agree)."""
    old = path.read_text() if path.exists() else ""
    if old == text:
        return None
    if update:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
        return None
    return unified_diff(old, text, str(path)) or f"{path}: differs\n"
