"""Code generation: SymPy expressions -> formatted, vectorised NumPy modules in ``generated/``.

Layout (after SymForce's ``symforce/codegen``):

* :mod:`~derivations.codegen.spec`: the records a derivation hands over (FunctionSpec,
  PolynomialColumns);
* :mod:`~derivations.codegen.config`: line length, indentation, dtype, float formatting;
* :mod:`~derivations.codegen.printer`: the NumPy printer subclass;
* ``templates/``: the file template ``module.py.jinja``, the macro file ``macros.jinja`` and the
  polynomial body ``polynomial.py.jinja``;
* :mod:`~derivations.codegen.generate`: CSE, rendering, ruff formatting, compare_or_update.
"""

from derivations.codegen.config import NumPyConfig
from derivations.codegen.generate import compare_or_update, render_init, render_module
from derivations.codegen.printer import NumPyCodePrinter
from derivations.codegen.spec import FunctionSpec, PolynomialColumns

__all__ = [
    "FunctionSpec",
    "NumPyCodePrinter",
    "NumPyConfig",
    "PolynomialColumns",
    "compare_or_update",
    "render_init",
    "render_module",
]
