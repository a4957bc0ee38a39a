"""A NumPy printer for generated modules (SymForce's ``PythonCodePrinter`` pattern).

Differences from ``sympy.printing.numpy.NumPyPrinter``:

* functions and constants carry the ``np.`` prefix (the generated module does
  ``import numpy as np``) instead of ``numpy.``;
* small integer powers are printed as repeated products (``x**2`` -> ``x*x``,
  ``x**-2`` -> ``1/(x*x)``), parenthesised as a product inside a product or quotient
  (``a/(x*x)``, not ``a/x*x``), larger ones as ``x**n``; ``x**(1/2)`` is ``np.sqrt(x)``;
* float constants are printed with ``repr`` (shortest round-trip form); rationals stay ``p/q``
  (true division in Python 3).
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.numpy import NumPyPrinter
from sympy.printing.precedence import PRECEDENCE, precedence

from derivations.codegen.config import NumPyConfig


class NumPyCodePrinter(NumPyPrinter):
    """Print SymPy expressions as NumPy code that broadcasts over frame arrays."""

    PREFIX = "np."
    SQRT = "np.sqrt"
    ATAN2 = "np.arctan2"

    def __init__(self, config: NumPyConfig | None = None) -> None:
        super().__init__({"fully_qualified_modules": True, "allow_unknown_functions": False})
        self.config = config or NumPyConfig()

    # ``numpy.sin`` -> ``np.sin``; ``math.pi`` never appears (constants go through _kc).
    def _module_format(self, fqn: str, register: bool = True) -> str:
        if fqn.startswith("numpy."):
            fqn = self.PREFIX + fqn[len("numpy.") :]
        elif fqn.startswith("math."):
            fqn = self.PREFIX + fqn[len("math.") :]
        return fqn

    def _print_Float(self, expr: sp.Float) -> str:
        return self.config.format_float(float(expr))

    def _print_Integer(self, expr: sp.Integer) -> str:
        return str(int(expr))

    def _print_Pow(self, expr: sp.Pow, rational: bool = False) -> str:
        base, exp = expr.base, expr.exp
        prec = precedence(expr)
        if exp.is_Integer:
            n = int(exp)
            limit = self.config.power_by_multiplication
            if n == 1:
                return self._print(base)
            if 2 <= n <= limit:
                b = self.parenthesize(base, PRECEDENCE["Mul"], strict=False)
                return "*".join([b] * n)
            if -limit <= n <= -1:
                if n == -1:
                    b = self.parenthesize(base, PRECEDENCE["Mul"], strict=True)
                    return f"1/{b}"
                b = self.parenthesize(base, PRECEDENCE["Mul"], strict=False)
                return "1/(" + "*".join([b] * (-n)) + ")"
            b = self.parenthesize(base, PRECEDENCE["Pow"], strict=True)
            return f"{b}**{n}" if n > 0 else f"{b}**({n})"
        if exp == sp.S.Half:
            return f"{self.SQRT}({self._print(base)})"
        if exp == -sp.S.Half:
            return f"1/{self.SQRT}({self._print(base)})"
        b = self.parenthesize(base, PRECEDENCE["Pow"], strict=True)
        e = self.parenthesize(exp, prec, strict=False)
        return f"{b}**{e}"

    def _print_Mul(self, expr: sp.Mul) -> str:
        # A negative product is printed at the precedence of a sum (SymPy's convention), so its
        # factors come to ``parenthesize`` with the level of an Add: mark that they are factors.
        self._factor_depth = getattr(self, "_factor_depth", 0) + 1
        try:
            return super()._print_Mul(expr)
        finally:
            self._factor_depth -= 1

    def parenthesize(self, item: sp.Basic, level: int, strict: bool = False) -> str:
        """As SymPy's, but a small positive power counts as a product (it prints as ``x*x``).

        Without this a lone denominator ``x**2`` printed as ``a/x*x``, i.e. ``(a/x)*x``: SymPy
        parenthesises a factor only below the precedence of a power.  Here such a power is put
        in parentheses wherever it is a factor (of a product or quotient) or a base.
        """
        if (
            isinstance(item, sp.Pow)
            and item.exp.is_Integer
            and 2 <= int(item.exp) <= self.config.power_by_multiplication
            and (level >= PRECEDENCE["Mul"] or getattr(self, "_factor_depth", 0) > 0)
        ):
            return f"({self._print(item)})"
        return super().parenthesize(item, level, strict)

    def _print_atan2(self, expr: sp.atan2) -> str:
        y, x = expr.args
        return f"{self.ATAN2}({self._print(y)}, {self._print(x)})"


class ScalarCodePrinter(NumPyCodePrinter):
    """Print SymPy expressions as scalar ``math`` code, for numba kernels that loop over frames
    (``templates/kernel.py.jinja``): ``math.sin``, ``math.sqrt``, ``math.atan2``.  Everything
    else (powers as products, float constants, parenthesisation) as the NumPy printer, so a
    kernel rounds as the NumPy module does, operation for operation."""

    PREFIX = "math."
    SQRT = "math.sqrt"
    ATAN2 = "math.atan2"

    def doprint(self, expr: sp.Basic, assign_to: object = None) -> str:
        text = super().doprint(expr, assign_to)
        if "np." in text or "numpy." in text:
            raise ValueError(f"a scalar kernel cannot call NumPy: {text[:80]}")
        return text
