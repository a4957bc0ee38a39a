"""The measurement model of the perspective and stereo Section 2 rows (rigid body, pinhole).

The orthographic model (``derivations/rigid_model.py``) with depth: a body point with body
vector ``q`` (relative to the reference point, frame 0's camera coordinates) is in frame f's
camera coordinates at

    X = T + R q,

``T`` the reference point's position in that frame (three coordinates, camera coordinates:
x right, y down, z along the optical axis) and ``R`` the frame's rotation relative to frame 0.
A calibrated pinhole camera (focal length ``focal`` and principal point ``(cx, cy)``, pixels)
sees it at

    x = focal X_x / X_z + cx,   y = focal X_y / X_z + cy.

A body direction ``u(polar, azimuth)`` at that point (a tangent) is seen along the derivative of
the projection, (u_x X_z - X_x u_z, u_y X_z - X_y u_z) (the focal length scales both), at the
image angle psi = atan2 of it (radians; a line: the runtime wraps residuals to (-pi/2, pi/2]).
Rotation Jacobians are with respect to the left increment w of R = exp([w]_x) Rbar at w = 0,
as in the orthographic model; camera 1 of a stereo pair is the same model with R1 = Rs R,
T1 = Rs T + ts (the runtime chains its Jacobians through Rs).

Lengths in the answer's units (the contract's: A's depth in frame 0, or the stereo rig's), image
positions in pixels, angles in radians.  ``generated_functions()`` hands the expressions to
``derivations.codegen``, which writes ``generated/rigid_pinhole.py``.
"""

from __future__ import annotations

import sympy as sp

from derivations.codegen.spec import FunctionSpec
from derivations.rigid_model import (
    BODY,
    DIRECTION,
    INCREMENT,
    ROTATION,
    current_rotation,
    incremented,
    unit_vector,
)

TRANSLATION: tuple[sp.Symbol, ...] = sp.symbols("tx ty tz", real=True)
INTRINSICS: tuple[sp.Symbol, ...] = sp.symbols("focal cx cy", real=True)


def _at_zero(expr: sp.Expr) -> sp.Expr:
    return expr.subs({w: 0 for w in INCREMENT})


def camera_point() -> sp.Matrix:
    """X = T + (I + [w]_x) Rbar q: the point in the frame's camera coordinates."""
    return sp.Matrix(TRANSLATION) + incremented(current_rotation()) * sp.Matrix(BODY)


def point_model() -> tuple[sp.Matrix, ...]:
    """(prediction (2,), d/dw, d/dq, d/dT (each 2 x 3)) of the pinhole image at w = 0."""
    x = camera_point()
    focal, cx, cy = INTRINSICS
    pred = sp.Matrix([focal * x[0] / x[2] + cx, focal * x[1] / x[2] + cy])
    jacs = [pred.jacobian(sp.Matrix(v)).applyfunc(_at_zero) for v in (INCREMENT, BODY, TRANSLATION)]
    return (pred.applyfunc(_at_zero), *jacs)


def tangent_model() -> tuple[sp.Expr, ...]:
    """(psi, d psi/dw (3,), d psi/dq (3,), d psi/dT (3,), d psi/d(polar, azimuth) (2,)) of a
    body direction's image angle at the point X; atan2's derivative in the quotient form
    d psi = (du d(dv) - dv d(du)) / (du^2 + dv^2)."""
    x = camera_point()
    d = incremented(current_rotation()) * unit_vector(*DIRECTION)
    du = d[0] * x[2] - x[0] * d[2]
    dv = d[1] * x[2] - x[1] * d[2]
    norm2 = du**2 + dv**2

    def derivative(wrt: sp.Symbol) -> sp.Expr:
        return _at_zero((du * sp.diff(dv, wrt) - dv * sp.diff(du, wrt)) / norm2)

    psi = _at_zero(sp.atan2(dv, du))
    groups = (INCREMENT, BODY, TRANSLATION, DIRECTION)
    return (psi, *[tuple(derivative(v) for v in g) for g in groups])


MODULE_DOC = """The pinhole rigid-body measurement model of the perspective and stereo rows.

A body point with body vector q (relative to the reference point, frame 0's camera coordinates)
is at X = T + R q in a frame with rotation R (relative to frame 0) and reference position T
(camera coordinates), seen at x = focal X_x / X_z + cx, y = focal X_y / X_z + cy (pixels); a
body direction u(polar, azimuth) there at the image angle psi = atan2(u_y X_z - X_y u_z,
u_x X_z - X_x u_z).  Rotation Jacobians are with respect to the left increment w of
R = exp([w]_x) Rbar at w = 0; rotation arguments r00 .. r22 are the entries of Rbar, row-major;
every argument is a 1-D array of length N or a scalar, everything broadcasts.  Lengths in the
answer's units, pixels, radians.  See derivations/rigid_pinhole.py.
"""


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/rigid_pinhole.py."""
    pred, jw, jq, jt = point_model()
    psi, tw, tq, tt, tu = tangent_model()
    return [
        FunctionSpec(
            name="pinhole_point",
            args=ROTATION + BODY + TRANSLATION + INTRINSICS,
            outputs={
                "prediction": tuple(pred),
                "jac_rotation": jw,
                "jac_body": jq,
                "jac_translation": jt,
            },
            doc=(
                "Pinhole image of a body point X = T + R q and its Jacobians.\n\n"
                "Returns (prediction (N, 2) pixels, jac_rotation (N, 2, 3) with respect to the\n"
                "left increment w of R, jac_body (N, 2, 3) with respect to q, jac_translation\n"
                "(N, 2, 3) with respect to T)."
            ),
        ),
        FunctionSpec(
            name="pinhole_tangent",
            args=ROTATION + BODY + TRANSLATION + DIRECTION,
            outputs={
                "psi": psi,
                "jac_rotation": tw,
                "jac_body": tq,
                "jac_translation": tt,
                "jac_direction": tu,
            },
            doc=(
                "Image angle of a body direction u(polar, azimuth) at the body point\n"
                "X = T + R q under a pinhole camera, and its Jacobians.\n\n"
                "Returns (psi (N,) radians, jac_rotation (N, 3) with respect to the left\n"
                "increment of R, jac_body (N, 3), jac_translation (N, 3), jac_direction (N, 2)\n"
                "with respect to (polar, azimuth))."
            ),
        ),
    ]
