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
NEAR_REAL = 1e-2
"""Largest |Im W| / (1 + |W|) of a root polished as a candidate (W on the data's unit scale).
Simple roots of exact data are real to about 1e-14; near z_f = 0 a real double root can split
into a complex pair of imaginary part ~1e-5 (1 of 1,000 scenes at 1e-7 in the bench)."""
DOMAIN_TOLERANCE = 1e-2
"""Slack on W >= 0 and W + k_f >= 0 of a candidate before polishing."""
DUPLICATE = 1e-9
"""Polished solutions closer than this (max |dz|, unit scale) are one solution."""
DEGENERATE = 1e-12
"""Largest |cofactor C_f| (or |k_f|) taken as zero (unit scale): all C_f vanish when the image
differences lie on one line (axis in the image plane), all k_f when the image lengths are equal
(axis along the viewing direction); either way the cubic vanishes identically."""
POLISH_STEPS = 8
POLISH_TOLERANCE = 1e-12
"""Largest residual of the polished system (unit scale) of an accepted solution."""


def _starts(roots: np.ndarray, k: np.ndarray) -> np.ndarray:
    """Newton starts (n, 4) = (z_0, z_1, z_2, z_3), z_0 >= 0, from the cubic's candidate roots W:
    every sign pattern of the later depths.  Near z_f = 0 two patterns meet and the cubic's
    roots there are near-double (even a complex pair by rounding), so every pattern is polished
    and duplicates dropped."""
    w = roots.real
    keep = (np.abs(roots.imag) <= NEAR_REAL * (1 + np.abs(roots))) & (w >= -DOMAIN_TOLERANCE)
    keep &= np.all(w[:, None] + k[None] >= -DOMAIN_TOLERANCE, axis=1)
    w = w[keep]
    signs = np.array(list(product((1.0, -1.0), repeat=3)))
    r = np.sqrt(np.maximum(w[:, None] + k[None], 0.0))  # (n, 3)
    later = (signs[None] * r[:, None]).reshape(-1, 3)
    z0 = np.repeat(np.sqrt(np.maximum(w, 0.0)), len(signs))
    return np.column_stack([z0, later])


def _residual(z: np.ndarray, cof: np.ndarray, k: np.ndarray) -> np.ndarray:
    """(n, 4): z_f^2 - z_0^2 - k_f (f = 1, 2, 3) and sum_f C_f (z_f - z_0)."""
    return np.column_stack([z[:, 1:] ** 2 - z[:, :1] ** 2 - k, (z[:, 1:] - z[:, :1]) @ cof])


def _polish(z: np.ndarray, cof: np.ndarray, k: np.ndarray) -> np.ndarray:
    """Newton's method on the unsquared system for every start at once (the cubic's
    coefficients lose digits by cancellation, the system does not); returns the starts that
    converge to POLISH_TOLERANCE."""
    jac = np.zeros((len(z), 4, 4))
    jac[:, 3] = [-cof.sum(), *cof]
    for _ in range(POLISH_STEPS):
        jac[:, :3, 0] = -2 * z[:, :1]
        jac[:, [0, 1, 2], [1, 2, 3]] = 2 * z[:, 1:]
        ok = np.abs(np.linalg.det(jac)) > 1e-300
        if not ok.all():
            z, jac = z[ok], jac[ok]
        z = z - np.linalg.solve(jac, _residual(z, cof, k)[..., None])[..., 0]
    scale = 1 + np.abs(cof).sum() * (1 + np.abs(z).max(axis=1, initial=0))
    return z[np.abs(_residual(z, cof, k)).max(axis=1) < POLISH_TOLERANCE * scale]


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
    if np.abs(cof).max() <= DEGENERATE or np.abs(k).max() <= DEGENERATE or not np.any(coefficients):
        # a curve of solutions (image differences on one line: axis in the image plane; equal
        # image lengths: axis along the viewing direction; frames alike): no finite set
        return assemble(pts, [], [], [], N_COMPLEX_SOLUTIONS)
    roots = np.roots(coefficients / np.max(np.abs(coefficients)))
    found: list[np.ndarray] = []
    for z in _polish(_starts(roots, k), cof, k):
        z = z if z[0] >= 0 else -z
        if all(np.abs(z - y).max() > DUPLICATE for y in found):
            found.append(z)
    depths, rots, motion = [], [], []
    for z in found:
        for zz in (z, -z):  # the solution and its mirror image
            r, m = _solution(vn, zz)
            depths.append((zz * scale)[:, None])
            rots.append(r)
            motion.append(m)
    return assemble(pts, depths, rots, motion, N_COMPLEX_SOLUTIONS)
