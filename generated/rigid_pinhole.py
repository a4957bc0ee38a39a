# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/rigid_pinhole.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""The pinhole rigid-body measurement model of the perspective and stereo rows.

A body point with body vector q (relative to the reference point, frame 0's camera coordinates)
is at X = T + R q in a frame with rotation R (relative to frame 0) and reference position T
(camera coordinates), seen at x = focal X_x / X_z + cx, y = focal X_y / X_z + cy (pixels); a
body direction u(polar, azimuth) there at the image angle psi = atan2(u_y X_z - X_y u_z,
u_x X_z - X_x u_z).  Rotation Jacobians are with respect to the left increment w of
R = exp([w]_x) Rbar at w = 0; rotation arguments r00 .. r22 are the entries of Rbar, row-major;
every argument is a 1-D array of length N or a scalar, everything broadcasts.  Lengths in the
answer's units, pixels, radians.  See derivations/rigid_pinhole.py.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt


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


def pinhole_point(
    r00: npt.ArrayLike,
    r01: npt.ArrayLike,
    r02: npt.ArrayLike,
    r10: npt.ArrayLike,
    r11: npt.ArrayLike,
    r12: npt.ArrayLike,
    r20: npt.ArrayLike,
    r21: npt.ArrayLike,
    r22: npt.ArrayLike,
    qx: npt.ArrayLike,
    qy: npt.ArrayLike,
    qz: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
    tz: npt.ArrayLike,
    focal: npt.ArrayLike,
    cx: npt.ArrayLike,
    cy: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Pinhole image of a body point X = T + R q and its Jacobians.

    Returns (prediction (N, 2) pixels, jac_rotation (N, 2, 3) with respect to the
    left increment w of R, jac_body (N, 2, 3) with respect to q, jac_translation
    (N, 2, 3) with respect to T).
    """
    r00 = np.asarray(r00, dtype=np.float64)
    r01 = np.asarray(r01, dtype=np.float64)
    r02 = np.asarray(r02, dtype=np.float64)
    r10 = np.asarray(r10, dtype=np.float64)
    r11 = np.asarray(r11, dtype=np.float64)
    r12 = np.asarray(r12, dtype=np.float64)
    r20 = np.asarray(r20, dtype=np.float64)
    r21 = np.asarray(r21, dtype=np.float64)
    r22 = np.asarray(r22, dtype=np.float64)
    qx = np.asarray(qx, dtype=np.float64)
    qy = np.asarray(qy, dtype=np.float64)
    qz = np.asarray(qz, dtype=np.float64)
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    tz = np.asarray(tz, dtype=np.float64)
    focal = np.asarray(focal, dtype=np.float64)
    cx = np.asarray(cx, dtype=np.float64)
    cy = np.asarray(cy, dtype=np.float64)
    _shape = np.broadcast_shapes(
        r00.shape,
        r01.shape,
        r02.shape,
        r10.shape,
        r11.shape,
        r12.shape,
        r20.shape,
        r21.shape,
        r22.shape,
        qx.shape,
        qy.shape,
        qz.shape,
        tx.shape,
        ty.shape,
        tz.shape,
        focal.shape,
        cx.shape,
        cy.shape,
    )

    # Common subexpressions (13).
    _tmp0 = qx * r00 + qy * r01 + qz * r02
    _tmp1 = _tmp0 + tx
    _tmp2 = qx * r20 + qy * r21 + qz * r22
    _tmp3 = _tmp2 + tz
    _tmp4 = 1 / _tmp3
    _tmp5 = _tmp4 * focal
    _tmp6 = qx * r10 + qy * r11 + qz * r12
    _tmp7 = _tmp6 + ty
    _tmp8 = focal / (_tmp3 * _tmp3)
    _tmp9 = _tmp1 * _tmp8
    _tmp10 = _tmp1 * _tmp4
    _tmp11 = _tmp4 * _tmp7
    _tmp12 = _tmp7 * _tmp8

    # Outputs.
    prediction = _stack(
        (
            _tmp1 * _tmp5 + cx,
            _tmp5 * _tmp7 + cy,
        ),
        _shape,
    )
    jac_rotation = _stack(
        (
            -_tmp6 * _tmp9,
            _tmp5 * (_tmp0 * _tmp10 + _tmp2),
            -_tmp5 * _tmp6,
            -_tmp5 * (_tmp11 * _tmp6 + _tmp2),
            _tmp0 * _tmp12,
            _tmp0 * _tmp5,
        ),
        _shape,
    ).reshape((*_shape, 2, 3))
    jac_body = _stack(
        (
            _tmp5 * (-_tmp10 * r20 + r00),
            _tmp5 * (-_tmp10 * r21 + r01),
            _tmp5 * (-_tmp10 * r22 + r02),
            _tmp5 * (-_tmp11 * r20 + r10),
            _tmp5 * (-_tmp11 * r21 + r11),
            _tmp5 * (-_tmp11 * r22 + r12),
        ),
        _shape,
    ).reshape((*_shape, 2, 3))
    jac_translation = _scatter(
        (
            (0, _tmp5),
            (2, -_tmp9),
            (4, _tmp5),
            (5, -_tmp12),
        ),
        6,
        _shape,
    ).reshape((*_shape, 2, 3))
    return prediction, jac_rotation, jac_body, jac_translation


def pinhole_tangent(
    r00: npt.ArrayLike,
    r01: npt.ArrayLike,
    r02: npt.ArrayLike,
    r10: npt.ArrayLike,
    r11: npt.ArrayLike,
    r12: npt.ArrayLike,
    r20: npt.ArrayLike,
    r21: npt.ArrayLike,
    r22: npt.ArrayLike,
    qx: npt.ArrayLike,
    qy: npt.ArrayLike,
    qz: npt.ArrayLike,
    tx: npt.ArrayLike,
    ty: npt.ArrayLike,
    tz: npt.ArrayLike,
    polar: npt.ArrayLike,
    azimuth: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Image angle of a body direction u(polar, azimuth) at the body point
    X = T + R q under a pinhole camera, and its Jacobians.

    Returns (psi (N,) radians, jac_rotation (N, 3) with respect to the left
    increment of R, jac_body (N, 3), jac_translation (N, 3), jac_direction (N, 2)
    with respect to (polar, azimuth)).
    """
    r00 = np.asarray(r00, dtype=np.float64)
    r01 = np.asarray(r01, dtype=np.float64)
    r02 = np.asarray(r02, dtype=np.float64)
    r10 = np.asarray(r10, dtype=np.float64)
    r11 = np.asarray(r11, dtype=np.float64)
    r12 = np.asarray(r12, dtype=np.float64)
    r20 = np.asarray(r20, dtype=np.float64)
    r21 = np.asarray(r21, dtype=np.float64)
    r22 = np.asarray(r22, dtype=np.float64)
    qx = np.asarray(qx, dtype=np.float64)
    qy = np.asarray(qy, dtype=np.float64)
    qz = np.asarray(qz, dtype=np.float64)
    tx = np.asarray(tx, dtype=np.float64)
    ty = np.asarray(ty, dtype=np.float64)
    tz = np.asarray(tz, dtype=np.float64)
    polar = np.asarray(polar, dtype=np.float64)
    azimuth = np.asarray(azimuth, dtype=np.float64)
    _shape = np.broadcast_shapes(
        r00.shape,
        r01.shape,
        r02.shape,
        r10.shape,
        r11.shape,
        r12.shape,
        r20.shape,
        r21.shape,
        r22.shape,
        qx.shape,
        qy.shape,
        qz.shape,
        tx.shape,
        ty.shape,
        tz.shape,
        polar.shape,
        azimuth.shape,
    )

    # Common subexpressions (25).
    _tmp0 = qx * r20 + qy * r21 + qz * r22
    _tmp1 = _tmp0 + tz
    _tmp2 = np.cos(polar)
    _tmp3 = np.sin(polar)
    _tmp4 = np.cos(azimuth)
    _tmp5 = _tmp3 * _tmp4
    _tmp6 = np.sin(azimuth)
    _tmp7 = _tmp3 * _tmp6
    _tmp8 = _tmp2 * r12 + _tmp5 * r10 + _tmp7 * r11
    _tmp9 = qx * r10 + qy * r11 + qz * r12
    _tmp10 = _tmp9 + ty
    _tmp11 = _tmp2 * r22 + _tmp5 * r20 + _tmp7 * r21
    _tmp12 = _tmp1 * _tmp8 - _tmp10 * _tmp11
    _tmp13 = _tmp2 * r02 + _tmp5 * r00 + _tmp7 * r01
    _tmp14 = _tmp1 * _tmp13
    _tmp15 = qx * r00 + qy * r01 + qz * r02
    _tmp16 = _tmp15 + tx
    _tmp17 = -_tmp11 * _tmp16 + _tmp14
    _tmp18 = 1 / (_tmp12 * _tmp12 + _tmp17 * _tmp17)
    _tmp19 = _tmp0 * _tmp11 - _tmp1 * _tmp11
    _tmp20 = _tmp11 * _tmp18
    _tmp21 = _tmp2 * _tmp4
    _tmp22 = _tmp2 * _tmp6
    _tmp23 = _tmp21 * r20 + _tmp22 * r21 - _tmp3 * r22
    _tmp24 = -_tmp4 * r21 + _tmp6 * r20

    # Outputs.
    psi = _full(np.arctan2(_tmp12, _tmp17), _shape)
    jac_rotation = _stack(
        (
            -_tmp18
            * (
                _tmp12 * (_tmp13 * _tmp9 - _tmp16 * _tmp8)
                - _tmp17 * (-_tmp10 * _tmp8 + _tmp19 + _tmp8 * _tmp9)
            ),
            _tmp18
            * (
                _tmp12 * (_tmp13 * _tmp15 - _tmp13 * _tmp16 + _tmp19)
                - _tmp17 * (-_tmp10 * _tmp13 + _tmp15 * _tmp8)
            ),
            -_tmp18
            * (-_tmp12 * (_tmp1 * _tmp8 - _tmp11 * _tmp9) + _tmp17 * (_tmp11 * _tmp15 - _tmp14)),
        ),
        _shape,
    )
    jac_body = _stack(
        (
            -_tmp18
            * (-_tmp12 * (_tmp11 * r00 - _tmp13 * r20) + _tmp17 * (_tmp11 * r10 - _tmp8 * r20)),
            -_tmp18
            * (-_tmp12 * (_tmp11 * r01 - _tmp13 * r21) + _tmp17 * (_tmp11 * r11 - _tmp8 * r21)),
            -_tmp18
            * (-_tmp12 * (_tmp11 * r02 - _tmp13 * r22) + _tmp17 * (_tmp11 * r12 - _tmp8 * r22)),
        ),
        _shape,
    )
    jac_translation = _stack(
        (
            _tmp12 * _tmp20,
            -_tmp17 * _tmp20,
            _tmp18 * (-_tmp12 * _tmp13 + _tmp17 * _tmp8),
        ),
        _shape,
    )
    jac_direction = _stack(
        (
            _tmp18
            * (
                -_tmp12 * (_tmp1 * (_tmp21 * r00 + _tmp22 * r01 - _tmp3 * r02) - _tmp16 * _tmp23)
                + _tmp17 * (_tmp1 * (_tmp21 * r10 + _tmp22 * r11 - _tmp3 * r12) - _tmp10 * _tmp23)
            ),
            -_tmp18
            * _tmp3
            * (
                _tmp12 * (-_tmp1 * (-_tmp4 * r01 + _tmp6 * r00) + _tmp16 * _tmp24)
                - _tmp17 * (-_tmp1 * (-_tmp4 * r11 + _tmp6 * r10) + _tmp10 * _tmp24)
            ),
        ),
        _shape,
    )
    return psi, jac_rotation, jac_body, jac_translation, jac_direction
