"""The seed's Section 2 table, orthographic rows: each row's minimal problem, derived and counted.

Every row is a rigid body seen under orthographic projection (x, y kept, depth lost) with a motion
model (CONTRACT.md, "Configurations beyond the paper's own"):

- ``fixed_axis``: X_f = Rot(n, theta_f) X_0 + T_f, one axis direction n, any angle per frame;
- ``uniform_rotation``: the same with theta_f = w (t_f - t_0), one rate w;
- ``free_3pt``: any rotation per frame, three traceable points A, B, C;
- ``force_field``: any rotation per frame, the mass centre G (an unknown body point) moving with
  constant acceleration, x_G(t) = g0 + g1 t + g2 t^2 / 2.

The translation is free in the first three rows, so only differences of points carry information:
D = B - A (and E = C - A), seen as v_f = xy(D_f) (u_f = xy(E_f)); the unknowns are the depths
z_f = D_f[2] (e_f = E_f[2]).  Each step below is a small function; ``checks()`` evaluates every
equation at the 3-D construction (random bodies and motions, float64) and ``facts()`` counts the
solutions with msolve over GF(p) (``derivations.minimal_count``: same tool, same prime).

Sources: the seed's Section 2 table (rows and frame numbers); the reductions are the standard ones
of the orthographic structure-from-motion literature (equal norms and coplanar differences for
rotation about one axis; Gram-matrix invariance for three points, Ullman's three-view setting).
"""

from __future__ import annotations

import random
from collections.abc import Sequence
from fractions import Fraction
from functools import cache
from itertools import combinations

import numpy as np
import sympy as sp

from derivations import minimal_count as mc
from derivations.codegen.spec import FunctionSpec

MODULE_DOC = (
    "The minimal problems of the seed's Section 2 orthographic rows (fixed axis, uniform rotation, "
    "three points, force field): coefficient and residual functions of the data, derived and "
    "checked in derivations/section2.py."
)

ROWS = ("uniform_rotation", "fixed_axis", "free_3pt", "force_field")
N_CHECK = 50  # random 3-D constructions per numeric check
CHECK_SEED = 2026

# ---------------------------------------------------------------------------------------------
# symbols
# ---------------------------------------------------------------------------------------------


def v_symbols(frames: int, name: str = "v") -> list[tuple[sp.Symbol, sp.Symbol]]:
    """Image differences (x, y) per frame: v_f = B'_f - A'_f (``name`` "u": C'_f - A'_f)."""
    return [sp.symbols(f"{name}{f}x {name}{f}y", real=True) for f in range(frames)]


def depth_symbols(frames: int, name: str = "z") -> list[sp.Symbol]:
    """Unknown depths per frame (relative to A): z_f of D_f = B_f - A_f, e_f of E_f."""
    return list(sp.symbols(f"{name}0:{frames}", real=True))


def vector(v: tuple[sp.Expr, sp.Expr], z: sp.Expr) -> sp.Matrix:
    """The 3-D difference vector (v_x, v_y, z) in a frame's camera coordinates."""
    return sp.Matrix([v[0], v[1], z])


# ---------------------------------------------------------------------------------------------
# the 3-D construction (rotation, projection)
# ---------------------------------------------------------------------------------------------


def rodrigues(n: sp.Matrix, c: sp.Expr, s: sp.Expr) -> sp.Matrix:
    """Rot(n, theta) = c I + s [n]x + (1 - c) n n^T, c = cos theta, s = sin theta, |n| = 1
    (right-handed about n)."""
    k = sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return c * sp.eye(3) + s * k + (1 - c) * n * n.T


def cayley(k: Sequence[object]) -> sp.Matrix:
    """(I - K)^-1 (I + K), K = [k]x: the rotation about k by 2 atan|k|, rational for rational k."""
    kk = sp.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return (sp.eye(3) - kk).inv() * (sp.eye(3) + kk)


def rotation_np(n: np.ndarray, theta: float) -> np.ndarray:
    """Rot(n, theta) in float64 (the same formula as :func:`rodrigues`)."""
    n = np.asarray(n, float) / np.linalg.norm(n)
    k = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.cos(theta) * np.eye(3) + np.sin(theta) * k + (1 - np.cos(theta)) * np.outer(n, n)


def random_rotation_np(rng: np.random.Generator) -> np.ndarray:
    """A uniformly random rotation (QR of a Gaussian matrix, determinant +1)."""
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def construct_np(row: str, rng: np.random.Generator, frames: int) -> dict[str, np.ndarray]:
    """One 3-D scene of ``row``: body points moved by the row's model, projected orthographically.

    Returns ``X3`` (F, P, 3) every point in every frame's camera coordinates (A, B[, C][, G]),
    ``times`` (F,), and the motion (``axis``, ``theta``, ``R`` (F, 3, 3) with R_0 = I relative to
    frame 0).  Lengths about 1, depth is the camera z.
    """
    npts = 3 if row == "free_3pt" else 2
    body = rng.normal(size=(npts + (1 if row == "force_field" else 0), 3))
    times = np.cumsum(rng.uniform(0.5, 1.5, frames)) - 0.7
    r0 = random_rotation_np(rng)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    rate = rng.uniform(0.2, 0.9) * rng.choice([-1, 1])
    theta = rng.uniform(-np.pi, np.pi, frames)
    if row == "uniform_rotation":
        theta = rate * (times - times[0])
    rel = np.array([rotation_np(axis, th - theta[0]) for th in theta])
    if row in ("free_3pt", "force_field"):
        rel = np.array([np.eye(3)] + [random_rotation_np(rng) for _ in range(frames - 1)])
    shift = rng.normal(size=(frames, 3))
    if row == "force_field":  # the mass centre (last body point) moves with constant acceleration
        g = rng.normal(size=(3, 3))
        path = g[0] + np.outer(times, g[1]) + np.outer(times**2 / 2, g[2])
    x3 = np.empty((frames, body.shape[0], 3))
    for f in range(frames):
        x3[f] = (rel[f] @ r0 @ body.T).T + shift[f]
        if row == "force_field":
            x3[f] += path[f] - x3[f, -1]
    return {"X3": x3, "times": times, "axis": axis, "theta": theta - theta[0], "R": rel}


# ---------------------------------------------------------------------------------------------
# equations per row
# ---------------------------------------------------------------------------------------------


def equal_norms(v: list, z: list) -> list[sp.Expr]:
    """|D_f|^2 = |D_0|^2 for f > 0 (a rotation keeps lengths): z_f^2 - z_0^2 - k_f with
    k_f = |v_0|^2 - |v_f|^2."""
    d0 = vector(v[0], z[0])
    return [sp.expand(vector(v[f], z[f]).dot(vector(v[f], z[f])) - d0.dot(d0))
            for f in range(1, len(v))]  # fmt: skip


def coplanar_differences(v: list, z: list) -> list[sp.Expr]:
    """det[D_i - D_0, D_j - D_0, D_l - D_0] = 0 for every triple i < j < l of later frames.

    Rotations about one axis n keep D.n: every D_f - D_0 is perpendicular to n.  With equal norms
    this is also sufficient: D_f and D_0 then have equal components along n and perpendicular to
    it, so one rotation about n takes D_0 to D_f (its angle is unique).
    """
    d0 = vector(v[0], z[0])
    diffs = [vector(v[f], z[f]) - d0 for f in range(len(v))]
    return [sp.expand(sp.Matrix.hstack(diffs[i], diffs[j], diffs[m]).det())
            for i, j, m in combinations(range(1, len(v)), 3)]  # fmt: skip


def equal_steps(v: list, z: list) -> list[sp.Expr]:
    """Equally spaced times, uniform rotation: D_{f+1}.D_f = D_1.D_0 and D_{f+2}.D_f = D_2.D_0.

    On the circle of equal norms, equal chords between consecutive frames mean equal angles (or
    D_{f+1} = D_{f-1}, which generic data exclude).
    """
    d = [vector(v[f], z[f]) for f in range(len(v))]
    out = [sp.expand(d[f + 1].dot(d[f]) - d[1].dot(d[0])) for f in range(1, len(v) - 1)]
    out += [sp.expand(d[f + 2].dot(d[f]) - d[2].dot(d[0])) for f in range(1, len(v) - 2)]
    return out


def gram_invariants(v: list, u: list, z: list, e: list) -> list[sp.Expr]:
    """Three points: |D_f|^2, |E_f|^2 and D_f.E_f equal frame 0's (a rotation keeps the Gram
    matrix; conversely equal Gram matrices of non-collinear D, E give exactly one rotation)."""
    out = []
    for f in range(1, len(v)):
        d0, e0 = vector(v[0], z[0]), vector(u[0], e[0])
        df, ef = vector(v[f], z[f]), vector(u[f], e[f])
        out += [df.dot(df) - d0.dot(d0), ef.dot(ef) - e0.dot(e0), df.dot(ef) - d0.dot(e0)]
    return [sp.expand(x) for x in out]


def fixed_axis_system(frames: int) -> tuple[list[sp.Symbol], list, list[sp.Expr]]:
    """(unknowns z_0..z_{F-1}, data v_f, equations): equal norms and coplanar differences."""
    v, z = v_symbols(frames), depth_symbols(frames)
    return z, v, equal_norms(v, z) + coplanar_differences(v, z)


def uniform_rotation_system(frames: int) -> tuple[list[sp.Symbol], list, list[sp.Expr]]:
    """Equally spaced times: equal norms, equal steps and (from 4 frames) coplanar differences."""
    v, z = v_symbols(frames), depth_symbols(frames)
    return z, v, equal_norms(v, z) + equal_steps(v, z) + coplanar_differences(v, z)


def free_3pt_system(frames: int) -> tuple[list[sp.Symbol], list, list[sp.Expr]]:
    """Depths (z_f of D, e_f of E) and the Gram invariants."""
    v, u = v_symbols(frames), v_symbols(frames, "u")
    z, e = depth_symbols(frames), depth_symbols(frames, "e")
    return z + e, v + u, gram_invariants(v, u, z, e)


# --- force field ---------------------------------------------------------------------------

FF_UNKNOWNS = sp.symbols("g0x g0y g1x g1y g2x g2y aa bb ab", real=True)
FF_DATA = sp.symbols("ax ay bx by t", real=True)


def force_field_equation() -> sp.Expr:
    """One frame: (|a|^2 - |p|^2)(|b|^2 - |q|^2) - (a.b - p.q)^2 = 0.

    a = A - G, b = B - G are body vectors (invariants aa = |a|^2, bb = |b|^2, ab = a.b); in frame
    f their images are p = A'_f - xy(G_f), q = B'_f - xy(G_f) with xy(G_f) = g0 + g1 t + g2 t^2/2.
    The unseen depths alpha, beta of a, b solve alpha^2 = aa - |p|^2, beta^2 = bb - |q|^2,
    alpha beta = ab - p.q; they exist iff this equation holds (the square of the third equals the
    product of the first two); their common sign is free in every frame.
    """
    g0x, g0y, g1x, g1y, g2x, g2y, aa, bb, ab = FF_UNKNOWNS
    ax, ay, bx, by, t = FF_DATA
    gx = g0x + g1x * t + g2x * t**2 / 2
    gy = g0y + g1y * t + g2y * t**2 / 2
    px, py, qx, qy = ax - gx, ay - gy, bx - gx, by - gy
    pp, qq, pq = px**2 + py**2, qx**2 + qy**2, px * qx + py * qy
    return (aa - pp) * (bb - qq) - (ab - pq) ** 2


# ---------------------------------------------------------------------------------------------
# closed forms
# ---------------------------------------------------------------------------------------------

W = sp.Symbol("W", real=True)


@cache
def fixed_axis_cubic_in_cofactors() -> tuple[sp.Expr, ...]:
    """The fixed-axis problem (four frames) as a cubic in W = z_0^2.

    With r_f = z_f (f = 1, 2, 3), r_f^2 = W + k_f (equal norms) and the coplanarity determinant
    expanded along its depth column, sum_f C_f (z_f - z_0) = 0 (C_f the cofactors, from the image
    differences only).  Eliminating r_1, r_2, r_3 by resultants (each the product over its two
    signs) leaves a polynomial in z_0 that is even, hence one in W; its degree is 3 (the
    all-plus sign pattern loses its leading term).  Returns its coefficients, highest first, in
    (C_1, C_2, C_3, k_1, k_2, k_3).
    """
    c = sp.symbols("C1:4", real=True)
    k = sp.symbols("k1:4", real=True)
    r = sp.symbols("r1:4", real=True)
    z0 = sp.Symbol("z0", real=True)
    res = sum(c[i] * r[i] for i in range(3)) - sum(c) * z0
    for i in range(3):
        res = sp.resultant(res, r[i] ** 2 - W - k[i], r[i])
    poly = sp.Poly(sp.expand(res), z0)
    if any(e % 2 for (e,) in poly.as_dict()):
        raise AssertionError("the eliminant is not even in z0")
    in_w = sp.Poly(sum(co * W ** (e // 2) for (e,), co in poly.as_dict().items()), W)
    return tuple(sp.factor(x) for x in in_w.all_coeffs())


def fixed_axis_cofactors(v: list) -> tuple[list[sp.Expr], list[sp.Expr]]:
    """(C_1, C_2, C_3) and (k_1, k_2, k_3) of four frames' image differences v_f."""
    z = depth_symbols(4)
    det = coplanar_differences(v, z)[0]
    cof = [sp.expand(sp.diff(det, z[f])) for f in range(1, 4)]
    k = [sp.expand(v[0][0] ** 2 + v[0][1] ** 2 - v[f][0] ** 2 - v[f][1] ** 2) for f in range(1, 4)]
    return cof, k


def free_3pt_quadratic() -> dict[str, sp.Expr]:
    """The three-point problem (three frames) as a quadratic in M = z_0 e_0.

    With P = z_0^2, Q = e_0^2, M = z_0 e_0 (so M^2 = P Q) the Gram invariants of frame f read
    z_f^2 = P + a_f, e_f^2 = Q + b_f, z_f e_f = M + c_f (a_f = |v_0|^2 - |v_f|^2,
    b_f = |u_0|^2 - |u_f|^2, c_f = v_0.u_0 - v_f.u_f).  Squaring the third and using the first
    two and M^2 = P Q leaves one *linear* equation per frame, b_f P + a_f Q - 2 c_f M =
    c_f^2 - a_f b_f.  Two frames give P and Q as linear functions of M (Cramer's rule, P =
    (pm M + p0) / det, Q = (qm M + q0) / det), and M^2 det^2 = (pm M + p0)(qm M + q0) is the
    quadratic.  Each root gives z_0 = +-sqrt(P), e_0 = M / z_0 and per later frame
    z_f = +-sqrt(P + a_f), e_f = (M + c_f) / z_f: 2 x 2^3 = 16 solutions (per-frame flips).
    """
    v, u = v_symbols(3), v_symbols(3, "u")

    def dot(x: tuple, y: tuple) -> sp.Expr:
        return x[0] * y[0] + x[1] * y[1]

    a = [dot(v[0], v[0]) - dot(v[f], v[f]) for f in (1, 2)]
    b = [dot(u[0], u[0]) - dot(u[f], u[f]) for f in (1, 2)]
    c = [dot(v[0], u[0]) - dot(v[f], u[f]) for f in (1, 2)]
    rhs = [c[i] ** 2 - a[i] * b[i] for i in range(2)]
    det = b[0] * a[1] - a[0] * b[1]
    pm = 2 * c[0] * a[1] - 2 * c[1] * a[0]
    p0 = rhs[0] * a[1] - rhs[1] * a[0]
    qm = 2 * c[1] * b[0] - 2 * c[0] * b[1]
    q0 = rhs[1] * b[0] - rhs[0] * b[1]
    quad = (det**2 - pm * qm, -(pm * q0 + p0 * qm), -p0 * q0)
    return {"quadratic": quad, "linear": (pm, p0, qm, q0, det), "abc": (*a, *b, *c)}


def uniform_rotation_angles() -> tuple[tuple[sp.Symbol, ...], dict[str, sp.Expr]]:
    """For a trial depth z_0 and signs s_1, s_2 of three frames: the atan2 arguments of the
    rotation angles theta_1 (frame 0 to 1) and theta_21 (frame 1 to 2) about the axis
    N = (D_1 - D_0) x (D_2 - D_0) (three points of equal norm always lie on one circle about an
    axis through the origin).  sin ~ N.(D_i x D_j) |N|, cos ~ (D_i.D_j) |N|^2 - (D_i.N)(D_j.N).
    """
    v = v_symbols(3)
    z0, s1, s2 = sp.symbols("z0 s1 s2", real=True)
    k = [v[0][0] ** 2 + v[0][1] ** 2 - v[f][0] ** 2 - v[f][1] ** 2 for f in (1, 2)]
    d = [vector(v[0], z0)] + [vector(v[f], s * sp.sqrt(z0**2 + k[f - 1]))
                              for f, s in ((1, s1), (2, s2))]  # fmt: skip
    n = (d[1] - d[0]).cross(d[2] - d[0])
    nn = n.dot(n)

    def args(i: int, j: int) -> tuple[sp.Expr, sp.Expr]:
        return n.dot(d[i].cross(d[j])) * sp.sqrt(nn), d[i].dot(d[j]) * nn - d[i].dot(n) * d[j].dot(
            n
        )

    y1, x1 = args(0, 1)
    y21, x21 = args(1, 2)
    flat = tuple(x for pair in v for x in pair)
    return (z0, s1, s2, *flat), {"atan2_args": (y1, x1, y21, x21), "axis": tuple(n)}


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/section2_minimal.py."""
    v4 = v_symbols(4)
    cof, k = fixed_axis_cofactors(v4)
    subs = dict(zip(sp.symbols("C1:4", real=True), cof, strict=True))
    subs.update(zip(sp.symbols("k1:4", real=True), k, strict=True))
    cubic = [x.xreplace(subs) for x in fixed_axis_cubic_in_cofactors()]
    flat4 = tuple(x for pair in v4 for x in pair)
    q = free_3pt_quadratic()
    v3, u3 = v_symbols(3), v_symbols(3, "u")
    flat3 = tuple(x for pair in v3 for x in pair) + tuple(x for pair in u3 for x in pair)
    ur_args, ur_out = uniform_rotation_angles()
    ff = force_field_equation()
    return [
        FunctionSpec(
            "fixed_axis_cubic",
            flat4,
            {"coefficients": cubic, "cofactors": cof, "k": k},
            "Fixed axis, four frames: the cubic in W = z0^2 (coefficients highest first) whose "
            "roots are the squared depths of D = B - A in frame 0; cofactors C_f and "
            "k_f = |v_0|^2 - |v_f|^2 (f = 1, 2, 3) pick each root's depth signs by "
            "sum_f C_f (z_f - z_0) = 0, z_f^2 = W + k_f.  Arguments: image differences "
            "v_f = B'_f - A'_f (input units).",
        ),
        FunctionSpec(
            "free_3pt_quadratic",
            flat3,
            {"coefficients": q["quadratic"], "linear": q["linear"], "abc": q["abc"]},
            "Three points, three frames: the quadratic in M = z0 e0 (coefficients highest "
            "first); P = z0^2 = (pm M + p0) / det and Q = e0^2 = (qm M + q0) / det from "
            "linear = (pm, p0, qm, q0, det); abc = (a_1, a_2, b_1, b_2, c_1, c_2) give the later "
            "frames' depths (z_f^2 = P + a_f, e_f^2 = Q + b_f, z_f e_f = M + c_f).  Arguments: "
            "v_f = B'_f - A'_f, then u_f = C'_f - A'_f (input units).",
        ),
        FunctionSpec(
            "uniform_rotation_angles",
            ur_args,
            ur_out,
            "Uniform rotation, three frames, at a trial depth z0 of D = B - A in frame 0 and "
            "depth signs s1, s2 of frames 1, 2: atan2 arguments (y1, x1, y21, x21) of the "
            "rotation angle from frame 0 to 1 and from 1 to 2 about axis = (D_1 - D_0) x "
            "(D_2 - D_0) (not normalised).  Arguments: z0, s1, s2, v_f = B'_f - A'_f.",
        ),
        FunctionSpec(
            "force_field_residual",
            (*FF_DATA, *FF_UNKNOWNS),
            {"residual": ff, "gradient": [sp.diff(ff, x) for x in FF_UNKNOWNS]},
            "Force field, one frame: (aa - |p|^2)(bb - |q|^2) - (ab - p.q)^2 with p = A' - xy(G), "
            "q = B' - xy(G), xy(G) = g0 + g1 t + g2 t^2 / 2, and its gradient in (g0x, g0y, "
            "g1x, g1y, g2x, g2y, aa, bb, ab); zero exactly when the frame's depths exist.",
        ),
    ]


# ---------------------------------------------------------------------------------------------
# checks against the 3-D construction
# ---------------------------------------------------------------------------------------------


def _numeric(exprs: Sequence[sp.Expr], values: dict[sp.Symbol, float]) -> np.ndarray:
    """|each expression| at ``values`` (float64)."""
    return np.array([abs(float(sp.sympify(e).xreplace(values))) for e in exprs])


def _frame_values(x3: np.ndarray, frames: int) -> dict[sp.Symbol, float]:
    """Data and depth symbols at a construction: v_f, z_f (and u_f, e_f with a third point)."""
    out: dict[sp.Symbol, float] = {}
    for name, depth, p in (("v", "z", 1), ("u", "e", 2)):
        if p >= x3.shape[1]:
            continue
        syms, zs = v_symbols(frames, name), depth_symbols(frames, depth)
        for f in range(frames):
            d = x3[f, p] - x3[f, 0]
            out.update({syms[f][0]: d[0], syms[f][1]: d[1], zs[f]: d[2]})
    return out


def _uniform_equal_steps_check(rng: np.random.Generator) -> float:
    """Equally spaced frames of a uniform rotation satisfy the equal-steps equations."""
    scene = construct_np("uniform_rotation", rng, 4)
    rate = scene["theta"][1] / (scene["times"][1] - scene["times"][0])
    x3 = scene["X3"].copy()
    base = x3[0, 1] - x3[0, 0]
    for f in range(4):  # the same body at equally spaced times
        x3[f, 1] = x3[f, 0] + rotation_np(scene["axis"], rate * f) @ base
    unknowns, _, eqs = uniform_rotation_system(4)
    return float(_numeric(eqs, _frame_values(x3, 4)).max())


@cache
def checks() -> dict[str, float]:
    """Largest residual of every row's equations at N_CHECK random 3-D constructions."""
    rng = np.random.default_rng(CHECK_SEED)
    worst = {"fixed_axis": 0.0, "uniform_rotation": 0.0, "free_3pt": 0.0, "force_field": 0.0}
    for _ in range(N_CHECK):
        scene = construct_np("fixed_axis", rng, 5)
        worst["fixed_axis"] = max(
            worst["fixed_axis"],
            float(_numeric(fixed_axis_system(5)[2], _frame_values(scene["X3"], 5)).max()),
        )
        worst["uniform_rotation"] = max(worst["uniform_rotation"], _uniform_equal_steps_check(rng))
        scene = construct_np("free_3pt", rng, 4)
        worst["free_3pt"] = max(
            worst["free_3pt"],
            float(_numeric(free_3pt_system(4)[2], _frame_values(scene["X3"], 4)).max()),
        )
        worst["force_field"] = max(worst["force_field"], _force_field_check(rng))
    return worst


def _force_field_truth(scene: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(per-frame data (ax, ay, bx, by, t), true unknowns) of a force-field construction."""
    x3, times = scene["X3"], scene["times"]
    g = np.array([np.polyfit(times, x3[:, 2, i], 2)[::-1] for i in range(2)])  # xy(G) exactly
    a, b = x3[0, 0] - x3[0, 2], x3[0, 1] - x3[0, 2]
    unknowns = np.array([g[0, 0], g[1, 0], g[0, 1], g[1, 1], 2 * g[0, 2], 2 * g[1, 2],
                         a @ a, b @ b, a @ b])  # fmt: skip
    data = np.column_stack([x3[:, 0, 0], x3[:, 0, 1], x3[:, 1, 0], x3[:, 1, 1], times])
    return data, unknowns


def _force_field_check(rng: np.random.Generator) -> float:
    """The force-field equation at the truth, relative to its terms' size."""
    data, unknowns = _force_field_truth(construct_np("force_field", rng, 9))
    e = force_field_equation()
    worst = 0.0
    for row in data:
        values = dict(zip((*FF_DATA, *FF_UNKNOWNS), (*row, *unknowns), strict=True))
        worst = max(worst, abs(float(e.xreplace(values))) / (1 + float(unknowns[6:8].prod())))
    return worst


@cache
def force_field_jacobian_ranks(seed: int = CHECK_SEED) -> dict[int, tuple[int, float]]:
    """{frames: (rank, smallest / largest singular value)} of the force-field equations' Jacobian
    in the 9 unknowns at the truth of one random construction (rank 9: an isolated solution)."""
    rng = np.random.default_rng(seed)
    scene = construct_np("force_field", rng, 10)
    data, unknowns = _force_field_truth(scene)
    e = force_field_equation()
    grad = sp.lambdify((*FF_DATA, *FF_UNKNOWNS), [sp.diff(e, x) for x in FF_UNKNOWNS], "numpy")
    jac = np.array([grad(*row, *unknowns) for row in data], float)
    out = {}
    for frames in (8, 9, 10):
        sv = np.linalg.svd(jac[:frames], compute_uv=False)
        out[frames] = (int((sv > 1e-9 * sv[0]).sum()), float(sv[-1] / sv[0]))
    return out


@cache
def _closed_forms() -> tuple:
    """The closed forms as float functions of the data: (cubic in W and the data, quadratic in M
    and the data, uniform rotation's atan2 arguments)."""
    v4, v3, u3 = v_symbols(4), v_symbols(3), v_symbols(3, "u")
    cof, k = fixed_axis_cofactors(v4)
    subs = dict(zip(sp.symbols("C1:4", real=True), cof, strict=True))
    subs.update(zip(sp.symbols("k1:4", real=True), k, strict=True))
    cubic = sum(
        c.xreplace(subs) * W ** (3 - i) for i, c in enumerate(fixed_axis_cubic_in_cofactors())
    )
    m = sp.Symbol("M", real=True)
    quad = sum(c * m ** (2 - i) for i, c in enumerate(free_3pt_quadratic()["quadratic"]))
    args, out = uniform_rotation_angles()
    return (
        sp.lambdify((W, *[x for p in v4 for x in p]), cubic, "numpy"),
        sp.lambdify((m, *[x for p in v3 + u3 for x in p]), quad, "numpy"),
        sp.lambdify(args, out["atan2_args"], "numpy"),
    )


def _root_error(poly: object, root: float, data: np.ndarray) -> float:
    """|p(root)| / (|p'(root)| |root|): the relative distance from ``root`` to a root of the
    polynomial ``poly(x, *data)`` (first order; derivative by a central difference)."""
    h = 1e-6 * abs(root)
    val = poly(root, *data)  # type: ignore[operator]
    slope = (poly(root + h, *data) - poly(root - h, *data)) / (2 * h)  # type: ignore[operator]
    return float(abs(val) / (abs(slope) * abs(root)))


@cache
def closed_form_checks() -> dict[str, tuple[float, float]]:
    """(median, max) over N_CHECK random 3-D constructions of: the true W = z_0^2 as a root of
    the cubic and the true M = z_0 e_0 as a root of the quadratic (relative distance to the
    nearest root, :func:`_root_error`), and the uniform rotation's equation
    wrap(theta_21 - rho theta_1) at the true z_0 and signs with general times (radians)."""
    cubic, quad, angles = _closed_forms()
    rng = np.random.default_rng(CHECK_SEED + 1)
    found: dict[str, list[float]] = {
        "fixed_axis_cubic": [],
        "free_3pt_quadratic": [],
        "uniform_rotation_angles": [],
    }
    for _ in range(N_CHECK):
        x3 = construct_np("fixed_axis", rng, 4)["X3"]
        d = x3[:, 1] - x3[:, 0]
        found["fixed_axis_cubic"].append(_root_error(cubic, d[0, 2] ** 2, d[:, :2].ravel()))
        x3 = construct_np("free_3pt", rng, 3)["X3"]
        d, e = x3[:, 1] - x3[:, 0], x3[:, 2] - x3[:, 0]
        data = np.concatenate([d[:, :2].ravel(), e[:, :2].ravel()])
        found["free_3pt_quadratic"].append(_root_error(quad, d[0, 2] * e[0, 2], data))
        scene = construct_np("uniform_rotation", rng, 3)
        d = scene["X3"][:, 1] - scene["X3"][:, 0]
        s = np.sign(d[1:, 2])
        y1, x1, y21, x21 = angles(d[0, 2], s[0], s[1], *d[:, :2].ravel())
        t = scene["times"]
        rho = (t[2] - t[1]) / (t[1] - t[0])
        res = np.angle(np.exp(1j * (np.arctan2(y21, x21) - rho * np.arctan2(y1, x1))))
        found["uniform_rotation_angles"].append(float(abs(res)))
    return {k: (float(np.median(v)), float(np.max(v))) for k, v in found.items()}


# ---------------------------------------------------------------------------------------------
# counts (msolve over GF(p), derivations.minimal_count)
# ---------------------------------------------------------------------------------------------

COUNT_SEEDS = (1, 2)  # random instances (data residues modulo the prime)
TRUE_SEED = 5  # noise-free rational constructions


def to_msolve(
    unknowns: Sequence[sp.Symbol], eqs: Sequence[sp.Expr], values: dict, prime: int
) -> list[str]:
    """The equations at the data ``values`` (integers or Fractions), modulo ``prime``."""
    exact = {k: sp.Rational(x.numerator, x.denominator) if isinstance(x, Fraction)
             else sp.Integer(x) for k, x in values.items()}  # fmt: skip
    out = []
    for e in eqs:
        poly = sp.Poly(e, *unknowns)
        terms: mc.Poly = {}
        for mono, co in poly.terms():
            value = sp.sympify(co).xreplace(exact)
            r = mc.residue(Fraction(int(sp.numer(value)), int(sp.denom(value))), prime)
            if r:
                terms[tuple(mono)] = (terms.get(tuple(mono), 0) + r) % prime
        out.append(mc.to_msolve(terms, [u.name for u in unknowns]))
    return out


def _random_values(data: Sequence, seed: int, prime: int = mc.PRIME) -> dict:
    """Random nonzero residues for every data symbol (a generic instance)."""
    rnd = random.Random(seed)
    flat = [x for item in data for x in (item if isinstance(item, tuple) else (item,))]
    return {x: rnd.randrange(1, prime) for x in flat}


def _rational_rotations(
    row: str, frames: int, rnd: random.Random, axis: Sequence[int] | None = None
) -> list[sp.Matrix]:
    """Exact rotations R_f (R_0 = I) of the row's model: Cayley rotations with rational vectors
    (about one axis for the rotation rows; equally spaced angles for the uniform rotation)."""
    nonzero = [x for x in range(-9, 10) if x]  # an axis in the image plane is degenerate
    axis = [sp.Rational(rnd.choice(nonzero) if axis is None else axis[i], 7) for i in range(3)]
    step = sp.Rational(rnd.randint(2, 6), 9)
    scales = rnd.sample([x for x in range(-9, 10) if x], frames)  # distinct angles
    out = [sp.eye(3)]
    for f in range(1, frames):
        if row == "uniform_rotation":
            out.append(cayley([x * step for x in axis]) * out[-1])
        elif row == "fixed_axis":
            out.append(cayley([x * sp.Rational(scales[f], 11) for x in axis]))
        else:
            out.append(cayley([sp.Rational(rnd.choice(nonzero), 8) for _ in range(3)]))
    return out


def _true_values(
    row: str, frames: int, seed: int = TRUE_SEED, axis: Sequence[int] | None = None
) -> dict:
    """Exact image differences of a rational body moved by the row's model (a noise-free
    instance; ``axis`` overrides the random axis direction): data symbols -> Fraction."""
    rnd = random.Random(seed)
    rots = _rational_rotations(row, frames, rnd, axis)
    body = [sp.Matrix([sp.Rational(rnd.randint(-20, 20), 9) for _ in range(3)]) for _ in "DE"]
    out: dict = {}
    for name, vec in (("v", body[0]), ("u", body[1])):
        for f, (sx, sy) in enumerate(v_symbols(frames, name)):
            img = rots[f] * vec
            out[sx], out[sy] = Fraction(str(img[0])), Fraction(str(img[1]))
    return out


SYSTEMS = {
    "fixed_axis": fixed_axis_system,
    "uniform_rotation": uniform_rotation_system,
    "free_3pt": free_3pt_system,
}
MINIMAL_FRAMES = {"uniform_rotation": 3, "fixed_axis": 4, "free_3pt": 3, "force_field": 9}


def count_row(row: str, frames: int, values: dict) -> mc.IdealCount:
    """msolve's count of the row's system for ``frames`` frames at the data ``values``."""
    unknowns, _, eqs = SYSTEMS[row](frames)
    polys = to_msolve(unknowns, eqs, values, mc.PRIME)
    return mc.count_solutions([u.name for u in unknowns], polys, mc.PRIME)


@cache
def facts() -> dict[str, dict[str, object]]:
    """Per row: the counts at the least number of frames (random and noise-free instances), the
    count one frame below (dimension) and at the frame number where the answer is unique."""
    out: dict[str, dict[str, object]] = {}
    for row, frames in MINIMAL_FRAMES.items():
        if row == "force_field":
            continue
        _, data, _ = SYSTEMS[row](frames)
        randoms = [count_row(row, frames, _random_values(data, seed)) for seed in COUNT_SEEDS]
        below = count_row(row, frames - 1, _random_values(SYSTEMS[row](frames - 1)[1], 1))
        truth = count_row(row, frames, _true_values(row, frames))
        more = count_row(row, frames + 1, _true_values(row, frames + 1))
        out[row] = {
            "frames": frames,
            "random": [c.degree for c in randoms],
            "random_dimensions": [c.dimension for c in randoms],
            "below_dimension": below.dimension,
            "noise_free": truth.degree,
            "noise_free_one_more": more.degree,
        }
    return out


@cache
def degenerate_axes() -> dict[str, dict[str, int]]:
    """Dimension of the solution set (msolve, noise-free instance) with the axis along the
    viewing direction (0, 0, 1) and in the image plane (2, 1, 0), per axis row at its least
    number of frames (0: finitely many; 1: a curve of solutions, the depth undetermined)."""
    out: dict[str, dict[str, int]] = {}
    for row in ("fixed_axis", "uniform_rotation"):
        frames = MINIMAL_FRAMES[row]
        out[row] = {
            name: count_row(row, frames, _true_values(row, frames, TRUE_SEED, axis)).dimension
            for name, axis in (
                ("along the viewing direction", (0, 0, 1)),
                ("in the image plane", (2, 1, 0)),
            )  # fmt: skip
        }
    return out


# --- real solutions of random real instances (msolve over the rationals) ------------------

REAL_SEEDS = range(100, 140)  # noise-free rational constructions whose real solutions are counted


def _to_msolve_qq(unknowns: Sequence[sp.Symbol], eqs: Sequence[sp.Expr], values: dict) -> list[str]:
    """The equations at exact rational data, denominators cleared, in msolve's syntax."""
    exact = {k: sp.Rational(x.numerator, x.denominator) for k, x in values.items()}
    out = []
    for e in eqs:
        _, poly = sp.Poly(sp.expand(e.xreplace(exact)), *unknowns, domain="QQ").clear_denoms()
        terms = []
        for mono, co in poly.terms():
            factors = "*".join(f"{u.name}^{p}" for u, p in zip(unknowns, mono, strict=True) if p)
            terms.append(f"({int(co)})*{factors}" if factors else f"({int(co)})")
        out.append("+".join(terms).replace("+(-", "-(").replace("(", "").replace(")", ""))
    return out


def real_solution_count(row: str, frames: int, values: dict) -> int:
    """Real solutions of the row's system at exact rational data (msolve's real root
    isolation over the rationals; zero-dimensional systems only)."""
    unknowns, _, eqs = SYSTEMS[row](frames)
    text = mc.run_msolve([u.name for u in unknowns], _to_msolve_qq(unknowns, eqs, values), 0, [])
    depth, count = 0, 0
    for ch in text:
        if ch == "[":
            depth += 1
            count += depth == 4
        elif ch == "]":
            depth -= 1
    if not text.lstrip().startswith("[0"):
        raise ValueError(f"msolve: not zero-dimensional ({text[:40]})")
    return count


@cache
def real_counts() -> dict[str, dict[int, int]]:
    """Per row: {real solutions: instances} over the REAL_SEEDS noise-free constructions at the
    least number of frames (equally spaced times for the uniform rotation)."""
    out: dict[str, dict[int, int]] = {}
    for row in SYSTEMS:
        hist: dict[int, int] = {}
        for seed in REAL_SEEDS:
            n = real_solution_count(
                row, MINIMAL_FRAMES[row], _true_values(row, MINIMAL_FRAMES[row], seed)
            )
            hist[n] = hist.get(n, 0) + 1
        out[row] = dict(sorted(hist.items()))
    return out


# --- the force field's count -----------------------------------------------------------------


def force_field_equations(frames: Sequence[dict]) -> list[sp.Expr]:
    """The force-field equation of every frame at its data {FF_DATA symbol: value}."""
    e = force_field_equation()
    exact = [{k: sp.Rational(x.numerator, x.denominator) if isinstance(x, Fraction)
              else sp.Integer(x) for k, x in f.items()} for f in frames]  # fmt: skip
    return [sp.expand(e.xreplace(f)) for f in exact]


def force_field_random_frames(frames: int, seed: int) -> list[dict]:
    """Random residues for every frame's (ax, ay, bx, by, t): a generic instance."""
    rnd = random.Random(seed)
    return [{x: rnd.randrange(1, mc.PRIME) for x in FF_DATA} for _ in range(frames)]


def force_field_true_frames(frames: int, seed: int = TRUE_SEED) -> list[dict]:
    """Exact images of a rational body (A, B, mass centre G) under rational rotations, G moving
    with a rational constant acceleration, at rational times: a noise-free instance."""
    rnd = random.Random(seed)
    rots = _rational_rotations("free_3pt", frames, rnd)
    body = [sp.Matrix([sp.Rational(rnd.randint(-20, 20), 9) for _ in range(3)]) for _ in "ABG"]
    g = [sp.Matrix([sp.Rational(rnd.randint(-9, 9), 5) for _ in range(3)]) for _ in range(3)]
    out = []
    time = sp.Rational(rnd.randint(-9, 0), 4)
    for f in range(frames):
        time += sp.Rational(rnd.randint(1, 9), 4)
        centre = g[0] + g[1] * time + g[2] * time**2 / 2
        a = rots[f] * (body[0] - body[2]) + centre
        b = rots[f] * (body[1] - body[2]) + centre
        values = (a[0], a[1], b[0], b[1], time)
        out.append({x: Fraction(str(y)) for x, y in zip(FF_DATA, values, strict=True)})
    return out


def count_force_field(frames: list[dict]) -> mc.IdealCount:
    """msolve's count of the force-field equations of ``frames`` over GF(PRIME)."""
    polys = to_msolve(list(FF_UNKNOWNS), force_field_equations(frames), {}, mc.PRIME)
    return mc.count_solutions([u.name for u in FF_UNKNOWNS], polys, mc.PRIME)


@cache
def force_field_facts() -> dict[str, object]:
    """Counts of the force field at 9 frames (random and noise-free instances) and at 10
    noise-free frames (about 5 s each).  Eight frames: msolve needs about 9 minutes for the
    dimension, so the Jacobian rank at the truth (:func:`force_field_jacobian_ranks`) says it."""
    ranks = force_field_jacobian_ranks()
    return {
        "frames": MINIMAL_FRAMES["force_field"],
        "random": [count_force_field(force_field_random_frames(9, s)).degree for s in COUNT_SEEDS],
        "below_dimension": len(FF_UNKNOWNS) - ranks[8][0],
        "noise_free": count_force_field(force_field_true_frames(9)).degree,
        "noise_free_one_more": count_force_field(force_field_true_frames(10)).degree,
    }
