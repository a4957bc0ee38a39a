# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/section2_perspective.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""The minimal problems of the seed's Section 2 perspective and stereo rows with a closed form
(rotation-free motion, stereo triangulation): their linear systems as functions of the rays,
derived and checked in derivations/section2_perspective.py.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

CHART_ROTATION = ((0.36, 0.48, -0.8), (-0.8, 0.6, 0.0), (0.48, 0.64, 0.6))


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


def rotation_free_linear(
    a0x: npt.ArrayLike,
    a0y: npt.ArrayLike,
    a0z: npt.ArrayLike,
    b0x: npt.ArrayLike,
    b0y: npt.ArrayLike,
    b0z: npt.ArrayLike,
    a1x: npt.ArrayLike,
    a1y: npt.ArrayLike,
    a1z: npt.ArrayLike,
    b1x: npt.ArrayLike,
    b1y: npt.ArrayLike,
    b1z: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Rotation-free motion, two frames: M u = rhs with u = (lambda_B0, lambda_A1, lambda_B1), the
    depths of B in frame 0 and of A, B in frame 1 in units of A's depth in frame 0 (D_1 = D_0).
    Arguments: the rays (x, y, 1) of A, B in frames 0 and 1, normalised image coordinates.
    """
    a0x = np.asarray(a0x, dtype=np.float64)
    a0y = np.asarray(a0y, dtype=np.float64)
    a0z = np.asarray(a0z, dtype=np.float64)
    b0x = np.asarray(b0x, dtype=np.float64)
    b0y = np.asarray(b0y, dtype=np.float64)
    b0z = np.asarray(b0z, dtype=np.float64)
    a1x = np.asarray(a1x, dtype=np.float64)
    a1y = np.asarray(a1y, dtype=np.float64)
    a1z = np.asarray(a1z, dtype=np.float64)
    b1x = np.asarray(b1x, dtype=np.float64)
    b1y = np.asarray(b1y, dtype=np.float64)
    b1z = np.asarray(b1z, dtype=np.float64)
    _shape = np.broadcast_shapes(
        a0x.shape,
        a0y.shape,
        a0z.shape,
        b0x.shape,
        b0y.shape,
        b0z.shape,
        a1x.shape,
        a1y.shape,
        a1z.shape,
        b1x.shape,
        b1y.shape,
        b1z.shape,
    )

    # Common subexpressions (0).

    # Outputs.
    matrix = _stack(
        (
            -b0x,
            -a1x,
            b1x,
            -b0y,
            -a1y,
            b1y,
            -b0z,
            -a1z,
            b1z,
        ),
        _shape,
    ).reshape((*_shape, 3, 3))
    rhs = _stack(
        (
            -a0x,
            -a0y,
            -a0z,
        ),
        _shape,
    ).reshape((*_shape, 3, 1))
    return matrix, rhs


def stereo_linear(
    p0x: npt.ArrayLike,
    p0y: npt.ArrayLike,
    p0z: npt.ArrayLike,
    p1x: npt.ArrayLike,
    p1y: npt.ArrayLike,
    p1z: npt.ArrayLike,
    r0: npt.ArrayLike,
    r1: npt.ArrayLike,
    r2: npt.ArrayLike,
    r3: npt.ArrayLike,
    r4: npt.ArrayLike,
    r5: npt.ArrayLike,
    r6: npt.ArrayLike,
    r7: npt.ArrayLike,
    r8: npt.ArrayLike,
    t0: npt.ArrayLike,
    t1: npt.ArrayLike,
    t2: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Stereo, one point: M (lambda_0, lambda_1) = rhs (three equations, least squares), lambda_0
    the depth in camera 0, lambda_1 in camera 1 (X1 = R X0 + t, R row by row as r0..r8, t in the
    units of the result).  Arguments: the point's rays in camera 0 and camera 1 (normalised), R,
    t.
    """
    p0x = np.asarray(p0x, dtype=np.float64)
    p0y = np.asarray(p0y, dtype=np.float64)
    p0z = np.asarray(p0z, dtype=np.float64)
    p1x = np.asarray(p1x, dtype=np.float64)
    p1y = np.asarray(p1y, dtype=np.float64)
    p1z = np.asarray(p1z, dtype=np.float64)
    r0 = np.asarray(r0, dtype=np.float64)
    r1 = np.asarray(r1, dtype=np.float64)
    r2 = np.asarray(r2, dtype=np.float64)
    r3 = np.asarray(r3, dtype=np.float64)
    r4 = np.asarray(r4, dtype=np.float64)
    r5 = np.asarray(r5, dtype=np.float64)
    r6 = np.asarray(r6, dtype=np.float64)
    r7 = np.asarray(r7, dtype=np.float64)
    r8 = np.asarray(r8, dtype=np.float64)
    t0 = np.asarray(t0, dtype=np.float64)
    t1 = np.asarray(t1, dtype=np.float64)
    t2 = np.asarray(t2, dtype=np.float64)
    _shape = np.broadcast_shapes(
        p0x.shape,
        p0y.shape,
        p0z.shape,
        p1x.shape,
        p1y.shape,
        p1z.shape,
        r0.shape,
        r1.shape,
        r2.shape,
        r3.shape,
        r4.shape,
        r5.shape,
        r6.shape,
        r7.shape,
        r8.shape,
        t0.shape,
        t1.shape,
        t2.shape,
    )

    # Common subexpressions (0).

    # Outputs.
    matrix = _stack(
        (
            -p0x * r0 - p0y * r1 - p0z * r2,
            p1x,
            -p0x * r3 - p0y * r4 - p0z * r5,
            p1y,
            -p0x * r6 - p0y * r7 - p0z * r8,
            p1z,
        ),
        _shape,
    ).reshape((*_shape, 3, 2))
    rhs = _stack(
        (
            t0,
            t1,
            t2,
        ),
        _shape,
    ).reshape((*_shape, 3, 1))
    return matrix, rhs
