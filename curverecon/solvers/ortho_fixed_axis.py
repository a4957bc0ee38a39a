"""Rotation about a fixed axis direction, A and B, four frames: every real solution in closed form.

Method (``derivations/section2.py``, docs/derivation.md): with D_f = B_f - A_f = (v_f, z_f), a
rotation about one axis n keeps |D_f| and D_f . n, so z_f^2 = z_0^2 + |v_0|^2 - |v_f|^2 and the
differences D_f - D_0 are coplanar (normal n); conversely these give one rotation per frame.
Eliminating the later depths leaves a **cubic in W = z_0^2** whose coefficients are generated
functions of the data (``generated/section2_minimal.py``, ``fixed_axis_cubic``).  Closed form
because the derivation finds one: its three roots (eigenvalues of the companion matrix,
``numpy.roots``) are every solution, no path can fail, and it costs microseconds.  Each real root
with real depths gives one solution and its mirror image (z -> -z): at most 6 real solutions, 6
complex ones in all (msolve, docs/derivation.md).  Four generic frames do not determine the
answer uniquely; five do (up to the mirror).

Output: :class:`RigidSolutions`; ``motion`` per solution ``{"axis": n (unit, frame 0's camera
coordinates), "angle_deg": per-frame angle about n from frame 0}``; the axis sign is chosen so
that frame 1's angle lies in [0, 180].
"""

from __future__ import annotations

from itertools import product

import numpy as np

from curverecon.generated import section2_minimal as gen
from curverecon.solvers.ortho_common import (
    angle_about,
    assemble,
    check_input,
    rotation,
    scale_of,
)
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 4
POINTS: tuple[str, ...] = ("A", "B")
ROW = "ortho_fixed_axis"
N_COMPLEX_SOLUTIONS = 6
"""Complex solutions of four generic frames (docs/derivation.md, msolve)."""
REAL_TOLERANCE = 1e-7
"""Largest |Im W| / (1 + |W|) of a root taken as real (W on the data's unit scale); exact data
give roots real to about 1e-14."""
SIGN_TOLERANCE = 1e-3
"""Largest relative misfit of the coplanarity equation accepted for a root's depth signs before
polishing (the cubic's roots are accurate to about 1e-5 at worst)."""
POLISH_STEPS = 4
POLISH_TOLERANCE = 1e-12
"""Largest residual of the polished system (unit scale) of an accepted solution."""


def _depth_signs(w: float, cof: np.ndarray, k: np.ndarray) -> np.ndarray | None:
    """Depths (z_0, z_1, z_2, z_3) for the root W with z_0 >= 0: the sign pattern that
    satisfies sum_f C_f (z_f - z_0) = 0, or None if no pattern does."""
    z0 = np.sqrt(max(w, 0.0))
    r = np.sqrt(np.maximum(w + k, 0.0))
    best, best_err = None, np.inf
    size = np.abs(cof) @ (r + z0) + 1e-300
    for signs in product((1.0, -1.0), repeat=3):
        z = np.array(signs) * r
        err = abs(cof @ (z - z0)) / size
        if err < best_err:
            best, best_err = z, err
    if best is None or best_err > SIGN_TOLERANCE:
        return None
    return np.concatenate([[z0], best])


def _polish(z: np.ndarray, cof: np.ndarray, k: np.ndarray) -> np.ndarray | None:
    """Newton's method on the unsquared system (z_f^2 - z_0^2 - k_f, sum_f C_f (z_f - z_0)) from
    the cubic's root: the cubic's coefficients lose digits by cancellation, the system does not.
    None when it does not converge to POLISH_TOLERANCE."""
    for _ in range(POLISH_STEPS):
        res = np.concatenate([z[1:] ** 2 - z[0] ** 2 - k, [cof @ (z[1:] - z[0])]])
        jac = np.zeros((4, 4))
        jac[:3, 0] = -2 * z[0]
        jac[[0, 1, 2], [1, 2, 3]] = 2 * z[1:]
        jac[3] = [-cof.sum(), *cof]
        try:
            z = z - np.linalg.solve(jac, res)
        except np.linalg.LinAlgError:
            break
    res = np.concatenate([z[1:] ** 2 - z[0] ** 2 - k, [cof @ (z[1:] - z[0])]])
    scale = 1 + np.abs(cof).sum() * (1 + np.abs(z).max())
    return z if np.abs(res).max() < POLISH_TOLERANCE * scale else None


def _solution(v: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, dict]:
    """Rotations (F, 3, 3) and motion for the depths z of D = B - A."""
    d = np.column_stack([v, z])
    _, _, vt = np.linalg.svd(d[1:] - d[0])
    axis = vt[-1]
    angles = np.array([angle_about(axis, d[0], d[f]) for f in range(len(d))])
    if angles[1] < 0:
        axis, angles = -axis, -angles
    rots = np.array([rotation(axis, a) for a in angles])
    return rots, {"axis": axis.tolist(), "angle_deg": np.degrees(angles).tolist()}


def solve(points: np.ndarray, times: np.ndarray) -> RigidSolutions:
    """Every real solution of four frames of A, B rotating about one fixed axis direction.

    ``points`` (4, 2, 2) image positions of A, B (input units), ``times`` (4,) increasing (not
    used by this model beyond the check).  Raises CurveReconError on bad shapes or times.
    """
    pts, _ = check_input(points, times, FRAMES, POINTS, ROW)
    v = pts[:, 1] - pts[:, 0]
    scale = scale_of(v, ROW)
    vn = v / scale
    coefficients, cof, k = gen.fixed_axis_cubic(*vn.ravel())
    roots = np.roots(coefficients / np.max(np.abs(coefficients)))
    depths, rots, motion = [], [], []
    for root in roots:
        if abs(root.imag) > REAL_TOLERANCE * (1 + abs(root)):
            continue
        w = float(root.real)
        if w < -SIGN_TOLERANCE or np.any(w + k < -SIGN_TOLERANCE):
            continue
        z = _depth_signs(w, cof, k)
        z = None if z is None else _polish(z, cof, k)
        if z is None:
            continue
        for zz in (z, -z):  # the solution and its mirror image
            r, m = _solution(vn, zz)
            depths.append((zz * scale)[:, None])
            rots.append(r)
            motion.append(m)
    return assemble(pts, depths, rots, motion, N_COMPLEX_SOLUTIONS)
