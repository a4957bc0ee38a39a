"""Free motion, three traceable points A, B, C, three frames: every real solution in closed form.

Method (``derivations/section2.py``, docs/derivation.md): a rotation keeps the Gram matrix of
D = B - A and E = C - A, and equal Gram matrices of non-collinear D, E give exactly one
rotation.  With the unknown depths z_f of D_f and e_f of E_f, P = z_0^2, Q = e_0^2, M = z_0 e_0,
every later frame gives one *linear* equation in (P, Q, M), and M^2 = P Q leaves a **quadratic in
M** whose coefficients are generated functions of the data (``generated/section2_minimal.py``,
``free_3pt_quadratic``).  Closed form because the derivation finds one: no path can fail.  Each
real root with real depths gives 2^3 = 8 solutions, the per-frame flips (z_f, e_f) -> -(z_f, e_f)
(orthographic Necker reversal of each frame, which includes the mirror image): 16 complex
solutions in all (msolve).  Three generic frames leave two shapes; four frames determine the
shape, up to the per-frame flips that no number of frames removes.

Output: :class:`RigidSolutions`, 8 solutions per real shape (frame 0 unflipped first);
``motion`` is ``{}`` (free motion has no parameters).
"""

from __future__ import annotations

from itertools import product

import numpy as np

from curverecon.generated import section2_minimal as gen
from curverecon.solvers.ortho_common import (
    assemble,
    check_input,
    rotation_from_pairs,
    scale_of,
)
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B", "C")
ROW = "ortho_free_3pt"
N_COMPLEX_SOLUTIONS = 16
"""Complex solutions of three generic frames (docs/derivation.md, msolve)."""
NEAR_REAL = 1e-3
"""Largest |Im M| / (1 + |M|) of a root polished as a candidate (unit scale): simple roots of
exact data are real to about 1e-14, a near-double real root can split into a complex pair by
rounding; Newton's method on the Gram equations then decides."""
DUPLICATE = 1e-9
"""Polished depths closer than this (max, unit scale) are one solution."""
DOMAIN_TOLERANCE = 1e-3
"""Slack on P, Q, P + a_f, Q + b_f >= 0 before polishing (unit scale)."""
POLISH_STEPS = 4
POLISH_TOLERANCE = 1e-12
"""Largest residual of the polished Gram equations (unit scale) of an accepted solution."""


def _gram_residual(x: np.ndarray, abc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Residuals and Jacobian of z_f^2 - z_0^2 - a_f, e_f^2 - e_0^2 - b_f, z_f e_f - z_0 e_0 - c_f
    (f = 1, 2) in x = (z_0, z_1, z_2, e_0, e_1, e_2)."""
    z, e = x[:3], x[3:]
    a, b, c = abc[0:2], abc[2:4], abc[4:6]
    res = np.concatenate(
        [z[1:] ** 2 - z[0] ** 2 - a, e[1:] ** 2 - e[0] ** 2 - b, z[1:] * e[1:] - z[0] * e[0] - c]
    )
    jac = np.zeros((6, 6))
    for i, f in enumerate((1, 2)):
        jac[i, [0, f]] = -2 * z[0], 2 * z[f]
        jac[2 + i, [3, 3 + f]] = -2 * e[0], 2 * e[f]
        jac[4 + i, [0, f, 3, 3 + f]] = -e[0], e[f], -z[0], z[f]
    return res, jac


def _polish(x: np.ndarray, abc: np.ndarray) -> np.ndarray | None:
    """Newton's method on the Gram equations; None unless it meets POLISH_TOLERANCE."""
    for _ in range(POLISH_STEPS):
        res, jac = _gram_residual(x, abc)
        try:
            x = x - np.linalg.solve(jac, res)
        except np.linalg.LinAlgError:
            break
    res, _ = _gram_residual(x, abc)
    return x if np.abs(res).max() < POLISH_TOLERANCE * (1 + np.abs(x).max() ** 2) else None


def _depths(m: float, linear: np.ndarray, abc: np.ndarray) -> np.ndarray | None:
    """(z_0, z_1, z_2, e_0, e_1, e_2) for the root M (no flips), or None if not real."""
    pm, p0, qm, q0, det = linear
    p, q = (pm * m + p0) / det, (qm * m + q0) / det
    pf = np.concatenate([[p], p + abc[0:2]])
    qf = np.concatenate([[q], q + abc[2:4]])
    mf = np.concatenate([[m], m + abc[4:6]])
    if np.any(pf < -DOMAIN_TOLERANCE) or np.any(qf < -DOMAIN_TOLERANCE):
        return None
    pf, qf = np.maximum(pf, 0), np.maximum(qf, 0)
    z, e = np.sqrt(pf), np.sqrt(qf)
    use_z = pf >= qf  # the larger square root divides
    e = np.where(use_z, mf / np.where(z > 0, z, 1), e)
    z = np.where(use_z, z, mf / np.where(e > 0, e, 1))
    return np.concatenate([z, e])


def solve(points: np.ndarray, times: np.ndarray) -> RigidSolutions:
    """Every real solution of three frames of A, B, C under free motion.

    ``points`` (3, 3, 2) image positions of A, B, C (input units); ``times`` (3,) increasing
    (checked, not used: free motion).  Raises CurveReconError on bad shapes or times.
    """
    pts, _ = check_input(points, times, FRAMES, POINTS, ROW)
    d, e = pts[:, 1] - pts[:, 0], pts[:, 2] - pts[:, 0]
    scale = scale_of(np.concatenate([d, e]), ROW)
    coefficients, linear, abc = gen.free_3pt_quadratic(*(d / scale).ravel(), *(e / scale).ravel())
    depths, rots, motion = [], [], []
    if linear[4] == 0:
        return assemble(pts, depths, rots, motion, N_COMPLEX_SOLUTIONS)
    found: list[np.ndarray] = []
    for root in np.roots(coefficients / np.max(np.abs(coefficients))):
        if abs(root.imag) > NEAR_REAL * (1 + abs(root)):
            continue
        x = _depths(float(root.real), linear, abc)
        x = None if x is None else _polish(x, abc)
        if x is None:
            continue
        flip = np.where(x[:3] < 0, -1.0, 1.0)  # the representative with every z_f >= 0
        x = x * np.concatenate([flip, flip])
        if all(np.abs(x - y).max() > DUPLICATE for y in found):
            found.append(x)
    for x in found:
        for flips in product((1.0, -1.0), repeat=3):
            s = np.array(flips * 2)
            z = x * s * scale
            dv = np.column_stack([d, z[:3]])
            ev = np.column_stack([e, z[3:]])
            depths.append(np.column_stack([z[:3], z[3:]]))
            rots.append([rotation_from_pairs(dv[0], ev[0], dv[f], ev[f]) for f in range(3)])
            motion.append({})
    return assemble(pts, depths, rots, motion, N_COMPLEX_SOLUTIONS)
