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
arguments (c, alpha, beta, phi) are scalars; everything broadcasts.  Angles in radians,
lengths in input units.
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


def _scatter(
    entries: tuple[tuple[int, np.ndarray | float], ...], size: int, shape: tuple[int, ...]
) -> np.ndarray:
    """Zeros of shape (*shape, size) with ``value`` broadcast into column k for each (k, value)."""
    out = np.zeros((*shape, size), dtype=np.float64)
    for k, value in entries:
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
    a3 = _scatter(
        (
            (0, tx),
            (1, ty),
        ),
        3,
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
    jac_global = _scatter(
        (
            (8, _tmp2),
            (12, _tmp5),
            (
                18,
                -_tmp30
                * (
                    _tmp22 * (-_tmp15 * _tmp2 + _tmp23 * _tmp31 + _tmp24 * _tmp32)
                    + _tmp25 * (-_tmp13 * _tmp32 + _tmp15 * _tmp5 + _tmp19 * _tmp31)
                ),
            ),
            (19, _tmp33),
            (
                21,
                -_tmp34
                * (
                    _tmp28 * (_tmp2 * _tmp27 + _tmp24 * _tmp26)
                    - _tmp29 * (_tmp13 * _tmp26 + _tmp27 * _tmp5)
                ),
            ),
        ),
        24,
        _shape,
    ).reshape((*_shape, 6, 4))
    jac_local = _scatter(
        (
            (3, 1),
            (9, 1),
            (11, -_tmp1 * _tmp35),
            (12, -_tmp6),
            (13, 1),
            (16, -_tmp35 * _tmp4),
            (17, _tmp3),
            (19, 1),
            (20, _tmp33),
            (
                21,
                _tmp30
                * (-_tmp1 * _tmp22 + _tmp25 * _tmp4)
                * (_tmp0 * _tmp21 * _tmp8 - _tmp10 * _tmp7 + _tmp16 * _tmp36),
            ),
            (22, 1),
            (25, -_tmp27 * _tmp34 * (_tmp19 * _tmp29 + _tmp23 * _tmp28)),
            (26, -_tmp34 * (_tmp1 * _tmp28 - _tmp29 * _tmp4) * (_tmp10 * _tmp26 + _tmp27 * _tmp36)),
            (27, 1),
        ),
        30,
        _shape,
    ).reshape((*_shape, 6, 5))
    return prediction, jac_global, jac_local


def residual_curvature(
    c: npt.ArrayLike,
    alpha: npt.ArrayLike,
    beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    delta: npt.ArrayLike,
    tau: npt.ArrayLike,
    theta: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
    u_ax: npt.ArrayLike,
    u_ay: npt.ArrayLike,
    u_bx: npt.ArrayLike,
    u_by: npt.ArrayLike,
    u_psi_a: npt.ArrayLike,
    u_psi_b: npt.ArrayLike,
) -> np.ndarray:
    """Second-order part of the Hessian, sum_k u_k d2 m_k / dx_i dx_j: (N, 9, 9).

    m = (ax, ay, bx, by, psi_a, psi_b), x = (c, alpha, beta, phi, delta, tau, theta,
    tx, ty); u_k per frame (pass u_k = w_k r_k, r_k = w_k (m_k - measured_k) the
    standardised residuals, for the Newton term sum_k r_k d2 r_k of chi2 / 2).
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
    u_ax = np.asarray(u_ax, dtype=np.float64)
    u_ay = np.asarray(u_ay, dtype=np.float64)
    u_bx = np.asarray(u_bx, dtype=np.float64)
    u_by = np.asarray(u_by, dtype=np.float64)
    u_psi_a = np.asarray(u_psi_a, dtype=np.float64)
    u_psi_b = np.asarray(u_psi_b, dtype=np.float64)
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
        u_ax.shape,
        u_ay.shape,
        u_bx.shape,
        u_by.shape,
        u_psi_a.shape,
        u_psi_b.shape,
    )

    # Common subexpressions (114).
    _tmp0 = np.sin(tau)
    _tmp1 = np.cos(theta)
    _tmp2 = _tmp1 * u_bx
    _tmp3 = np.sin(theta)
    _tmp4 = _tmp3 * u_by
    _tmp5 = _tmp2 + _tmp4
    _tmp6 = -_tmp0 * _tmp5
    _tmp7 = np.cos(tau)
    _tmp8 = -_tmp1 * u_by + _tmp3 * u_bx
    _tmp9 = -_tmp7 * _tmp8
    _tmp10 = np.cos(alpha)
    _tmp11 = _tmp10 * _tmp7
    _tmp12 = np.sin(alpha)
    _tmp13 = np.cos(delta)
    _tmp14 = _tmp1 * _tmp13
    _tmp15 = np.sin(delta)
    _tmp16 = _tmp15 * _tmp3
    _tmp17 = _tmp0 * _tmp16 + _tmp14
    _tmp18 = -_tmp11 * _tmp3 + _tmp12 * _tmp17
    _tmp19 = _tmp13 * _tmp3
    _tmp20 = _tmp1 * _tmp15
    _tmp21 = _tmp0 * _tmp20 - _tmp19
    _tmp22 = -_tmp1 * _tmp11 + _tmp12 * _tmp21
    _tmp23 = _tmp18 * _tmp18 + _tmp22 * _tmp22
    _tmp24 = _tmp12 * _tmp7
    _tmp25 = _tmp10 * _tmp17 + _tmp24 * _tmp3
    _tmp26 = _tmp1 * _tmp24 + _tmp10 * _tmp21
    _tmp27 = _tmp18 * _tmp26 - _tmp22 * _tmp25
    _tmp28 = _tmp0 * _tmp14 + _tmp16
    _tmp29 = _tmp18 * _tmp28
    _tmp30 = -_tmp0 * _tmp19 + _tmp20
    _tmp31 = _tmp22 * _tmp30
    _tmp32 = 1 / _tmp23
    _tmp33 = 2 * _tmp32
    _tmp34 = _tmp12 * _tmp33 * (-_tmp18 * _tmp30 + _tmp22 * _tmp28)
    _tmp35 = _tmp32 * u_psi_b
    _tmp36 = _tmp35 * (
        -_tmp10 * _tmp29
        - _tmp10 * _tmp31
        + _tmp12 * _tmp25 * _tmp28
        + _tmp12 * _tmp26 * _tmp30
        + _tmp27 * _tmp34
    )
    _tmp37 = _tmp0 * _tmp10 + _tmp15 * _tmp24
    _tmp38 = _tmp1 * _tmp37
    _tmp39 = _tmp0 * _tmp12
    _tmp40 = -_tmp11 * _tmp15 + _tmp39
    _tmp41 = _tmp1 * _tmp18
    _tmp42 = _tmp3 * _tmp37
    _tmp43 = _tmp22 * _tmp3
    _tmp44 = _tmp1 * _tmp22 + _tmp18 * _tmp3
    _tmp45 = _tmp33 * _tmp44
    _tmp46 = _tmp35 * (
        _tmp25 * _tmp38
        - _tmp26 * _tmp42
        + _tmp27 * _tmp37 * _tmp45
        + _tmp40 * _tmp41
        - _tmp40 * _tmp43
    )
    _tmp47 = np.cos(beta)
    _tmp48 = _tmp47 * _tmp7
    _tmp49 = np.sin(beta)
    _tmp50 = np.sin(phi)
    _tmp51 = _tmp28 * _tmp50
    _tmp52 = np.cos(phi)
    _tmp53 = _tmp21 * _tmp52
    _tmp54 = _tmp1 * _tmp48 + _tmp49 * _tmp51 + _tmp49 * _tmp53
    _tmp55 = _tmp30 * _tmp50
    _tmp56 = _tmp17 * _tmp52
    _tmp57 = _tmp3 * _tmp48 + _tmp49 * _tmp56
    _tmp58 = -_tmp49 * _tmp55 + _tmp57
    _tmp59 = _tmp54 * _tmp54 + _tmp58 * _tmp58
    _tmp60 = _tmp49 * _tmp7
    _tmp61 = -_tmp1 * _tmp60 + _tmp47 * _tmp51 + _tmp47 * _tmp53
    _tmp62 = -_tmp30
    _tmp63 = _tmp50 * _tmp62
    _tmp64 = _tmp49 * _tmp63 + _tmp57
    _tmp65 = _tmp3 * _tmp60
    _tmp66 = _tmp17 * _tmp47 * _tmp52 - _tmp47 * _tmp55 - _tmp65
    _tmp67 = 2 * _tmp54 * _tmp66 - 2 * _tmp58 * _tmp61
    _tmp68 = _tmp28 * _tmp52
    _tmp69 = -_tmp21 * _tmp50 + _tmp68
    _tmp70 = _tmp54 * _tmp69
    _tmp71 = _tmp17 * _tmp50
    _tmp72 = _tmp52 * _tmp62 - _tmp71
    _tmp73 = _tmp64 * _tmp72
    _tmp74 = _tmp70 + _tmp73
    _tmp75 = 1 / _tmp59
    _tmp76 = _tmp67 * _tmp75
    _tmp77 = _tmp49 * _tmp76
    _tmp78 = _tmp30 * _tmp52 + _tmp71
    _tmp79 = _tmp54 * _tmp78
    _tmp80 = _tmp58 * _tmp69
    _tmp81 = _tmp47 * _tmp79 + _tmp47 * _tmp80 - _tmp49 * _tmp61 * _tmp78 - _tmp49 * _tmp66 * _tmp69
    _tmp82 = _tmp75 * u_psi_a
    _tmp83 = -_tmp82 * (_tmp74 * _tmp77 + _tmp81)
    _tmp84 = -_tmp21
    _tmp85 = _tmp50 * _tmp84 + _tmp68
    _tmp86 = _tmp54 * _tmp85 + _tmp73
    _tmp87 = -_tmp82 * (_tmp77 * _tmp86 + _tmp81)
    _tmp88 = _tmp0 * _tmp49
    _tmp89 = _tmp15 * _tmp52
    _tmp90 = _tmp13 * _tmp50
    _tmp91 = _tmp48 * _tmp89 + _tmp48 * _tmp90 + _tmp88
    _tmp92 = _tmp3 * _tmp54
    _tmp93 = -_tmp0 * _tmp47 + _tmp60 * _tmp89 + _tmp60 * _tmp90
    _tmp94 = _tmp3 * _tmp93
    _tmp95 = _tmp1 * _tmp93
    _tmp96 = _tmp1 * _tmp54
    _tmp97 = _tmp3 * _tmp64 + _tmp96
    _tmp98 = -_tmp82 * (
        _tmp1 * _tmp58 * _tmp91
        + _tmp61 * _tmp94
        - _tmp66 * _tmp95
        + _tmp76 * _tmp93 * _tmp97
        - _tmp91 * _tmp92
    )
    _tmp99 = -_tmp54 * (_tmp56 + _tmp63)
    _tmp100 = -_tmp54 * _tmp72
    _tmp101 = 2 * _tmp75
    _tmp102 = _tmp101 * _tmp49
    _tmp103 = _tmp49 * _tmp82
    _tmp104 = _tmp51 - _tmp52 * _tmp84
    _tmp105 = _tmp79 + _tmp80
    _tmp106 = _tmp103 * (
        _tmp102 * _tmp105 * (-_tmp58 * _tmp78 + _tmp70) + _tmp104 * _tmp58 + _tmp99
    )
    _tmp107 = -_tmp13 * _tmp52 + _tmp15 * _tmp50
    _tmp108 = _tmp103 * (
        _tmp1 * _tmp107 * _tmp58 * _tmp7
        + 2 * _tmp105 * _tmp75 * _tmp93 * (_tmp3 * _tmp58 + _tmp96)
        - _tmp107 * _tmp7 * _tmp92
        - _tmp69 * _tmp94
        - _tmp78 * _tmp95
    )
    _tmp109 = _tmp29 + _tmp31
    _tmp110 = _tmp108 + _tmp12 * _tmp35 * (
        2 * _tmp109 * _tmp32 * _tmp37 * _tmp44
        + _tmp13 * _tmp22 * _tmp3 * _tmp7
        - _tmp14 * _tmp18 * _tmp7
        - _tmp28 * _tmp42
        - _tmp30 * _tmp38
    )
    _tmp111 = _tmp7 * c
    _tmp112 = -_tmp1 * _tmp58 + _tmp92
    _tmp113 = _tmp0 * _tmp8 * c

    # Outputs.
    curvature = _scatter(
        (
            (5, _tmp6),
            (6, _tmp9),
            (10, 2 * _tmp27 * u_psi_b * (_tmp18 * _tmp25 + _tmp22 * _tmp26) / (_tmp23 * _tmp23)),
            (13, _tmp36),
            (14, _tmp46),
            (
                20,
                -_tmp67
                * u_psi_a
                * (_tmp54 * _tmp61 + _tmp64 * (_tmp47 * _tmp56 + _tmp47 * _tmp63 - _tmp65))
                / (_tmp59 * _tmp59),
            ),
            (21, _tmp83),
            (22, _tmp87),
            (23, _tmp98),
            (29, _tmp83),
            (
                30,
                -_tmp103
                * (
                    -_tmp102 * _tmp74 * (_tmp100 + _tmp64 * _tmp69)
                    - _tmp64 * (_tmp51 + _tmp53)
                    - _tmp99
                ),
            ),
            (31, _tmp106),
            (32, _tmp108),
            (37, _tmp36),
            (38, _tmp87),
            (39, _tmp106),
            (
                40,
                -_tmp103
                * (
                    -_tmp102 * _tmp86 * (_tmp100 + _tmp64 * _tmp85)
                    - _tmp104 * _tmp64
                    - _tmp54 * (_tmp55 - _tmp56)
                )
                + _tmp12
                * _tmp32
                * u_psi_b
                * (_tmp109 * _tmp34 - _tmp17 * _tmp22 + _tmp18 * _tmp21),
            ),
            (41, _tmp110),
            (45, _tmp6),
            (46, _tmp46),
            (47, _tmp98),
            (48, _tmp108),
            (49, _tmp110),
            (
                50,
                -_tmp111 * _tmp2
                - _tmp111 * _tmp4
                + _tmp32
                * u_psi_b
                * (_tmp41 - _tmp43)
                * (-_tmp11 + _tmp15 * _tmp39 + (_tmp37 * _tmp37) * _tmp45)
                + _tmp75
                * u_psi_a
                * (
                    -_tmp101 * _tmp112 * (_tmp93 * _tmp93) * _tmp97
                    - _tmp112 * (_tmp48 + _tmp88 * _tmp89 + _tmp88 * _tmp90)
                ),
            ),
            (51, _tmp113),
            (54, _tmp9),
            (59, _tmp113),
            (60, -_tmp111 * _tmp5),
        ),
        81,
        _shape,
    ).reshape((*_shape, 9, 9))
    return curvature
