"""The paper's linearisation (section 3), made determinate by grouping by observable monomials.

Per frame the lean elimination (generated ``lean_polynomial``) is a polynomial
``sum_k M_k(c', d', e') u_k(c, tan alpha, tan beta, cos phi) = 0``.  Taking every unknown
monomial as a new unknown (the paper's literal recipe) is rank-deficient: several unknown
monomials share one observable monomial.  Grouping by observable monomial gives K columns (39)
whose unknown parts u_k are a vector with a one-dimensional null space on noise-free data:

1. lengths (c', d', e' and so c) are divided by a common length L (the mean c'),
2. the frames' rows M (N x K) are column-scaled to unit norm and the right singular vector v of
   the smallest singular value is the homogeneous solution (u proportional to v),
3. the four unknowns follow from v: the single-monomial columns (MONOMIAL_COLUMNS) give cos^2 phi
   and K = c^8 tan^4 alpha tan^4 beta by ratios, the columns (8,0,4) and (8,4,0)
   (= c^4 tan^4 alpha (1 + tan^2 beta cos^2 phi)^2 and its mirror) give 1/c^2 from a quadratic,
   then a small least-squares fit of u(x) = lambda v (analytic ``unknown_columns_jacobian``)
   makes the estimate consistent with every column, and a last least-squares step on the frames'
   polynomial values (all frames, the same grouped columns) polishes it.

Minimum number of frames: K - 1 = 38.  A one-dimensional null space of an N x K matrix needs rank
K - 1, so at least K - 1 frames (rows) in general position; with fewer the null space has
dimension K - N >= 2 and v is not determined.  The method is exact on noise-free data and, as the
paper's recipe is, very sensitive to noise (NOTES item 5): use ``reconstruct`` for real data.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations


def _lean():
    from curverecon.generated import lean_polynomial

    return lean_polynomial


def n_columns() -> int:
    """K, the number of observable-monomial columns of the lean polynomial."""
    return len(_lean().OBSERVABLE_EXPONENTS)


def min_frames() -> int:
    """Frames the linearisation needs: K - 1 (rank K - 1 for a one-dimensional null space)."""
    return n_columns() - 1


@dataclass
class LinearResult:
    """Outcome of :func:`solve_linear`.

    Attributes:
        shape: (4,) c, alpha, beta, phi (input units, radians; alpha, beta in [0, pi/2],
            phi in [0, pi]).
        singular_values: singular values of the column-scaled frame matrix, descending.
        null_vector: (K,) the homogeneous solution v in the original (unscaled) column units of
            the length-normalised problem (c / L).
        rank_gap: smallest / second smallest singular value (small: well-determined null space).
        fit_residual: relative misfit of u(x) = lambda v after the ratio fit.
        length_scale: L.
    """

    shape: np.ndarray
    singular_values: np.ndarray
    null_vector: np.ndarray
    rank_gap: float
    fit_residual: float
    length_scale: float


def frame_matrix(obs: Observations, length_scale: float | None = None) -> tuple[np.ndarray, float]:
    """(N, K) lean-polynomial rows of every frame with lengths divided by L; returns (M, L)."""
    cp, dp, ep = obs.cp, obs.dp, obs.ep
    scale = float(np.mean(cp)) if length_scale is None else float(length_scale)
    return _lean().observable_matrix(cp / scale, dp / scale, ep / scale), scale


def _initial_guesses(v: np.ndarray, n_scan: int = 120) -> list[np.ndarray]:
    """Estimates of (c / L, tan alpha, tan beta, cos phi) from the null vector v (any scale).

    With K = c^8 tan^4 alpha tan^4 beta and C = cos phi the columns (4,0,4), (4,1,3), (0,4,4) are
    K C^4, 4 K C^2, K (1 - C^2)^2 (so K and C^2 by ratios), and (8,0,4), (8,4,0) are
    c^4 tan^4 alpha (1 + tan^2 beta C^2)^2 and c^4 tan^4 beta (1 + tan^2 alpha C^2)^2, whose
    square roots over K give a (x + C^2) and a (y + C^2) with a = 1/c^2, x = 1/tan^2 beta,
    y = 1/tan^2 alpha.  The remaining scale a is scanned (log grid) against all columns.
    """
    lean = _lean()
    exps = list(lean.OBSERVABLE_EXPONENTS)
    col = {e: v[exps.index(e)] for e in exps}
    cands = []
    for sign in (1.0, -1.0):
        w = {e: sign * val for e, val in col.items()}
        k4, k2, k0 = w[(4, 0, 4)], w[(4, 1, 3)], w[(0, 4, 4)]
        big_k = k0 + k2 / 2.0 - k4
        if not big_k > 0:
            continue
        cos2 = float(np.clip(k2 / (4.0 * big_k), 0.0, 1.0))
        p, q = w[(8, 0, 4)] / big_k, w[(8, 4, 0)] / big_k
        if p <= 0 or q <= 0:
            continue
        s1, s2 = np.sqrt(p), np.sqrt(q)
        a_max = min(s1, s2) / max(cos2, 1e-12)  # x, y > 0
        for a in np.geomspace(1e-4, 1e4, n_scan):
            if a >= a_max:
                break
            x, y = s1 / a - cos2, s2 / a - cos2
            for cs in (1.0, -1.0):
                z = np.array([1 / np.sqrt(a), 1 / np.sqrt(y), 1 / np.sqrt(x), cs * np.sqrt(cos2)])
                u = lean.unknown_columns(*z)
                nu = np.linalg.norm(u)
                if nu > 0 and np.isfinite(nu):
                    cands.append((1.0 - abs(u @ v) / (nu * np.linalg.norm(v)), z))
    cands.sort(key=lambda t: t[0])
    return [z for _, z in cands[:3]]


def _fit(v: np.ndarray, col_scale: np.ndarray, x0: np.ndarray) -> tuple[np.ndarray, float]:
    lean = _lean()
    vs = v * col_scale

    def fun(z: np.ndarray) -> np.ndarray:
        u = lean.unknown_columns(*z[:4]) * col_scale
        return u / np.linalg.norm(u) - z[4] * vs

    def jac(z: np.ndarray) -> np.ndarray:
        u = lean.unknown_columns(*z[:4]) * col_scale
        ju = lean.unknown_columns_jacobian(*z[:4]) * col_scale[:, None]
        nu = np.linalg.norm(u)
        jn = ju / nu - np.outer(u, u @ ju) / nu**3
        return np.column_stack([jn, -vs])

    u0 = lean.unknown_columns(*x0) * col_scale
    lam0 = float(np.sign(u0 @ vs) or 1.0) / np.linalg.norm(vs)
    sol = least_squares(
        fun, np.append(x0, lam0), jac=jac, method="lm", xtol=1e-15, ftol=1e-15, max_nfev=300
    )
    return sol.x[:4], float(np.linalg.norm(sol.fun))


def _polish(m: np.ndarray, norms: np.ndarray, x0: np.ndarray) -> np.ndarray:
    """Least squares of the frames' polynomial values M u(x) / |u(x)| (column-scaled) over x.

    The ratio fit uses the null vector only; this last step uses every frame directly, so a
    poorly separated smallest singular value (near the minimum number of frames) costs nothing
    on noise-free data.
    """
    lean = _lean()
    ms = m / norms

    def parts(z):
        u = lean.unknown_columns(*z) * norms
        return u, np.linalg.norm(u)

    def fun(z):
        u, nu = parts(z)
        return ms @ u / nu

    def jac(z):
        u, nu = parts(z)
        ju = lean.unknown_columns_jacobian(*z) * norms[:, None]
        jn = ju / nu - np.outer(u, u @ ju) / nu**3
        return ms @ jn

    try:
        sol = least_squares(
            fun, x0, jac=jac, method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15, max_nfev=300
        )
    except (ValueError, np.linalg.LinAlgError):
        return x0
    if np.all(np.isfinite(sol.x)) and np.linalg.norm(sol.fun) <= np.linalg.norm(fun(x0)):
        return sol.x
    return x0


def solve_linear(obs: Observations) -> LinearResult:
    """Shape from the paper's linearisation alone (SVD null vector, then ratios).

    Raises CurveReconError when there are fewer than ``min_frames()`` frames.
    """
    need = min_frames()
    if obs.n_frames < need:
        raise CurveReconError(
            f"the linearisation needs at least {need} frames ({need + 1} grouped columns with a "
            f"one-dimensional null space), got {obs.n_frames}; use --method auto"
        )
    with np.errstate(all="ignore"):
        return _solve_linear(obs)


def _solve_linear(obs: Observations) -> LinearResult:
    m, scale = frame_matrix(obs)
    norms = np.linalg.norm(m, axis=0)
    norms = np.where(norms > 0, norms, 1.0)
    _, sv, vt = np.linalg.svd(m / norms, full_matrices=True)  # N may be K - 1 < K
    v = vt[-1] / norms  # back to unscaled columns
    rank_gap = float(sv[-1] / sv[-2]) if sv.size > 1 and sv[-2] > 0 else 1.0
    best = None
    for x0 in _initial_guesses(v / np.linalg.norm(v)):
        try:
            x, res = _fit(v / np.linalg.norm(v * norms), norms, x0)
        except (ValueError, np.linalg.LinAlgError):
            continue
        if best is None or res < best[1]:
            best = (x, res)
    if best is None:
        raise CurveReconError(
            "the linearisation's null vector does not correspond to any shape "
            "(data too noisy or inconsistent for the linear method)"
        )
    x, res = best
    x = _polish(m, norms, x)
    c = abs(x[0]) * scale
    alpha = float(np.arctan(abs(x[1])))
    beta = float(np.arctan(abs(x[2])))
    cosphi = float(np.clip(x[3], -1.0, 1.0))
    if x[1] * x[2] < 0:
        cosphi = -cosphi  # tan alpha -> -tan alpha (or beta) is phi -> phi + pi
    shape = np.array([c, alpha, beta, float(np.arccos(cosphi))])
    return LinearResult(shape, sv, v, rank_gap, res, scale)
