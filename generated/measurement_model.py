# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/measurement.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""The maximum-likelihood measurement model of one frame (generated).

Curve frame: A = (0, 0, 0), B = (c, 0, 0), t_B = (-cos(alpha), sin(alpha), 0),
t_A = (cos(beta), sin(beta) cos(phi), sin(beta) sin(phi)).  Pose: X_cam = R X + t with
R = R_z(theta) R_y(tau) R_x(delta), t = (tx, ty, 0); orthographic projection keeps (x, y).
Predictions per frame: (ax, ay, bx, by, psi_a, psi_b), psi = atan2(dy, dx) of the projected
tangent directions (radians).  See docs/CONVENTIONS.md.

Frame arguments (delta, tau, theta, tx, ty) are 1-D arrays of length N (or scalars); shape
arguments (c, alpha, beta, phi) are scalars; everything broadcasts.  Angles in radians, lengths
in
input units.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

GLOBAL_PARAMETERS = ("c", "alpha", "beta", "phi")
LOCAL_PARAMETERS = ("delta", "tau", "theta", "tx", "ty")
PREDICTIONS = ("ax", "ay", "bx", "by", "psi_a", "psi_b")


def _full(value: np.ndarray | float, shape: tuple[int, ...]) -> np.ndarray:
    """``value`` broadcast to ``shape`` as a new, writable array."""
    out = np.empty(shape, dtype=np.float64)
    out[...] = value
    return out


def _stack(values: tuple[np.ndarray | float, ...], shape: tuple[int, ...]) -> np.ndarray:
    """Broadcast each of ``values`` to ``shape`` and stack them along a new last axis."""
    out = np.empty((*shape, len(values)), dtype=np.float64)
    for k, value in enumerate(values):
        out[..., k] = value
    return out


def rotation_matrix(delta: npt.ArrayLike, tau: npt.ArrayLike, theta: npt.ArrayLike) -> np.ndarray:
    """Curve-to-camera rotation R = R_z(theta) @ R_y(tau) @ R_x(delta).

    Shape (N, 3, 3); angles in radians; X_cam = R X_curve + t.
    """
    delta = np.asarray(delta, dtype=np.float64)
    tau = np.asarray(tau, dtype=np.float64)
    theta = np.asarray(theta, dtype=np.float64)
    _shape = np.broadcast_shapes(delta.shape, tau.shape, theta.shape)

    # Common subexpressions (9).
    _tmp0 = np.cos(tau)
    _tmp1 = np.cos(theta)
    _tmp2 = np.sin(theta)
    _tmp3 = np.cos(delta)
    _tmp4 = np.sin(tau)
    _tmp5 = np.sin(delta)
    _tmp6 = _tmp1 * _tmp5
    _tmp7 = _tmp2 * _tmp5
    _tmp8 = _tmp1 * _tmp3

    # Outputs.
    rotation = _stack(
        (
            _tmp0 * _tmp1,
            -_tmp2 * _tmp3 + _tmp4 * _tmp6,
            _tmp4 * _tmp8 + _tmp7,
            _tmp0 * _tmp2,
            _tmp4 * _tmp7 + _tmp8,
            _tmp2 * _tmp3 * _tmp4 - _tmp6,
            -_tmp4,
            _tmp0 * _tmp5,
            _tmp0 * _tmp3,
        ),
        _shape,
    ).reshape((*_shape, 3, 3))
    return rotation


def points_3d(
    c: npt.ArrayLike,
    alpha: npt.ArrayLike,
    beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    delta: npt.ArrayLike,
    tau: npt.ArrayLike,
    theta: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A, B and the unit tangent directions at A and B in camera coordinates.

    Returns (A3, B3, tangent_A3, tangent_B3), each (N, 3); A3 = (tx, ty, 0) (depth
    is unobservable, A is put at z = 0), B3 z = -c sin(tau).  Lengths in input units.
    """
    c = np.asarray(c, dtype=np.float64)
    alpha = np.asarray(alpha, dtype=np.float64)
    beta = np.asarray(beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    tau = np.asarray(tau, dtype=np.float64)
    theta = np.asarray(theta, dtype=np.float64)
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape,
        alpha.shape,
        beta.shape,
        phi.shape,
        delta.shape,
        tau.shape,
        theta.shape,
        tx.shape,
        ty.shape,
    )

    # Common subexpressions (22).
    _tmp0 = np.cos(theta)
    _tmp1 = np.cos(tau)
    _tmp2 = _tmp1 * c
    _tmp3 = np.sin(theta)
    _tmp4 = np.sin(tau)
    _tmp5 = np.cos(beta)
    _tmp6 = _tmp1 * _tmp5
    _tmp7 = np.sin(delta)
    _tmp8 = _tmp3 * _tmp7
    _tmp9 = np.cos(delta)
    _tmp10 = _tmp0 * _tmp9
    _tmp11 = np.sin(beta)
    _tmp12 = _tmp11 * np.sin(phi)
    _tmp13 = _tmp3 * _tmp9
    _tmp14 = _tmp0 * _tmp7
    _tmp15 = -_tmp13 + _tmp14 * _tmp4
    _tmp16 = _tmp11 * np.cos(phi)
    _tmp17 = _tmp10 + _tmp4 * _tmp8
    _tmp18 = _tmp1 * _tmp7
    _tmp19 = np.cos(alpha)
    _tmp20 = _tmp1 * _tmp19
    _tmp21 = np.sin(alpha)

    # Outputs.
    a3 = _stack(
        (
            tx,
            ty,
            0,
        ),
        _shape,
    )
    b3 = _stack(
        (
            _tmp0 * _tmp2 + tx,
            _tmp2 * _tmp3 + ty,
            -_tmp4 * c,
        ),
        _shape,
    )
    tangent_a3 = _stack(
        (
            _tmp0 * _tmp6 + _tmp12 * (_tmp10 * _tmp4 + _tmp8) + _tmp15 * _tmp16,
            -_tmp12 * (-_tmp13 * _tmp4 + _tmp14) + _tmp16 * _tmp17 + _tmp3 * _tmp6,
            _tmp1 * _tmp12 * _tmp9 + _tmp16 * _tmp18 - _tmp4 * _tmp5,
        ),
        _shape,
    )
    tangent_b3 = _stack(
        (
            -_tmp0 * _tmp20 + _tmp15 * _tmp21,
            _tmp17 * _tmp21 - _tmp20 * _tmp3,
            _tmp18 * _tmp21 + _tmp19 * _tmp4,
        ),
        _shape,
    )
    return a3, b3, tangent_a3, tangent_b3


def predict(
    c: npt.ArrayLike,
    alpha: npt.ArrayLike,
    beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    delta: npt.ArrayLike,
    tau: npt.ArrayLike,
    theta: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
) -> np.ndarray:
    """Predicted observations (ax, ay, bx, by, psi_a, psi_b) per frame, shape (N, 6).

    Points in input units, psi = atan2(dy, dx) of the projected tangents in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    alpha = np.asarray(alpha, dtype=np.float64)
    beta = np.asarray(beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    tau = np.asarray(tau, dtype=np.float64)
    theta = np.asarray(theta, dtype=np.float64)
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape,
        alpha.shape,
        beta.shape,
        phi.shape,
        delta.shape,
        tau.shape,
        theta.shape,
        tx.shape,
        ty.shape,
    )

    # Common subexpressions (19).
    _tmp0 = np.cos(theta)
    _tmp1 = np.cos(tau)
    _tmp2 = _tmp1 * c
    _tmp3 = np.sin(theta)
    _tmp4 = _tmp1 * np.cos(beta)
    _tmp5 = np.cos(delta)
    _tmp6 = _tmp0 * _tmp5
    _tmp7 = np.sin(tau)
    _tmp8 = np.sin(delta)
    _tmp9 = _tmp3 * _tmp8
    _tmp10 = _tmp6 + _tmp7 * _tmp9
    _tmp11 = np.sin(beta)
    _tmp12 = _tmp11 * np.cos(phi)
    _tmp13 = _tmp0 * _tmp8
    _tmp14 = _tmp3 * _tmp5
    _tmp15 = _tmp11 * np.sin(phi)
    _tmp16 = _tmp13 * _tmp7 - _tmp14
    _tmp17 = _tmp1 * np.cos(alpha)
    _tmp18 = np.sin(alpha)

    # Outputs.
    prediction = _stack(
        (
            tx,
            ty,
            _tmp0 * _tmp2 + tx,
            _tmp2 * _tmp3 + ty,
            np.arctan2(
                _tmp10 * _tmp12 - _tmp15 * (_tmp13 - _tmp14 * _tmp7) + _tmp3 * _tmp4,
                _tmp0 * _tmp4 + _tmp12 * _tmp16 + _tmp15 * (_tmp6 * _tmp7 + _tmp9),
            ),
            np.arctan2(_tmp10 * _tmp18 - _tmp17 * _tmp3, -_tmp0 * _tmp17 + _tmp16 * _tmp18),
        ),
        _shape,
    )
    return prediction


def predict_with_jacobians(
    c: npt.ArrayLike,
    alpha: npt.ArrayLike,
    beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    delta: npt.ArrayLike,
    tau: npt.ArrayLike,
    theta: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Predictions and their analytic Jacobians.

    Returns (pred (N, 6), jac_global (N, 6, 4), jac_local (N, 6, 5)): derivatives of
    (ax, ay, bx, by, psi_a, psi_b) with respect to (c, alpha, beta, phi) and
    (delta, tau, theta, tx, ty).
    """
    c = np.asarray(c, dtype=np.float64)
    alpha = np.asarray(alpha, dtype=np.float64)
    beta = np.asarray(beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    tau = np.asarray(tau, dtype=np.float64)
    theta = np.asarray(theta, dtype=np.float64)
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape,
        alpha.shape,
        beta.shape,
        phi.shape,
        delta.shape,
        tau.shape,
        theta.shape,
        tx.shape,
        ty.shape,
    )

    # Common subexpressions (37).
    _tmp0 = np.cos(tau)
    _tmp1 = np.cos(theta)
    _tmp2 = _tmp0 * _tmp1
    _tmp3 = _tmp2 * c
    _tmp4 = np.sin(theta)
    _tmp5 = _tmp0 * _tmp4
    _tmp6 = _tmp5 * c
    _tmp7 = np.cos(beta)
    _tmp8 = np.cos(delta)
    _tmp9 = _tmp1 * _tmp8
    _tmp10 = np.sin(tau)
    _tmp11 = np.sin(delta)
    _tmp12 = _tmp11 * _tmp4
    _tmp13 = _tmp10 * _tmp12 + _tmp9
    _tmp14 = np.cos(phi)
    _tmp15 = np.sin(beta)
    _tmp16 = _tmp14 * _tmp15
    _tmp17 = _tmp1 * _tmp11
    _tmp18 = _tmp4 * _tmp8
    _tmp19 = -_tmp10 * _tmp18 + _tmp17
    _tmp20 = np.sin(phi)
    _tmp21 = _tmp15 * _tmp20
    _tmp22 = _tmp13 * _tmp16 - _tmp19 * _tmp21 + _tmp5 * _tmp7
    _tmp23 = _tmp10 * _tmp9 + _tmp12
    _tmp24 = _tmp10 * _tmp17 - _tmp18
    _tmp25 = _tmp16 * _tmp24 + _tmp2 * _tmp7 + _tmp21 * _tmp23
    _tmp26 = np.cos(alpha)
    _tmp27 = np.sin(alpha)
    _tmp28 = _tmp13 * _tmp27 - _tmp26 * _tmp5
    _tmp29 = -_tmp2 * _tmp26 + _tmp24 * _tmp27
    _tmp30 = 1 / (_tmp22 * _tmp22 + _tmp25 * _tmp25)
    _tmp31 = _tmp20 * _tmp7
    _tmp32 = _tmp14 * _tmp7
    _tmp33 = (
        -_tmp15
        * _tmp30
        * (
            _tmp22 * (_tmp14 * _tmp23 - _tmp20 * _tmp24)
            + _tmp25 * (_tmp13 * _tmp20 + _tmp14 * _tmp19)
        )
    )
    _tmp34 = 1 / (_tmp28 * _tmp28 + _tmp29 * _tmp29)
    _tmp35 = _tmp10 * c
    _tmp36 = _tmp0 * _tmp11

    # Outputs.
    prediction = _stack(
        (
            tx,
            ty,
            _tmp3 + tx,
            _tmp6 + ty,
            np.arctan2(_tmp22, _tmp25),
            np.arctan2(_tmp28, _tmp29),
        ),
        _shape,
    )
    jac_global = _stack(
        (
            0,
            0,
            0,
            0,
            0,
            0,
            0,
            0,
            _tmp2,
            0,
            0,
            0,
            _tmp5,
            0,
            0,
            0,
            0,
            0,
            -_tmp30
            * (
                _tmp22 * (-_tmp15 * _tmp2 + _tmp23 * _tmp31 + _tmp24 * _tmp32)
                + _tmp25 * (-_tmp13 * _tmp32 + _tmp15 * _tmp5 + _tmp19 * _tmp31)
            ),
            _tmp33,
            0,
            -_tmp34
            * (
                _tmp28 * (_tmp2 * _tmp27 + _tmp24 * _tmp26)
                - _tmp29 * (_tmp13 * _tmp26 + _tmp27 * _tmp5)
            ),
            0,
            0,
        ),
        _shape,
    ).reshape((*_shape, 6, 4))
    jac_local = _stack(
        (
            0,
            0,
            0,
            1,
            0,
            0,
            0,
            0,
            0,
            1,
            0,
            -_tmp1 * _tmp35,
            -_tmp6,
            1,
            0,
            0,
            -_tmp35 * _tmp4,
            _tmp3,
            0,
            1,
            _tmp33,
            _tmp30
            * (-_tmp1 * _tmp22 + _tmp25 * _tmp4)
            * (_tmp0 * _tmp21 * _tmp8 - _tmp10 * _tmp7 + _tmp16 * _tmp36),
            1,
            0,
            0,
            -_tmp27 * _tmp34 * (_tmp19 * _tmp29 + _tmp23 * _tmp28),
            -_tmp34 * (_tmp1 * _tmp28 - _tmp29 * _tmp4) * (_tmp10 * _tmp26 + _tmp27 * _tmp36),
            1,
            0,
            0,
        ),
        _shape,
    ).reshape((*_shape, 6, 5))
    return prediction, jac_global, jac_local
