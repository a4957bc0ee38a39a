"""Code-generation settings (the analogue of SymForce's ``PythonConfig``).

Everything that decides how generated text looks lives here, so that a change of style is one
edit and a full ``make derive``.  The defaults match the repository's ruff configuration
(``pyproject.toml``: line length 100, target Python 3.10).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

#: The folder that holds ``module.py.jinja`` and ``macros.jinja``.
TEMPLATE_DIR = Path(__file__).resolve().parent / "templates"


@dataclass(frozen=True)
class NumPyConfig:
    """How a NumPy module is printed.

    Attributes:
        line_length: maximum line length of the emitted code (ruff ``line-length``).
        indent: one indentation level.
        dtype: the NumPy dtype every argument is converted to and every output has.
        float_digits: significant digits of printed floating-point constants (17 round-trips
            an IEEE double exactly, so the printed module reproduces the SymPy constant).
        power_by_multiplication: print ``x**n`` for ``|n| <= power_by_multiplication`` as a
            product ``x*x*...`` (exact rounding behaviour, faster than ``np.power``).
        cse_optimizations: passed to ``sympy.cse`` (``"basic"`` pulls out negations and
            common factors of products, which shortens the measurement model).
        run_ruff_format: pipe the emitted text through the venv's pinned ``ruff format``.
        table_row_items: items per line of the integer tables of polynomial modules.
    """

    line_length: int = 100
    indent: str = "    "
    dtype: str = "np.float64"
    float_digits: int = 17
    power_by_multiplication: int = 4
    cse_optimizations: str | None = "basic"
    run_ruff_format: bool = True
    table_row_items: int = 24

    def format_float(self, value: float) -> str:
        """A float literal that round-trips ``value`` (``repr`` is shortest round-trip)."""
        text = repr(float(value))
        if text in ("inf", "-inf", "nan"):
            raise ValueError(f"cannot print non-finite constant {text}")
        return text
