"""Uniform rotation about a fixed axis, A and B, three frames: every real solution by a 1-D search.

Method (``derivations/section2.py``, docs/derivation.md): with D_f = B_f - A_f = (v_f, z_f), equal
norms give z_f = s_f sqrt(z_0^2 + |v_0|^2 - |v_f|^2), so one unknown z_0 and two signs remain;
three points of equal norm always lie on one circle about an axis through the origin, which fixes
the axis and the angles theta_1 (frame 0 to 1) and theta_21 (frame 1 to 2) as functions of z_0
(``generated/section2_minimal.py``, ``uniform_rotation_angles``).  The uniform rate asks
theta_21 = w (t_2 - t_1) with w = theta_1 / (t_1 - t_0): **one equation in one unknown**.  For
general times it is transcendental (w and w + 2 pi k / (t_1 - t_0) alias), so neither a
polynomial closed form nor a parameter homotopy applies; for equally spaced times it is
polynomial with 4 complex solutions (msolve), 2 up to the mirror.  The solver therefore
brackets every sign change of the wrapped residual on a grid of z_0 >= 0 for each sign pair,
refines it by regula falsi, keeps roots whose residual vanishes, and adds each root's mirror image
(z -> -z).  Sampling condition: the rotation between consecutive frames is below half a turn
(|w| (t_{f+1} - t_f) < pi), without which the rate is not determined by the frames.  No path
can fail (``n_failed_paths`` = 0); a root tangent to zero on the grid could be missed.  Four
generic frames determine the answer uniquely (up to the mirror).

Output: :class:`RigidSolutions`; ``motion`` per solution ``{"axis": n, "rate_deg": w (degrees
per unit of t, >= 0; the axis sign carries the sense), "angle_deg": w (t_f - t_0) per frame}``.
"""

from __future__ import annotations

import numpy as np

from curverecon.generated import section2_minimal as gen
from curverecon.solvers.ortho_common import assemble, check_input, rotation, scale_of
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B")
ROW = "ortho_uniform_rotation"
N_COMPLEX_SOLUTIONS = 4
"""Complex solutions of three generic equally spaced frames (docs/derivation.md, msolve); the
count the solver reports as ``n_paths`` (general times have no finite complex count)."""
GRID = 1000
"""Grid points in u, z_0 = z_min + tan(u)^2 on the unit scale, u in [0, 1.56] (z_0 up to about
8,500 times the image length).  On 500 bench scenes 600, 1,000 and 20,000 points find the same
roots; 1,000 keeps a margin at half the time of 2,000."""
U_MAX = 1.56
ILLINOIS_STEPS = 12
"""Regula falsi steps (Illinois variant) from each grid bracket: superlinear, the residual is at
rounding level after about 8 on the bench's scenes."""
ROOT_TOLERANCE = 1e-8
"""Largest |residual| (radians) of an accepted root (jumps of the wrapped residual by 2 pi, or
of the axis orientation, are sign changes without a root)."""
DEGENERATE = 1e-24
"""|(D_1 - D_0) x (D_2 - D_0)|^2 (unit scale) below which three frames define no circle."""
CONTINUUM = 0.5
"""A sign pair whose residual vanishes (ROOT_TOLERANCE) on more than this share of the grid has a
curve of solutions, not roots (frames alike, axis along the viewing direction): none listed."""
SIGNS = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))


def _residual(u: np.ndarray, s1: np.ndarray, s2: np.ndarray, data: tuple) -> np.ndarray:
    """wrap(theta_21 - rho theta_1) at z_0 = z_min + tan(u)^2 (nan where the sampling condition
    fails); ``data`` = (z_min, rho, v flattened)."""
    zmin, rho, v = data
    with np.errstate(invalid="ignore"):  # z_f^2 below 0 by rounding at z_min: nan, no root
        args, axis = gen.uniform_rotation_angles(zmin + np.tan(u) ** 2, s1, s2, *v)
    flat = np.sum(axis**2, axis=-1) <= DEGENERATE  # D_0, D_1, D_2 on one line: no circle
    args = np.where(flat[..., None], np.nan, args)
    th1 = np.arctan2(args[..., 0], args[..., 1])
    th21 = np.arctan2(args[..., 2], args[..., 3])
    pred = rho * th1
    out = np.angle(np.exp(1j * (th21 - pred)))
    return np.where(np.abs(pred) < np.pi, out, np.nan)


def _roots(data: tuple) -> list[tuple[float, float, float]]:
    """(z_0, s_1, s_2) of every root with z_0 >= z_min."""
    u = np.linspace(0.0, U_MAX, GRID)
    uu = np.tile(u, len(SIGNS))
    s1 = np.repeat([s[0] for s in SIGNS], GRID)
    s2 = np.repeat([s[1] for s in SIGNS], GRID)
    h = _residual(uu, s1, s2, data).reshape(len(SIGNS), GRID)
    if np.any(np.mean(np.abs(np.nan_to_num(h, nan=1.0)) < ROOT_TOLERANCE, axis=1) > CONTINUUM):
        return []
    lo_h, hi_h = h[:, :-1], h[:, 1:]
    with np.errstate(invalid="ignore"):
        cross = (lo_h * hi_h <= 0) & (np.abs(lo_h) < 1) & (np.abs(hi_h) < 1)
    rows, cols = np.nonzero(cross)
    if len(rows) == 0:
        return []
    a, b = u[cols], u[cols + 1]
    sg1, sg2 = np.array(SIGNS)[rows, 0], np.array(SIGNS)[rows, 1]
    fa, fb = lo_h[rows, cols], hi_h[rows, cols]
    for _ in range(ILLINOIS_STEPS):  # regula falsi, Illinois variant: stays in the bracket
        denom = fb - fa
        c = np.where(denom != 0, b - fb * (b - a) / np.where(denom != 0, denom, 1), b)
        fc = _residual(c, sg1, sg2, data)
        fc = np.where(np.isnan(fc), fb, fc)
        flip = fc * fb < 0
        a, fa = np.where(flip, b, a), np.where(flip, fb, 0.5 * fa)
        b, fb = c, fc
        if np.all(np.abs(fb) < 1e-3 * ROOT_TOLERANCE):
            break
    mid = b
    ok = np.abs(fb) < ROOT_TOLERANCE
    zmin = data[0]
    return [
        (zmin + np.tan(m) ** 2, a, b) for m, a, b, k in zip(mid, sg1, sg2, ok, strict=True) if k
    ]


def _solution(v: np.ndarray, z: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, dict]:
    """Rotations and motion for the depths z of D = B - A (three frames, exact circle)."""
    d = np.column_stack([v, z])
    n = np.cross(d[1] - d[0], d[2] - d[0])
    n /= np.linalg.norm(n)
    p0 = d[0] - (d[0] @ n) * n
    p1 = d[1] - (d[1] @ n) * n
    theta1 = float(np.arctan2(n @ np.cross(p0, p1), p0 @ p1))
    rate = theta1 / (t[1] - t[0])
    if rate < 0:
        n, rate = -n, -rate
    angles = rate * (t - t[0])
    rots = np.array([rotation(n, a) for a in angles])
    motion = {"axis": n.tolist(), "rate_deg": float(np.degrees(rate)),
              "angle_deg": np.degrees(angles).tolist()}  # fmt: skip
    return rots, motion


def solve(points: np.ndarray, times: np.ndarray) -> RigidSolutions:
    """Every real solution of three frames of A, B under a uniform rotation about a fixed axis.

    ``points`` (3, 2, 2) image positions of A, B (input units), ``times`` (3,) increasing (units
    of t: the rate is per unit of t).  Raises CurveReconError on bad shapes or times.
    """
    pts, t = check_input(points, times, FRAMES, POINTS, ROW)
    v = pts[:, 1] - pts[:, 0]
    scale = scale_of(v, ROW)
    vn = v / scale
    k = np.sum(vn[0] ** 2) - np.sum(vn[1:] ** 2, axis=1)
    zmin = float(np.sqrt(max(0.0, -k.min())))
    rho = (t[2] - t[1]) / (t[1] - t[0])
    depths, rots, motion = [], [], []
    for z0, s1, s2 in _roots((zmin, rho, vn.ravel())):
        z = np.array([z0, s1 * np.sqrt(max(z0**2 + k[0], 0)), s2 * np.sqrt(max(z0**2 + k[1], 0))])
        for zz in (z, -z):  # the solution and its mirror image
            r, m = _solution(vn, zz, t)
            depths.append((zz * scale)[:, None])
            rots.append(r)
            motion.append(m)
    return assemble(pts, depths, rots, motion, N_COMPLEX_SOLUTIONS)
