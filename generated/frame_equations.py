# -------------------------------------------------------------------------------------------------
# Generated, do not edit / do not modify: change derivations/ and run `make derive`.
#
# Derivation: derivations/section3.py
# Template:   derivations/codegen/templates/module.py.jinja
# SymPy:      1.14.0
# -------------------------------------------------------------------------------------------------
"""Per-frame equations of section 3 of the paper (aux terms, (10), (11), (12), the pose from the
shape, the predicted d', e'), derived and checked in derivations/section3.py.
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


def aux_terms(
    c: npt.ArrayLike,
    tan_alpha: npt.ArrayLike,
    tan_beta: npt.ArrayLike,
    cp: npt.ArrayLike,
    dp: npt.ArrayLike,
    ep: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Auxiliary frame terms of section 3: p1 = d' c tan(alpha) sin(tau), q1 = c' c tan(alpha), p2
    = e' c tan(beta) sin(tau), q2 = c' c tan(beta). Conventions (docs/CONVENTIONS.md): paper's
    frame (A' at the origin, B' on +x), R = R_y(tau) R_x(delta), d' = -c' u_y/u_x, e' = c'
    u_y/u_x, sin_tau signed (B_z = -c sin(tau)). Lengths in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_alpha = np.asarray(tan_alpha, dtype=np.float64)
    tan_beta = np.asarray(tan_beta, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    dp = np.asarray(dp, dtype=np.float64)
    ep = np.asarray(ep, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape, tan_alpha.shape, tan_beta.shape, cp.shape, dp.shape, ep.shape, sin_tau.shape
    )

    # Common subexpressions (2).
    _tmp0 = c * sin_tau
    _tmp1 = c * cp

    # Outputs.
    p1 = _full(_tmp0 * dp * tan_alpha, _shape)
    q1 = _full(_tmp1 * tan_alpha, _shape)
    p2 = _full(_tmp0 * ep * tan_beta, _shape)
    q2 = _full(_tmp1 * tan_beta, _shape)
    return p1, q1, p2, q2


def residual_10(
    c: npt.ArrayLike,
    tan_alpha: npt.ArrayLike,
    cp: npt.ArrayLike,
    dp: npt.ArrayLike,
    delta: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> np.ndarray:
    """Equation (10): q1 cos(delta) + p1 sin(delta) - d'c' (zero on true data; units length^2).
    Conventions (docs/CONVENTIONS.md): paper's frame (A' at the origin, B' on +x), R = R_y(tau)
    R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau signed (B_z = -c sin(tau)). Lengths
    in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_alpha = np.asarray(tan_alpha, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    dp = np.asarray(dp, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape, tan_alpha.shape, cp.shape, dp.shape, delta.shape, sin_tau.shape
    )

    # Common subexpressions (1).
    _tmp0 = c * tan_alpha

    # Outputs.
    residual = _full(
        _tmp0 * cp * np.cos(delta) + _tmp0 * dp * sin_tau * np.sin(delta) - cp * dp, _shape
    )
    return residual


def residual_11(
    c: npt.ArrayLike,
    tan_beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    cp: npt.ArrayLike,
    ep: npt.ArrayLike,
    delta: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> np.ndarray:
    """Equation (11): q2 cos(delta + phi) - p2 sin(delta + phi) - e'c' (zero on true data; units
    length^2). Conventions (docs/CONVENTIONS.md): paper's frame (A' at the origin, B' on +x), R
    = R_y(tau) R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau signed (B_z = -c
    sin(tau)). Lengths in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_beta = np.asarray(tan_beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    ep = np.asarray(ep, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape, tan_beta.shape, phi.shape, cp.shape, ep.shape, delta.shape, sin_tau.shape
    )

    # Common subexpressions (1).
    _tmp0 = delta + phi

    # Outputs.
    residual = _full(
        c * cp * tan_beta * np.cos(_tmp0) - c * ep * sin_tau * tan_beta * np.sin(_tmp0) - cp * ep,
        _shape,
    )
    return residual


def residual_12(
    c: npt.ArrayLike,
    tan_alpha: npt.ArrayLike,
    tan_beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    cp: npt.ArrayLike,
    dp: npt.ArrayLike,
    ep: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> np.ndarray:
    """Equation (12), branch-free and dimensionless: (cos(phi + omega1 + omega2) - u1 u2)^2 - (1 -
    u1^2)(1 - u2^2) with u1 = d'c'/sqrt(p1^2 + q1^2), u2 = e'c'/sqrt(p2^2 + q2^2), omega_k =
    atan2(p_k, q_k); zero on true data for every branch of arccos and both signs of sin(tau).
    Conventions (docs/CONVENTIONS.md): paper's frame (A' at the origin, B' on +x), R = R_y(tau)
    R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau signed (B_z = -c sin(tau)). Lengths
    in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_alpha = np.asarray(tan_alpha, dtype=np.float64)
    tan_beta = np.asarray(tan_beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    dp = np.asarray(dp, dtype=np.float64)
    ep = np.asarray(ep, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape,
        tan_alpha.shape,
        tan_beta.shape,
        phi.shape,
        cp.shape,
        dp.shape,
        ep.shape,
        sin_tau.shape,
    )

    # Common subexpressions (12).
    _tmp0 = tan_alpha * tan_alpha
    _tmp1 = tan_beta * tan_beta
    _tmp2 = cp * cp
    _tmp3 = dp * dp
    _tmp4 = sin_tau * sin_tau
    _tmp5 = _tmp3 * _tmp4
    _tmp6 = ep * ep
    _tmp7 = _tmp4 * _tmp6
    _tmp8 = dp * ep
    _tmp9 = c * c
    _tmp10 = _tmp9 * tan_alpha * tan_beta
    _tmp11 = _tmp2 * _tmp9

    # Outputs.
    residual = _full(
        -(
            (_tmp0 * _tmp11 + _tmp0 * _tmp5 * _tmp9 - _tmp2 * _tmp3)
            * (_tmp1 * _tmp11 + _tmp1 * _tmp7 * _tmp9 - _tmp2 * _tmp6)
            - (
                (
                    _tmp10 * cp * sin_tau * (dp + ep) * np.sin(phi)
                    - _tmp10 * (_tmp2 - _tmp4 * _tmp8) * np.cos(phi)
                    + _tmp2 * _tmp8
                )
                * (
                    _tmp10 * cp * sin_tau * (dp + ep) * np.sin(phi)
                    - _tmp10 * (_tmp2 - _tmp4 * _tmp8) * np.cos(phi)
                    + _tmp2 * _tmp8
                )
            )
        )
        / (_tmp0 * _tmp1 * (c * c * c * c) * (_tmp2 + _tmp5) * (_tmp2 + _tmp7)),
        _shape,
    )
    return residual


def pose_from_shape(
    c: npt.ArrayLike,
    tan_alpha: npt.ArrayLike,
    tan_beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    cp: npt.ArrayLike,
    dp: npt.ArrayLike,
    ep: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """(10) and (11) solved as a linear system in cos(delta), sin(delta) (Cramer's rule); cos^2 +
    sin^2 = 1 exactly on true data. Conventions (docs/CONVENTIONS.md): paper's frame (A' at the
    origin, B' on +x), R = R_y(tau) R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau
    signed (B_z = -c sin(tau)). Lengths in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_alpha = np.asarray(tan_alpha, dtype=np.float64)
    tan_beta = np.asarray(tan_beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    dp = np.asarray(dp, dtype=np.float64)
    ep = np.asarray(ep, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape,
        tan_alpha.shape,
        tan_beta.shape,
        phi.shape,
        cp.shape,
        dp.shape,
        ep.shape,
        sin_tau.shape,
    )

    # Common subexpressions (6).
    _tmp0 = ep * sin_tau
    _tmp1 = np.sin(phi)
    _tmp2 = np.cos(phi)
    _tmp3 = _tmp0 * _tmp2 + _tmp1 * cp
    _tmp4 = dp * (-_tmp0 * _tmp1 + _tmp2 * cp)
    _tmp5 = cp / (c * tan_alpha * tan_beta * (_tmp3 * cp + _tmp4 * sin_tau))

    # Outputs.
    cos_delta = _full(_tmp5 * dp * (_tmp0 * tan_alpha + _tmp3 * tan_beta), _shape)
    sin_delta = _full(-_tmp5 * (-_tmp4 * tan_beta + cp * ep * tan_alpha), _shape)
    return cos_delta, sin_delta


def predicted_d_e(
    c: npt.ArrayLike,
    tan_alpha: npt.ArrayLike,
    tan_beta: npt.ArrayLike,
    phi: npt.ArrayLike,
    cp: npt.ArrayLike,
    delta: npt.ArrayLike,
    sin_tau: npt.ArrayLike,
) -> tuple[np.ndarray, np.ndarray]:
    """Predicted d', e' (signed, input units) from shape and pose: the 3-D construction's D' on l1
    and E' on l2. Conventions (docs/CONVENTIONS.md): paper's frame (A' at the origin, B' on +x),
    R = R_y(tau) R_x(delta), d' = -c' u_y/u_x, e' = c' u_y/u_x, sin_tau signed (B_z = -c
    sin(tau)). Lengths in input units, angles in radians.
    """
    c = np.asarray(c, dtype=np.float64)
    tan_alpha = np.asarray(tan_alpha, dtype=np.float64)
    tan_beta = np.asarray(tan_beta, dtype=np.float64)
    phi = np.asarray(phi, dtype=np.float64)
    cp = np.asarray(cp, dtype=np.float64)
    delta = np.asarray(delta, dtype=np.float64)
    sin_tau = np.asarray(sin_tau, dtype=np.float64)
    _shape = np.broadcast_shapes(
        c.shape, tan_alpha.shape, tan_beta.shape, phi.shape, cp.shape, delta.shape, sin_tau.shape
    )

    # Common subexpressions (3).
    _tmp0 = c * sin_tau
    _tmp1 = c * cp
    _tmp2 = delta + phi

    # Outputs.
    d = _full(-_tmp1 * tan_alpha * np.cos(delta) / (_tmp0 * tan_alpha * np.sin(delta) - cp), _shape)
    e = _full(_tmp1 * tan_beta * np.cos(_tmp2) / (_tmp0 * tan_beta * np.sin(_tmp2) + cp), _shape)
    return d, e
