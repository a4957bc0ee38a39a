"""The seed's Section 2 table, perspective and stereo rows: each row's minimal problem, derived.

Every row is a rigid body seen by a calibrated pinhole camera (CONTRACT.md, "Configurations beyond
the paper's own").  A pixel (u, v) of a camera with focal length f and principal point (cx, cy)
is the ray m = ((u - cx) / f, (v - cy) / f, 1) (normalised coordinates); a point X in camera
coordinates is X = lambda m, lambda its depth (camera z).  The global scale is fixed as the
contract says: A's depth in frame 0 is 1 (lambda_A0 = 1), so A_0 = m_A0.  Motion models:

- ``rotation_free``: X_f = X_0 + T_f (A, B; the table says 2 frames);
- ``uniform_rotation``: X_f = Rot(n, w (t_f - t_0)) X_0 + T_f (A, B; 5 frames);
- ``fixed_axis_3pt``: X_f = Rot(n, theta_f) X_0 + T_f (A, B, C; 3 frames);
- ``free_4pt``: X_f = R_f X_0 + T_f (A, B, C, D; 3 frames);
- ``force_field``: any rotation, the mass centre G (an unknown body point) moves as
  g0 + g1 t + g2 t^2 / 2 (A, B; "n" frames);
- ``stereo_free``: two calibrated cameras, camera 1 at X1 = R X0 + t, one frame (A, B).

The translation is free in every row but the force field, so only differences of points carry
information.  The key reduction (``plane_equation``): for two points A, B the difference
D_f = B_f - A_f = lambda_Bf m_Bf - lambda_Af m_Af lies in the plane through the camera centre
and the image line A'_f B'_f, whose normal is N_f = m_Af x m_Bf: N_f . D_f = 0, one equation per
frame and pair of points, free of the depths.  Conversely, given D_f in that plane the depths
follow (``depths_from_difference``, two linear equations).  For three points the three edge
planes (AB, AC, BC) are equivalent to the triangle being inscribed in the three rays.  Rotations
are written in Cayley form, Rot = cayley(mu n) = ((1 - k.k) I + 2 [k]x + 2 k k^T) / (1 + k.k),
k = mu n with the axis in the chart n = (n1, n2, 1) (the rotation about n by 2 atan(mu |n|));
the denominator is dropped (the counts saturate it away).  The runtime turns the camera by a
fixed generic rotation first (``CHART_ROTATION``), so that an axis in the image plane (a
turntable seen from the side) is not on the chart's boundary n3 = 0.

Each step is a small function; ``checks()`` evaluates every equation at the 3-D construction
(random bodies and motions, float64) and ``facts()`` counts the solutions with msolve over
GF(p) (``derivations.minimal_count``: the same tool and prime as the orthographic rows).

Sources: the seed's Section 2 table (rows, points and frame numbers); the plane constraint of a
line seen by a pinhole camera is the standard one of line-based structure from motion; the
four-point, three-view count is Nister and Schaffalitzky, "Four points in two or three calibrated
views: theory and practice", IJCV 2006 (two views leave a one-parameter family, three views are
overdetermined by one).
"""

from __future__ import annotations

import random
from collections.abc import Callable, Sequence
from functools import cache
from types import SimpleNamespace

import mpmath
import numpy as np
import sympy as sp

from derivations import minimal_count as mc
from derivations.codegen.generate import system_terms
from derivations.codegen.spec import FunctionSpec, PolynomialSystem
from derivations.section2 import to_msolve

MODULE_DOC = (
    "The minimal problems of the seed's Section 2 perspective and stereo rows with a closed "
    "form (rotation-free motion, stereo triangulation): their linear systems as functions of "
    "the rays, derived and checked in derivations/section2_perspective.py."
)

ROWS = (
    "rotation_free",
    "uniform_rotation",
    "fixed_axis_3pt",
    "free_4pt",
    "force_field",
    "stereo_free",
)
POINTS = {
    "rotation_free": "AB",
    "uniform_rotation": "AB",
    "fixed_axis_3pt": "ABC",
    "free_4pt": "ABCD",
    "force_field": "AB",
    "stereo_free": "AB",
}
TABLE_FRAMES = {
    "rotation_free": "2",
    "uniform_rotation": "5",
    "fixed_axis_3pt": "3",
    "free_4pt": "3",
    "force_field": "n",
    "stereo_free": "1",
}
MINIMAL_FRAMES = {
    "rotation_free": 2,
    "uniform_rotation": 5,
    "fixed_axis_3pt": 3,
    "free_4pt": 3,
    "force_field": 11,
    "stereo_free": 1,
}
N_CHECK = 8
CHECK_SEED = 2026_11_28
COUNT_SEEDS = (1, 2)
TRUE_SEED = 7
MONODROMY_SEED = 2026_11_28
STABLE_LOOPS = 12
MAX_LOOPS = 80
POLISH_DPS = 30

CHART_ROTATION = (
    (0.36, 0.48, -0.80),
    (-0.80, 0.60, 0.00),
    (0.48, 0.64, 0.60),
)
"""The fixed rotation G the runtime applies to every ray (m -> G m) before the homotopy: the
axis chart n = (n1, n2, 1) then fails only for axes perpendicular to G^T e3, not for the common
axes in the image plane.  Exact rationals (a Pythagorean rotation), so G is orthogonal in
float64 to rounding."""


# ---------------------------------------------------------------------------------------------
# symbols
# ---------------------------------------------------------------------------------------------


def ray(point: str, frame: int) -> sp.Matrix:
    """The ray of ``point`` in ``frame`` as three parameters (m_x, m_y, m_z): normalised image
    coordinates are (x, y, 1); the runtime passes G m (``CHART_ROTATION``)."""
    return sp.Matrix(sp.symbols(f"{point.lower()}{frame}x {point.lower()}{frame}y "
                                f"{point.lower()}{frame}z"))  # fmt: skip


def rays(points: str, frames: int) -> dict[tuple[str, int], sp.Matrix]:
    """Every ray of ``points`` in ``frames`` frames, keyed (point, frame)."""
    return {(p, f): ray(p, f) for f in range(frames) for p in points}


def ray_parameters(points: str, frames: int) -> tuple[sp.Symbol, ...]:
    """The rays' parameters in a fixed order: frame by frame, point by point, x y z."""
    return tuple(s for f in range(frames) for p in points for s in ray(p, f))


PAIRS = {"uniform_rotation": ("AB",), "fixed_axis_3pt": ("AB", "AC", "BC")}
"""The point pairs whose plane normals N_f = m_Pf x m_Qf are the homotopy rows' parameters."""


def normal(pair: str, frame: int) -> sp.Matrix:
    """The normal N = m_P x m_Q of the plane through the camera centre and the image line of the
    pair PQ in ``frame`` (three parameters; the runtime passes G m_P x G m_Q)."""
    return sp.Matrix(sp.symbols(" ".join(f"n{pair.lower()}{frame}{c}" for c in "xyz")))


def system_parameters(row: str, frames: int) -> tuple[sp.Symbol, ...]:
    """The parameters of a homotopy row: frame 0's rays (A, B[, C]), then per later frame the
    plane normals of ``PAIRS[row]``.  Rotation-free and four points: the rays of every frame."""
    if row not in PAIRS:
        return ray_parameters(POINTS[row], frames)
    out = list(ray_parameters(POINTS[row], 1))
    for f in range(1, frames):
        for pair in PAIRS[row]:
            out.extend(normal(pair, f))
    return tuple(out)


def skew(k: sp.Matrix) -> sp.Matrix:
    """[k]x, the cross-product matrix: [k]x v = k x v."""
    return sp.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])


def cayley_numerator(k: sp.Matrix) -> sp.Matrix:
    """(1 + k.k) cayley(k) = (1 - k.k) I + 2 [k]x + 2 k k^T: the rotation about k / |k| by
    2 atan |k|, times its denominator (integer coefficients, as the generated tables need)."""
    return (1 - k.dot(k)) * sp.eye(3) + 2 * skew(k) + 2 * k * k.T


# ---------------------------------------------------------------------------------------------
# the 3-D construction (float64): bodies, motions, pinhole projection
# ---------------------------------------------------------------------------------------------


def rotation_np(axis: np.ndarray, angle: float) -> np.ndarray:
    """Rot(axis, angle), right-handed (Rodrigues), ``axis`` normalised here."""
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * (k @ k)


def random_rotation_np(rng: np.random.Generator) -> np.ndarray:
    """A uniformly random rotation (QR of a Gaussian matrix, determinant +1)."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def construct_np(row: str, rng: np.random.Generator, frames: int) -> dict[str, np.ndarray]:
    """One 3-D scene of ``row`` in camera coordinates, scaled so that A's depth in frame 0 is 1.

    Body points of size about 1 at a distance of about 5, moved by the row's model, projected by
    the pinhole: ``X3`` (F, P, 3) (A, B[, C, D] and for the force field the mass centre G last),
    ``rays`` (F, P, 3) = X3 / X3_z, ``times`` (F,), ``axis``, ``theta`` (F,) radians from frame
    0, ``R`` (F, 3, 3) with X_f - A_f = R_f (X_0 - A_0).  Stereo: also ``R1``, ``t1`` (camera
    1: X1 = R1 X0 + t1) and ``rays1``.
    """
    npts = len(POINTS[row]) + (1 if row == "force_field" else 0)
    body = rng.normal(size=(npts, 3)) * 0.6
    times = np.cumsum(rng.uniform(0.5, 1.5, frames)) - 0.7
    if row == "uniform_rotation":
        times = times[0] + 0.8 * np.arange(frames)  # equally spaced (the solver's case)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    theta = np.concatenate([[0.0], rng.uniform(-2.5, 2.5, frames - 1)])
    if row == "uniform_rotation":
        theta = rng.uniform(0.2, 0.9) * rng.choice([-1, 1]) * (times - times[0]) / 0.8
    rel = np.array([rotation_np(axis, th) for th in theta])
    if row in ("free_4pt", "force_field", "stereo_free"):
        rel = np.array([np.eye(3)] + [random_rotation_np(rng) for _ in range(frames - 1)])
    if row == "rotation_free":
        rel = np.array([np.eye(3)] * frames)
    centre = np.array([0.0, 0.0, 5.0])
    x3 = np.empty((frames, npts, 3))
    if row == "force_field":
        g = np.vstack([centre, rng.normal(size=(2, 3)) * 0.5])
        path = g[0] + np.outer(times, g[1]) + np.outer(times**2 / 2, g[2])
        for f in range(frames):  # body about G (the last point), G on its parabola
            x3[f] = (rel[f] @ (body - body[-1]).T).T + path[f]
    else:
        for f in range(frames):
            x3[f] = (rel[f] @ body.T).T + centre + rng.normal(size=3) * 0.5
    scale = x3[0, 0, 2]
    x3 /= scale
    out = {"X3": x3, "rays": x3 / x3[:, :, 2:], "times": times, "axis": axis,
           "theta": theta, "R": rel}  # fmt: skip
    if row == "stereo_free":
        r1 = rotation_np(rng.normal(size=3), rng.uniform(0.05, 0.3))
        t1 = np.array([-rng.uniform(0.1, 0.4), rng.normal() * 0.05, rng.normal() * 0.05])
        x1 = x3 @ r1.T + t1
        out.update({"R1": r1, "t1": t1, "rays1": x1 / x1[:, :, 2:]})
    return out


# ---------------------------------------------------------------------------------------------
# equations
# ---------------------------------------------------------------------------------------------


def plane_equation(ma: sp.Matrix, mb: sp.Matrix, d: sp.Matrix) -> sp.Expr:
    """(m_A x m_B) . D = 0: the difference D = B - A of two points on the rays m_A, m_B lies in
    the plane through the camera centre and the image line A'B' (it is a combination of the two
    rays).  Free of the depths; with it, D fixes them (``depths_from_difference``)."""
    return sp.expand(ma.cross(mb).dot(d))


def depths_from_difference(ma: np.ndarray, mb: np.ndarray, d: np.ndarray) -> tuple[float, float]:
    """(lambda_A, lambda_B) with lambda_B m_B - lambda_A m_A = D (D in the plane of m_A, m_B):
    least squares of the three components (exact when the plane equation holds)."""
    sol, *_ = np.linalg.lstsq(np.column_stack([-ma, mb]), d, rcond=None)
    return float(sol[0]), float(sol[1])


def rotation_free_system(frames: int) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """Rotation-free motion: D_f = D_0 for every later frame, D_f = lambda_Bf m_Bf -
    lambda_Af m_Af, lambda_A0 = 1.  Linear: 3 (F - 1) equations in 2 F - 1 depths; two frames
    give 3 equations in 3 unknowns (lambda_B0, lambda_A1, lambda_B1), one solution."""
    m = rays("AB", frames)
    lam = {(p, f): sp.Symbol(f"l{p}{f}") for f in range(frames) for p in "AB"}
    lam[("A", 0)] = sp.Integer(1)
    d = [lam[("B", f)] * m[("B", f)] - lam[("A", f)] * m[("A", f)] for f in range(frames)]
    eqs = [sp.expand(x) for f in range(1, frames) for x in d[f] - d[0]]
    unknowns = [s for s in lam.values() if isinstance(s, sp.Symbol)]
    return unknowns, eqs


UR_UNKNOWNS = sp.symbols("n1 n2 mu b0")


def uniform_rotation_unknowns(frames: int = 5) -> list[sp.Symbol]:
    """(n1, n2, mu, b0) and the auxiliary vectors v_f = Q^f D_0 (f = 1 .. F - 1, x y z)."""
    return list(UR_UNKNOWNS) + [sp.Symbol(f"v{f}{c}") for f in range(1, frames) for c in "xyz"]


def uniform_rotation_system(frames: int = 5) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """Uniform rotation, equally spaced times: one step Q = cayley(mu n), R_f = Q^f.  Per later
    frame the plane equation of AB: N_f . Q^f D_0 = 0, N_f = m_Af x m_Bf, with
    D_0 = b0 m_B0 - m_A0 (lambda_A0 = 1).  Written with auxiliary vectors v_f = Q v_{f-1},
    v_0 = D_0, as (1 + k.k) v_f = Qn v_{f-1} (Qn = (1 + k.k) Q the Cayley numerator): every
    equation has degree at most 3, and the v_f keep the length of D_0 (with Qn^f D_0 instead,
    they grew like (1 + k.k)^f and paths jumped); the v_f are determined by (n1, n2, mu, b0),
    so the solutions are those of the four plane equations N_f . Q^f D_0 = 0 in
    (n1, n2, mu, b0): F - 1 equations, five frames the least, as the table says.  General times
    are not polynomial (cos w t_f); the solver takes equally spaced ones (a constant frame
    rate)."""
    n1, n2, mu, b0 = UR_UNKNOWNS
    unknowns = uniform_rotation_unknowns(frames)
    k = mu * sp.Matrix([n1, n2, 1])
    q = cayley_numerator(k)
    prev = b0 * ray("B", 0) - ray("A", 0)
    eqs: list[sp.Expr] = []
    for f in range(1, frames):
        v = sp.Matrix(unknowns[4 + 3 * (f - 1) : 7 + 3 * (f - 1)])
        eqs += [sp.expand(x) for x in (1 + k.dot(k)) * v - q * prev]
        eqs.append(sp.expand(normal("AB", f).dot(v)))
        prev = v
    return unknowns, eqs


def fixed_axis_unknowns(frames: int) -> list[sp.Symbol]:
    """(b0, c0, n1, n2, mu_1 .. mu_{F-1}): depths of B, C in frame 0, the axis chart and one
    Cayley parameter per later frame (theta_f = 2 atan(mu_f |n|))."""
    return list(sp.symbols("b0 c0 n1 n2")) + list(sp.symbols(f"mu1:{frames}"))


def fixed_axis_system(frames: int = 3) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """Three points, rotation about a fixed direction: R_f = cayley(mu_f n).  Per later frame the
    three edge planes: N_AB . R D_0, N_AC . R E_0, N_BC . R (E_0 - D_0) (N_PQ = m_P x m_Q the
    later frame's plane normals, the parameters with frame 0's rays), D_0 = b0 m_B0 - m_A0,
    E_0 = c0 m_C0 - m_A0.  3 (F - 1) equations in F + 3 unknowns: three
    frames are the least, as the table says."""
    m = rays("ABC", frames)
    unknowns = fixed_axis_unknowns(frames)
    b0, c0, n1, n2 = unknowns[:4]
    d = b0 * m[("B", 0)] - m[("A", 0)]
    e = c0 * m[("C", 0)] - m[("A", 0)]
    eqs = []
    for f, mu in enumerate(unknowns[4:], start=1):
        r = cayley_numerator(mu * sp.Matrix([n1, n2, 1]))
        eqs += [sp.expand(normal(pair, f).dot(r * x))
                for pair, x in (("AB", d), ("AC", e), ("BC", e - d))]  # fmt: skip
    return unknowns, eqs


def free_4pt_system(frames: int = 3) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """Four points, free motion: the six distances of every later frame equal frame 0's
    (|X_Qf - X_Pf|^2 = |X_Q0 - X_P0|^2 with X_Pf = lambda_Pf m_Pf, lambda_A0 = 1).  Equal
    distances of four points admit the motion or its mirror image; the mirror is excluded by
    det[D, E, F] keeping its sign (checked by the runtime, not an equation).  6 (F - 1)
    equations in 4 F - 1 unknowns: two frames leave a curve, three are overdetermined by one."""
    m = rays("ABCD", frames)
    lam = {(p, f): sp.Symbol(f"l{p}{f}") for f in range(frames) for p in "ABCD"}
    lam[("A", 0)] = sp.Integer(1)
    x = {k: lam[k] * m[k] for k in lam}
    eqs = []
    for f in range(1, frames):
        for i, p in enumerate("ABCD"):
            for q in "ABCD"[i + 1 :]:
                df, d0 = x[(q, f)] - x[(p, f)], x[(q, 0)] - x[(p, 0)]
                eqs.append(sp.expand(df.dot(df) - d0.dot(d0)))
    return [s for s in lam.values() if isinstance(s, sp.Symbol)], eqs


FF_GLOBALS = sp.symbols("g0x g0y g0z g1x g1y g1z g2x g2y g2z aa bb ab")


def force_field_frame(frame: int, t: sp.Symbol) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """One frame of the force field: with G_f = g0 + g1 t + g2 t^2 / 2 (camera coordinates,
    unknown) and the body invariants aa = |A - G|^2, bb = |B - G|^2, ab = (A - G).(B - G), the
    frame's points A_f = lambda_A m_A, B_f = lambda_B m_B satisfy the three invariants: 3
    equations in 2 depths (lambda_A0 = 1 in frame 0)."""
    g0x, g0y, g0z, g1x, g1y, g1z, g2x, g2y, g2z, aa, bb, ab = FF_GLOBALS
    gf = sp.Matrix([g0x + g1x * t + g2x * t**2 / 2, g0y + g1y * t + g2y * t**2 / 2,
                    g0z + g1z * t + g2z * t**2 / 2])  # fmt: skip
    la = sp.Integer(1) if frame == 0 else sp.Symbol(f"lA{frame}")
    lb = sp.Symbol(f"lB{frame}")
    a = la * ray("A", frame) - gf
    b = lb * ray("B", frame) - gf
    unknowns = [lb] if frame == 0 else [la, lb]
    return unknowns, [a.dot(a) - aa, b.dot(b) - bb, a.dot(b) - ab]


def stereo_triangulation() -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """Stereo, one point: lambda_1 m_1 = R (lambda_0 m_0) + t, camera 1 at X1 = R X0 + t: three
    linear equations in the two depths (the epipolar constraint is their consistency), so each
    traceable point is triangulated on its own and one frame gives A and B, hence c = |AB|."""
    m0, m1 = ray("P", 0), ray("P", 1)
    r = sp.Matrix(3, 3, sp.symbols("r0:9"))
    t = sp.Matrix(sp.symbols("t0:3"))
    l0, l1 = sp.symbols("l0 l1")
    return [l0, l1], list(l1 * m1 - (r * (l0 * m0) + t))


# ---------------------------------------------------------------------------------------------
# generated closed forms
# ---------------------------------------------------------------------------------------------


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/section2_perspective.py: the linear systems of the two
    closed-form rows."""
    unknowns, eqs = rotation_free_system(2)
    mat, rhs = sp.linear_eq_to_matrix(eqs, unknowns)
    l0, l1 = sp.symbols("l0 l1")
    _, st = stereo_triangulation()
    smat, srhs = sp.linear_eq_to_matrix(st, [l0, l1])
    r = sp.symbols("r0:9")
    t = sp.symbols("t0:3")
    return [
        FunctionSpec(
            "rotation_free_linear",
            ray_parameters("AB", 2),
            {"matrix": mat, "rhs": rhs},
            "Rotation-free motion, two frames: M u = rhs with u = (lambda_B0, lambda_A1, "
            "lambda_B1), the depths of B in frame 0 and of A, B in frame 1 in units of A's "
            "depth in frame 0 (D_1 = D_0).  Arguments: the rays (x, y, 1) of A, B in frames 0 "
            "and 1, normalised image coordinates.",
        ),
        FunctionSpec(
            "stereo_linear",
            (*ray("P", 0), *ray("P", 1), *r, *t),
            {"matrix": smat, "rhs": srhs},
            "Stereo, one point: M (lambda_0, lambda_1) = rhs (three equations, least squares), "
            "lambda_0 the depth in camera 0, lambda_1 in camera 1 (X1 = R X0 + t, R row by row "
            "as r0..r8, t in the units of the result).  Arguments: the point's rays in camera 0 "
            "and camera 1 (normalised), R, t.",
        ),
    ]


# ---------------------------------------------------------------------------------------------
# homotopy systems: start solutions by monodromy
# ---------------------------------------------------------------------------------------------


def _crandn(rng: np.random.Generator, *shape: int) -> np.ndarray:
    return (rng.normal(size=shape) + 1j * rng.normal(size=shape)) / np.sqrt(2)


def _round(z: complex, digits: int = 15) -> complex:
    return complex(float(f"{z.real:.{digits}g}"), float(f"{z.imag:.{digits}g}"))


def _cayley_c(k: np.ndarray) -> np.ndarray:
    """cayley(k) for complex k (the rotation the numerator / (1 + k.k) gives)."""
    kk = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return ((1 - k @ k) * np.eye(3) + 2 * kk + 2 * np.outer(k, k)) / (1 + k @ k)


def _complex_scene(row: str, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(parameters q0, one solution x0): a complex body moved by the row's model, seen on complex
    rays (each a random complex multiple of its point, frame 0's scaled to the depths); the
    parameters are frame 0's rays and the later frames' plane normals (``system_parameters``)."""
    frames = MINIMAL_FRAMES[row]
    npts = len(POINTS[row])
    x0 = np.array([_round(z) for z in _crandn(rng, 4 if row == "uniform_rotation" else 3 + frames)])
    if row == "uniform_rotation":
        n1, n2, mu, b0 = x0
        q = _cayley_c(mu * np.array([n1, n2, 1]))
        rots = [np.linalg.matrix_power(q, f) for f in range(frames)]
        depth0 = [1.0, b0]
    else:
        b0, c0, n1, n2 = x0[:4]
        rots = [np.eye(3)] + [_cayley_c(mu * np.array([n1, n2, 1])) for mu in x0[4:]]
        depth0 = [1.0, b0, c0]
    body = _crandn(rng, npts, 3) + np.array([0, 0, 3.0])
    params = [body[p] / depth0[p] for p in range(npts)]
    for f in range(1, frames):
        pts = (rots[f] @ body.T).T + _crandn(rng, 3)
        m = {p: pts[i] * _crandn(rng, 1)[0] for i, p in enumerate(POINTS[row])}
        params += [np.cross(m[pair[0]], m[pair[1]]) for pair in PAIRS[row]]
    q0 = np.array([_round(z) for z in np.concatenate(params)])
    if row == "uniform_rotation":  # the auxiliary vectors v_f = Q^f D_0 at the rounded x0
        qn = _cayley_c(x0[2] * np.array([x0[0], x0[1], 1]))
        v, aux = x0[3] * q0[3:6] - q0[0:3], []
        for _ in range(1, frames):
            v = qn @ v
            aux.extend(v)
        x0 = np.concatenate([x0, aux])
    return q0, x0


SYSTEMS: dict[str, Callable[[], tuple[list[sp.Symbol], list[sp.Expr]]]] = {
    "uniform_rotation": uniform_rotation_system,
    "fixed_axis_3pt": fixed_axis_system,
}


def _tables(row: str) -> SimpleNamespace:
    """The generated module's tables, built the same way (for monodromy before emitting)."""
    unknowns, eqs = SYSTEMS[row]()
    params = system_parameters(row, MINIMAL_FRAMES[row])
    umons, pmons, terms = system_terms(eqs, unknowns, params)
    return SimpleNamespace(
        UNKNOWNS=tuple(s.name for s in unknowns),
        PARAMETERS=tuple(s.name for s in params),
        EQUATIONS=tuple(range(len(eqs))),
        UNKNOWN_EXPONENTS=np.array(umons, dtype=np.int64),
        PARAMETER_EXPONENTS=np.array(pmons, dtype=np.int64),
        TERMS=np.array([t[:3] for t in terms], dtype=np.int64),
        COEFFICIENTS=np.array([t[3] for t in terms], dtype=np.float64),
        START_PARAMETERS=np.zeros(len(params), complex),
        START_SOLUTIONS=np.zeros((1, len(unknowns)), complex),
    )


def _new_points(known: np.ndarray, pts: np.ndarray, tol: float = 1e-6) -> list[np.ndarray]:
    """Rows of ``pts`` (finite) not within ``tol`` (relative) of a known row or of each other."""
    out: list[np.ndarray] = []
    for p in pts:
        if not np.all(np.isfinite(p)):
            continue
        ref = np.vstack([known, *out]) if out else known
        if np.min(np.linalg.norm(ref - p, axis=1) / (1 + np.linalg.norm(p))) < tol:
            continue
        out.append(p)
    return out


def monodromy(row: str, expected: int | None) -> tuple[np.ndarray, np.ndarray, int]:
    """Every solution of the row's start system: (q0, solutions, loops).  Loops the parameters
    around random triangles from one constructed solution, tracking every known solution with
    the runtime's tracker, until the count reaches ``expected`` (msolve's) and one more loop
    adds nothing, or ``STABLE_LOOPS`` loops in a row add nothing.  For the fixed axis that
    happens at 84 of msolve's 88 (80 loops found no more): the other four lie on a component
    of the solution set that no loop from a constructed scene reaches, so the truth of a real
    scene is never among them."""
    from curverecon.solvers import homotopy

    rng = np.random.default_rng(MONODROMY_SEED + ROWS.index(row))
    system = homotopy.PolynomialSystem.from_module(_tables(row))
    q0, x0 = _complex_scene(row, rng)
    sols = system.polish(x0[None], q0, 8)
    stable = loops = 0
    opts = homotopy.HomotopyOptions(max_step=0.1, predictor_tolerance=1e-4)
    while loops < MAX_LOOPS and stable < (1 if len(sols) == expected else STABLE_LOOPS):
        loops += 1
        q1 = q0 + _crandn(rng, q0.size)
        q2 = q0 + _crandn(rng, q0.size)
        x, ok = sols, np.ones(len(sols), bool)
        for qa, qb in ((q0, q1), (q1, q2), (q2, q0)):
            x, status, _ = homotopy.track_once(system, qa, qb, x, None, opts)
            ok &= status == homotopy.OK
        new = _new_points(sols, x[ok])
        if new:
            sols = np.vstack([sols, *new])
            stable = 0
        else:
            stable += 1
    return q0, sols, loops


def polish(row: str, q0: np.ndarray, sols: np.ndarray) -> np.ndarray:
    """Newton's method at POLISH_DPS digits (mpmath); rows sorted (rounded) for a fixed order."""
    unknowns, eqs = SYSTEMS[row]()
    return _polish(unknowns, eqs, system_parameters(row, MINIMAL_FRAMES[row]), q0, sols)


def _polish(
    unknowns: Sequence[sp.Symbol],
    eqs: Sequence[sp.Expr],
    params: Sequence[sp.Symbol],
    q0: np.ndarray,
    sols: np.ndarray,
) -> np.ndarray:
    """``polish`` of any system."""
    fun = sp.lambdify((unknowns, params), eqs, "mpmath")
    jac = sp.lambdify((unknowns, params), sp.Matrix(eqs).jacobian(unknowns), "mpmath")
    out = []
    with mpmath.workdps(POLISH_DPS):
        qm = [mpmath.mpc(complex(z)) for z in q0]
        for row_x in sols:
            x = [mpmath.mpc(complex(z)) for z in row_x]
            for _ in range(4):
                dx = mpmath.lu_solve(mpmath.matrix(jac(x, qm)), mpmath.matrix(fun(x, qm)))
                x = [xi - dx[i] for i, xi in enumerate(x)]
            out.append([complex(float(z.real), float(z.imag)) for z in x])
    arr = np.array(out)
    keys = [np.round(arr[:, k].imag, 9) for k in range(arr.shape[1] - 1, -1, -1)]
    keys += [np.round(arr[:, k].real, 9) for k in range(arr.shape[1] - 1, -1, -1)]
    return arr[np.lexsort(keys)]


def _system_record(row: str, name: str, doc: str) -> PolynomialSystem:
    unknowns, eqs = SYSTEMS[row]()
    params = system_parameters(row, MINIMAL_FRAMES[row])
    expected = counts()[row]["random"][0]
    q0, sols, loops = monodromy(row, expected)
    sols = polish(row, q0, sols)
    return PolynomialSystem(
        name=name,
        unknowns=tuple(unknowns),
        parameters=params,
        equations=tuple(eqs),
        equation_names=tuple(f"plane equation {i}" for i in range(len(eqs))),
        start_parameters=tuple(complex(z) for z in q0),
        start_solutions=tuple(tuple(complex(z) for z in r) for r in sols),
        doc=doc,
        facts={"solutions": len(sols), "msolve": expected, "monodromy_loops": loops},
    )


@cache
def uniform_rotation_record() -> PolynomialSystem:
    """Perspective uniform rotation, five equally spaced frames (``uniform_rotation_system``)."""
    return _system_record(
        "uniform_rotation",
        "persp_uniform_rotation_system",
        "Perspective, uniform rotation, two points, five equally spaced frames: per later frame "
        "f the plane equation (m_Af x m_Bf) . Q^f D_0 = 0 with Q = cayley(mu (n1, n2, 1)) times "
        "its denominator and D_0 = b0 m_B0 - m_A0; unknowns (n1, n2, mu, b0), parameters the "
        "rays (x, y, z) of A and B in each frame, turned by the chart rotation G.  "
        "START_SOLUTIONS are every solution at START_PARAMETERS (monodromy, count checked "
        "against msolve's); curverecon.solvers.homotopy tracks them to any frames' rays.",
    )


@cache
def fixed_axis_chart_record() -> PolynomialSystem:
    """Perspective rotation about a fixed direction, three points, three frames, in the Cayley
    chart (``fixed_axis_system``): its start solutions by monodromy, for
    ``fixed_axis_record``."""
    return _system_record(
        "fixed_axis_3pt",
        "persp_fixed_axis_chart",
        "The fixed-axis row in the Cayley chart (``fixed_axis_system``).",
    )


ANGLE_CHART = (sp.Rational(1, 2) + sp.Rational(7, 10) * sp.I, sp.Rational(-3, 5) + sp.I / 2)
"""zeta_f, the fixed-axis row's angle chart per later frame: mu_f = m_f / (1 + zeta_f m_f)
(``fixed_axis_patch_system``).  Not real, so that no real angle, the half turn included, is at
the chart's infinity; moduli near 1, as the Cayley parameters of the start system."""


def fixed_axis_patch_parameters(frames: int = 3) -> tuple[sp.Symbol, ...]:
    """The fixed-axis row's parameters, then the angle chart's zeta_1 .. zeta_{F-1}."""
    return system_parameters("fixed_axis_3pt", frames) + tuple(sp.symbols(f"z1:{frames}"))


def fixed_axis_patch_system(frames: int = 3) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """``fixed_axis_system`` in a chart in which no real motion is at infinity: the Cayley
    parameter mu_f = s_f / c_f homogenised and put on the line (s_f, c_f) = (m_f, 1 + zeta_f m_f)
    (zeta_f a parameter, held at a fixed non-real value: ``ANGLE_CHART``), so that a half turn
    (c_f = 0) is a finite m_f = -1 / zeta_f; the rotation's numerator times c_f^2 is
    (c^2 - s^2 n.n) I + 2 c s [n]x + 2 s^2 n n^T.  The axis chart n = (n1, n2, 1) is made
    generic by the runtime, which turns the rays by a complex rotation (a real axis is then at
    the chart's infinity only along one direction).  Unknowns (b0, c0, n1, n2, m1, m2)."""
    m = rays("ABC", frames)
    b0, c0, n1, n2 = sp.symbols("b0 c0 n1 n2")
    ms = sp.symbols(f"m1:{frames}")
    zetas = fixed_axis_patch_parameters(frames)[-(frames - 1) :]
    d = b0 * m[("B", 0)] - m[("A", 0)]
    e = c0 * m[("C", 0)] - m[("A", 0)]
    n = sp.Matrix([n1, n2, 1])
    eqs = []
    for f, (s, zeta) in enumerate(zip(ms, zetas, strict=True), start=1):
        c = 1 + zeta * s
        r = (c**2 - s**2 * n.dot(n)) * sp.eye(3) + 2 * c * s * skew(n) + 2 * s**2 * n * n.T
        eqs += [sp.expand(normal(pair, f).dot(r * x))
                for pair, x in (("AB", d), ("AC", e), ("BC", e - d))]  # fmt: skip
    return [b0, c0, n1, n2, *ms], eqs


NEAR_START_SEED = 20261128
NEAR_START_SPREAD = 0.5
"""The fixed-axis start parameters are a real scene's (``construct_np``, seed
``NEAR_START_SEED``) plus complex Gaussian noise of this size relative to their mean modulus:
near the real scenes the runtime solves, paths are short.  Bench scenes (seed 0, 20): 0.5
took 47 steps a path (median), 0.2 51, 0.1 57, 1.0 50, a random complex start 71."""


def _near_real_parameters() -> np.ndarray:
    """Generic complex parameters near a real fixed-axis scene: frame 0's rays, the later
    frames' plane normals scaled to unit length (as the runtime scales them), plus noise."""
    rng = np.random.default_rng(NEAR_START_SEED)
    r = construct_np("fixed_axis_3pt", rng, MINIMAL_FRAMES["fixed_axis_3pt"])["rays"]
    out = [r[0].reshape(-1)]
    for f in range(1, r.shape[0]):
        for i, j in ((0, 1), (0, 2), (1, 2)):
            normal_f = np.cross(r[f, i], r[f, j])
            out.append(normal_f / np.linalg.norm(normal_f))
    q = np.concatenate(out)
    q = q + NEAR_START_SPREAD * np.abs(q).mean() * _crandn(rng, q.size)
    return np.array([_round(z) for z in q])


def _tables_of(
    unknowns: Sequence[sp.Symbol],
    eqs: Sequence[sp.Expr],
    params: Sequence[sp.Symbol],
    q0: np.ndarray,
    sols: np.ndarray,
) -> SimpleNamespace:
    """A system's tables with start data (``_tables`` of any system)."""
    umons, pmons, terms = system_terms(eqs, unknowns, params)
    return SimpleNamespace(
        UNKNOWNS=tuple(s.name for s in unknowns),
        PARAMETERS=tuple(s.name for s in params),
        EQUATIONS=tuple(range(len(eqs))),
        UNKNOWN_EXPONENTS=np.array(umons, dtype=np.int64),
        PARAMETER_EXPONENTS=np.array(pmons, dtype=np.int64),
        TERMS=np.array([t[:3] for t in terms], dtype=np.int64),
        COEFFICIENTS=np.array([t[3] for t in terms], dtype=np.float64),
        START_PARAMETERS=np.asarray(q0, complex),
        START_SOLUTIONS=np.asarray(sols, complex),
    )


@cache
def fixed_axis_record() -> PolynomialSystem:
    """Perspective rotation about a fixed direction, three points, three frames, in the chart
    of ``fixed_axis_patch_system``: the Cayley chart's start solutions
    (``fixed_axis_chart_record``) with m_f = mu_f / (1 - zeta_f mu_f), tracked to start
    parameters near a real scene (``_near_real_parameters``; every path must arrive, at
    distinct points) and polished."""
    from curverecon.solvers import homotopy

    chart = fixed_axis_chart_record()
    unknowns, eqs = fixed_axis_patch_system()
    params = fixed_axis_patch_parameters()
    zetas = np.array([complex(z) for z in ANGLE_CHART])
    x = np.array(chart.start_solutions)
    x[:, 4:] = x[:, 4:] / (1 - zetas * x[:, 4:])
    tables = homotopy.PolynomialSystem.from_module(
        _tables_of(unknowns, eqs, params, np.concatenate([chart.start_parameters, zetas]), x)
    )
    q0 = np.concatenate([_near_real_parameters(), zetas])
    careful = homotopy.HomotopyOptions(max_step=0.05, predictor_tolerance=1e-3)
    moved = homotopy.track(tables, q0, careful)
    ends = moved.solutions
    if moved.n_failed or len(_new_points(ends[:1], ends[1:])) != len(x) - 1:
        raise RuntimeError(f"fixed axis: start solutions lost on the way ({moved.failures})")
    sols = _polish(unknowns, eqs, params, q0, moved.solutions)
    return PolynomialSystem(
        name="persp_fixed_axis_system",
        unknowns=tuple(unknowns),
        parameters=params,
        equations=tuple(eqs),
        equation_names=tuple(f"plane equation {i}" for i in range(len(eqs))),
        start_parameters=tuple(complex(z) for z in q0),
        start_solutions=tuple(tuple(complex(z) for z in r) for r in sols),
        doc="Perspective, rotation about a fixed direction, three points, three frames: per "
        "later frame f the three edge-plane equations (m_Pf x m_Qf) . R_f (X_Q0 - X_P0) = 0 for "
        "the pairs AB, AC, BC, R_f = cayley(mu_f (n1, n2, 1)) with mu_f = m_f / (1 + z_f m_f), "
        "times (1 + z_f m_f)^2 (1 + mu_f^2 n.n), X_B0 - X_A0 = b0 m_B0 - m_A0, X_C0 - X_A0 = "
        "c0 m_C0 - m_A0; unknowns (b0, c0, n1, n2, m1, m2), parameters the rays (x, y, z) of "
        "A, B, C in each frame, turned by the runtime's complex chart rotation, and the angle "
        "chart z1, z2 (held at their START_PARAMETERS values).  START_SOLUTIONS are every "
        "solution at START_PARAMETERS (monodromy in the Cayley chart, count checked against "
        "msolve's, then tracked to these parameters near a real scene, whose plane normals "
        "have unit length); curverecon.solvers.homotopy tracks them to any frames' rays.",
        facts=chart.facts,
        horner=tuple(unknowns[i] for i in (0, 1, 4, 5, 2, 3)),
        sparse_solve=True,
    )


def module_constants() -> dict[str, object]:
    """Constants of generated/section2_perspective.py."""
    return {"CHART_ROTATION": CHART_ROTATION}


# ---------------------------------------------------------------------------------------------
# checks against the 3-D construction
# ---------------------------------------------------------------------------------------------


def _values(points: str, rays_np: np.ndarray) -> dict[sp.Symbol, float]:
    """Ray symbols -> the construction's normalised rays (x, y, 1)."""
    out: dict[sp.Symbol, float] = {}
    for f in range(rays_np.shape[0]):
        for i, p in enumerate(points):
            out.update(dict(zip(ray(p, f), rays_np[f, i], strict=True)))
    return out


def _normal_values(row: str, rays_np: np.ndarray) -> dict[sp.Symbol, float]:
    """Plane-normal symbols of the later frames -> m_P x m_Q of the construction's rays."""
    out: dict[sp.Symbol, float] = {}
    for f in range(1, rays_np.shape[0]):
        for pair in PAIRS[row]:
            i, j = POINTS[row].index(pair[0]), POINTS[row].index(pair[1])
            out.update(zip(normal(pair, f), np.cross(rays_np[f, i], rays_np[f, j]), strict=True))
    return out


def _cayley_of(rotation: np.ndarray) -> tuple[np.ndarray, float]:
    """(axis chart n = (n1, n2, 1), mu) with cayley(mu n) = rotation (angle below pi)."""
    w, v = np.linalg.eig(rotation)
    axis = np.real(v[:, np.argmin(np.abs(w - 1))])
    angle = np.arctan2(0.5 * np.dot(axis, [rotation[2, 1] - rotation[1, 2],
                                           rotation[0, 2] - rotation[2, 0],
                                           rotation[1, 0] - rotation[0, 1]]),
                       0.5 * (np.trace(rotation) - 1))  # fmt: skip
    n = axis / axis[2]
    return n, float(np.tan(angle / 2) * np.sign(axis[2]) / np.linalg.norm(n))


def _residual(eqs: Sequence[sp.Expr], values: dict) -> float:
    return max(abs(float(sp.sympify(e).xreplace(values))) for e in eqs)


def _check_row(row: str, rng: np.random.Generator) -> float:
    """Largest residual of ``row``'s equations at one random construction (float64)."""
    frames = MINIMAL_FRAMES[row] if row != "force_field" else 4
    scene = construct_np(row, rng, frames)
    x3, vals = scene["X3"], _values(POINTS[row] if row != "force_field" else "ABG", scene["rays"])
    depth = {(p, f): x3[f, i, 2] for f in range(frames) for i, p in enumerate(POINTS[row])}
    if row == "rotation_free":
        unknowns, eqs = rotation_free_system(frames)
        vals.update({u: depth[(u.name[1], int(u.name[2:]))] for u in unknowns})
    elif row == "free_4pt":
        unknowns, eqs = free_4pt_system(frames)
        vals.update({u: depth[(u.name[1], int(u.name[2:]))] for u in unknowns})
    elif row == "uniform_rotation":
        unknowns, eqs = uniform_rotation_system(frames)
        n, mu = _cayley_of(scene["R"][1])
        k = mu * n
        qn = scene["R"][1]
        v, aux = x3[0, 1] - x3[0, 0], []
        for _ in range(1, frames):
            v = qn @ v
            aux.extend(v)
        vals.update(_normal_values(row, scene["rays"]))
        vals.update(dict(zip(unknowns, (n[0], n[1], mu, x3[0, 1, 2], *aux), strict=True)))
        return _residual(eqs, vals) / (1 + k @ k)
    elif row == "fixed_axis_3pt":
        unknowns, eqs = fixed_axis_system(frames)
        vals.update(_normal_values(row, scene["rays"]))
        n, mu1 = _cayley_of(scene["R"][1])
        mus = [np.tan(th / 2) / np.linalg.norm(n) * np.sign(n @ scene["axis"]) for th in
               scene["theta"][1:]]  # fmt: skip
        vals.update(dict(zip(unknowns, (x3[0, 1, 2], x3[0, 2, 2], n[0], n[1], *mus),
                             strict=True)))  # fmt: skip
        return _residual(eqs, vals) / (1 + abs(mu1) ** 2 * n @ n)
    elif row == "force_field":
        return _force_field_residual(scene)
    else:
        return _stereo_residual(scene)
    return _residual(eqs, vals)


def _force_field_residual(scene: dict[str, np.ndarray]) -> float:
    """The force field's per-frame invariants at the construction (G recovered exactly)."""
    x3, times = scene["X3"], scene["times"]
    g = np.array([np.polyfit(times, x3[:, 2, i], 2)[::-1] for i in range(3)])  # (3, 3)
    a, b = x3[0, 0] - x3[0, 2], x3[0, 1] - x3[0, 2]
    glob = [*g[:, 0], *g[:, 1], *(2 * g[:, 2]), a @ a, b @ b, a @ b]
    worst = 0.0
    t = sp.Symbol("t")
    rays_ab = _values("AB", scene["rays"])
    for f in range(len(times)):
        unknowns, eqs = force_field_frame(f, t)
        vals = dict(zip(FF_GLOBALS, glob, strict=True)) | rays_ab
        vals.update({u: x3[f, "AB".index(u.name[1]), 2] for u in unknowns})
        vals[t] = times[f]
        worst = max(worst, _residual(eqs, vals))
    return worst


def _stereo_residual(scene: dict[str, np.ndarray]) -> float:
    """Triangulation equations at the construction, both points."""
    unknowns, eqs = stereo_triangulation()
    worst = 0.0
    for i in range(2):
        vals = dict(zip(ray("P", 0), scene["rays"][0, i], strict=True))
        vals.update(zip(ray("P", 1), scene["rays1"][0, i], strict=True))
        vals.update(zip(sp.symbols("r0:9"), scene["R1"].ravel(), strict=True))
        vals.update(zip(sp.symbols("t0:3"), scene["t1"], strict=True))
        x1 = scene["R1"] @ scene["X3"][0, i] + scene["t1"]
        vals.update({unknowns[0]: scene["X3"][0, i, 2], unknowns[1]: x1[2]})
        worst = max(worst, _residual(eqs, vals))
    return worst


def _plane_depths_check(rng: np.random.Generator) -> float:
    """D_f known: ``depths_from_difference`` gives back the construction's depths (relative)."""
    scene = construct_np("free_4pt", rng, 2)
    x3, m = scene["X3"], scene["rays"]
    la, lb = depths_from_difference(m[1, 0], m[1, 1], x3[1, 1] - x3[1, 0])
    return max(abs(la - x3[1, 0, 2]), abs(lb - x3[1, 1, 2])) / x3[1, 1, 2]


@cache
def checks() -> dict[str, float]:
    """Largest residual of every row's equations at N_CHECK random 3-D constructions (scaled by
    the dropped Cayley denominators), and of the depths recovered from a plane difference."""
    rng = np.random.default_rng(CHECK_SEED)
    worst = dict.fromkeys((*ROWS, "depths_from_difference"), 0.0)
    for _ in range(N_CHECK):
        for row in ROWS:
            worst[row] = max(worst[row], _check_row(row, rng))
        worst["depths_from_difference"] = max(
            worst["depths_from_difference"], _plane_depths_check(rng)
        )
    return worst


@cache
def force_field_jacobian_ranks(seed: int = CHECK_SEED) -> dict[int, tuple[int, int]]:
    """{frames: (rank, unknowns)} of the force field's equations' Jacobian at the truth of one
    random construction: unknowns the 12 globals and 2 F - 1 depths, 3 F equations.  Full rank
    (= unknowns) means an isolated solution; below, a family."""
    rng = np.random.default_rng(seed)
    scene = construct_np("force_field", rng, 13)
    x3, times, m = scene["X3"], scene["times"], scene["rays"]
    g = np.array([np.polyfit(times, x3[:, 2, i], 2)[::-1] for i in range(3)])
    a, b = x3[0, 0] - x3[0, 2], x3[0, 1] - x3[0, 2]
    glob = np.array([*g[:, 0], *g[:, 1], *(2 * g[:, 2]), a @ a, b @ b, a @ b])
    out = {}
    for frames in (10, 11, 12):
        rows = []
        for f in range(frames):
            gf = glob[0:3] + glob[3:6] * times[f] + glob[6:9] * times[f] ** 2 / 2
            dg = np.hstack([np.eye(3), np.eye(3) * times[f], np.eye(3) * times[f] ** 2 / 2])
            pa, pb = x3[f, 0] - gf, x3[f, 1] - gf
            n_unk = 12 + 2 * frames - 1
            block = np.zeros((3, n_unk))
            block[0, :9], block[1, :9] = -2 * pa @ dg, -2 * pb @ dg
            block[2, :9] = -(pa + pb) @ dg
            block[:, 9:12] = -np.eye(3)
            ia, ib = (None if f == 0 else 12 + 2 * f - 1), 12 + 2 * f
            if ia is not None:
                block[0, ia], block[2, ia] = 2 * pa @ m[f, 0], pb @ m[f, 0]
            block[1, ib], block[2, ib] = 2 * pb @ m[f, 1], pa @ m[f, 1]
            rows.append(block)
        jac = np.vstack(rows)
        sv = np.linalg.svd(jac, compute_uv=False)
        out[frames] = (int((sv > 1e-9 * sv[0]).sum()), jac.shape[1])
    return out


# ---------------------------------------------------------------------------------------------
# counts (msolve over GF(p))
# ---------------------------------------------------------------------------------------------


def _saturation(row: str, unknowns: list[sp.Symbol]) -> tuple[list[sp.Symbol], list[sp.Expr]]:
    """An unknown w and w * s - 1 with s the product of every Cayley parameter and every
    dropped denominator (1 + mu^2 |n|^2): solutions with a zero or singular rotation go.  Four
    points: s the volume det[B - A, C - A, D - A] of frame 0 (planar solutions go: four
    coplanar points have only five independent distances, so they satisfy three frames'
    equations on random data)."""
    w = sp.Symbol("w_sat")
    if row == "free_4pt":  # a tetrahedron in frame 0: det[B - A, C - A, D - A] != 0
        lam = {u.name: u for u in unknowns}
        x = [sp.Integer(1) * ray("A", 0)] + [lam[f"l{p}0"] * ray(p, 0) for p in "BCD"]
        return [w], [sp.expand(w * sp.Matrix.hstack(*[x[i] - x[0] for i in (1, 2, 3)]).det() - 1)]
    if row not in SYSTEMS:
        return [], []
    n = sp.Matrix([sp.Symbol("n1"), sp.Symbol("n2"), 1])
    prod = sp.Integer(1)
    for u in unknowns:
        if u.name.startswith("mu"):
            prod *= u * (1 + u**2 * n.dot(n))
    return [w], [sp.expand(w * prod - 1)]


def count_system(row: str, frames: int, values: dict) -> mc.IdealCount:
    """msolve's count of ``row``'s system for ``frames`` frames at the data ``values``."""
    build = {
        "rotation_free": rotation_free_system,
        "free_4pt": free_4pt_system,
        "uniform_rotation": uniform_rotation_system,
        "fixed_axis_3pt": fixed_axis_system,
    }
    unknowns, eqs = build[row](frames)  # fmt: skip
    extra, sat = _saturation(row, unknowns)
    unknowns, eqs = unknowns + extra, eqs + sat
    polys = to_msolve(unknowns, eqs, values, mc.PRIME)
    return mc.count_solutions([u.name for u in unknowns], polys, mc.PRIME)


def _random_values(row: str, frames: int, seed: int) -> dict:
    """Random residues for every parameter of the row's system (a generic instance)."""
    rnd = random.Random(seed)
    return {s: rnd.randrange(1, mc.PRIME) for s in system_parameters(row, frames)}


def _true_values(row: str, frames: int, seed: int = TRUE_SEED) -> dict:
    """Exact rays of a rational body moved by the row's model (a noise-free instance): Cayley
    rotations with rational parameters, rational translations; rays are the points themselves
    (the equations are homogeneous in each ray) except frame 0's, scaled to A's depth."""
    from fractions import Fraction

    rnd = random.Random(seed)
    npts = len(POINTS[row])

    def rat(lo: int = -9, hi: int = 9, den: int = 7) -> sp.Rational:
        return sp.Rational(rnd.randint(lo, hi), den)

    axis = sp.Matrix([rat(), rat(), 1])
    step = rat(2, 6, 9)
    rots = [sp.eye(3)]
    for f in range(1, frames):
        if row == "uniform_rotation":
            k = step * axis
            rots.append((cayley_numerator(k) / (1 + k.dot(k))) * rots[-1])
        elif row == "fixed_axis_3pt":
            k = rat(1, 9, 11) * f * axis
            rots.append(cayley_numerator(k) / (1 + k.dot(k)))
        elif row == "rotation_free":
            rots.append(sp.eye(3))
        else:
            k = sp.Matrix([rat(), rat(), rat()])
            rots.append(cayley_numerator(k) / (1 + k.dot(k)))
    body = [sp.Matrix([rat(-20, 20, 9), rat(-20, 20, 9), 6 + rat(-9, 9, 5)]) for _ in range(npts)]
    out: dict = {}
    for f in range(frames):
        shift = sp.zeros(3, 1) if f == 0 else sp.Matrix([rat(), rat(), rat()])
        for i, p in enumerate(POINTS[row]):
            x = rots[f] * body[i] + shift
            if f == 0:
                x = x / body[0][2]
            for s, v in zip(ray(p, f), x, strict=True):
                out[s] = Fraction(int(sp.numer(v)), int(sp.denom(v)))
    if row in PAIRS:  # frame 0's rays and the later frames' plane normals (exact)
        for f in range(1, frames):
            for pair in PAIRS[row]:
                mp, mq = ([out[s] for s in ray(p, f)] for p in pair)
                cross = np.cross(np.array(mp, dtype=object), np.array(mq, dtype=object))
                out.update(zip(normal(pair, f), cross, strict=True))
        out = {k: v for k, v in out.items() if k in set(system_parameters(row, frames))}
    return out


@cache
def counts() -> dict[str, dict[str, object]]:
    """Per counted row: msolve's counts at the least number of frames (random and noise-free
    instances), the dimension one frame below and the noise-free count one frame above."""
    out: dict[str, dict[str, object]] = {}
    for row in ("rotation_free", "uniform_rotation", "fixed_axis_3pt", "free_4pt"):
        frames = MINIMAL_FRAMES[row]
        randoms = [count_system(row, frames, _random_values(row, frames, s)) for s in COUNT_SEEDS]
        below = (  # one frame of rotation-free motion: no equation, lambda_B0 free
            count_system(row, frames - 1, _random_values(row, frames - 1, 1)).dimension
            if frames > 2
            else 1
        )
        truth = count_system(row, frames, _true_values(row, frames))
        more = count_system(row, frames + 1, _true_values(row, frames + 1))
        out[row] = {
            "frames": frames,
            "random": [c.degree for c in randoms],
            "random_dimensions": [c.dimension for c in randoms],
            "below_dimension": below,
            "noise_free": truth.degree,
            "noise_free_one_more": more.degree,
        }
    out["free_4pt"]["relaxed"] = free_4pt_relaxed_count()
    return out


def free_4pt_relaxed_count() -> int | None:
    """Four points, three frames with the last distance of frame 2 left out (a square system,
    the problem "overdetermined by one" relaxed): msolve's count at a random instance."""
    unknowns, eqs = free_4pt_system(3)
    extra, sat = _saturation("free_4pt", unknowns)
    unknowns, eqs = unknowns + extra, eqs[:-1] + sat
    polys = to_msolve(unknowns, eqs, _random_values("free_4pt", 3, 1), mc.PRIME)
    return mc.count_solutions([u.name for u in unknowns], polys, mc.PRIME).degree


# ---------------------------------------------------------------------------------------------
# the report (docs/derivation.md and docs/errata.md, by derivations/report.py)
# ---------------------------------------------------------------------------------------------

SOLVERS = {
    "rotation_free": "closed form: one 3 x 3 linear solve (`persp_rotation_free.py`)",
    "uniform_rotation": "parameter homotopy, 26 paths (`persp_uniform_rotation.py`); equally "
    "spaced times",
    "fixed_axis_3pt": "parameter homotopy, 84 paths, one solve in a chart with no real motion "
    "at infinity: mu_f = m_f / (1 + zeta_f m_f), zeta_f not real (a half turn is finite), the "
    "rays turned by a complex rotation (`persp_fixed_axis_3pt.py`); kernels in Horner form, "
    "the solve without F_x's structural zeros (`horner`, `sparse_solve`)",
    "free_4pt": "none practical: overdetermined by one; the square relaxation has 1,280 "
    "solutions (`persp_free_4pt.py` says why)",
    "force_field": "none practical: 33 quadrics in 33 unknowns (`persp_force_field.py` says why)",
    "stereo_free": "closed form: each point triangulated (`stereo_free.py`)",
}


def _count_cells(row: str, c: dict[str, dict[str, object]]) -> tuple[str, str, str]:
    """(least frames, complex solutions there, frames for a unique answer) as table cells."""
    if row == "force_field":
        ranks = force_field_jacobian_ranks()
        rank_text = ", ".join(f"{f} frames: {r}/{n}" for f, (r, n) in sorted(ranks.items()))
        return f"11 (Jacobian rank {rank_text})", "not counted (33 quadrics)", "11 (generic)"
    if row == "stereo_free":
        return "1", "1 per point (linear)", "1"
    f = c[row]
    if row == "free_4pt":
        return (
            f"3 (2 frames: dimension {f['below_dimension']}; 3 frames: random instances "
            f"{f['random']} solutions, overdetermined by one)",
            f"{f['noise_free']} on noise-free data (truth and per-frame point reflections); "
            f"relaxed square system {f['relaxed']}",
            f"3 ({f['noise_free_one_more']} at 4 frames: the same reflections)",
        )
    below = f["frames"] - 1
    unique = f["frames"] if f["noise_free"] == 1 else f["frames"] + 1
    key = "noise_free" if unique == f["frames"] else "noise_free_one_more"
    return (
        f"{f['frames']} ({below} frame{'s' if below > 1 else ''}: dimension "
        f"{f['below_dimension']})",
        f"{f['random'][0]} (random instances {f['random']}, noise-free {f['noise_free']})",
        f"{unique} (noise-free: {f[key]})",
    )


def derivation_lines() -> list[str]:
    """docs/derivation.md's section on the perspective and stereo rows."""
    c, chk = counts(), checks()
    out = [
        "## Section 2 table, perspective and stereo rows (derivations/section2_perspective.py)\n",
        "A calibrated pinhole camera: a pixel (u, v) is the ray m = ((u - cx)/f, (v - cy)/f, 1), "
        "a point X = lambda m with lambda its depth; the scale is fixed by A's depth in frame 0 "
        "(lambda_A0 = 1).  The key reduction: the difference D = B - A of two points on rays "
        "m_A, m_B lies in the plane through the camera centre and the image line A'B', "
        "(m_A x m_B) . D = 0, free of the depths; D in that plane fixes both depths.  For three "
        "points the three edge planes say the triangle is inscribed in the rays.  Rotations in "
        "Cayley form cayley(mu n), n = (n1, n2, 1) (the runtime turns the rays by a fixed "
        "rotation first, so that axes in the image plane are generic).  Counts by msolve over "
        f"GF({mc.PRIME}), saturated by the Cayley parameters and denominators (and for four "
        "points by frame 0's volume: coplanar points have only five independent distances and "
        "give spurious solutions on random data).\n",
        "| row | points | frames (seed) | least frames for finitely many | complex solutions "
        "there | unique from | symmetries | minimal solver |",
        "|---|---|---|---|---|---|---|---|",
    ]
    sym = {
        "rotation_free": "none",
        "uniform_rotation": "none in the chart ((n, theta) and (-n, -theta) are one rotation); "
        "the rate aliases by 360/dt degrees",
        "fixed_axis_3pt": "none in the chart; 4 of the 88 on a component no real scene reaches",
        "free_4pt": "per later frame the point reflection -X (mirror, behind the camera)",
        "force_field": "none (one scale, fixed)",
        "stereo_free": "none (metric)",
    }
    for row in ROWS:
        least, num, unique = _count_cells(row, c)
        out.append(f"| {row} | {POINTS[row]} | {TABLE_FRAMES[row]} | {least} | {num} | "
                   f"{unique} | {sym[row]} | {SOLVERS[row]} |")  # fmt: skip
    out += [
        "",
        "Checks against the 3-D construction (largest residual of the row's equations at "
        f"{N_CHECK} random scenes, float64, the Cayley denominators divided out): "
        + ", ".join(f"{k} {v:.0e}" for k, v in chk.items())
        + ".\n",
        "Stereo with A and B and one frame: each point is triangulated from its two rays "
        "(3 equations, 2 depths), so one frame gives A and B in metric units and the chord "
        "c = |AB|; it cannot give the tangents (alpha, beta, phi): two points say nothing about "
        "the curve between them, which needs the tangents or the polylines in both views.\n",
        "Uniform rotation with general times is not polynomial (cos w t); with equally spaced "
        "times R_f = Q^f.  The solver takes equally spaced times (a constant frame rate).\n",
        "At a large distance every row tends to the orthographic one: the rays of a body of "
        "size s at distance d differ by about s/d, so the rotation-free system (whose "
        "orthographic twin leaves the depth of AB free) becomes singular like (s/d)^2 and its "
        "solver lists nothing once the determinant is at rounding (tests/"
        "test_section2_perspective.py).\n",
    ]
    return out


def errata_lines() -> list[str]:
    """docs/errata.md's entries for the perspective and stereo rows."""
    c = counts()
    ranks = force_field_jacobian_ranks()
    return [
        "## Section 2 table, perspective and stereo rows\n",
        "- Perspective, free motion bounded by a homogeneous force field, 2 points: printed "
        '"n" frames; derived: 11.  The mass centre\'s path (9 unknowns) and the body '
        "invariants |A - G|^2, |B - G|^2, (A - G).(B - G) (3) against one net equation a frame "
        "(3 equations in its 2 depths, A's depth in frame 0 fixed): the Jacobian at the truth "
        f"has rank {ranks[10][0]} of {ranks[10][1]} unknowns at 10 frames and full rank "
        f"{ranks[11][0]} at 11 (derivations/section2_perspective.py, "
        "force_field_jacobian_ranks).",
        "- Perspective, free motion, 4 points, 3 frames: the frame count is right, but three "
        "frames are overdetermined by one (msolve: no solution on random instances "
        f"{c['free_4pt']['random']}, {c['free_4pt']['noise_free']} on noise-free data: the "
        "truth and per-frame point reflections), and two frames leave a curve "
        f"(dimension {c['free_4pt']['below_dimension']}): there is no square minimal problem "
        "with whole frames.",
        "- Perspective, uniform rotation, 2 points, 5 frames: right for equally spaced times "
        f"({c['uniform_rotation']['random'][0]} complex solutions, unique from 6 frames); for "
        "other times the equations are not polynomial and the count is not defined this way.",
        "- The other perspective and stereo rows (rotation-free 2 points 2 frames, fixed axis "
        "3 points 3 frames, stereo 2 points 1 frame) are as printed; stereo gives the chord, "
        "not the tangents.\n",
    ]
