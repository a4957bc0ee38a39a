# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/lean.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Lean elimination of delta and tau (NOTES item 4): (10), (11) solved for cos(delta), sin(delta),
cos^2 + sin^2 = 1, squared once to remove sin(phi) sin(tau), the factor c**10 divided out.
Vanishes on noise-free frames for both signs of tau; depends on cos(phi) only.  Lengths in input
units.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

UNKNOWNS = ("c", "tan_alpha", "tan_beta", "cos_phi")
OBSERVABLES = ("cp", "dp", "ep")

#: Exponents (cp, dp, ep) of the observable monomial of each column (K = 39).
OBSERVABLE_EXPONENTS = (
    (0, 4, 4),
    (2, 2, 4),
    (2, 3, 3),
    (2, 4, 2),
    (2, 4, 4),
    (4, 0, 4),
    (4, 1, 3),
    (4, 2, 2),
    (4, 2, 4),
    (4, 3, 1),
    (4, 3, 3),
    (4, 4, 0),
    (4, 4, 2),
    (4, 4, 4),
    (6, 0, 2),
    (6, 0, 4),
    (6, 1, 1),
    (6, 1, 3),
    (6, 2, 0),
    (6, 2, 2),
    (6, 2, 4),
    (6, 3, 1),
    (6, 3, 3),
    (6, 4, 0),
    (6, 4, 2),
    (6, 4, 4),
    (8, 0, 0),
    (8, 0, 2),
    (8, 0, 4),
    (8, 1, 1),
    (8, 1, 3),
    (8, 2, 0),
    (8, 2, 2),
    (8, 2, 4),
    (8, 3, 1),
    (8, 3, 3),
    (8, 4, 0),
    (8, 4, 2),
    (8, 4, 4),
)

#: Columns whose unknown part is a single monomial: (column, coefficient, exponents of UNKNOWNS).
MONOMIAL_COLUMNS = (
    (5, 1, (8, 4, 4, 4)),
    (6, 4, (8, 4, 4, 2)),
    (9, 4, (8, 4, 4, 2)),
    (11, 1, (8, 4, 4, 4)),
)

#: Facts recorded by the derivation (degrees, term counts).
FACTS = {
    "columns": 39,
    "degree_in_observables": 16,
    "degree_in_unknowns": 20,
    "degrees": {"c": 8, "cos_phi": 4, "cp": 8, "dp": 4, "ep": 4, "tan_alpha": 4, "tan_beta": 4},
    "divided_out": "c**10",
    "exact_checks": {
        "frames": 12,
        "nonzero_c_plus_1": 12,
        "nonzero_other_branch_cos_phi": 12,
        "nonzero_tan_alpha_times_1.1": 12,
        "zero_at_truth": 12,
    },
    "irreducible": True,
    "monomial_columns": (
        (5, 1, (8, 4, 4, 4)),
        (6, 4, (8, 4, 4, 2)),
        (9, 4, (8, 4, 4, 2)),
        (11, 1, (8, 4, 4, 4)),
    ),
    "null_space_dimension": 1,
    "null_space_dimension_exact": 1,
    "observable_monomials": 39,
    "rank_mod_p": (39, 38),
    "ratio_recovery_exact_columns_below_1e-9": True,
    "ratio_recovery_svd_80_frames_below_1e-4": True,
    "svd_second_smallest_above_1e-16": True,
    "svd_smallest_below_1e-18": True,
    "terms": 221,
    "total_degree": 28,
    "unknown_monomials": 57,
}

_N_COLUMNS = 39
_N_UNKNOWNS = 4
#: Highest exponent of each unknown / each observable.
_UNKNOWN_DEGREES = (8, 4, 4, 4)
_OBSERVABLE_DEGREES = (8, 4, 4)
# Distinct monomials in UNKNOWNS (57 x 4 exponents, flattened).
# fmt: off
_MONOMIAL_TABLE = (
    0, 0, 4, 0, 0, 1, 3, 1, 0, 2, 2, 0, 0, 2, 2, 2, 0, 2, 4, 0, 0, 2, 4, 2, 0, 3, 1, 1,
    0, 3, 3, 1, 0, 3, 3, 3, 0, 4, 0, 0, 0, 4, 2, 0, 0, 4, 2, 2, 0, 4, 4, 0, 0, 4, 4, 2,
    0, 4, 4, 4, 2, 0, 4, 0, 2, 1, 3, 1, 2, 2, 2, 0, 2, 2, 2, 2, 2, 2, 4, 0, 2, 2, 4, 2,
    2, 3, 1, 1, 2, 3, 3, 1, 2, 3, 3, 3, 2, 4, 0, 0, 2, 4, 2, 0, 2, 4, 2, 2, 2, 4, 4, 0,
    2, 4, 4, 2, 2, 4, 4, 4, 4, 0, 4, 0, 4, 1, 3, 1, 4, 2, 2, 0, 4, 2, 2, 2, 4, 2, 4, 0,
    4, 2, 4, 2, 4, 3, 1, 1, 4, 3, 3, 1, 4, 3, 3, 3, 4, 4, 0, 0, 4, 4, 2, 0, 4, 4, 2, 2,
    4, 4, 4, 0, 4, 4, 4, 2, 4, 4, 4, 4, 6, 2, 4, 0, 6, 2, 4, 2, 6, 3, 3, 1, 6, 3, 3, 3,
    6, 4, 2, 0, 6, 4, 2, 2, 6, 4, 4, 0, 6, 4, 4, 2, 6, 4, 4, 4, 8, 4, 4, 0, 8, 4, 4, 2,
    8, 4, 4, 4,
)
# fmt: on

# Terms (221): (column, monomial index) pairs, flattened.
# fmt: off
_TERM_TABLE = (
    0, 54, 0, 55, 0, 56, 1, 55, 1, 56, 2, 54, 2, 55, 3, 55, 3, 56, 4, 45, 4, 46, 4, 47, 4, 48,
    4, 49, 4, 50, 4, 51, 4, 52, 4, 53, 5, 56, 6, 55, 7, 54, 7, 55, 7, 56, 8, 46, 8, 47, 8, 48,
    8, 49, 8, 52, 8, 53, 9, 55, 10, 45, 10, 46, 10, 47, 10, 48, 10, 49, 10, 50, 10, 51, 10, 52,
    11, 56, 12, 45, 12, 47, 12, 48, 12, 50, 12, 52, 12, 53, 13, 30, 13, 31, 13, 32, 13, 33,
    13, 34, 13, 35, 13, 36, 13, 37, 13, 38, 13, 39, 13, 40, 13, 41, 13, 42, 13, 43, 13, 44,
    14, 55, 14, 56, 15, 50, 15, 53, 16, 54, 16, 55, 17, 47, 17, 48, 17, 49, 17, 50, 17, 52,
    18, 55, 18, 56, 19, 45, 19, 47, 19, 48, 19, 49, 19, 51, 19, 52, 19, 53, 20, 32, 20, 33,
    20, 35, 20, 36, 20, 37, 20, 38, 20, 39, 20, 40, 20, 43, 20, 44, 21, 45, 21, 46, 21, 47,
    21, 48, 21, 52, 22, 31, 22, 32, 22, 34, 22, 35, 22, 36, 22, 37, 22, 38, 22, 40, 22, 41,
    22, 42, 22, 43, 23, 46, 23, 53, 24, 30, 24, 31, 24, 32, 24, 33, 24, 34, 24, 37, 24, 38,
    24, 41, 24, 43, 24, 44, 25, 15, 25, 16, 25, 17, 25, 18, 25, 19, 25, 20, 25, 21, 25, 22,
    25, 23, 25, 24, 25, 25, 25, 26, 25, 27, 25, 28, 25, 29, 26, 54, 26, 55, 26, 56, 27, 49,
    27, 50, 27, 52, 27, 53, 28, 39, 28, 41, 28, 44, 29, 47, 29, 48, 29, 51, 29, 52, 30, 36,
    30, 37, 30, 38, 30, 40, 30, 41, 30, 43, 31, 45, 31, 46, 31, 52, 31, 53, 32, 32, 32, 33,
    32, 34, 32, 37, 32, 38, 32, 40, 32, 42, 32, 43, 32, 44, 33, 17, 33, 18, 33, 20, 33, 21,
    33, 22, 33, 23, 33, 24, 33, 25, 33, 28, 33, 29, 34, 31, 34, 34, 34, 35, 34, 37, 34, 38,
    34, 43, 35, 16, 35, 17, 35, 19, 35, 20, 35, 21, 35, 22, 35, 23, 35, 25, 35, 26, 35, 27,
    35, 28, 36, 30, 36, 35, 36, 44, 37, 15, 37, 16, 37, 17, 37, 18, 37, 19, 37, 22, 37, 23,
    37, 26, 37, 28, 37, 29, 38, 0, 38, 1, 38, 2, 38, 3, 38, 4, 38, 5, 38, 6, 38, 7, 38, 8,
    38, 9, 38, 10, 38, 11, 38, 12, 38, 13, 38, 14,
)
# fmt: on

# Coefficient of each term (exact integers or round-trip floats).
# fmt: off
_COEFFICIENT_TABLE = (
    1, -2, 1, -2, 2, -4, 4, -2, 2, -2, 2, -4, 4, -2, 2, -4, 8, -4, 1, 4, 6, -4, 4, -2, -8, 4,
    -2, 6, -6, 4, 4, -8, -4, -4, 4, -8, 12, -12, 1, -2, -8, 4, -2, 6, -6, 1, 4, 2, 4, 6, -6, 4,
    12, -12, 1, 6, -6, 6, -12, 6, -2, 2, -2, -2, -4, 4, 8, -4, 4, -8, -8, -2, 2, -2, 4, 4, -2,
    -12, 8, -8, -2, 4, 4, 4, 16, -8, 2, 4, -6, 6, 4, -8, 8, -4, -8, -4, -8, -8, 16, -4, 8, 8,
    -8, 16, -12, 12, -2, -2, 2, 4, -2, 4, 4, 16, -8, 4, -6, 6, -2, -8, -4, -8, -6, 6, -8, -12,
    12, -2, -6, 6, -4, 8, -4, 1, -2, 1, -2, 2, 2, -2, 1, 2, 1, 4, -4, 4, -4, -4, -8, 4, -4, 8,
    4, -2, 2, 2, -2, 2, 4, 2, -4, -4, 2, 6, -4, 4, 2, -4, -2, -4, -8, 4, -2, -2, 2, -2, -4, -4,
    8, -8, 4, 4, 4, 8, 4, -8, 4, -4, -4, 4, -8, 4, -4, 1, 2, 1, -2, -4, 2, -4, -2, -8, 4, -2, 2,
    -2, 1, 4, 2, 4, 2, -2, 4, 4, -4, 1, 2, -2, 1, -2, 1,
)
# fmt: on


_OBSERVABLE_EXPONENT_ARRAY = np.array(OBSERVABLE_EXPONENTS, dtype=np.int64).reshape(-1, 3)
_MONOMIAL_ARRAY = np.array(_MONOMIAL_TABLE, dtype=np.int64).reshape(-1, _N_UNKNOWNS)
_TERM_ARRAY = np.array(_TERM_TABLE, dtype=np.int64).reshape(-1, 2)
_TERM_COLUMN = _TERM_ARRAY[:, 0].copy()
_TERM_MONOMIAL = _TERM_ARRAY[:, 1].copy()
_TERM_COEFFICIENT = np.array(_COEFFICIENT_TABLE, dtype=np.float64)


def _powers(x: np.ndarray, degree: int) -> np.ndarray:
    """``x**0, ..., x**degree`` along a new last axis, by repeated multiplication."""
    out = np.empty((*x.shape, degree + 1), dtype=np.float64)
    out[..., 0] = 1.0
    for k in range(1, degree + 1):
        out[..., k] = out[..., k - 1] * x
    return out


def observable_matrix(cp: npt.ArrayLike, dp: npt.ArrayLike, ep: npt.ArrayLike) -> np.ndarray:
    """Observable monomials of each frame, shape (N, K).

    Row n, column k: ``cp**i * dp**j * ep**l`` of frame n, (i, j, l) = OBSERVABLE_EXPONENTS[k];
    per frame, ``observable_matrix(...) @ unknown_columns(...)`` is the polynomial, which vanishes
    on noise-free frames at the true shape.  Powers are formed by repeated multiplication.

    Scaling: the polynomial is homogeneous of degree 16 in the lengths (c, cp, dp, ep);
    divide all of them by one common length L (for example the mean of cp) before
    calling, so that the powers stay within floating-point range; the polynomial then changes
    by the constant factor L**-16 only.
    """
    arrays = np.broadcast_arrays(
        *(
            np.atleast_1d(np.asarray(v, dtype=np.float64))
            for v in (
                cp,
                dp,
                ep,
            )
        )
    )
    if arrays[0].ndim != 1:
        raise ValueError("observable_matrix expects 1-D frame arrays")
    result = np.ones((arrays[0].shape[0], _N_COLUMNS), dtype=np.float64)
    for v, (values, degree) in enumerate(zip(arrays, _OBSERVABLE_DEGREES, strict=True)):
        result *= _powers(values, degree)[:, _OBSERVABLE_EXPONENT_ARRAY[:, v]]
    return result


def _monomials(unknowns: tuple[float, ...], wrt: int | None = None) -> np.ndarray:
    """Values of the distinct monomials (or their derivatives with respect to unknown ``wrt``)."""
    result = np.ones(_MONOMIAL_ARRAY.shape[0], dtype=np.float64)
    for v, (value, degree) in enumerate(zip(unknowns, _UNKNOWN_DEGREES, strict=True)):
        powers = _powers(np.asarray(value, dtype=np.float64), degree)
        exponents = _MONOMIAL_ARRAY[:, v]
        if v == wrt:
            result *= exponents * powers[np.maximum(exponents - 1, 0)]
        else:
            result *= powers[exponents]
    return result


def unknown_columns(c: float, tan_alpha: float, tan_beta: float, cos_phi: float) -> np.ndarray:
    """The unknown part u_k(c, tan_alpha, tan_beta, cos_phi) of each column, shape (K,)."""
    monomials = _monomials(
        (
            c,
            tan_alpha,
            tan_beta,
            cos_phi,
        )
    )
    return np.bincount(
        _TERM_COLUMN, weights=_TERM_COEFFICIENT * monomials[_TERM_MONOMIAL], minlength=_N_COLUMNS
    )


def unknown_columns_jacobian(
    c: float, tan_alpha: float, tan_beta: float, cos_phi: float
) -> np.ndarray:
    """d u_k / d(c, tan_alpha, tan_beta, cos_phi), shape (K, 4)."""
    unknowns = (
        c,
        tan_alpha,
        tan_beta,
        cos_phi,
    )
    result = np.empty((_N_COLUMNS, _N_UNKNOWNS), dtype=np.float64)
    for v in range(_N_UNKNOWNS):
        monomials = _monomials(unknowns, wrt=v)
        result[:, v] = np.bincount(
            _TERM_COLUMN,
            weights=_TERM_COEFFICIENT * monomials[_TERM_MONOMIAL],
            minlength=_N_COLUMNS,
        )
    return result
