"""What a derivation hands to code generation.

The derivation modules (``derivations.section3``, ``derivations.lean``, ``derivations.squaring``,
``derivations.measurement``) describe their outputs with these two records; ``derivations.codegen``
turns them into NumPy modules under ``generated/``.  Nothing here depends on a template.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp


@dataclass(frozen=True)
class FunctionSpec:
    """One generated function: ``name(*args) -> outputs`` (a tuple in the order given).

    ``args`` are SymPy symbols whose names become the Python argument names.  ``outputs`` maps
    an output name to its expression; all outputs of one function share one
    common-subexpression pass.  ``doc`` is the docstring: say the equation number,
    the convention and the units.

    Output shapes (every argument broadcasts; N is the broadcast frame shape): a scalar
    expression gives an array of shape (N,); a tuple or list of n expressions gives (N, n);
    an r x k ``sympy.Matrix`` gives (N, r, k).  One output is returned as an array, several as
    a tuple in the order of ``outputs``.
    """

    name: str
    args: tuple[sp.Symbol, ...]
    outputs: dict[str, sp.Expr]
    doc: str


@dataclass(frozen=True)
class PolynomialColumns:
    """A polynomial in unknowns and per-frame observables, grouped by observable monomial.

    ``columns[k] = ((i, j, l), u_k)`` means the polynomial equals
    ``sum_k cp**i * dp**j * ep**l * u_k(unknowns)``, ``u_k`` a polynomial in ``unknowns`` only.
    Columns are sorted by their observable exponent tuple, so the order is deterministic.
    """

    name: str
    unknowns: tuple[sp.Symbol, ...]
    observables: tuple[sp.Symbol, ...]
    columns: tuple[tuple[tuple[int, int, int], sp.Expr], ...]
    doc: str
    facts: dict[str, object] = field(default_factory=dict)  # degree, term counts... for the report


@dataclass(frozen=True)
class PolynomialSystem:
    """A square polynomial system with parameters, and every solution at one start point.

    ``equations`` are SymPy expressions, polynomial in ``unknowns`` and ``parameters``.
    ``start_parameters`` (complex, generic) and ``start_solutions`` (every isolated solution
    there, one row each) seed the parameter homotopy of ``curverecon.solvers.homotopy``:
    emitted as data, they let the runtime reach every solution at any other parameter value.
    """

    name: str
    unknowns: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]
    equations: tuple[sp.Expr, ...]
    equation_names: tuple[str, ...]
    start_parameters: tuple[complex, ...]
    start_solutions: tuple[tuple[complex, ...], ...]
    doc: str
    facts: dict[str, object] = field(default_factory=dict)
    horner: tuple[sp.Symbol, ...] = ()
    """Unknowns in the order the residual kernels nest F, F_x and F_t in (Horner form, before
    the common-subexpression pass: fewer multiplications where each equation is a sum of many
    monomials of few unknowns); empty: the expanded sums."""
    sparse_solve: bool = False
    """The unrolled linear solve leaves out arithmetic on entries of F_x that are zero for
    every x and q (``print_linear_solver``'s ``structure``)."""
