"""Every frame's pose by Gauss-Newton with the shape held fixed: a numba loop over frames.

The kernel behind ``refine.ml.optimise_poses`` (its docstring states the iteration: a frame keeps
a step only if it lowers that frame's chi2; a rejected step is halved up to ``halvings`` times;
a frame none of whose trials lowered its chi2 stops).  Per frame it calls the generated scalar
measurement model (``generated/measurement_kernel.py``), forms the 5 x 5 Gauss-Newton block
and solves it by Cholesky: no (N, 6, 5) temporaries, no NumPy call per step.  The kernel
releases the interpreter lock (``nogil``), so ``refine.ml`` runs chunks of frames on a thread
pool, one thread per core; each frame's arithmetic is its own, so the result does not depend on
the threads.  (Not ``numba.prange``: numba's default threading layer aborts when two threads
enter it at once, and its threads do not survive a fork.)

Conventions: poses (delta, tau, theta, tx, ty), radians and input units; residuals are
standardised, ``(predicted - measured) * w8`` with the angle residuals wrapped to
(-pi/2, pi/2] (a tangent is a line) before the weighting.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from curverecon import jit_cache
from curverecon.generated import measurement_kernel
from curverecon.generated.measurement_kernel import (
    predict_frame,
    predict_frame_with_pose_jacobian,
)

_JIT = {"cache": True, "nogil": True, "fastmath": False}

RIDGE_RELATIVE = 1e-9
"""Each diagonal entry of a frame's block is raised by this fraction of itself (as the NumPy
iteration did: it keeps a block whose pose is weakly determined solvable)."""

RIDGE_TRACE = 1e-13
"""... and by this fraction of the block's trace (``ml._batched_inverse``'s tiny ridge)."""


@numba.njit(**_JIT)
def _wrap_line(x: float) -> float:
    """An angle of a line (period pi) wrapped to (-pi/2, pi/2] (``wrap_line_angle``)."""
    y = (x + 0.5 * math.pi) % math.pi - 0.5 * math.pi
    if y <= -0.5 * math.pi:
        y += math.pi
    return y


@numba.njit(**_JIT)
def _residual(g, p, meas, w8, pred, r) -> float:
    """Standardised residuals ``r`` (6,) of one frame at shape g, pose p; returns chi2."""
    predict_frame(g[0], g[1], g[2], g[3], p[0], p[1], p[2], p[3], p[4], pred)
    f = 0.0
    for k in range(6):
        d = pred[k] - meas[k]
        if k >= 4:
            d = _wrap_line(d)
        r[k] = d * w8[k]
        f += r[k] * r[k]
    return f


@numba.njit(**_JIT)
def _gauss_newton_step(g, p, r, w8, pred, jac, v, step) -> bool:
    """The Gauss-Newton step ``step`` (5,) of one frame's pose (residuals ``r`` at ``p``);
    False where the block is not positive definite (the frame stops)."""
    predict_frame_with_pose_jacobian(
        g[0], g[1], g[2], g[3], p[0], p[1], p[2], p[3], p[4], pred, jac
    )
    for k in range(6):
        for j in range(5):
            jac[k, j] *= w8[k]
    trace = 0.0
    for i in range(5):
        e = 0.0
        for k in range(6):
            e += jac[k, i] * r[k]
        step[i] = -e
        for j in range(i + 1):
            s = 0.0
            for k in range(6):
                s += jac[k, i] * jac[k, j]
            v[i, j] = s
        v[i, i] += RIDGE_RELATIVE * v[i, i]
        trace += v[i, i]
    ridge = RIDGE_TRACE * max(trace, 1e-300)
    # Cholesky v = L L^T in the lower triangle, then two triangular solves
    for i in range(5):
        v[i, i] += ridge
    for j in range(5):
        d = v[j, j]
        for k in range(j):
            d -= v[j, k] * v[j, k]
        if not d > 0.0:
            return False
        d = math.sqrt(d)
        v[j, j] = d
        for i in range(j + 1, 5):
            s = v[i, j]
            for k in range(j):
                s -= v[i, k] * v[j, k]
            v[i, j] = s / d
    for i in range(5):
        s = step[i]
        for k in range(i):
            s -= v[i, k] * step[k]
        step[i] = s / v[i, i]
    for i in range(4, -1, -1):
        s = step[i]
        for k in range(i + 1, 5):
            s -= v[k, i] * step[k]
        step[i] = s / v[i, i]
    for i in range(5):
        if not math.isfinite(step[i]):
            return False
    return True


@numba.njit(**_JIT)
def optimise_frames(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    halvings: int,
    p_out: np.ndarray,
    r_out: np.ndarray,
) -> None:
    """Gauss-Newton on every frame's pose, shape fixed, in place.

    Args:
        g: (1, 4) one shape for all frames, or (N, 4) one per frame.
        p: (N, 5) start poses; meas: (N, 6) measurements.
        w8: (1, 6) or (N, 6) weights (1 / sigma) of (ax, ay, bx, by, psi_a, psi_b).
        n_iter: iterations at most; halvings: halvings of a rejected step before the frame
            stops.
        p_out: (N, 5) the poses; r_out: (N, 6) their standardised residuals (written).
    """
    n = p.shape[0]
    g_step = 1 if g.shape[0] > 1 else 0  # one shape (weights) for all frames, or one per frame
    w_step = 1 if w8.shape[0] > 1 else 0
    for i in range(n):
        gi = g[i * g_step]
        wi = w8[i * w_step]
        pred = np.empty(6)
        jac = np.empty((6, 5))
        v = np.empty((5, 5))
        step = np.empty(5)
        pose = p[i].copy()
        pt = np.empty(5)
        r = np.empty(6)
        rt = np.empty(6)
        f = _residual(gi, pose, meas[i], wi, pred, r)
        for _ in range(n_iter):
            if not _gauss_newton_step(gi, pose, r, wi, pred, jac, v, step):
                break
            taken = False
            for h in range(halvings + 1):
                for j in range(5):
                    pt[j] = pose[j] + step[j]
                ft = _residual(gi, pt, meas[i], wi, pred, rt)
                if ft < f:
                    taken = True
                    break
                if h < halvings:
                    for j in range(5):
                        step[j] *= 0.5
            if not taken:
                break
            f = ft
            pose[:] = pt
            r[:] = rt
        p_out[i] = pose
        r_out[i] = r


# numba caches these on this file's source alone; the measurement model they call is generated
# elsewhere (curverecon.jit_cache)
jit_cache.drop_stale(
    (_wrap_line, _residual, _gauss_newton_step, optimise_frames), (measurement_kernel,)
)
