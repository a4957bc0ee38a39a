"""Shape refinement by the marginal likelihood: every frame's pose integrated out (Laplace).

Why.  Each frame carries six measurements (A', B', two tangent angles) and five pose parameters
of its own (delta, tau, theta, tx, ty), so it tells the shape one number.  Maximising the
likelihood over the poses as well ("profile likelihood", ``refine.refine``) is then biased at
realistic noise, the Neyman-Scott effect of incidental parameters (the bias does not shrink as
frames are added, the bound does).  Measured on the benchmark's 1 px / 1 deg, 20-frame scenes
refined from the truth: the maximum-likelihood c comes out long (mean error +0.7 of its
Cramer-Rao bound) and its RMSE is 3.5 times the bound.

What.  Integrate each frame's pose out instead, over the invariant (Haar) measure of rotations
and a flat measure of the image translation, and maximise what is left over the shape alone.
Laplace's method around each frame's best pose p_i gives, up to a constant,

    F(g) = sum_i [ chi2_i(g, p_i) / kappa + log det H_i - 2 log |cos tau_i| ]

- ``chi2_i``: the frame's squared standardised residuals at its best pose for shape g;
- ``H_i``: the Hessian of chi2_i / 2 over the pose (``volume_terms``; 1/kappa scales it by a
  constant that drops out);
- ``|cos tau|``: the Haar density of R_z(theta) R_y(tau) R_x(delta) (tau is the middle angle);
- ``kappa = chi2_ML / (N - 4)``: the noise scale measured from the maximum-likelihood fit, so
  the estimate does not depend on the stated sigmas (only on their ratio), and noise-free data
  (kappa -> 0) keep the exact answer.

How.  Quasi-Newton (BFGS) on the four shape parameters, in coordinates whitened by the chi2
part's Gauss-Newton Hessian (2 S / kappa, S the Schur-reduced information as in ``refine``), so
one unit is one standard deviation and the start has the right curvature.  Every evaluation of
F re-solves each frame's pose (``solve_poses``, warm-started); the gradient is by forward
differences of F, its points in one batch.  Tried and dropped: analytic gradients (they need
dp/dg, and its Gauss-Newton form -V^-1 W^T is off by tens of percent on frames seen near
broadside), a joint Levenberg-Marquardt over shape and poses (it crept without the volume
terms' Hessian), and summing each frame's two pose branches (no better, twice the cost).

What it does not do: the estimate is not unbiased either (c comes out slightly short, mean
-0.3 of its bound on the same scenes); the bench reports it next to maximum likelihood.

Units: shapes (c, alpha, beta, phi) and poses (N, 5) as in ``refine``; radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.generated import measurement_model
from curverecon.observations import wrap_line_angle
from curverecon.refine import _curvature, _split, schur_information

FD_STEP = 1e-4
"""Forward-difference step of F's gradient, in standard deviations of the shape."""

GTOL = 1e-2
"""BFGS stops when F's gradient (per standard deviation) is below this."""

MAX_ITER = 40
"""BFGS iterations at most."""

POSE_ITERATIONS = 4
"""Gauss-Newton iterations at most of each pose solve (warm-started, it stops earlier)."""

HALVINGS = 8
"""Step halvings of a frame's pose update before that frame gives up for this iteration."""

KAPPA_MIN = 1e-12
"""Below this noise scale (chi2 per degree of freedom) the correction, proportional to kappa,
is beneath double precision of the shape: noise-free data keep the maximum-likelihood answer."""


@dataclass
class MarginalResult:
    """Outcome of :func:`refine_marginal`.

    Attributes:
        shape: (4,) c, alpha, beta, phi.
        poses: (N, 5) each frame's best pose for that shape.
        value: F at the answer (see the module docstring).
        kappa: the noise scale used (chi2 / (N - 4) of the start).
        iterations: BFGS iterations; converged: whether BFGS met its gradient test.
    """

    shape: np.ndarray
    poses: np.ndarray
    value: float
    kappa: float
    iterations: int
    converged: bool


def _residuals(g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """(K, N, 6) standardised residuals for shapes (K, 4) and poses (K, N, 5)."""
    r = measurement_model.predict(*_split(g, p)) - meas
    r[..., 4:6] = wrap_line_angle(r[..., 4:6])
    return r * w8


def solve_poses(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    tol: float = 1e-12,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every frame's best pose for each of K shapes (K, 4), from poses (K, N, 5).

    Newton (Gauss-Newton where the Hessian is not positive definite) with per-frame step
    halving: a plain step can overshoot on a frame seen near broadside (B' = c cos tau is flat
    in tau), and such a frame would then never move.  A frame
    stops when its step lowers its chi2 by less than ``tol / N``.  Vectorised over shapes and
    frames.  Returns poses (K, N, 5), standardised residuals (K, N, 6) and pose Jacobians
    (K, N, 6, 5).
    """
    r = _residuals(g, p, meas, w8)
    f = np.sum(r * r, axis=-1)
    eye5 = np.eye(5)
    active = np.ones(f.shape, dtype=bool)  # frames still improving
    per_frame_tol = tol / p.shape[1]
    for _ in range(n_iter):
        _, _, jl = measurement_model.predict_with_jacobians(*_split(g, p))
        jl = jl * w8[:, None]
        v = np.einsum("...ki,...kj->...ij", jl, jl)
        v = v + 1e-12 * np.trace(v, axis1=-2, axis2=-1)[..., None, None] * eye5
        # Newton where the full Hessian (with the residuals' second derivatives, refine's
        # analytic ``_curvature``) is positive definite, Gauss-Newton elsewhere: near the fold
        # tau = 0 Gauss-Newton alone converges slowly, and F's volume term is sensitive there
        hess = v + _curvature(g, p, r, w8)[..., 4:, 4:]
        newton = np.linalg.eigvalsh(hess)[..., 0] > 1e-9 * np.trace(v, axis1=-2, axis2=-1)
        hess = np.where(newton[..., None, None], hess, v)
        step = -np.linalg.solve(hess, np.einsum("...ki,...k->...i", jl, r)[..., None])[..., 0]
        todo = active.copy()
        gain = np.zeros(f.shape)
        for _ in range(HALVINGS):
            p_try = np.where(todo[..., None], p + step, p)
            r_try = _residuals(g, p_try, meas, w8)
            f_try = np.sum(r_try * r_try, axis=-1)
            take = todo & (f_try < f)
            gain = np.where(take, f - f_try, gain)
            p = np.where(take[..., None], p_try, p)
            r = np.where(take[..., None], r_try, r)
            f = np.where(take, f_try, f)
            todo &= ~take
            if not todo.any():
                break
            step = 0.5 * step
        active &= gain > per_frame_tol
        if not active.any():
            break
    _, _, jl = measurement_model.predict_with_jacobians(*_split(g, p))
    return p, r, jl * w8[:, None]


def volume_terms(
    g: np.ndarray, p: np.ndarray, r: np.ndarray, jl: np.ndarray, w8: np.ndarray
) -> np.ndarray:
    """log det H - 2 log|cos tau| of every frame, (K, N): Laplace volume and Haar prior.

    H is the Hessian of the frame's chi2 / 2 over its pose, J^T J + sum_k r_k d2 r_k (the
    second-order part from ``refine._curvature``), or J^T J alone where H is not positive
    definite.  (With J^T J alone the estimate of c over-corrects: mean error -0.7 of its bound
    against -0.3 with H, on the bench's 1 px / 1 deg, 20-frame scenes.)  Shapes (K, 4), poses
    (K, N, 5), standardised residuals (K, N, 6) and pose Jacobians (K, N, 6, 5).
    """
    v = np.einsum("...ki,...kj->...ij", jl, jl)
    sign, logdet_h = np.linalg.slogdet(v + _curvature(g, p, r, w8)[..., 4:, 4:])
    logdet = np.where(sign > 0, logdet_h, np.linalg.slogdet(v)[1])
    return logdet - 2.0 * np.log(np.maximum(np.abs(np.cos(p[..., 1])), 1e-300))


def shape_information(g: np.ndarray, p: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """(4, 4) Schur-reduced Gauss-Newton information of the shape at (g, p), standardised."""
    _, jg, jl = measurement_model.predict_with_jacobians(*g, *p.T)
    return schur_information(jg * w8[None, :, None], jl * w8[None, :, None])


def _setup(
    meas: np.ndarray, point_sigma: float, tangent_sigma: float, chi2: float
) -> tuple[float, np.ndarray] | None:
    """(kappa, weights), or None where the marginal step does not apply."""
    n = meas.shape[0]
    if n < 5 or not chi2 > 0:
        return None
    kappa = chi2 / (n - 4)
    if kappa < KAPPA_MIN:
        return None
    return kappa, np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)


def _frame_values(
    gs: np.ndarray, start: np.ndarray, meas: np.ndarray, w8: np.ndarray, kappa: float
) -> tuple[np.ndarray, np.ndarray]:
    """Per-frame terms of F (K, N) for shapes (K, 4), poses re-solved from ``start`` (K, N, 5);
    and those poses."""
    ps, rs, jls = solve_poses(gs, start, meas, w8, POSE_ITERATIONS, 1e-9 * kappa)
    return np.sum(rs * rs, axis=2) / kappa + volume_terms(gs, ps, rs, jls, w8), ps


def marginal_value(
    meas: np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    chi2: float,
) -> float | None:
    """F (module docstring) at a shape, every frame's pose re-solved from ``poses``.

    ``chi2`` sets the noise scale kappa = chi2 / (N - 4): pass the same one (the best fit's)
    to compare the basins of several fits.  None where the marginal step does not apply
    (see :func:`refine_marginal`).
    """
    setup = _setup(meas, point_sigma, tangent_sigma, chi2)
    if setup is None:
        return None
    kappa, w8 = setup
    g = np.array(shape, float)[None]
    frames, _ = _frame_values(g, np.array(poses, float)[None], meas, w8, kappa)
    value = float(np.sum(frames))
    return value if np.isfinite(value) else None


def refine_marginal(
    meas: np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    chi2: float,
) -> MarginalResult | None:
    """Maximise the marginal likelihood over the shape, from the maximum-likelihood fit.

    Args:
        meas: (N, 6) measurements (``Observations.measurements()``) of the inlier frames.
        shape, poses: the maximum-likelihood fit (``refine.refine``) on those frames.
        point_sigma (input units), tangent_sigma (radians): the stated noise; only their ratio
            matters (the scale is measured, ``kappa``).
        chi2: that fit's chi2.
    Returns:
        The result, or None where it is not defined: fewer than 5 frames (no degree of freedom
        to measure the noise scale), a noise scale below ``KAPPA_MIN`` (noise-free data), or a
        singular information matrix at the start.
    """
    setup = _setup(meas, point_sigma, tangent_sigma, chi2)
    if setup is None:
        return None
    kappa, w8 = setup
    n = meas.shape[0]
    g0 = np.array(shape, float)
    p0 = np.array(poses, float)
    best = {"x": np.zeros(4), "p": p0, "f": np.inf}

    def values(xs: np.ndarray) -> np.ndarray:
        """F at K whitened points (K, 4), poses warm-started from the best point so far."""
        gs = g0 + xs @ to_shape.T
        ok = gs[:, 0] > 0
        gs = np.where(ok[:, None], gs, g0)
        start = np.broadcast_to(best["p"], (len(xs), n, 5))
        frames, ps = _frame_values(gs, start, meas, w8, kappa)
        fs = np.sum(frames, axis=1)
        fs = np.where(ok & np.isfinite(fs), fs, np.inf)
        k = int(np.argmin(fs))
        if fs[k] < best["f"]:
            best.update(x=np.array(xs[k], float), p=ps[k], f=float(fs[k]))
        return fs

    try:
        chol = np.linalg.cholesky(2.0 * shape_information(g0, p0, w8) / kappa)
    except np.linalg.LinAlgError:
        return None
    to_shape = np.linalg.inv(chol.T)
    if not np.isfinite(values(np.zeros((1, 4)))[0]):
        return None

    def gradient(x: np.ndarray) -> tuple[np.ndarray, float]:
        """Forward-difference gradient of F at x (the four points in one batch), and F(x)."""
        fs = values(np.vstack([x, x + FD_STEP * np.eye(4)]))
        if not np.all(np.isfinite(fs)):
            return np.full(4, np.nan), float(fs[0])
        return (fs[1:] - fs[0]) / FD_STEP, float(fs[0])

    # quasi-Newton (BFGS update of the inverse Hessian, identity start: the whitened chi2
    # part) with a backtracking line search on F alone
    x = np.zeros(4)
    grad, f = gradient(x)
    h_inv = np.eye(4)
    converged = False
    iterations = 0
    for _ in range(MAX_ITER):
        if np.max(np.abs(grad)) < GTOL:
            converged = True
            break
        step = -h_inv @ grad
        slope = float(grad @ step)
        if slope >= 0:  # not a descent direction: restart from steepest descent
            h_inv = np.eye(4)
            step, slope = -grad, -float(grad @ grad)
        # backtracking; each trial point comes with its gradient points in one batch
        t = 1.0
        while t > 1e-4:
            x_new = x + t * step
            grad_new, f_try = gradient(x_new)
            if np.all(np.isfinite(grad_new)) and f_try <= f + 1e-4 * t * slope:
                break
            t *= 0.5
        else:
            converged = True  # no decrease along a descent direction: F's resolution reached
            break
        s_k, y_k = x_new - x, grad_new - grad
        sy = float(s_k @ y_k)
        if sy > 1e-12:
            rho = 1.0 / sy
            m = np.eye(4) - rho * np.outer(s_k, y_k)
            h_inv = m @ h_inv @ m.T + rho * np.outer(s_k, s_k)
        x, f, grad = x_new, f_try, grad_new
        iterations += 1
    g = g0 + to_shape @ best["x"]
    return MarginalResult(g, best["p"], best["f"], kappa, iterations, converged)
