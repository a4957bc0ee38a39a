"""Pose conventions: rotations, translations and the symmetries that normalise a solution.

Pose of frame i (docs/CONVENTIONS.md): ``X_cam = R_z(theta) R_y(tau) R_x(delta) X_curve + t`` with
t = (tx, ty, 0) (A at z = 0).  ``poses`` arrays are (N, 5): delta, tau, theta, tx, ty (radians,
input units).  Shapes are (4,): c, alpha, beta, phi (input units, radians).
"""

from __future__ import annotations

import numpy as np

from curverecon.generated import measurement_model
from curverecon.model.observations import wrap_angle, wrap_line_angle


def sin_tau_magnitude(c: float, cp: np.ndarray) -> np.ndarray:
    """|sin(tau)| = sqrt(1 - (c'/c)^2), clipped to 0 where c' >= c (noise)."""
    ratio = np.clip(np.asarray(cp, float) / c, 0.0, 1.0)
    return np.sqrt(1.0 - ratio**2)


def normalise(shape: np.ndarray, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Map a solution to alpha, beta in [0, pi/2], phi in [0, pi], tau in (-pi/2, pi/2].

    Symmetries (docs/CONVENTIONS.md), none of which changes any prediction:
    alpha -> alpha + pi and beta -> beta + pi (a tangent is a line);
    tau -> pi - tau with theta -> theta - pi, delta -> delta + pi
    (R_z(theta + pi) R_y(tau + pi) = R_z(theta) R_y(-tau) R_x(pi));
    alpha -> -alpha with phi -> phi + pi, delta -> delta + pi; beta -> -beta with phi -> phi + pi;
    the mirror z -> -z: (phi, delta, tau) -> (-phi, -delta, -tau).
    """
    c, alpha, beta, phi = (float(v) for v in shape)
    poses = np.array(poses, dtype=float, copy=True)
    delta, tau, theta = poses[:, 0], poses[:, 1], poses[:, 2]
    tau[:] = wrap_angle(tau)
    flip = np.abs(tau) > np.pi / 2
    tau[flip] = wrap_angle(np.pi - tau[flip])
    theta[flip] -= np.pi
    delta[flip] += np.pi
    alpha = float(wrap_line_angle(alpha))
    if alpha < 0:
        alpha, phi = -alpha, phi + np.pi
        delta += np.pi
    beta = float(wrap_line_angle(beta))
    if beta < 0:
        beta, phi = -beta, phi + np.pi
    phi = float(wrap_angle(phi))
    if phi < 0:
        phi = -phi
        delta *= -1.0
        tau *= -1.0
    delta[:] = wrap_angle(delta)
    theta[:] = wrap_angle(theta)
    return np.array([abs(c), alpha, beta, phi]), poses


def rotations(poses: np.ndarray) -> np.ndarray:
    """(N, 3, 3) curve-to-camera rotations R_z(theta) R_y(tau) R_x(delta)."""
    poses = np.asarray(poses, float)
    return np.asarray(measurement_model.rotation_matrix(poses[:, 0], poses[:, 1], poses[:, 2]))


def translations(poses: np.ndarray) -> np.ndarray:
    """(N, 3) translations (tx, ty, 0): A at z = 0."""
    poses = np.asarray(poses, float)
    return np.column_stack([poses[:, 3], poses[:, 4], np.zeros(len(poses))])
