"""The measurement model of the orthographic Section 2 rows (rigid body, traceable points).

A rigid body is seen under orthographic projection in frames f = 0 .. N-1.  Its points are given
relative to a reference point (A, or the mass centre G for the force field) in frame 0's camera
coordinates: the body vector ``q`` of a point X.  Frame f sees

    x_X,f = s_f + [R_f q]_xy,

``R_f`` the frame's rotation relative to frame 0 (R_0 = I), ``s_f`` the image of the reference
point (a free translation per frame, or the force field's parabola in t).  A tangent direction
``u`` at A or B (a unit vector of the body, polar angles ``polar``, ``azimuth`` in frame 0:
u = (sin polar cos azimuth, sin polar sin azimuth, cos polar)) is seen as the image angle
psi = atan2([R_f u]_y, [R_f u]_x) (radians; a line, so the runtime wraps residuals to
(-pi/2, pi/2]).

Rotations enter through a left increment: R_f is written R_f = exp([w]_x) Rbar_f about the
current estimate Rbar_f, and every Jacobian below is taken with respect to w at w = 0 (the
free rotations of the ``free`` and ``force-field`` rows are updated as Rbar <- exp([dw]_x) Rbar).
A rotation about a fixed axis, ``Rot(n(kappa, lam), angle)`` with
n = (sin kappa cos lam, sin kappa sin lam, cos kappa) in frame 0's camera coordinates, gives its
derivatives in the same form: the increments w_p with dR/dp = [w_p]_x R (``axis_rotation``), so
the runtime chains d(prediction)/dp = d(prediction)/dw . w_p.  kappa = 0 is the axis along the
viewing direction, the degenerate motion the runtime refuses.

Lengths in input units (pixels), angles in radians.  ``generated_functions()`` hands the
expressions to ``derivations.codegen``, which writes ``generated/rigid_model.py``.
"""

from __future__ import annotations

import sympy as sp

from derivations.codegen.spec import FunctionSpec

# ---------------------------------------------------------------------------------------------
# Symbols (argument names of the generated functions; all real).
# ---------------------------------------------------------------------------------------------

ROTATION: tuple[sp.Symbol, ...] = tuple(
    sp.Symbol(f"r{i}{j}", real=True) for i in range(3) for j in range(3)
)
INCREMENT: tuple[sp.Symbol, ...] = sp.symbols("w1 w2 w3", real=True)
BODY: tuple[sp.Symbol, ...] = sp.symbols("qx qy qz", real=True)
SHIFT: tuple[sp.Symbol, ...] = sp.symbols("sx sy", real=True)
DIRECTION: tuple[sp.Symbol, ...] = sp.symbols("polar azimuth", real=True)
AXIS: tuple[sp.Symbol, ...] = sp.symbols("kappa lam", real=True)
ANGLE: sp.Symbol = sp.Symbol("angle", real=True)


def skew(v: tuple[sp.Expr, ...] | sp.Matrix) -> sp.Matrix:
    """[v]_x, the cross-product matrix: [v]_x y = v x y."""
    return sp.Matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def vee(m: sp.Matrix) -> sp.Matrix:
    """The vector of a skew-symmetric matrix (inverse of :func:`skew`)."""
    return sp.Matrix([m[2, 1], m[0, 2], m[1, 0]])


def unit_vector(polar: sp.Expr, azimuth: sp.Expr) -> sp.Matrix:
    """(sin polar cos azimuth, sin polar sin azimuth, cos polar): polar 0 is the viewing axis."""
    return sp.Matrix(
        [sp.sin(polar) * sp.cos(azimuth), sp.sin(polar) * sp.sin(azimuth), sp.cos(polar)]
    )


def rodrigues(axis: sp.Matrix, angle: sp.Expr) -> sp.Matrix:
    """Rot(n, angle) = cos I + sin [n]_x + (1 - cos) n n^T for a unit axis n (right-handed)."""
    co, si = sp.cos(angle), sp.sin(angle)
    return co * sp.eye(3) + si * skew(axis) + (1 - co) * axis * axis.T


def current_rotation() -> sp.Matrix:
    """Rbar, the frame's current rotation, as nine free symbols (row-major r00 .. r22)."""
    return sp.Matrix(3, 3, ROTATION)


def incremented(rot: sp.Matrix) -> sp.Matrix:
    """exp([w]_x) Rbar to first order in w, (I + [w]_x) Rbar: exact value and first derivative
    at w = 0, which is all the generated Jacobians use."""
    return (sp.eye(3) + skew(INCREMENT)) * rot


def _at_zero(expr: sp.Expr) -> sp.Expr:
    return expr.subs({w: 0 for w in INCREMENT})


def point_model() -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """(prediction (2,), d/dw (2, 3), d/dq (2, 3)) of x = s + [R q]_xy at w = 0."""
    x = sp.Matrix(SHIFT).col_join(sp.Matrix([0])) + incremented(current_rotation()) * sp.Matrix(
        BODY
    )
    pred = sp.Matrix([x[0], x[1]])
    jw = pred.jacobian(sp.Matrix(INCREMENT)).applyfunc(_at_zero)
    jq = pred.jacobian(sp.Matrix(BODY)).applyfunc(_at_zero)
    return pred.applyfunc(_at_zero), jw, jq


def tangent_model() -> tuple[sp.Expr, sp.Matrix, sp.Matrix, sp.Matrix]:
    """(psi, d psi/dw (1, 3), d psi/d(polar, azimuth) (1, 2), the direction in the frame (3,))
    for the image angle of a body direction; derivatives of atan2 in the quotient form
    d psi = (dx d(dy) - dy d(dx)) / (dx^2 + dy^2)."""
    d = incremented(current_rotation()) * unit_vector(*DIRECTION)
    dx, dy = d[0], d[1]
    norm2 = dx**2 + dy**2

    def derivative(wrt: sp.Symbol) -> sp.Expr:
        return _at_zero((dx * sp.diff(dy, wrt) - dy * sp.diff(dx, wrt)) / norm2)

    jw = sp.Matrix([[derivative(w) for w in INCREMENT]])
    ju = sp.Matrix([[derivative(p) for p in DIRECTION]])
    psi = _at_zero(sp.atan2(dy, dx))
    return psi, jw, ju, d.applyfunc(_at_zero)


def axis_model() -> tuple[sp.Matrix, sp.Matrix]:
    """(Rot(n(kappa, lam), angle) (3, 3), increments (3, 3)): row p of the increments is w_p with
    dR/dp = [w_p]_x R for p in (kappa, lam, angle) (so w_angle = n)."""
    axis = unit_vector(*AXIS)
    rot = rodrigues(axis, ANGLE)
    rows = []
    for p in (*AXIS, ANGLE):
        w = vee(sp.diff(rot, p) * rot.T)
        rows.append([sp.simplify(v) for v in w])
    return rot, sp.Matrix(rows)


# ---------------------------------------------------------------------------------------------
# What code generation sees.
# ---------------------------------------------------------------------------------------------

MODULE_DOC = """The orthographic rigid-body measurement model of the Section 2 rows (generated).

A body point with body vector q (relative to the reference point, frame 0's camera coordinates)
is seen in a frame with rotation R (relative to frame 0) and reference image s at
x = s + [R q]_xy; a body direction u(polar, azimuth) at the image angle psi = atan2 of [R u]_xy.
Rotation Jacobians are with respect to the left increment w of R = exp([w]_x) Rbar at w = 0;
``axis_rotation`` gives Rot(n(kappa, lam), angle) with the increments w_p of its parameters
(dR/dp = [w_p]_x R).  Rotation arguments r00 .. r22 are the entries of Rbar, row-major; every
argument is a 1-D array of length N or a scalar, everything broadcasts.  Lengths in input
units, angles in radians.  See derivations/rigid_model.py.
"""


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/rigid_model.py."""
    pred, jw, jq = point_model()
    psi, tw, tu, direction = tangent_model()
    rot, increments = axis_model()
    return [
        FunctionSpec(
            name="point_prediction",
            args=ROTATION + BODY + SHIFT,
            outputs={"prediction": tuple(pred), "jac_rotation": jw, "jac_body": jq},
            doc=(
                "Image of a body point, x = s + [R q]_xy, and its Jacobians.\n\n"
                "Returns (prediction (N, 2), jac_rotation (N, 2, 3) with respect to the left\n"
                "increment w of R, jac_body (N, 2, 3) with respect to q); d x / d s is the\n"
                "identity.  Input units."
            ),
        ),
        FunctionSpec(
            name="tangent_prediction",
            args=ROTATION + DIRECTION,
            outputs={
                "psi": psi,
                "jac_rotation": tuple(tw),
                "jac_direction": tuple(tu),
                "direction": tuple(direction),
            },
            doc=(
                "Image angle of a body direction u(polar, azimuth) and its Jacobians.\n\n"
                "Returns (psi (N,) radians, jac_rotation (N, 3) with respect to the left\n"
                "increment of R, jac_direction (N, 2) with respect to (polar, azimuth),\n"
                "direction (N, 3) = R u in the frame's camera coordinates)."
            ),
        ),
        FunctionSpec(
            name="axis_rotation",
            args=(*AXIS, ANGLE),
            outputs={"rotation": rot, "increments": increments},
            doc=(
                "Rot(n, angle), n = (sin kappa cos lam, sin kappa sin lam, cos kappa), and the\n"
                "left increments of its parameters.\n\n"
                "Returns (rotation (N, 3, 3), increments (N, 3, 3)): row p of the increments is\n"
                "w_p with dR/dp = [w_p]_x R for p = kappa, lam, angle.  Radians."
            ),
        ),
        FunctionSpec(
            name="unit_direction",
            args=DIRECTION,
            outputs={"direction": tuple(unit_vector(*DIRECTION))},
            doc=(
                "(sin polar cos azimuth, sin polar sin azimuth, cos polar), shape (N, 3): a body\n"
                "direction or a rotation axis from its polar angles (radians)."
            ),
        ),
    ]
