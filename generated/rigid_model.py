# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/rigid_model.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""The orthographic rigid-body measurement model of the Section 2 rows (generated).

A body point with body vector q (relative to the reference point, frame 0's camera coordinates)
is seen in a frame with rotation R (relative to frame 0) and reference image s at
x = s + [R q]_xy; a body direction u(polar, azimuth) at the image angle psi = atan2 of [R u]_xy.
Rotation Jacobians are with respect to the left increment w of R = exp([w]_x) Rbar at w = 0;
``axis_rotation`` gives Rot(n(kappa, lam), angle) with the increments w_p of its parameters
(dR/dp = [w_p]_x R).  Rotation arguments r00 .. r22 are the entries of Rbar, row-major; every
argument is a 1-D array of length N or a scalar, everything broadcasts.  Lengths in input
units, angles in radians.  See derivations/rigid_model.py.
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


def point_prediction(
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
    sx: npt.ArrayLike,
    sy: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Image of a body point, x = s + [R q]_xy, and its Jacobians.

    Returns (prediction (N, 2), jac_rotation (N, 2, 3) with respect to the left
    increment w of R, jac_body (N, 2, 3) with respect to q); d x / d s is the
    identity.  Input units.
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
    sx = np.asarray(sx, dtype=np.float64)
    sy = np.asarray(sy, dtype=np.float64)
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
        sx.shape,
        sy.shape,
    )

    # Common subexpressions (3).
    _tmp0 = qx * r00 + qy * r01 + qz * r02
    _tmp1 = qx * r10 + qy * r11 + qz * r12
    _tmp2 = qx * r20 + qy * r21 + qz * r22

    # Outputs.
    prediction = _stack(
        (
            _tmp0 + sx,
            _tmp1 + sy,
        ),
        _shape,
    )
    jac_rotation = _scatter(
        (
            (1, _tmp2),
            (2, -_tmp1),
            (3, -_tmp2),
            (5, _tmp0),
        ),
        6,
        _shape,
    ).reshape((*_shape, 2, 3))
    jac_body = _stack(
        (
            r00,
            r01,
            r02,
            r10,
            r11,
            r12,
        ),
        _shape,
    ).reshape((*_shape, 2, 3))
    return prediction, jac_rotation, jac_body


def tangent_prediction(
    r00: npt.ArrayLike,
    r01: npt.ArrayLike,
    r02: npt.ArrayLike,
    r10: npt.ArrayLike,
    r11: npt.ArrayLike,
    r12: npt.ArrayLike,
    r20: npt.ArrayLike,
    r21: npt.ArrayLike,
    r22: npt.ArrayLike,
    polar: npt.ArrayLike,
    azimuth: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Image angle of a body direction u(polar, azimuth) and its Jacobians.

    Returns (psi (N,) radians, jac_rotation (N, 3) with respect to the left
    increment of R, jac_direction (N, 2) with respect to (polar, azimuth),
    direction (N, 3) = R u in the frame's camera coordinates).
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
        polar.shape,
        azimuth.shape,
    )

    # Common subexpressions (13).
    _tmp0 = np.cos(polar)
    _tmp1 = np.sin(polar)
    _tmp2 = np.cos(azimuth)
    _tmp3 = _tmp1 * _tmp2
    _tmp4 = np.sin(azimuth)
    _tmp5 = _tmp1 * _tmp4
    _tmp6 = _tmp0 * r12 + _tmp3 * r10 + _tmp5 * r11
    _tmp7 = _tmp0 * r02 + _tmp3 * r00 + _tmp5 * r01
    _tmp8 = 1 / (_tmp6 * _tmp6 + _tmp7 * _tmp7)
    _tmp9 = _tmp0 * r22 + _tmp3 * r20 + _tmp5 * r21
    _tmp10 = _tmp8 * _tmp9
    _tmp11 = _tmp0 * _tmp2
    _tmp12 = _tmp0 * _tmp4

    # Outputs.
    psi = _full(np.arctan2(_tmp6, _tmp7), _shape)
    jac_rotation = _stack(
        (
            -_tmp10 * _tmp7,
            -_tmp10 * _tmp6,
            1,
        ),
        _shape,
    )
    jac_direction = _stack(
        (
            _tmp8
            * (
                -_tmp6 * (-_tmp1 * r02 + _tmp11 * r00 + _tmp12 * r01)
                + _tmp7 * (-_tmp1 * r12 + _tmp11 * r10 + _tmp12 * r11)
            ),
            -_tmp1
            * _tmp8
            * (-_tmp6 * (-_tmp2 * r01 + _tmp4 * r00) + _tmp7 * (-_tmp2 * r11 + _tmp4 * r10)),
        ),
        _shape,
    )
    direction = _stack(
        (
            _tmp7,
            _tmp6,
            _tmp9,
        ),
        _shape,
    )
    return psi, jac_rotation, jac_direction, direction


def axis_rotation(
    kappa: npt.ArrayLike, lam: npt.ArrayLike, angle: npt.ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Rot(n, angle), n = (sin kappa cos lam, sin kappa sin lam, cos kappa), and the
    left increments of its parameters.

    Returns (rotation (N, 3, 3), increments (N, 3, 3)): row p of the increments is
    w_p with dR/dp = [w_p]_x R for p = kappa, lam, angle.  Radians.
    """
    kappa = np.asarray(kappa, dtype=np.float64)
    lam = np.asarray(lam, dtype=np.float64)
    angle = np.asarray(angle, dtype=np.float64)
    _shape = np.broadcast_shapes(kappa.shape, lam.shape, angle.shape)

    # Common subexpressions (19).
    _tmp0 = np.cos(angle)
    _tmp1 = -_tmp0
    _tmp2 = np.cos(lam)
    _tmp3 = _tmp0 - 1
    _tmp4 = np.sin(kappa)
    _tmp5 = _tmp3 * (_tmp4 * _tmp4)
    _tmp6 = np.sin(angle)
    _tmp7 = np.cos(kappa)
    _tmp8 = _tmp6 * _tmp7
    _tmp9 = np.sin(lam)
    _tmp10 = _tmp2 * _tmp5 * _tmp9
    _tmp11 = _tmp2 * _tmp7
    _tmp12 = _tmp11 * _tmp3
    _tmp13 = _tmp2 * _tmp6
    _tmp14 = _tmp7 * _tmp9
    _tmp15 = _tmp14 * _tmp3
    _tmp16 = _tmp6 * _tmp9
    _tmp17 = _tmp0 * _tmp9
    _tmp18 = _tmp0 * _tmp2

    # Outputs.
    rotation = _stack(
        (
            -_tmp1 - (_tmp2 * _tmp2) * _tmp5,
            -_tmp10 - _tmp8,
            _tmp4 * (-_tmp12 + _tmp6 * _tmp9),
            -_tmp10 + _tmp6 * _tmp7,
            -_tmp1 - _tmp5 * (_tmp9 * _tmp9),
            -_tmp4 * (_tmp13 + _tmp15),
            -_tmp4 * (_tmp12 + _tmp16),
            _tmp4 * (-_tmp15 + _tmp2 * _tmp6),
            -_tmp1 - _tmp3 * (_tmp7 * _tmp7),
        ),
        _shape,
    ).reshape((*_shape, 3, 3))
    increments = _stack(
        (
            _tmp17 + _tmp2 * _tmp8 - _tmp9,
            -_tmp18 + _tmp2 + _tmp8 * _tmp9,
            -_tmp4 * _tmp6,
            -_tmp4 * (_tmp11 + _tmp16 - _tmp18 * _tmp7),
            _tmp4 * (_tmp13 - _tmp14 + _tmp17 * _tmp7),
            -_tmp5,
            _tmp2 * _tmp4,
            _tmp4 * _tmp9,
            _tmp7,
        ),
        _shape,
    ).reshape((*_shape, 3, 3))
    return rotation, increments


def unit_direction(polar: npt.ArrayLike, azimuth: npt.ArrayLike) -> np.ndarray:
    """(sin polar cos azimuth, sin polar sin azimuth, cos polar), shape (N, 3): a body
    direction or a rotation axis from its polar angles (radians).
    """
    polar = np.asarray(polar, dtype=np.float64)
    azimuth = np.asarray(azimuth, dtype=np.float64)
    _shape = np.broadcast_shapes(polar.shape, azimuth.shape)

    # Common subexpressions (1).
    _tmp0 = np.sin(polar)

    # Outputs.
    direction = _stack(
        (
            _tmp0 * np.cos(azimuth),
            _tmp0 * np.sin(azimuth),
            np.cos(polar),
        ),
        _shape,
    )
    return direction
