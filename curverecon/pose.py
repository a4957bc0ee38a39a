"""Per-frame pose from a shape, and the symmetries that normalise a solution.

Pose of frame i (docs/CONVENTIONS.md): ``X_cam = R_z(theta) R_y(tau) R_x(delta) X_curve + t`` with
t = (tx, ty, 0) (A at z = 0).  ``poses`` arrays are (N, 5): delta, tau, theta, tx, ty (radians,
input units).  Shapes are (4,): c, alpha, beta, phi (input units, radians).
"""

from __future__ import annotations

import numpy as np

from curverecon.generated import frame_equations, measurement_model
from curverecon.observations import Observations, wrap_angle, wrap_line_angle


def sin_tau_magnitude(c: float, cp: np.ndarray) -> np.ndarray:
    """|sin(tau)| = sqrt(1 - (c'/c)^2), clipped to 0 where c' >= c (noise)."""
    ratio = np.clip(np.asarray(cp, float) / c, 0.0, 1.0)
    return np.sqrt(1.0 - ratio**2)


def poses_from_shape(obs: Observations, shape: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-frame poses (N, 5) for a given shape, and each frame's tangent-angle misfit (N,).

    delta, tau from (10) and (11) (``frame_equations.pose_from_shape``) for both signs of
    sin(tau) -- B may be nearer or farther than A, and that differs between frames -- keeping per
    frame the sign whose predicted tangent angles fit the observed ones better; |tau| from
    c' = c cos(tau); theta from the image chord; tx, ty = A'.  The misfit is the root sum of
    squares of the two wrapped tangent-angle residuals (radians).
    """
    c, alpha, beta, phi = (float(v) for v in shape)
    cp, dp, ep = obs.cp, obs.dp, obs.ep
    s_abs = sin_tau_magnitude(c, cp)
    tau_abs = np.arccos(np.clip(cp / c, 0.0, 1.0))
    theta = obs.theta
    meas = obs.measurements()
    best_poses = None
    best_err = None
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for sign in (1.0, -1.0):
            cos_d, sin_d = frame_equations.pose_from_shape(
                c, np.tan(alpha), np.tan(beta), phi, cp, dp, ep, sign * s_abs
            )
            cos_d = np.broadcast_to(np.asarray(cos_d, float), cp.shape)
            sin_d = np.broadcast_to(np.asarray(sin_d, float), cp.shape)
            bad = ~(np.isfinite(cos_d) & np.isfinite(sin_d)) | (np.hypot(cos_d, sin_d) == 0)
            delta = np.where(bad, 0.0, np.arctan2(sin_d, cos_d))
            poses = np.column_stack([delta, sign * tau_abs, theta, obs.a[:, 0], obs.a[:, 1]])
            pred = measurement_model.predict(c, alpha, beta, phi, *poses.T)
            err = np.hypot(*wrap_line_angle(pred[:, 4:6] - meas[:, 4:6]).T)
            err = np.where(bad, np.inf, err)
            if best_poses is None:
                best_poses, best_err = poses, err
            else:
                take = err < best_err
                best_poses = np.where(take[:, None], poses, best_poses)
                best_err = np.where(take, err, best_err)
    return best_poses, best_err


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
