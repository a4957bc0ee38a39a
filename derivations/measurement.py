"""The maximum-likelihood measurement model, derived symbolically (PX4 ``ekf_derivation`` style).

Each quantity is a small typed function of SymPy symbols, built step by step from the geometry in
``docs/CONVENTIONS.md``; ``generated_functions()`` hands the finished expressions (and their
analytic Jacobians) to ``derivations.codegen``, which writes ``generated/measurement_model.py``.

Conventions (``docs/CONVENTIONS.md``, "Geometry"):

* Curve frame ("canonical"): A = (0, 0, 0), B = (c, 0, 0);
  tangent at B ``t_B = (-cos(alpha), sin(alpha), 0)``;
  tangent at A ``t_A = (cos(beta), sin(beta) cos(phi), sin(beta) sin(phi))``.
* Pose of one frame: ``X_cam = R X_curve + t`` with
  ``R = R_z(theta) @ R_y(tau) @ R_x(delta)`` (standard right-handed rotations) and
  ``t = (tx, ty, 0)``: depth is unobservable under orthographic projection, so A is put at z = 0.
* Orthographic projection keeps (x, y).  The observations of one frame are the image points
  A' = (ax, ay), B' = (bx, by) (input length units, e.g. pixels) and the image directions
  psi_a, psi_b (radians) of the projected tangents at A and B, ``psi = atan2(dy, dx)``.
  A tangent is a line, so the runtime wraps angle residuals to (-pi/2, pi/2].

Parameters: 4 global shape parameters (c, alpha, beta, phi) shared by all frames, 5 local pose
parameters (delta, tau, theta, tx, ty) per frame.  Angles in radians, lengths in input units.
"""

from __future__ import annotations

import sympy as sp

from derivations.codegen.spec import FunctionSpec
from derivations.construction import rot_x, rot_y

# ---------------------------------------------------------------------------------------------
# Symbols.  Names are the generated functions' argument names; all are real.
# ---------------------------------------------------------------------------------------------

c, alpha, beta, phi = sp.symbols("c alpha beta phi", real=True)
delta, tau, theta, tx, ty = sp.symbols("delta tau theta tx ty", real=True)

GLOBAL_PARAMETERS: tuple[sp.Symbol, ...] = (c, alpha, beta, phi)
LOCAL_PARAMETERS: tuple[sp.Symbol, ...] = (delta, tau, theta, tx, ty)
PREDICTIONS: tuple[str, ...] = ("ax", "ay", "bx", "by", "psi_a", "psi_b")

#: The argument list of predict / predict_with_jacobians / points_3d: globals first, then locals.
ALL_PARAMETERS: tuple[sp.Symbol, ...] = GLOBAL_PARAMETERS + LOCAL_PARAMETERS


# ---------------------------------------------------------------------------------------------
# Rotation.  Standard right-handed elementary rotations (active, column vectors).
# ---------------------------------------------------------------------------------------------


# R_x and R_y are the section-3 construction's own (derivations.construction); theta adds R_z.


def rot_z(angle: sp.Expr) -> sp.Matrix:
    """R_z(angle): rotation about +z (the camera's depth axis) by ``angle`` radians."""
    ca, sa = sp.cos(angle), sp.sin(angle)
    return sp.Matrix([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]])


def rotation(delta_: sp.Expr, tau_: sp.Expr, theta_: sp.Expr) -> sp.Matrix:
    """Curve-to-camera rotation ``R = R_z(theta) R_y(tau) R_x(delta)``.

    delta turns the curve about its chord AB (the x axis of the curve frame), tau tilts the chord
    out of the image plane (B_z = -c sin(tau)), theta is the image direction of A'B'.
    """
    return rot_z(theta_) * rot_y(tau_) * rot_x(delta_)


# ---------------------------------------------------------------------------------------------
# The curve in its canonical frame.
# ---------------------------------------------------------------------------------------------


def canonical_points(c_: sp.Expr) -> tuple[sp.Matrix, sp.Matrix]:
    """A = (0, 0, 0) and B = (c, 0, 0) in the curve frame (c: chord length, input units)."""
    return sp.Matrix([0, 0, 0]), sp.Matrix([c_, 0, 0])


def tangent_b(alpha_: sp.Expr) -> sp.Matrix:
    """Unit tangent direction at B, t_B = (-cos(alpha), sin(alpha), 0).

    The tangent line at B meets the plane through A perpendicular to AB at S = (0, c tan(alpha), 0).
    """
    return sp.Matrix([-sp.cos(alpha_), sp.sin(alpha_), 0])


def tangent_a(beta_: sp.Expr, phi_: sp.Expr) -> sp.Matrix:
    """Unit tangent direction at A, t_A = (cos(beta), sin(beta) cos(phi), sin(beta) sin(phi)).

    phi is the signed angle, about +x, from AS to BT (T = the tangent line at A met with the plane
    through B perpendicular to AB).
    """
    return sp.Matrix([sp.cos(beta_), sp.sin(beta_) * sp.cos(phi_), sp.sin(beta_) * sp.sin(phi_)])


# ---------------------------------------------------------------------------------------------
# One frame: pose, 3-D points, projection.
# ---------------------------------------------------------------------------------------------


def translation(tx_: sp.Expr, ty_: sp.Expr) -> sp.Matrix:
    """t = (tx, ty, 0): orthographic depth is unobservable, A is placed at z = 0."""
    return sp.Matrix([tx_, ty_, 0])


def camera_points(
    params: tuple[sp.Expr, ...] = ALL_PARAMETERS,
) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]:
    """A, B and the tangent directions at A, B in camera coordinates.

    Points transform as X_cam = R X + t, directions as R t (no translation).
    Returns (A3, B3, tangent_A3, tangent_B3), 3-vectors; A3 = (tx, ty, 0).
    """
    c_, alpha_, beta_, phi_, delta_, tau_, theta_, tx_, ty_ = params
    rot = rotation(delta_, tau_, theta_)
    trans = translation(tx_, ty_)
    a0, b0 = canonical_points(c_)
    a3 = rot * a0 + trans
    b3 = rot * b0 + trans
    ta3 = rot * tangent_a(beta_, phi_)
    tb3 = rot * tangent_b(alpha_)
    return a3, b3, ta3, tb3


def project(v: sp.Matrix) -> tuple[sp.Expr, sp.Expr]:
    """Orthographic projection onto the image: keep (x, y), drop depth z."""
    return v[0], v[1]


def image_angle(direction: sp.Matrix) -> sp.Expr:
    """psi = atan2(dy, dx) of a projected direction (radians, in (-pi, pi])."""
    dx, dy = project(direction)
    return sp.atan2(dy, dx)


def predictions(params: tuple[sp.Expr, ...] = ALL_PARAMETERS) -> list[sp.Expr]:
    """The six predicted observables (ax, ay, bx, by, psi_a, psi_b) of one frame."""
    a3, b3, ta3, tb3 = camera_points(params)
    ax, ay = project(a3)
    bx, by = project(b3)
    return [ax, ay, bx, by, image_angle(ta3), image_angle(tb3)]


# ---------------------------------------------------------------------------------------------
# Jacobians.  Points are differentiated directly; angles through
#   d atan2(dy, dx) = (dx * d(dy) - dy * d(dx)) / (dx^2 + dy^2),
# which keeps the (unsimplified) derivative of atan2 out of the generated code and shares dx, dy
# and their derivatives with the prediction in the common-subexpression pass.
# ---------------------------------------------------------------------------------------------


def angle_derivative(direction: sp.Matrix, wrt: sp.Symbol) -> sp.Expr:
    """d psi / d wrt for psi = atan2(dy, dx) of the projected ``direction``."""
    dx, dy = project(direction)
    ddx, ddy = sp.diff(dx, wrt), sp.diff(dy, wrt)
    numerator = dx * ddy - dy * ddx
    denominator = dx**2 + dy**2
    # A rotation about the viewing axis (theta) turns every image direction by the same angle:
    # there the numerator equals the denominator and the derivative is exactly 1.
    if sp.expand(numerator - denominator) == 0:
        return sp.Integer(1)
    return numerator / denominator


def jacobian(wrt: tuple[sp.Symbol, ...], params: tuple[sp.Expr, ...] = ALL_PARAMETERS) -> sp.Matrix:
    """6 x len(wrt) matrix d(prediction)/d(wrt), rows in PREDICTIONS order."""
    a3, b3, ta3, tb3 = camera_points(params)
    rows: list[list[sp.Expr]] = []
    for point in (a3, b3):
        x, y = project(point)
        rows.append([sp.diff(x, s) for s in wrt])
        rows.append([sp.diff(y, s) for s in wrt])
    for direction in (ta3, tb3):
        rows.append([angle_derivative(direction, s) for s in wrt])
    return sp.Matrix(rows)


# ---------------------------------------------------------------------------------------------
# Second derivatives, contracted with the residuals.  The Hessian of chi2 / 2 over all nine
# parameters of a frame is J^T J + sum_k r_k d2 r_k (r_k standardised residuals, r_k = w_k (m_k -
# measured_k)); Gauss-Newton drops the second term, Newton's method (``curverecon.refine.ml``)
# and the Laplace volume of the marginal likelihood (``curverecon.refine.marginal``) need it.
# One generated
# function returns sum_k u_k d2 m_k / dx_i dx_j for per-frame weights u_k (the runtime passes
# u_k = w_k r_k), so the six 9 x 9 Hessians are never formed one by one.
# Angles: d2 psi = d(first derivative) with the first derivative in the quotient form above.
# theta turns every image direction rigidly (d psi / d theta = 1), so any second derivative of
# an angle that involves theta is exactly 0; taking theta first gives that without simplifying.
# ---------------------------------------------------------------------------------------------

#: Weights of the contraction, one per prediction (PREDICTIONS order).
CURVATURE_WEIGHTS: tuple[sp.Symbol, ...] = tuple(
    sp.Symbol(f"u_{name}", real=True) for name in PREDICTIONS
)


def angle_second_derivative(direction: sp.Matrix, first: sp.Symbol, second: sp.Symbol) -> sp.Expr:
    """d2 psi / (d first d second) for psi = atan2(dy, dx) of the projected ``direction``."""
    if theta in (first, second):
        return sp.Integer(0)  # d psi / d theta = 1 (see the comment above)
    return sp.diff(angle_derivative(direction, first), second)


def contracted_hessian(
    wrt: tuple[sp.Symbol, ...] = ALL_PARAMETERS,
    weights: tuple[sp.Symbol, ...] = CURVATURE_WEIGHTS,
) -> sp.Matrix:
    """Symmetric len(wrt) x len(wrt) matrix sum_k u_k d2 m_k / d wrt_i d wrt_j.

    m_k are the six predictions (ax, ay, bx, by, psi_a, psi_b); entries are built for i <= j and
    mirrored, so the matrix is exactly symmetric.
    """
    a3, b3, ta3, tb3 = camera_points()
    coordinates = [*project(a3), *project(b3)]
    n = len(wrt)
    out = sp.zeros(n, n)
    for i in range(n):
        for j in range(i, n):
            s1, s2 = wrt[i], wrt[j]
            value = sum(
                (u * sp.diff(x, s1, s2) for u, x in zip(weights[:4], coordinates, strict=True)),
                sp.Integer(0),
            )
            for u, direction in zip(weights[4:], (ta3, tb3), strict=True):
                value += u * angle_second_derivative(direction, s1, s2)
            out[i, j] = out[j, i] = value
    return out


# ---------------------------------------------------------------------------------------------
# What code generation sees.
# ---------------------------------------------------------------------------------------------

MODULE_DOC = """The maximum-likelihood measurement model of one frame (generated).

Curve frame: A = (0, 0, 0), B = (c, 0, 0), t_B = (-cos(alpha), sin(alpha), 0),
t_A = (cos(beta), sin(beta) cos(phi), sin(beta) sin(phi)).  Pose: X_cam = R X + t with
R = R_z(theta) R_y(tau) R_x(delta), t = (tx, ty, 0); orthographic projection keeps (x, y).
Predictions per frame: (ax, ay, bx, by, psi_a, psi_b), psi = atan2(dy, dx) of the projected
tangent directions (radians).  See docs/CONVENTIONS.md.

Frame arguments (delta, tau, theta, tx, ty) are 1-D arrays of length N (or scalars); shape
arguments (c, alpha, beta, phi) are scalars; everything broadcasts.  Angles in radians,
lengths in input units.
"""


def module_constants() -> dict[str, tuple[str, ...]]:
    """Module-level constants of generated/measurement_model.py (names in argument order)."""
    return {
        "GLOBAL_PARAMETERS": tuple(s.name for s in GLOBAL_PARAMETERS),
        "LOCAL_PARAMETERS": tuple(s.name for s in LOCAL_PARAMETERS),
        "PREDICTIONS": PREDICTIONS,
    }


def generated_functions() -> list[FunctionSpec]:
    """The functions of generated/measurement_model.py.

    Output conventions of the code generator: a scalar expression gives an array of the broadcast
    frame shape (N,); a tuple of n expressions gives (N, n); an r x k Matrix gives (N, r, k).
    """
    rot = rotation(delta, tau, theta)
    a3, b3, ta3, tb3 = camera_points()
    pred = tuple(predictions())
    return [
        FunctionSpec(
            name="rotation_matrix",
            args=(delta, tau, theta),
            outputs={"rotation": rot},
            doc=(
                "Curve-to-camera rotation R = R_z(theta) @ R_y(tau) @ R_x(delta).\n\n"
                "Shape (N, 3, 3); angles in radians; X_cam = R X_curve + t."
            ),
        ),
        FunctionSpec(
            name="points_3d",
            args=ALL_PARAMETERS,
            outputs={
                "a3": tuple(a3),
                "b3": tuple(b3),
                "tangent_a3": tuple(ta3),
                "tangent_b3": tuple(tb3),
            },
            doc=(
                "A, B and the unit tangent directions at A and B in camera coordinates.\n\n"
                "Returns (A3, B3, tangent_A3, tangent_B3), each (N, 3); A3 = (tx, ty, 0) (depth\n"
                "is unobservable, A is put at z = 0), B3 z = -c sin(tau).  Lengths in input units."
            ),
        ),
        FunctionSpec(
            name="predict",
            args=ALL_PARAMETERS,
            outputs={"prediction": pred},
            doc=(
                "Predicted observations (ax, ay, bx, by, psi_a, psi_b) per frame, shape (N, 6).\n\n"
                "Points in input units, psi = atan2(dy, dx) of the projected tangents in radians."
            ),
        ),
        FunctionSpec(
            name="predict_with_jacobians",
            args=ALL_PARAMETERS,
            outputs={
                "prediction": pred,
                "jac_global": jacobian(GLOBAL_PARAMETERS),
                "jac_local": jacobian(LOCAL_PARAMETERS),
            },
            doc=(
                "Predictions and their analytic Jacobians.\n\n"
                "Returns (pred (N, 6), jac_global (N, 6, 4), jac_local (N, 6, 5)): derivatives of\n"
                "(ax, ay, bx, by, psi_a, psi_b) with respect to (c, alpha, beta, phi) and\n"
                "(delta, tau, theta, tx, ty)."
            ),
        ),
        FunctionSpec(
            name="residual_curvature",
            args=ALL_PARAMETERS + CURVATURE_WEIGHTS,
            outputs={"curvature": contracted_hessian()},
            doc=(
                "Second-order part of the Hessian, sum_k u_k d2 m_k / dx_i dx_j: (N, 9, 9).\n\n"
                "m = (ax, ay, bx, by, psi_a, psi_b), x = (c, alpha, beta, phi, delta, tau, theta,\n"
                "tx, ty); u_k per frame (pass u_k = w_k r_k, r_k = w_k (m_k - measured_k) the\n"
                "standardised residuals, for the Newton term sum_k r_k d2 r_k of chi2 / 2)."
            ),
        ),
    ]


KERNEL_DOC = """Scalar numba kernels of the measurement model, for loops over frames (generated).

The same expressions as generated/measurement_model.py (derivations/measurement.py), one frame
per call: float arguments (c, alpha, beta, phi, delta, tau, theta, tx, ty), outputs written
into arrays the caller passes.  Used by the per-frame pose iterations of long sequences
(curverecon.refine.pose_kernel), where NumPy's per-call overhead on (N, 6, 5) blocks was most
of the time.  Conventions and units as in measurement_model.py and docs/CONVENTIONS.md.
"""


def kernel_functions() -> list[FunctionSpec]:
    """The kernels of generated/measurement_kernel.py: one frame's prediction, and its
    prediction with the Jacobian of the pose (delta, tau, theta, tx, ty)."""
    pred = tuple(predictions())
    return [
        FunctionSpec(
            name="predict_frame",
            args=ALL_PARAMETERS,
            outputs={"prediction": pred},
            doc="Predicted (ax, ay, bx, by, psi_a, psi_b) of one frame (input units, radians).",
        ),
        FunctionSpec(
            name="predict_frame_with_pose_jacobian",
            args=ALL_PARAMETERS,
            outputs={"prediction": pred, "jac_local": jacobian(LOCAL_PARAMETERS)},
            doc=(
                "Prediction of one frame and its Jacobian (6, 5) with respect to the pose\n"
                "(delta, tau, theta, tx, ty)."
            ),
        ),
    ]
