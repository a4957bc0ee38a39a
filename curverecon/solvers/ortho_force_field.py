"""Homogeneous force field, A and B: no practical minimal solver; the per-frame equation instead.

The derivation (``derivations/section2.py``, docs/derivation.md): the mass centre G is an unseen
body point whose image moves as g0 + g1 t + g2 t^2 / 2 (6 unknowns); with the body invariants
|a|^2, |b|^2, a.b of a = A - G, b = B - G (3 unknowns) every frame gives one quartic,
(|a|^2 - |p|^2)(|b|^2 - |q|^2) = (a.b - p.q)^2, p = A' - xy(G), q = B' - xy(G).  Nine unknowns,
so nine frames: the Jacobian of nine frames' equations at the truth has rank 9 (an isolated
solution; eight frames: rank 8, a curve of solutions), which makes the seed's "n" a 9.  Nine
quartics in nine unknowns have up to 4^9 = 262,144 solutions (Bezout); msolve does not finish
them within ``make derive``'s budget, and a homotopy over that many paths would take minutes per
solve, so there is no practical minimal solver: estimation starts from a global search over
all frames instead (``rigid/parabola.py``: the equation as a Sampson distance, a batch of starts
of the parabola refined at once).  :func:`residuals` evaluates the generated equation and its
gradient (``generated/section2_minimal.py``, ``force_field_residual``) for that search.
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.generated import section2_minimal as gen
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 9
POINTS: tuple[str, ...] = ("A", "B")
ROW = "ortho_force_field"
PRACTICAL = False
"""No practical minimal solver (see the module docstring)."""
UNKNOWNS = ("g0x", "g0y", "g1x", "g1y", "g2x", "g2y", "aa", "bb", "ab")
"""The order of :func:`residuals`'s parameter vector: xy(G) = g0 + g1 t + g2 t^2 / 2 (input
units, per unit of t), aa = |A - G|^2, bb = |B - G|^2, ab = (A - G).(B - G)."""


def solve(points: np.ndarray, times: np.ndarray) -> RigidSolutions:
    """Always raises CurveReconError: the force field has no practical minimal solver."""
    raise CurveReconError(
        f"{ROW}: no practical minimal solver (9 quartics in 9 unknowns, up to 262,144 "
        "solutions); the rigid stage seeds this model otherwise"
    )


def residuals(
    points: np.ndarray, times: np.ndarray, params: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Per frame the force-field equation (input units^4) and its gradient (F, 9) in UNKNOWNS.

    ``points`` (F, 2, 2) image positions of A, B; ``times`` (F,); zero exactly where every
    frame's depths of A - G and B - G exist for the parameters ``params`` (9,).
    """
    pts = np.asarray(points, dtype=float)
    t = np.asarray(times, dtype=float)
    res, grad = gen.force_field_residual(
        pts[:, 0, 0], pts[:, 0, 1], pts[:, 1, 0], pts[:, 1, 1], t, *np.asarray(params, float)
    )
    return res, grad
