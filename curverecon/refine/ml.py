"""Maximum-likelihood refinement over all frames (Levenberg-Marquardt with a Schur complement).

Parameters: the shape (c, alpha, beta, phi) shared by all frames and per frame the pose
(delta, tau, theta, tx, ty) (input units, radians).  Residuals per frame, in units of their
standard deviation: the image points A', B' (``(pred - obs) / point_sigma``) and the tangent
angles (``wrap(pred - obs) / tangent_sigma``, wrapped to (-pi/2, pi/2]: a tangent is a line).
Predictions and their analytic Jacobians come from ``measurement_model.predict_with_jacobians``.

The normal matrix is block-arrow shaped: a 4x4 shape block U, per-frame 5x5 pose blocks V_i and
4x5 couplings W_i.  Each step eliminates the pose blocks (batched 5x5 inverses, batched products;
no Python loop over frames) and solves the 4x4 Schur complement S = U - sum W_i V_i^-1 W_i^T.
The shape's covariance is S^-1 at the solution (undamped, Gauss-Newton); at the true parameters
it is the Cramer-Rao bound.  ``refine_batch`` runs K independent starts at once (a leading axis).

Cost.  With tens of frames every NumPy call costs more than its arithmetic, so an iteration is
organised to make few calls (see the comments at ``_lin_aug``, ``_normal_blocks``,
``_add_curvature``, ``_angle_hessian`` and in ``refine_batch``): one J^T J product per frame for
all blocks, LAPACK gufuncs called directly, the damping's scales and the whole normal system
kept while a start's point does not move (a rejected step only re-solves it with more damping),
no evaluation where no step is taken, only the non-zero entries of the second-order term.  Every
floating-point operation is the one of the plain formulation, in the same order and with the
same kernels: the results are identical to the bit (tests/test_refine_convergence.py).

Two phases per start.  Far from a minimum the model is Gauss-Newton (convex; its short steps
keep the start's basin, as plain LM always did).  Once an accepted Gauss-Newton step predicts a
decrease below ``NEWTON_SWITCH`` times chi2 the model becomes Newton's: the blocks get the
second-order term sum_k r_k d2 r_k (``curvature``, analytic: B' = A' + c cos(tau) (cos theta,
sin theta) and the two projected tangent angles).  Gauss-Newton alone crawls here: frames with
c' close to c sit at the fold tau = 0 of c cos(tau), where that term dwarfs the Gauss-Newton term
in tau, so Gauss-Newton overshoots, zig-zags and creeps along the curved valley (c against
every such tau) for 40-130 iterations; Newton converges quadratically.  In the Newton phase each
shape step is followed by ``pose_iterations`` damped Gauss-Newton steps on every frame's pose
with the shape fixed (embedded pose iterations: the poses follow the shape along the valley).
``refine_batch(..., newton_phase=False)`` stays Gauss-Newton (cheap screening of many starts).

Damping: lambda times the Gauss-Newton diagonal.  Nielsen's update (lambda times
max(1/3, 1 - (2 rho - 1)^3) after an accepted step, times 4 after a rejected one; rho = actual
over predicted decrease, the prediction -e.d + lambda d^T D d of the solved damped model), so
lambda shrinks geometrically while the model predicts well.  A Newton model that is not
positive definite (or predicts no decrease) gets lambda times 10 at once, within the iteration;
lambda restarts at 1e-3 at the switch to Newton.

Convergence: a relative step below ``xtol``, or a predicted decrease below ``ftol`` times chi2
(statistically meaningless for noisy data at the default 1e-10; for noise-free data chi2 itself
goes to zero, the test is relative, and the result is exact to rounding).  Not at an iteration
whose Newton model was indefinite (a saddle's tiny damped steps are no convergence).

A local method: from the same start, a different path can end in a different local minimum
(frames near the fold choose tau or -tau, some frames have several delta basins).
``refine(..., frame_search=True)`` looks for better pose basins frame by frame after
convergence (:func:`_frame_search`) and iterates again from them.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from curverecon.generated import measurement_model
from curverecon.model.observations import Observations, wrap_line_angle
from curverecon.refine.pose_kernel import optimise_frames


@dataclass
class RefineResult:
    """Outcome of :func:`refine`.

    Attributes:
        shape: (4,) c, alpha, beta, phi (not normalised).
        poses: (N, 5) delta, tau, theta, tx, ty.
        chi2: sum of squared standardised residuals.
        frame_chi2: (N,) per-frame sums of squared standardised residuals.
        residuals: (N, 6) standardised residuals (ax, ay, bx, by, psi_a, psi_b).
        covariance: (4, 4) covariance of the shape (from the given sigmas) or None if singular.
        iterations: LM iterations taken; converged: whether a convergence test was met.
    """

    shape: np.ndarray
    poses: np.ndarray
    chi2: float
    frame_chi2: np.ndarray
    residuals: np.ndarray
    covariance: np.ndarray | None
    iterations: int
    converged: bool

    @property
    def std(self) -> np.ndarray | None:
        """(4,) standard deviations of c, alpha, beta, phi, or None."""
        if self.covariance is None:
            return None
        return np.sqrt(np.clip(np.diag(self.covariance), 0.0, None))


def _weights(point_sigma: float, tangent_sigma: float) -> np.ndarray:
    if not (point_sigma > 0 and tangent_sigma > 0):
        raise ValueError("point_sigma and tangent_sigma must be positive")
    return np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)


def _measurements(obs: Observations | np.ndarray) -> np.ndarray:
    if isinstance(obs, Observations):
        return obs.measurements()
    meas = np.asarray(obs, dtype=float)
    if meas.ndim != 2 or meas.shape[1] != 6:
        raise ValueError("measurements must be (N, 6): ax, ay, bx, by, psi_a, psi_b")
    return meas


def standardised_residuals(
    shape: np.ndarray,
    poses: np.ndarray,
    meas: np.ndarray,
    weights: np.ndarray,
) -> np.ndarray:
    """(N, 6) residuals (prediction - observation) in units of their standard deviation."""
    pred = measurement_model.predict(*shape, *np.asarray(poses).T)
    r = pred - meas
    r[:, 4:6] = wrap_line_angle(r[:, 4:6])
    return r * weights


def _linearise(shape, poses, meas, weights):
    pred, jg, jl = measurement_model.predict_with_jacobians(*shape, *poses.T)
    r = pred - meas
    r[:, 4:6] = wrap_line_angle(r[:, 4:6])
    r *= weights
    jg = jg * weights[None, :, None]
    jl = jl * weights[None, :, None]
    return r, jg, jl


SCHUR_COND_MAX = 1e10
"""Pose normal matrices V of a worse condition number go through ``_frame_schur_qr``."""

FRAME_CHUNK = 4096
"""Frames per chunk of the per-frame computations of long sequences (each frame's own, so the
result does not depend on it): arrays of a few thousand frames stay in the processor's cache,
and the cost per frame stays that of a short sequence (measured per frame: the curvature
0.47 us at 2,000 frames, 2.8 us at 100,000 in one piece)."""


T = TypeVar("T")


def _rows(w8: np.ndarray, c: slice) -> np.ndarray:
    """The weights of a chunk of frames: ``w8`` (6,) for all, or its rows (N, 6) per frame."""
    return w8[c] if np.ndim(w8) == 2 else w8


def frame_chunks(n: int, chunk: int | None = None) -> list[slice]:
    """Slices of ``chunk`` (default ``FRAME_CHUNK``) consecutive frames covering ``n`` frames."""
    chunk = chunk or FRAME_CHUNK
    return [slice(i, min(i + chunk, n)) for i in range(0, n, chunk)] or [slice(0, 0)]


_POOL: ThreadPoolExecutor | None = None
_POOL_PREFIX = "curverecon-frames"


def _forget_pool() -> None:
    """In a forked child the parent's worker threads do not exist: start a pool of its own."""
    global _POOL
    _POOL = None


os.register_at_fork(after_in_child=_forget_pool)


def map_chunks(function: Callable[[slice], T], n: int) -> list[T]:
    """``function`` on every chunk of ``n`` frames (``frame_chunks``), in order, on a pool of
    threads (one per core): the chunks are independent and NumPy releases the interpreter lock
    in its loops, so long sequences use every core; the result does not depend on the threads
    (each chunk's arithmetic is its own)."""
    global _POOL
    chunks = frame_chunks(n)
    if len(chunks) == 1 or threading.current_thread().name.startswith(_POOL_PREFIX):
        # one chunk, or called from a worker of the pool itself (waiting there on the same
        # pool's workers could deadlock): in this thread
        return [function(c) for c in chunks]
    if _POOL is None:
        _POOL = ThreadPoolExecutor(max_workers=os.cpu_count() or 1, thread_name_prefix=_POOL_PREFIX)
    return list(_POOL.map(function, chunks))


POSE_HALVINGS = 6
"""Step halvings of a frame's pose update in ``optimise_poses`` before it gives up."""


def optimise_poses(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    halvings: int = POSE_HALVINGS,
) -> tuple[np.ndarray, np.ndarray]:
    """A few Gauss-Newton steps on every frame's pose with the shape held fixed (vectorised).

    "Embedded point iterations": keeping the poses at their optimum for the current shape makes
    the outer iteration follow the curved valley (c against every tau) in a few steps.  A frame
    keeps a step only if it lowers that frame's chi2; a step that does not is halved (at most
    ``halvings`` times) before the frame gives up for that iteration: the tangent angles
    are far from linear in delta, and a full step from a few degrees off can overshoot (without
    the halving such a frame stayed where it was, chi2 50-2000 against 2 at the pose a few
    degrees away, and was then flagged as an outlier; the global search's many candidate shapes
    use ``halvings=0``, for speed).  ``g`` is one shape (4,) or one per row
    of ``p`` (N, 4).  Returns (poses, standardised residuals).  The loop over frames is the
    numba kernel ``refine.pose_kernel.optimise_frames`` (100,000 frames: 24.6 s of NumPy calls
    on (N, 6, 5) blocks in the scaling bench's profile).
    """
    g = np.ascontiguousarray(np.atleast_2d(np.asarray(g, float)))
    p = np.ascontiguousarray(p, dtype=float)
    w = np.ascontiguousarray(np.atleast_2d(np.asarray(w8, float)))
    meas = np.ascontiguousarray(meas, dtype=float)
    p_out = np.empty_like(p)
    r_out = np.empty((p.shape[0], 6))

    def part(c: slice) -> None:  # the kernel releases the interpreter lock: chunks in parallel
        gc = g[c] if len(g) > 1 else g
        wc = w[c] if len(w) > 1 else w
        optimise_frames(gc, p[c], meas[c], wc, int(n_iter), int(halvings), p_out[c], r_out[c])

    if p.shape[0]:
        map_chunks(part, p.shape[0])
    return p_out, r_out


def _batched_inverse(v: np.ndarray) -> np.ndarray:
    """Inverse of each 5x5 block; nearly singular blocks get a tiny relative ridge."""
    m = v.shape[-1]
    vr = np.array(v, dtype=float, copy=True).reshape(*v.shape[:-2], m * m)
    diag = vr[..., :: m + 1]  # a view: the diagonal of each block
    diag += 1e-13 * np.maximum(np.sum(diag, axis=-1), 1e-300)[..., None]
    return np.linalg.inv(vr.reshape(v.shape))


def schur_information(jg: np.ndarray, jl: np.ndarray) -> np.ndarray:
    """(4, 4) Schur-reduced normal matrix of the shape, the poses eliminated: U - sum W V^-1 W^T
    from the standardised Jacobians (N, 6, 4) and (N, 6, 5); frames whose V is ill-conditioned
    by :func:`_frame_schur_qr` instead."""
    v = np.einsum("nki,nkj->nij", jl, jl)
    u = np.einsum("nki,nkj->ij", jg, jg)
    w = np.einsum("nki,nkj->nij", jg, jl)
    vinv = _batched_inverse(v)
    s = u - np.einsum("nij,njk,nlk->il", w, vinv, w)
    s = 0.5 * (s + s.T)
    if _suspicious(s):  # only then the frames' condition numbers (an SVD each)
        bad = _ill_conditioned(v)
        if bad.any():
            good = ~bad
            s = schur_information(jg[good], jl[good]) + np.sum(
                _frame_schur_qr(jg[bad], jl[bad]), axis=0
            )
            s = 0.5 * (s + s.T)
    return s


def _suspicious(s: np.ndarray) -> bool:
    """Whether a (4, 4) information matrix may carry the normal equations' cancellation: not
    finite, or its condition number above ``SCHUR_COND_MAX`` (not positive definite included)."""
    if not np.all(np.isfinite(s)):
        return True
    ev = np.linalg.eigvalsh(s)
    return not ev[0] > ev[-1] / SCHUR_COND_MAX


def _ill_conditioned(v: np.ndarray) -> np.ndarray:
    """(N,) whether each frame's pose normal matrix V (N, 5, 5) is too ill-conditioned for
    U - W V^-1 W^T (condition number above ``SCHUR_COND_MAX``, or not finite)."""
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(v)
    return ~(cond < SCHUR_COND_MAX)


def _frame_schur_qr(jg: np.ndarray, jl: np.ndarray) -> np.ndarray:
    """(N, 4, 4) each frame's U_i - W_i V_i^-1 W_i^T from a Householder QR of [J_l | J_g]
    (6 x 9) with its rows sorted by decreasing norm: R = [[R11, R12], [0, r22]] and the frame's
    information is r22^T r22 (r22 the last row's shape part, 1 x 4).

    Exact where one measurement's row is huge (a tangent seen nearly end-on: its projected
    length near 0, its angle's derivatives ~1e9), where U - W V^-1 W^T cancels to noise: a
    10,000-frame scene's information matrix came out indefinite from one such frame, and the
    shape was reported undetermined.  (Householder QR is accurate under widely different row
    scales when the rows are sorted by norm first, Powell and Reid 1969: on the test's frame it
    agreed with 60-digit arithmetic to 2e-16; unsorted to 3e-12, an SVD projector to 5e-5.)
    Where J_l has lost rank exactly (the fold tau = 0, to the last digit) it keeps one of the
    frame's two directions, a lower bound.
    """
    a = np.concatenate([jl, jg], axis=2)  # (N, 6, 9)
    order = np.argsort(-np.linalg.norm(a, axis=2), axis=1)
    a = np.take_along_axis(a, order[:, :, None], axis=1)
    tail = np.linalg.qr(a, mode="r")[:, 5, 5:]  # (N, 4)
    return tail[:, :, None] * tail[:, None, :]


def frame_information(
    shape: np.ndarray, poses: np.ndarray, meas: np.ndarray, weights: np.ndarray
) -> np.ndarray:
    """(N, 4, 4) each frame's own Schur-reduced information on the shape (its pose eliminated):
    U_i - W_i V_i^-1 W_i^T (:func:`_frame_schur_qr` where V_i is ill-conditioned);
    :func:`schur_information` is their sum."""
    _, jg, jl = _linearise(np.asarray(shape, float), np.asarray(poses, float), meas, weights)
    u = np.einsum("nki,nkj->nij", jg, jg)
    v = np.einsum("nki,nkj->nij", jl, jl)
    w = np.einsum("nki,nkj->nij", jg, jl)
    out = u - np.einsum("nij,njk,nlk->nil", w, _batched_inverse(v), w)
    if _suspicious(np.sum(out, axis=0)):
        bad = _ill_conditioned(v)
        if bad.any():
            out[bad] = _frame_schur_qr(jg[bad], jl[bad])
    return out


def frame_leverages(
    shape: np.ndarray,
    poses: np.ndarray,
    meas: np.ndarray,
    weights: np.ndarray,
    among: np.ndarray | None = None,
) -> np.ndarray:
    """(N,) each frame's leverage on the shape: tr(S^-1 S_i), S_i its own Schur-reduced
    information (its pose eliminated) and S their sum; they add up to 4 (the shape's parameters).
    ``among`` (N,) bool: S sums only those frames (the others' leverages are then their h in
    the deleted-residual variance 1 + h).

    A frame's six measurements less its five pose parameters leave it one residual degree of
    freedom, and a fit pulls that residual towards zero by the frame's own weight in the shape:
    linearised, its expected chi2 at the fit is 1 - leverage, not 1.  An outlier frame with a
    large leverage drags the shape after itself and hides (masking); ``chi2 / (1 - leverage)``
    undoes that (the studentised residual).
    """
    s_i = frame_information(shape, poses, meas, weights)
    s = np.sum(s_i if among is None else s_i[among], axis=0)
    try:
        s_inv = np.linalg.inv(0.5 * (s + s.T))
    except np.linalg.LinAlgError:
        return np.zeros(len(s_i))
    return np.einsum("ij,nji->n", s_inv, s_i)


def schur_covariance(jg: np.ndarray, jl: np.ndarray) -> np.ndarray | None:
    """(4, 4) shape covariance: inverse of the Schur-reduced normal matrix (or None)."""
    s = schur_information(jg, jl)
    try:
        cond = np.linalg.cond(s)
        if not np.isfinite(cond) or cond > 1e15:
            return None
        return np.linalg.inv(s)
    except np.linalg.LinAlgError:
        return None


def split_params(g: np.ndarray, p: np.ndarray) -> list[np.ndarray]:
    """Arguments of the generated functions for batched shapes (K, 4) and poses (K, N, 5)."""
    return [g[:, i : i + 1] for i in range(4)] + [p[..., i] for i in range(5)]


# ------------------------------------------------------------------------------------------------
# For N = 20 frames every NumPy call costs more than its arithmetic (about a microsecond against
# a few hundred flops), so the iteration below is organised to make few calls.  The Jacobians
# of a frame are kept side by side, [J_pose | J_shape] (K, N, 6, 9), so that one batched product
# J^T J per frame gives V, W and U at once (three products before; numpy computes each entry as
# the same dot product of two columns).  Where a fused product would round differently (the
# matrix-vector products J^T r: BLAS uses a different kernel for them) the separate product is
# kept, so that results stay identical to the bit with those of the plain formulation.


def _lin_aug(
    g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Standardised residuals (K, N, 6) and Jacobian (K, N, 6, 9) of g (K, 4), p (K, N, 5).

    Jacobian columns: d/d(delta, tau, theta, tx, ty), then d/d(c, alpha, beta, phi) (the pose
    first).  Residuals: prediction - observation, angles wrapped, times ``w8``.
    """
    n = p.shape[-2]
    if n > FRAME_CHUNK:  # every frame is its own: in chunks (cache)
        r = np.empty((*p.shape[:-1], 6))
        ja = np.empty((*p.shape[:-1], 6, 9))

        def part(c: slice) -> None:
            r[:, c], ja[:, c] = _lin_aug(g, p[:, c], meas[c], _rows(w8, c))

        map_chunks(part, n)
        return r, ja
    pred, jg, jl = measurement_model.predict_with_jacobians(*split_params(g, p))
    r = pred - meas
    # wrap_line_angle's operations, inlined with fewer temporaries (same values)
    y = np.mod(r[..., 4:6] + np.pi / 2, np.pi)
    y -= np.pi / 2
    np.add(y, np.pi, out=y, where=y <= -np.pi / 2)
    r[..., 4:6] = y
    r *= w8
    ja = np.empty((*pred.shape, 9))
    wc = w8[..., None]
    np.multiply(jl, wc, out=ja[..., :5])  # written in place: no concatenation
    np.multiply(jg, wc, out=ja[..., 5:])
    return r, ja


def _lin_batch(g, p, meas, w8):
    """Standardised (r (K, N, 6), jg (K, N, 6, 4), jl (K, N, 6, 5)) (Jacobians: views)."""
    r, ja = _lin_aug(g, p, meas, w8)
    return r, ja[..., 5:], ja[..., :5]


def _curvature_map() -> np.ndarray:
    """(17, 81) map of the terms of :func:`curvature` onto a flattened symmetric 9x9 block."""
    # parameters: c 0, alpha 1, beta 2, phi 3, delta 4, tau 5, theta 6, tx 7, ty 8
    pairs = (
        ((0, 5),),  # B': c-tau
        ((0, 6),),  # c-theta
        ((5, 5),),  # tau-tau
        ((6, 6),),  # theta-theta
        ((5, 6),),  # tau-theta
        ((5, 5),),  # tangent at A over (tau, beta, gamma = delta + phi)
        ((5, 2),),
        ((5, 4), (5, 3)),
        ((2, 2),),
        ((2, 4), (2, 3)),
        ((4, 4), (3, 3), (4, 3)),
        ((5, 5),),  # tangent at B over (tau, alpha, gamma = delta)
        ((5, 1),),
        ((5, 4),),
        ((1, 1),),
        ((1, 4),),
        ((4, 4),),
    )
    m = np.zeros((len(pairs), 81))
    for k, where in enumerate(pairs):
        for i, j in where:
            m[k, 9 * i + j] += 1.0
            if i != j:
                m[k, 9 * j + i] += 1.0
    return m


_CURVATURE_MAP = _curvature_map()
_CURVATURE_SLOTS = tuple(
    (j, np.flatnonzero(_CURVATURE_MAP[:, j])) for j in range(81) if _CURVATURE_MAP[:, j].any()
)
"""(flat position in the 9x9 block, the terms summed there); cheaper than a BLAS product."""
_CURVATURE_COPY = (
    np.array([j for j, ks in _CURVATURE_SLOTS if ks.size == 1]),
    np.array([ks[0] for _, ks in _CURVATURE_SLOTS if ks.size == 1]),
)
"""The positions that take a single term, and that term: filled by one indexed copy."""
_CURVATURE_SUMS = tuple((j, ks) for j, ks in _CURVATURE_SLOTS if ks.size > 1)


def _angle_hessian(
    sgn: float | np.ndarray,
    tau: np.ndarray,
    a: np.ndarray,
    gam: np.ndarray,
    trig: tuple[np.ndarray, np.ndarray] | None = None,
) -> np.ndarray:
    """Second derivatives of atan2(m1, m0) over (tau, a, gamma) of a projected tangent.

    m0 = sgn cos(tau) cos(a) + sin(tau) sin(a) sin(gamma), m1 = sin(a) cos(gamma) is the
    direction R_y(tau) R_x(delta) t up to the rotation theta (which only adds to the angle):
    tangent at B: sgn = -1, a = alpha, gamma = delta; at A: sgn = 1, a = beta, gamma = delta + phi.
    ``trig``: (cos(tau), sin(tau)) if already known.  Returns the entries (tt, ta, tg, aa, ag,
    gg) of the symmetric 3x3 Hessian stacked on a new first axis.

    Written for few NumPy calls: products shared by several entries are computed once, and the
    entries of the same form are computed together on stacked arrays.  Every entry is still
    the same sequence of floating-point operations as the expanded formula in its comment
    (multiplying by sgn = +-1 and negating are exact), so the values are unchanged to the bit.
    """
    ct, st = (np.cos(tau), np.sin(tau)) if trig is None else trig
    cg, sg = np.cos(gam), np.sin(gam)
    shape = np.broadcast_shapes(np.shape(sgn), ct.shape, np.shape(a), cg.shape)
    # every factor as a contiguous array of the full shape (copies): NumPy's broadcasting
    # loops cost several times the same-shape ones on these small arrays
    full = np.empty((8, *shape))
    for i, v in enumerate((ct, st, np.cos(a), np.sin(a), cg, sg, sgn, -sgn)):
        full[i] = v
    ct, st, ca, sa, cg, sg, sgn, nsgn = full
    x = sgn * ct * ca
    ssa = st * sa
    y = ssa * sg
    m0 = x + y  # sgn ct ca + st sa sg
    m1 = sa * cg
    cts, stc = ct * sa, st * ca
    # first derivatives of m0 (t, a, g) and of m1 (0, a, g)
    d0 = np.empty((3, *shape))
    d0[0] = nsgn * st * ca + cts * sg  # -sgn st ca + ct sa sg
    d0[1] = nsgn * ct * sa + stc * sg  # -sgn ct sa + st ca sg
    d0[2] = ssa * cg  # st sa cg
    d1 = np.zeros((3, *shape))
    d1[1] = ca * cg
    d1[2] = (-sa) * sg
    # second derivatives of m0 (tt, ta, tg, aa, ag) and of m1 (0, 0, 0, aa, ag); m1 has no tau
    h0 = np.empty((5, *shape))
    h0[0] = -m0  # -sgn ct ca - st sa sg
    h0[1] = sgn * ssa + ct * ca * sg  # sgn st sa + ct ca sg
    h0[2] = cts * cg  # ct sa cg
    h0[3] = h0[0]
    h0[4] = stc * cg  # st ca cg
    h1 = np.zeros((5, *shape))
    h1[3] = -m1
    h1[4] = (-ca) * sg
    inv = 1.0 / (m0 * m0 + m1 * m1)
    grad = (m0 * d1 - m1 * d0) * inv
    dden = 2.0 * (m0 * d0 + m1 * d1)
    out = np.empty((6, *shape))
    # symmetric part of (m0 h1 - m1 h0) / den - grad_i dden_j / den; (i, j) = (0, 0..2), (1, 1..2)
    gd = np.empty((5, *shape))
    np.add(grad[0] * dden[0:3], grad[0:3] * dden[0], out=gd[0:3])
    np.add(grad[1] * dden[1:3], grad[1:3] * dden[1], out=gd[3:5])
    np.multiply(m0 * h1 - m1 * h0 - 0.5 * gd, inv, out=out[:5])
    # gg: h0 gg = -st sa sg, h1 gg = -m1
    np.multiply(m0 * h1[3] - m1 * (-y) - grad[2] * dden[2], inv, out=out[5])
    return out


_SIGNS = np.array([1.0, -1.0])
"""sgn of the two tangents (A, B) in :func:`_angle_hessian`."""
_PHI_SELECT = np.array([1.0, 0.0])
"""gamma of the two tangents (A, B): delta + phi, delta (+ 0)."""


def _split_view(terms: np.ndarray) -> np.ndarray:
    """Columns 5-16 of a C-ordered ``terms`` (K, N, 20) as a (K, N, 2, 6) view (never a copy)."""
    k, n, m = terms.shape
    item = terms.itemsize
    return np.ndarray(
        (k, n, 2, 6), float, terms, 5 * item, (n * m * item, m * item, 6 * item, item)
    )


def _curvature_terms(g: np.ndarray, p: np.ndarray, r: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """(K, N, 20) the distinct terms of :func:`curvature` (rows of :func:`_curvature_map`).

    Columns 0-16 as in :func:`_curvature_map`; 17-19 the sums of the entries that take several
    terms, in :func:`curvature`'s order: delta-tau t7 + t13, delta-delta t10 + t16, tau-tau
    (t2 + t5) + t11.
    """
    n = p.shape[-2]
    if n > FRAME_CHUNK:  # every frame is its own: in chunks (cache)
        out = np.empty((*p.shape[:-1], 20))

        def part(ch: slice) -> None:
            out[:, ch] = _curvature_terms(g, p[:, ch], r[:, ch], _rows(w8, ch))

        map_chunks(part, n)
        return out
    c = g[:, 0, None]
    tau, theta = p[..., 1], p[..., 2]
    ct, st = np.cos(tau), np.sin(tau)
    cth, sth = np.cos(theta), np.sin(theta)
    wp = w8[..., 2]
    q = wp * (r[..., 2] * cth + r[..., 3] * sth)  # B' residual along A'B'
    qp = wp * (r[..., 3] * cth - r[..., 2] * sth)  # and across
    terms = np.empty((*q.shape, 20))
    qcc = terms[..., 2]
    np.multiply(-q * c, ct, out=qcc)  # -q c cos(tau)
    terms[..., 0] = -q * st
    terms[..., 1] = qp * ct
    terms[..., 3] = qcc
    terms[..., 4] = -qp * c * st
    # both tangents at once (last axis: A, B): a = (beta, alpha), gamma = (delta + phi, delta)
    a = g[:, None, 2:0:-1]  # (K, 1, 2): the same in every frame
    gam = p[..., 0, None] + g[:, None, 3:4] * _PHI_SELECT
    h = _angle_hessian(_SIGNS, tau[..., None], a, gam, (ct[..., None], st[..., None]))
    # times the standardised residual, written as columns 5-10 (A) and 11-16 (B) at once: a
    # (K, N, 2, 6) view of those 12 columns
    np.multiply(
        h.transpose(1, 2, 3, 0),
        (w8[..., 4:6] * r[..., 4:6])[..., None],
        out=_split_view(terms),
    )
    np.add(terms[..., 7], terms[..., 13], out=terms[..., 17])
    np.add(terms[..., 10], terms[..., 16], out=terms[..., 18])
    np.add(qcc, terms[..., 5], out=terms[..., 19])
    terms[..., 19] += terms[..., 11]
    return terms


def curvature(g: np.ndarray, p: np.ndarray, r: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """Second-order term sum_k r_k d2 r_k of the residuals of every frame, (K, N, 9, 9).

    Over (c, alpha, beta, phi, delta, tau, theta, tx, ty).  Gauss-Newton drops it; here it is
    not small: near the fold tau = 0 (c' close to c, often c' > c with noise) the B' residual's
    curvature c cos(tau) dwarfs the Gauss-Newton term in tau (Gauss-Newton overshoots, zig-zag),
    and the tangent angles' curvature is of the order of their Gauss-Newton term where a
    projected tangent is short.  With it the iteration is Newton's method (quadratic
    convergence); the damping and the positive-definiteness test keep it safe.
    """
    terms = _curvature_terms(g, p, r, w8)
    out = np.zeros((*terms.shape[:-1], 81))
    out[..., _CURVATURE_COPY[0]] = terms[..., _CURVATURE_COPY[1]]
    for j, ks in _CURVATURE_SUMS:
        out[..., j] = np.sum(terms[..., ks], axis=-1)
    return out.reshape(*terms.shape[:-1], 9, 9)


# Where the refinement adds the second-order term: the used blocks V (pose x pose) and W (shape
# x pose) of each frame's 9x9 block in the pose-first order (flat positions), and U summed over
# the frames; the values are those of :func:`curvature` (columns of :func:`_curvature_terms`).
_CURVATURE_VW = (
    np.array([10, 20, 11, 19, 1, 9, 0, 46, 47, 64, 73, 63, 72, 55, 54]),
    np.array([19, 3, 4, 4, 17, 17, 18, 0, 1, 6, 7, 9, 10, 12, 15]),
)
"""V: tau-tau, theta-theta, tau-theta (2), delta-tau (2), delta-delta; W: c-tau, c-theta,
beta-tau, phi-tau, beta-delta, phi-delta, alpha-tau, alpha-delta: (positions, terms)."""
_CURVATURE_U = (np.array([5, 10, 11, 14, 15]), np.array([14, 8, 9, 9, 10]))
"""U (flat 4x4): alpha-alpha, beta-beta, beta-phi (2), phi-phi: (positions, terms)."""


def _add_curvature(
    h: np.ndarray, u: np.ndarray, g: np.ndarray, p: np.ndarray, r: np.ndarray, w8: np.ndarray
) -> None:
    """Add the second-order term to the blocks h (K, N, 9, 9) (V, W) and u (K, 4, 4), in place.

    Only its ~20 non-zero entries (of 81 per frame, :func:`curvature`) are gathered from the
    terms and added, with one indexed addition for the frames' blocks and one for U; the values
    and the order of every sum are those of adding :func:`curvature` (bit-identical).
    """
    terms = _curvature_terms(g, p, r, w8)
    k, n = terms.shape[:2]
    h.reshape(k, n, 81)[..., _CURVATURE_VW[0]] += terms[..., _CURVATURE_VW[1]]
    # np.take: a C-ordered (K, N, 5) result, so that the sum runs over the frames in order
    u.reshape(k, 16)[:, _CURVATURE_U[0]] += np.take(terms, _CURVATURE_U[1], axis=-1).sum(axis=1)


try:  # numpy's LAPACK gufuncs: no exception (NaN results) where a block is singular / not PD
    from numpy.linalg import _umath_linalg

    _CHOLESKY_LO = _umath_linalg.cholesky_lo
    _SOLVE, _SOLVE1, _INV = _umath_linalg.solve, _umath_linalg.solve1, _umath_linalg.inv
except (ImportError, AttributeError):  # pragma: no cover - other numpy versions
    _CHOLESKY_LO = _SOLVE = _SOLVE1 = _INV = None


def _inverse(a: np.ndarray) -> np.ndarray:
    """Batched inverse of (..., n, n) blocks: ``np.linalg.inv``'s gufunc called directly.

    For 5x5 blocks the wrapper's checks cost as much as the inverse.  Singular blocks give NaN
    (no exception).
    """
    if _INV is None:  # pragma: no cover
        try:
            return np.linalg.inv(a)
        except np.linalg.LinAlgError:
            return np.full(a.shape, np.nan)
    if a.ndim >= 3 and a.shape[-3] > FRAME_CHUNK:  # blocks of many frames: chunks in parallel
        out = np.empty_like(a, dtype=float)

        def part(c: slice) -> None:
            with np.errstate(all="ignore"):
                out[..., c, :, :] = _INV(a[..., c, :, :], signature="d->d")

        map_chunks(part, a.shape[-3])
        return out
    with np.errstate(all="ignore"):
        return _INV(a, signature="d->d")


def _solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Batched solution of a x = b, a (..., n, n), b (..., n, m): ``np.linalg.solve``'s gufunc.

    A singular block gives NaN (no exception).
    """
    if _SOLVE is None:  # pragma: no cover
        try:
            return np.linalg.solve(a, b)
        except np.linalg.LinAlgError:
            return np.full(b.shape, np.nan)
    with np.errstate(all="ignore"):
        return _SOLVE(a, b, signature="dd->d")


def _positive_definite(m: np.ndarray, axes: int = 2) -> np.ndarray:
    """Whether each symmetric block of ``m`` (..., n, n) is positive definite.

    The test is whether a Cholesky factorisation succeeds: numpy's Cholesky gufunc, called
    directly, returns NaN factors where it fails (no exception; the eigenvalue test where that
    gufunc is not available).  ``axes`` > 2 also reduces over leading block axes (``axes`` = 3:
    (K, N, n, n) -> (K,), every block of a start).
    """
    if _CHOLESKY_LO is None:  # pragma: no cover
        pd = np.linalg.eigvalsh(m)[..., 0] > 0
        return pd.reshape(*pd.shape[: pd.ndim + 2 - axes], -1).all(axis=-1)
    with np.errstate(all="ignore"):
        factor = _CHOLESKY_LO(m, signature="d->d")
    return np.isfinite(factor.reshape(*m.shape[: m.ndim - axes], -1)).all(axis=-1)


def _normal_blocks(
    g: np.ndarray, p: np.ndarray, r: np.ndarray, ja: np.ndarray, w8: np.ndarray, nwt: np.ndarray
) -> tuple[np.ndarray, ...]:
    """The blocks of the (Gauss-Newton, or where ``nwt`` Newton) normal equations.

    From residuals ``r`` (K, N, 6) and Jacobian ``ja`` (K, N, 6, 9) (:func:`_lin_aug`) at
    shapes g (K, 4) and poses p (K, N, 5).  Returns (h, u, el, eg, dv, du, sv, su): h
    (K, N, 9, 9) every frame's block of the Hessian in the pose-first order (V = h[..., :5, :5],
    W = h[..., 5:, :5]; the other two blocks are not used), U (K, 4, 4) summed over the frames,
    the gradients e = J^T r of the poses (K, N, 5) and of the shape (K, 4), the Gauss-Newton
    diagonals of V (K, N, 5) and U (K, 4), and the damping's scales (sv, su: those diagonals
    plus 1e-12 times their largest entry; computed once per point, not once per lambda).
    """
    h = ja.swapaxes(-1, -2) @ ja  # V, W^T, W and U_n in one product
    u = h[..., 5:, 5:].sum(axis=1)
    # matrix-vector products of their own: the same kernel (and rounding) as before
    rc = r[..., None]
    el = (ja[..., :5].swapaxes(-1, -2) @ rc)[..., 0]
    eg = (ja[..., 5:].swapaxes(-1, -2) @ rc).sum(axis=1)[..., 0]
    dv = h.reshape(*h.shape[:-2], 81)[..., 0:50:10].copy()  # diagonal of V
    du = u.reshape(-1, 16)[:, ::5].copy()
    sv = dv + 1e-12 * dv.max(axis=2)[..., None]
    su = du + 1e-12 * du.max(axis=1)[:, None]
    if nwt.all():  # the second-order term (Newton)
        _add_curvature(h, u, g, p, r, w8)
    elif nwt.any():
        i = np.flatnonzero(nwt)
        hi, ui = h[i], u[i]
        _add_curvature(hi, ui, g[i], p[i], r[i], w8)
        h[i], u[i] = hi, ui
    if nwt.any() and h.shape[1] >= LONG_FRAMES:
        _gauss_newton_where_indefinite(h, u, g, p, r, ja, w8, nwt)
    return h, u, el, eg, dv, du, sv, su


def _gauss_newton_where_indefinite(
    h: np.ndarray,
    u: np.ndarray,
    g: np.ndarray,
    p: np.ndarray,
    r: np.ndarray,
    ja: np.ndarray,
    w8: np.ndarray,
    nwt: np.ndarray,
) -> None:
    """Long sequences: the frames whose Newton pose block V is not positive definite go back to
    their Gauss-Newton blocks (in place; U loses their second-order terms).

    Among thousands of frames a few are always away from a minimum of their own (a fold, a
    saddle); one such frame made the whole Newton model indefinite, lambda rose tenfold, and
    the iteration crept (30,000 frames: 46 iterations, 1 to 7 such frames in most of them).
    Per frame Newton where it is positive definite, Gauss-Newton elsewhere, as the marginal
    step's pose solves do (``refine.marginal``)."""
    bad = ~_positive_definite(h[..., :5, :5]) & nwt[:, None]
    if not bad.any():
        return
    ks, ns = np.nonzero(bad)
    jb = ja[ks, ns]
    h[ks, ns] = jb.swapaxes(-1, -2) @ jb
    wb = w8[ns][:, None] if np.ndim(w8) == 2 else w8
    terms = _curvature_terms(g[ks], p[ks, ns][:, None], r[ks, ns][:, None], wb)[:, 0]
    part = np.take(terms, _CURVATURE_U[1], axis=-1)  # (M, 5)
    for k in np.unique(ks):
        u.reshape(-1, 16)[k, _CURVATURE_U[0]] -= part[ks == k].sum(axis=0)


def _damped_solve(
    h: np.ndarray,
    u: np.ndarray,
    el: np.ndarray,
    eg: np.ndarray,
    dv: np.ndarray,
    du: np.ndarray,
    sv: np.ndarray,
    su: np.ndarray,
    lam: np.ndarray,
    check: bool = True,
    decrement: bool = False,
) -> tuple[np.ndarray, ...]:
    """Solve the damped block-arrow system by the Schur complement.

    (H + lam D) d = -e with H = [[U, W], [W^T, V]] (Gauss-Newton plus the second-order blocks)
    and D its Gauss-Newton diagonal (plus 1e-12 of its largest entry); the blocks as returned by
    :func:`_normal_blocks`.  Returns the shape step (K, 4), the pose steps (K, N, 5), the
    decrease of chi2 the quadratic model predicts (K,) and whether the damped matrix was
    positive definite (K,) (``check`` False: not tested, True).

    ``decrement``: also the shape's Newton decrement e_r^T S^-1 e_r (K,), S the Schur complement
    with the shape block U undamped and e_r the reduced gradient: the decrease of chi2 the
    profile model (every pose at its optimum) predicts for the undamped shape step, twice;
    divided by the noise scale, the squared length of that step in standard deviations.  Unlike
    the damped step it does not shrink as lambda grows.  The pose blocks keep their damping
    (lambda times their own diagonal, a relative change of lambda): inf where lambda is above
    ``DECREMENT_MAX_LAMBDA`` or S is not positive definite (no estimate).
    """
    k, n = h.shape[:2]
    ud = u.reshape(k, 16).copy()
    ud[:, ::5] += lam[:, None] * su
    vd = h[..., :5, :5].copy()
    vdiag = vd.reshape(k, n, 25)[..., ::6]  # a view: the diagonal of each damped block
    vdiag += lam[:, None, None] * sv
    pd = _positive_definite(vd, 3) if check else np.ones(k, dtype=bool)
    vdiag += 1e-13 * np.maximum(vdiag.sum(axis=-1), 1e-300)[..., None]  # tiny ridge
    vinv = _inverse(vd)
    w = h[..., 5:, :5]  # W (4 x 5 per frame)
    wt = w.swapaxes(-1, -2)
    y = w @ vinv
    sc = ud.reshape(k, 4, 4) - (y @ wt).sum(axis=1)
    rhs = (y @ el[..., None]).sum(axis=1) - eg[..., None]  # (K, 4, 1)
    scdiag = sc.reshape(k, 16)[:, ::5]  # a view: a tiny ridge
    scdiag += 1e-14 * scdiag.sum(axis=1)[:, None]
    sc = 0.5 * (sc + sc.swapaxes(-1, -2))
    if check:
        pd &= _positive_definite(sc)
    dec = None
    if decrement:
        sc_u = sc.copy()  # the Schur complement with U undamped
        sc_u.reshape(k, 16)[:, ::5] -= lam[:, None] * su
        dec = np.full(k, np.inf)
        ok = (lam <= DECREMENT_MAX_LAMBDA) & _positive_definite(sc_u)
        if ok.any():
            dec[ok] = np.einsum("kia,kia->k", rhs[ok], _solve(sc_u[ok], rhs[ok]))
    dg = _solve(sc, rhs)[..., 0]
    if not np.isfinite(dg).all():
        singular = ~np.all(np.isfinite(dg), axis=1) & np.all(np.isfinite(sc), axis=(1, 2))
        if singular.any():  # a singular Schur complement: the least-squares step
            dg[singular] = (np.linalg.pinv(sc[singular]) @ rhs[singular])[..., 0]
    dl = (vinv @ (-el - (wt @ dg[:, None, :, None])[..., 0])[..., None])[..., 0]
    # model decrease: -e.d + lam d^T D d (exact for the solved system)
    predicted = -(np.einsum("ki,ki->k", eg, dg) + np.einsum("kni,kni->k", el, dl))
    predicted += lam * (np.einsum("ki,ki->k", du, dg * dg) + np.einsum("kni,kni->k", dv, dl * dl))
    if decrement:
        return dg, dl, predicted, pd, dec
    return dg, dl, predicted, pd


DECREMENT_MAX_LAMBDA = 1e-2
"""``_damped_solve``'s shape decrement only up to this lambda: the pose blocks' damping (lambda
times their own diagonal) then changes them by at most 1 %."""


def _pose_steps(
    g: np.ndarray,
    p: np.ndarray,
    r: np.ndarray,
    ja: np.ndarray,
    f: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    rtol: float,
    lam: np.ndarray | None = None,
    mask: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Damped Gauss-Newton steps on every frame's pose, shape ``g`` (K, 4) fixed; batched (K, N).

    ``r``, ``ja``: residuals and Jacobian at ``p`` (:func:`_lin_aug`).  Damped like the outer
    iteration: ``lam`` (K,) times the Gauss-Newton diagonal (None: undamped).  Each frame keeps
    its step only if the step lowers that frame's chi2 ``f`` (K, N) (and, given ``mask`` (K,),
    only in the starts it marks).  Stops after ``n_iter`` steps or when the steps gain less than
    ``rtol`` times the total chi2.  Returns the updated (p, r, ja, f).
    """
    for _ in range(n_iter):
        jlt = ja[..., :5].swapaxes(-1, -2)
        v = jlt @ ja[..., :5]
        vdiag = v.reshape(*v.shape[:-2], 25)[..., ::6]  # a view: the diagonal of each block
        if lam is not None:
            vdiag += lam[:, None, None] * vdiag
        vdiag += 1e-13 * np.maximum(vdiag.sum(axis=-1), 1e-300)[..., None]  # tiny ridge
        el = jlt @ r[..., None]
        dl = -(_inverse(v) @ el)[..., 0]
        descent = (dl * el[..., 0]).sum(axis=-1) < 0
        p_try = p + dl
        r_t, ja_t = _lin_aug(g, p_try, meas, w8)
        f_t = (r_t * r_t).sum(axis=-1)
        take = (f_t < f) & descent
        if mask is not None:
            take &= mask[:, None]
        if take.all():  # every frame moves: no selection
            gain = (f - f_t).sum()
            p, r, ja, f = p_try, r_t, ja_t, f_t
        elif take.any():
            gain = np.sum(np.where(take, f - f_t, 0.0))
            p = np.where(take[..., None], p_try, p)
            r = np.where(take[..., None], r_t, r)
            ja = np.where(take[..., None, None], ja_t, ja)
            f = np.where(take, f_t, f)
        else:
            break
        if gain <= rtol * f.sum():
            break
    return p, r, ja, f


def refine_batch(
    obs: Observations | np.ndarray,
    shapes: np.ndarray,
    poses: np.ndarray,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    max_iter: int = 100,
    xtol: float = 1e-11,
    ftol: float = 1e-10,
    drop_factor: float | None = None,
    act_floor: float = 10.0,
    frame_weights: np.ndarray | None = None,
    drop_after: int = 8,
    pose_iterations: int = 1,
    newton_phase: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Damped Gauss-Newton, then Newton (module docstring) on K independent starts at once.

    Args:
        obs: observations or (N, 6) measurements.
        shapes: (K, 4) start shapes; poses: (K, N, 5) start poses.
        point_sigma (input units), tangent_sigma (radians): noise of the measurements.
        drop_factor: after ``drop_after`` iterations stop starts whose chi2 exceeds
            drop_factor * (best chi2 + act_floor) (screening many starts); None keeps all.
        frame_weights: (N,) optional weights of the frames' squared residuals (robust IRLS);
            residuals and chi2 returned are then weighted too.
        pose_iterations: embedded pose iterations after each shape step in the Newton phase.
        newton_phase: False stays Gauss-Newton throughout (no Newton phase, no embedded pose steps):
            cheaper iterations that keep the start's basin but crawl along the curved valley
            near a minimum - for screening many starts, whose best few are then refined again
            with the Newton phase.
    From ``PROFILE_FRAMES`` frames on (with the Newton phase) every start is fitted by the
    profile iteration :func:`_profile_batch` instead (``drop_factor``, ``drop_after`` and
    ``pose_iterations`` do not apply there).
    Returns:
        shapes (K, 4), poses (K, N, 5), residuals (K, N, 6) standardised, chi2 (K,),
        iterations (K,), converged (K,) bool.

    An iteration, on the starts still active (:class:`_Batch`, :class:`_Step`): the damped
    step (:func:`_damped_step`), the stopping tests (:func:`_stop_tests`), the trial point
    (:func:`_try_step`), lambda and the switch to Newton (:func:`_update_damping`), the
    accepted points taken (:func:`_take_accepted`).
    """
    meas = _measurements(obs)
    w8 = _weights(point_sigma, tangent_sigma)
    if frame_weights is not None:
        w8 = w8[None, :] * np.sqrt(np.asarray(frame_weights, float))[:, None]
    g = np.array(shapes, dtype=float, ndmin=2)
    p = np.array(poses, dtype=float, ndmin=3)
    if newton_phase and p.shape[1] >= PROFILE_FRAMES:
        return _profile_batch(g, p, meas, w8, max_iter, xtol, ftol)
    b = _Batch.start(g, p, meas, w8, newton_phase, pose_iterations)
    tol = max(ftol, 0.5 * LONG_STEP_STD**2 / p.shape[1]) if b.long else ftol
    for it in range(max_iter):
        dropping = it >= drop_after and drop_factor is not None
        act = b.active(drop_factor if dropping else None, act_floor)
        if act.size == 0:
            break
        s = _damped_step(b, act)
        _stop_tests(b, s, xtol, tol)
        _try_step(b, s)
        _update_damping(b, s)
        _take_accepted(b, s)
    if b.long:
        b.polish_poses()
    return b.g, b.p, b.r, b.chi2, b.iters, b.converged


@dataclass
class _Batch:
    """``refine_batch``'s K starts: their points (shape g, poses p, residuals r, Jacobian ja,
    chi2), damping lambda, which are in the Newton phase, done, converged, their iterations,
    and their normal blocks (:func:`_normal_blocks`), kept with the point: a rejected step
    changes only lambda, and the next iteration solves the same blocks with more damping
    (``stale`` marks the starts whose point moved, whose blocks are built again)."""

    g: np.ndarray
    p: np.ndarray
    r: np.ndarray
    ja: np.ndarray
    chi2: np.ndarray
    lam: np.ndarray
    newton: np.ndarray
    done: np.ndarray
    converged: np.ndarray
    iters: np.ndarray
    stale: np.ndarray
    blocks: tuple[np.ndarray, ...]
    meas: np.ndarray
    w8: np.ndarray
    long: bool
    shrink: float
    newton_phase: bool
    pose_iterations: int

    @classmethod
    def start(
        cls,
        g: np.ndarray,
        p: np.ndarray,
        meas: np.ndarray,
        w8: np.ndarray,
        newton_phase: bool,
        pose_iterations: int,
    ) -> _Batch:
        """The starts at their start points: Gauss-Newton while far from a minimum (convex
        model, short steps: the start's basin is kept); Newton with embedded pose steps once a
        Gauss-Newton step predicts little."""
        k = g.shape[0]
        long = p.shape[1] >= LONG_FRAMES
        r, ja = _lin_aug(g, p, meas, w8)
        return cls(
            g=g,
            p=p,
            r=r,
            ja=ja,
            chi2=np.einsum("kna,kna->k", r, r),
            lam=np.full(k, 1e-3),
            newton=np.zeros(k, dtype=bool),
            done=np.zeros(k, dtype=bool),
            converged=np.zeros(k, dtype=bool),
            iters=np.zeros(k, dtype=int),
            stale=np.ones(k, dtype=bool),
            blocks=(),
            meas=meas,
            w8=w8,
            long=long,
            shrink=LONG_SHRINK if long else 1.0 / 3.0,
            newton_phase=newton_phase,
            pose_iterations=pose_iterations,
        )

    def active(self, drop_factor: float | None, act_floor: float) -> np.ndarray:
        """The starts not done; given ``drop_factor``, those far worse than the best one are
        given up first (they are not the answer)."""
        act = np.flatnonzero(~self.done)
        if act.size > 1 and drop_factor is not None:
            hopeless = self.chi2[act] > drop_factor * (np.min(self.chi2) + act_floor)
            self.done[act[hopeless]] = True
            act = act[~hopeless]
        return act

    def update_blocks(self, act: np.ndarray) -> None:
        """The normal blocks of the active starts whose point moved, built again."""
        full = act.size == self.g.shape[0]
        if not self.blocks or (full and self.stale.all()):
            self.blocks = _normal_blocks(self.g, self.p, self.r, self.ja, self.w8, self.newton)
            return
        rb = act[self.stale[act]]
        if rb.size:
            new = _normal_blocks(
                self.g[rb], self.p[rb], self.r[rb], self.ja[rb], self.w8, self.newton[rb]
            )
            for cache, value in zip(self.blocks, new, strict=True):
                cache[rb] = value

    def polish_poses(self) -> None:
        """Long sequences: the stop leaves a few frames short of their pose optimum
        (``LONG_STEP_STD``): every frame's pose polished for its start's shape (a frame keeps
        only steps that lower it)."""
        for j in range(self.g.shape[0]):
            pj, _ = optimise_poses(self.g[j], self.p[j], self.meas, self.w8, 10)
            rj, jj = _lin_aug(self.g[j : j + 1], pj[None], self.meas, self.w8)
            self.p[j], self.r[j], self.ja[j] = pj, rj[0], jj[0]
            self.chi2[j] = float(np.sum(rj * rj))


@dataclass
class _Step:
    """One iteration of ``refine_batch`` on its active starts ``act``: their state (``full``,
    every start active: the batch's arrays themselves, no index arithmetic, no copies; else
    copies, written back by :func:`_take_accepted`), the damped step, and its trial point."""

    act: np.ndarray
    full: bool
    g: np.ndarray
    p: np.ndarray
    lam: np.ndarray
    chi2: np.ndarray
    newton: np.ndarray
    blocks: tuple[np.ndarray, ...]
    check: bool
    dg: np.ndarray | None = None
    dl: np.ndarray | None = None
    predicted: np.ndarray | None = None
    saddle: np.ndarray | None = None
    """Where the Newton model was indefinite (None: nowhere)."""
    indefinite: np.ndarray | None = None
    small: np.ndarray | None = None
    every: bool = False
    """Every active start takes a trial step (else ``moving`` lists those that do)."""
    moving: np.ndarray | None = None
    g_new: np.ndarray | None = None
    p_new: np.ndarray | None = None
    r_new: np.ndarray | None = None
    ja_new: np.ndarray | None = None
    chi2_new: np.ndarray | None = None
    accept: np.ndarray | None = None
    lam_new: np.ndarray | None = None
    switch: np.ndarray | None = None


def _damped_step(b: _Batch, act: np.ndarray) -> _Step:
    """The active starts' damped step on the Newton (or Gauss-Newton) model; an indefinite
    damped model gets more damping at once."""
    b.update_blocks(act)
    if act.size == b.g.shape[0]:
        b.iters += 1
        s = _Step(act, True, b.g, b.p, b.lam, b.chi2, b.newton.copy(), b.blocks, False)
    else:
        b.iters[act] += 1
        s = _Step(
            act,
            False,
            b.g[act],
            b.p[act],
            b.lam[act],
            b.chi2[act],
            b.newton[act],
            tuple(x[act] for x in b.blocks),
            False,
        )
    s.check = bool(s.newton.any())  # a damped Gauss-Newton matrix is positive definite
    dg, dl, predicted, pd = _damped_solve(*s.blocks, s.lam, s.check)
    indefinite = ~((predicted > 0) & pd)
    if indefinite.any():
        for _ in range(12):
            bad = indefinite & (s.lam <= 1e12)
            if not bad.any():
                break
            s.saddle = bad if s.saddle is None else s.saddle | bad
            s.lam = np.where(bad, np.maximum(s.lam * 10.0, 1e-4), s.lam)
            dg2, dl2, pred2, pd2 = _damped_solve(*s.blocks, s.lam, s.check)
            dg = np.where(bad[:, None], dg2, dg)
            dl = np.where(bad[:, None, None], dl2, dl)
            predicted = np.where(bad, pred2, predicted)
            pd = np.where(bad, pd2, pd)
            indefinite = ~((predicted > 0) & pd)
    s.dg, s.dl, s.predicted, s.indefinite = dg, dl, predicted, indefinite
    return s


def _stop_tests(b: _Batch, s: _Step, xtol: float, tol: float) -> None:
    """Starts whose step or predicted decrease is negligible are done (converged unless lambda
    ran away); neither a tiny damped step near a saddle nor an indefinite model is
    convergence."""
    step = np.maximum(
        (np.abs(s.dg) / np.maximum(np.abs(s.g), 1.0)).max(axis=1),
        (np.abs(s.dl) / np.maximum(np.abs(s.p), 1.0)).reshape(s.act.size, -1).max(axis=1),
    )
    huge = s.lam > 1e12
    small = (step < xtol) | (s.predicted <= tol * np.maximum(s.chi2, 1e-300)) | huge
    small &= ~(s.indefinite if s.saddle is None else s.indefinite | s.saddle) | huge
    if small.any():
        b.converged[s.act[small & ~huge]] = True
        b.done[s.act[small]] = True
    s.small = small


def _try_step(b: _Batch, s: _Step) -> None:
    """The trial points and whether they lower chi2 (``s.accept``).  Only the starts that take
    a trial step are evaluated: a start that stops or whose model was indefinite keeps its
    point and chi2, and cannot accept anything."""
    g_new, p_new = s.g + s.dg, s.p + s.dl
    ka = s.act.size
    ok = np.isfinite(g_new).all(axis=1) & np.isfinite(p_new).reshape(ka, -1).all(axis=1)
    ok &= (g_new[:, 0] > 0) & ~(s.small | s.indefinite)
    s.every = every = bool(ok.all())
    s.moving = mv = None if every else np.flatnonzero(ok)
    if not (every or mv.size):
        s.accept = ok  # nothing moved: all False
        return
    if not every:
        g_new, p_new = g_new[mv], p_new[mv]
    r_new, ja_new = _lin_aug(g_new, p_new, b.meas, b.w8)
    if b.long:
        rows = s.act if every else s.act[mv]
        pa = s.p if every else s.p[mv]
        _keep_poses_that_fit(g_new, p_new, r_new, ja_new, pa, b.r[rows], b.meas, b.w8)
    if b.pose_iterations > 0 and s.check:
        f_new = (r_new * r_new).sum(axis=-1)
        nm = s.newton if every else s.newton[mv]
        if nm.any():
            # variable projection: the poses follow the new shape (the curved valley)
            p_new, r_new, ja_new, f_new = _pose_steps(
                g_new,
                p_new,
                r_new,
                ja_new,
                f_new,
                b.meas,
                b.w8,
                b.pose_iterations,
                1e-6,
                s.lam if every else s.lam[mv],
                nm,
            )
        c2m = f_new.sum(axis=-1)  # (as before, not the einsum: same rounding)
    else:
        c2m = np.einsum("kna,kna->k", r_new, r_new)
    if every:
        s.chi2_new = c2m
        s.accept = c2m < s.chi2
    else:
        s.chi2_new = s.chi2.copy()
        s.chi2_new[mv] = c2m
        s.accept = np.zeros(ka, dtype=bool)
        s.accept[mv] = c2m < s.chi2[mv]
    s.g_new, s.p_new, s.r_new, s.ja_new = g_new, p_new, r_new, ja_new


def _update_damping(b: _Batch, s: _Step) -> None:
    """Nielsen's damping update (the accepted and the rejected branch only where taken), and
    the switch to Newton; written to the batch (lambda, the Newton phase, stale blocks)."""
    accept, lama, c2 = s.accept, s.lam, s.chi2
    if accept.all():
        rho = (c2 - s.chi2_new) / np.maximum(s.predicted, 1e-300)
        rho = np.minimum(np.maximum(rho, 0.0), 1.0)
        lam_new = np.maximum(lama * np.maximum(b.shrink, 1.0 - (2.0 * rho - 1.0) ** 3), 1e-15)
    elif accept.any():
        rho = (c2 - s.chi2_new) / np.maximum(s.predicted, 1e-300)
        rho = np.minimum(np.maximum(rho, 0.0), 1.0)
        factor = np.maximum(b.shrink, 1.0 - (2.0 * rho - 1.0) ** 3)
        lam_new = np.where(accept, np.maximum(lama * factor, 1e-15), lama * 4.0)
    else:
        lam_new = lama * 4.0
    switching = b.newton_phase and not s.newton.all()
    if switching:
        # With thousands of frames a rejected Gauss-Newton step that predicted little also
        # switches: its joint step moves a few frames near a fold far off (chi2 28,277 ->
        # 124,805 for a predicted decrease of 95 at 30,000 frames), and each rejection only
        # raised lambda (8 rejections); Newton's embedded per-frame pose steps keep the
        # frames that gain (the same fit took 18 -> 9 iterations).
        switch = ~s.newton & (accept | b.long) & (s.predicted <= NEWTON_SWITCH * c2)
        if switch.any():  # a new model: trust it afresh
            lam_new[switch] = np.minimum(lam_new[switch], 1e-3)
            b.newton[s.act[switch]] = True
    moved = accept | (switch if switching else False)
    if s.full:
        b.lam = lam_new
        b.stale = moved  # a new array each iteration (a new model: its blocks built again)
    else:
        b.lam[s.act] = lam_new
        b.stale[s.act] = moved


def _take_accepted(b: _Batch, s: _Step) -> None:
    """The accepted trial points replace the starts' points."""
    accept = s.accept
    if not accept.any():
        return
    if s.full and s.every and accept.all():  # the new arrays replace the old ones
        b.g, b.p, b.r, b.ja, b.chi2 = s.g_new, s.p_new, s.r_new, s.ja_new, s.chi2_new
        return
    sel = accept if s.every else accept[s.moving]  # the accepted among the evaluated starts
    acc = s.act[sel] if s.every else s.act[s.moving[sel]]
    b.g[acc], b.p[acc], b.r[acc] = s.g_new[sel], s.p_new[sel], s.r_new[sel]
    b.ja[acc] = s.ja_new[sel]
    b.chi2[acc] = s.chi2_new[accept]


def _profile_batch(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    max_iter: int,
    xtol: float,
    ftol: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``refine_batch`` from ``PROFILE_FRAMES`` frames on: :func:`_profile_fit` per start."""
    k, n = p.shape[:2]
    g, p = g.copy(), p.copy()
    r = np.empty((k, n, 6))
    chi2 = np.empty(k)
    iters = np.zeros(k, dtype=int)
    converged = np.zeros(k, dtype=bool)
    for j in range(k):
        g[j], p[j], r[j], chi2[j], iters[j], converged[j] = _profile_fit(
            g[j], p[j], meas, w8, max_iter, xtol, ftol
        )
    return g, p, r, chi2, iters, converged


def _profile_fit(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    max_iter: int,
    xtol: float,
    ftol: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, int, bool]:
    """The profile (variable projection) iteration of one start: Newton on the shape alone.

    The profile chi2 of a shape is the chi2 with every frame's pose at its optimum for that
    shape (``optimise_poses``, ``PROFILE_POSE_ITERATIONS`` steps per frame).  Each iteration
    builds the Newton blocks at the current point (poses optimal: the Schur complement S is
    then the profile chi2's Hessian, the reduced gradient its gradient), takes the shape step
    of S (damped by lambda only where S or a pose block is not positive definite), re-optimises
    every pose from its back-substituted step for the trial shape, and accepts the trial if the
    profile chi2 fell; else the step is halved (``PROFILE_HALVINGS``), then lambda rises.  A
    frame whose chi2 rose by more than ``LONG_JUMP_CHI2`` on the trial (thrown to another pose
    basin by the back-substitution) keeps its old pose re-optimised where that fits better.

    Stops (converged) when the shape's Newton decrement is below ``PROFILE_STEP_STD`` standard
    deviations, the predicted decrease below ``ftol`` times chi2, or the relative shape step
    below ``xtol``; also (converged if within ``LONG_STEP_STD`` standard deviations) after two
    iterations in a row without an accepted step.  Returns (shape (4,), poses (N, 5),
    standardised residuals (N, 6), chi2, iterations, converged).
    """
    n = p.shape[0]
    rows = np.ndim(w8) == 2
    p, r = optimise_poses(g, p, meas, w8, PROFILE_POSE_ITERATIONS)
    f = np.sum(r * r, axis=1)
    c2 = float(f.sum())
    lam, failures, it, converged = 0.0, 0, 0, False
    blocks: tuple[np.ndarray, ...] = ()
    while it < max_iter:
        it += 1
        if not blocks:
            r3, ja = _lin_aug(g[None], p[None], meas, w8)
            blocks = _normal_blocks(g[None], p[None], r3, ja, w8, np.ones(1, dtype=bool))
        for _ in range(12):  # a model that is not positive definite gets damping at once
            dg, dl, pred, pd, dec = _damped_solve(*blocks, np.array([lam]), True, decrement=True)
            if (pd[0] and pred[0] > 0) or lam > 1e12:
                break
            lam = max(10.0 * lam, 1e-4)
        dg, dl = dg[0], dl[0]
        kappa = c2 / n
        rel_step = float(np.max(np.abs(dg) / np.maximum(np.abs(g), 1.0)))
        if (
            dec[0] <= PROFILE_STEP_STD**2 * kappa
            or pred[0] <= ftol * max(c2, 1e-300)
            or rel_step < xtol
        ):
            converged = True
            break
        accepted = False
        step = 1.0
        for _ in range(int(PROFILE_HALVINGS) + 1):
            g_t = g + step * dg
            if np.all(np.isfinite(g_t)) and g_t[0] > 0:
                p_t, r_t = optimise_poses(g_t, p + step * dl, meas, w8, PROFILE_POSE_ITERATIONS)
                f_t = np.sum(r_t * r_t, axis=1)
                jumped = np.flatnonzero(~(f_t <= f + LONG_JUMP_CHI2))
                if jumped.size:
                    w_j = w8[jumped] if rows else w8
                    p_j, r_j = optimise_poses(
                        g_t, p[jumped], meas[jumped], w_j, PROFILE_POSE_ITERATIONS
                    )
                    f_j = np.sum(r_j * r_j, axis=1)
                    better = ~(f_t[jumped] <= f_j)
                    p_t[jumped[better]] = p_j[better]
                    f_t[jumped[better]] = f_j[better]
                c_t = float(f_t.sum())
                if c_t < c2:
                    g, p, f, c2 = g_t, p_t, f_t, c_t
                    accepted = True
                    break
            step *= 0.5
        if accepted:
            blocks, failures = (), 0
            lam = 0.0 if lam <= 1e-4 else lam / 10.0
            continue
        failures += 1
        if failures >= 2 or lam > 1e12:
            converged = bool(dec[0] <= LONG_STEP_STD**2 * kappa)
            break
        lam = max(10.0 * lam, 1e-4)
    r3, _ = _lin_aug(g[None], p[None], meas, w8)
    return g, p, r3[0], float(np.sum(r3 * r3)), it, converged


PROFILE_POSE_ITERATIONS = 10
"""Pose steps per frame (``optimise_poses``) for each trial shape of the profile iteration:
from the back-substituted poses a frame converges in a few; the rest stop early."""


LONG_JUMP_CHI2 = 9.0
"""Long sequences: a frame whose chi2 rises by more than this on a trial step ..."""


def _keep_poses_that_fit(
    g_new: np.ndarray,
    p_new: np.ndarray,
    r_new: np.ndarray,
    ja_new: np.ndarray,
    p_old: np.ndarray,
    r_old: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
) -> None:
    """A trial step of a long sequence, safeguarded per frame (in place).

    The joint step moves every pose by its Schur back-substitution, exact for the quadratic
    model only; a frame near a fold of (10) can be thrown far (100,000 frames, held-out scene
    1002: steps predicted to lower chi2 by 6 raised it by 4,000, lambda rose and fell for 44
    iterations).  Each frame whose chi2 rises by more than ``LONG_JUMP_CHI2`` instead starts
    from its old pose polished for the trial shape (``optimise_poses``) where that fits it
    better.  The trial is still a point (shape, poses) whose chi2 is evaluated exactly, so
    accepting it is sound; only the poses of the thrown frames differ from the joint step's.
    """
    f_new = np.sum(r_new * r_new, axis=-1)
    f_old = np.sum(r_old * r_old, axis=-1)
    ks, ns = np.nonzero(f_new > f_old + LONG_JUMP_CHI2)
    if ks.size == 0:
        return
    w_rows = w8[ns] if np.ndim(w8) == 2 else w8
    pj, rj = optimise_poses(g_new[ks], p_old[ks, ns], meas[ns], w_rows, 10)
    better = np.sum(rj * rj, axis=1) < f_new[ks, ns]
    ks, ns, pj = ks[better], ns[better], pj[better]
    for k in np.unique(ks):
        sel = ns[ks == k]
        p_new[k, sel] = pj[ks == k]
        rk, jk = _lin_aug(g_new[k : k + 1], p_new[k : k + 1, sel], meas[sel], _rows(w8, sel))
        r_new[k, sel], ja_new[k, sel] = rk[0], jk[0]


LONG_FRAMES = 1000
"""From this many frames on, lambda shrinks by up to ``LONG_SHRINK`` per well-predicted step."""

LONG_SHRINK = 0.1
"""Nielsen's update shrinks lambda by at most 1/3 per step.  With thousands of frames the last
iterations are a creep along the valley of c (its Schur-reduced curvature is a small fraction
of the Gauss-Newton diagonal that scales the damping), each step shortened by lambda until
lambda is below that fraction: 30,000 frames, the predicted decrease fell 2.7-fold per step for
12 steps.  Below ``LONG_FRAMES`` frames 1/3 (the headline's fits unchanged)."""

LONG_STEP_STD = 0.1
"""From ``LONG_FRAMES`` frames on, the iteration stops once the model's predicted decrease of
chi2 is below 0.5 * LONG_STEP_STD**2 * kappa, kappa = chi2 / N the noise scale: the step left
is then below this many standard deviations of the shape (rather than ``ftol`` of chi2).  With
many frames the last iterations are a creep of inexact Newton models (100,000 frames, held-out
scene 1002: chi2 fell by 0.3 over 15 iterations, predicted decreases 0.001 to 0.2), at a cost
of half a second each, for a fraction of a standard deviation that the estimator's bias
exceeds twentyfold (``bench.scale``'s ``scale_error_std``).  Those frames' poses are polished
for the final shape at the end (``optimise_poses``).  Noise-free data keep converging to the
exact fit: the threshold is relative to chi2."""

PROFILE_FRAMES = 10_000
"""From this many frames on the fit is the profile iteration (:func:`_profile_batch`): Newton
steps on the shape alone, every pose re-optimised for each trial shape.  The joint damped
iteration mispredicts there: the predicted decrease of each step counts the poses of a few
frames near a fold of (10), which gain far less than predicted, so lambda rises and the shape
creeps (100,000 frames, held-out scene 1003: 25 and 23 iterations, 15.2 s and 13.9 s, the shape
moving 0.001 standard deviations per step).  The profile iteration fits the same problems in 5
and 3 steps (4.4 s and 2.7 s; chi2 0.34 above and 0.0002 below the joint iteration's, of
87,858).  Below, the joint iteration stays: the
marginal step that follows depends on its start along singular surfaces of its objective
(``refine.marginal``; a 1,200-frame scene, ``tests/test_pipeline_speed_paths.py``)."""

PROFILE_STEP_STD = 0.01
"""The profile iteration stops once the shape's Newton decrement (the undamped step of the
profile model, :func:`_damped_solve` with ``decrement``) is below this many standard deviations
of the shape.  Near the optimum one step takes it from about 1 standard deviation to 1e-3, so
the tight threshold costs no extra step in the smooth case."""

PROFILE_HALVINGS = 4
"""A trial shape step that does not lower the profile chi2 is halved up to this many times
before the damping rises (a frame whose pose optimum jumps between branches of (10) makes the
profile chi2 kinked: a full step overshot on held-out scene 1003, half of it gained)."""

NEWTON_SWITCH = 1e-2
"""Switch to Newton once a Gauss-Newton step predicts a decrease below this times chi2."""


def _frame_search(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_delta: int = 8,
    n_iter: int = 5,
) -> np.ndarray | None:
    """Per frame, shape ``g`` (4,) fixed: a better pose basin than ``p`` (N, 5), or None.

    A frame's pose can have several local minima (in delta, and tau against -tau near the fold
    tau = 0); which one a local iteration ends in depends on its path.  Starts on a grid of
    ``n_delta`` delta offsets, each with tau and -tau, get ``n_iter`` Newton steps (vectorised
    over starts and frames); a frame moves to the best start if that lowers its chi2.
    """
    offsets = np.arange(n_delta) * (2.0 * np.pi / n_delta)
    cands = np.repeat(p[None], 2 * n_delta, axis=0)  # (2 n_delta, N, 5)
    cands[:, :, 0] += np.concatenate([offsets, offsets])[:, None]
    cands[:, :, 0] = np.mod(cands[:, :, 0] + np.pi, 2.0 * np.pi) - np.pi
    cands[n_delta:, :, 1] *= -1.0
    gm = np.repeat(g[None], len(cands), axis=0)
    r, ja = _lin_aug(gm, cands, meas, w8)
    f = np.sum(r * r, axis=-1)
    f_now = f[0].copy()
    cands, r, ja, f = _pose_steps(gm, cands, r, ja, f, meas, w8, n_iter, 0.0)
    cols = np.arange(p.shape[0])
    best = np.argmin(f, axis=0)
    better = f[best, cols] < np.minimum(f_now, f[0]) - 1e-9 * (1.0 + f_now)
    if not better.any():
        return None
    return np.where(better[:, None], cands[best, cols], p)


def refine(
    obs: Observations | np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    max_iter: int = 100,
    xtol: float = 1e-11,
    ftol: float = 1e-10,
    covariance: bool = True,
    frame_weights: np.ndarray | None = None,
    pose_iterations: int = 1,
    frame_search: bool = False,
) -> RefineResult:
    """Maximum-likelihood fit of the shape and all poses (Levenberg-Marquardt, Schur complement).

    Args:
        obs: observations, or an (N, 6) array ax, ay, bx, by, psi_a, psi_b (radians).
        shape: (4,) start c, alpha, beta, phi (input units, radians).
        poses: (N, 5) start delta, tau, theta, tx, ty.
        point_sigma: standard deviation of image point coordinates (input units).
        tangent_sigma: standard deviation of tangent angles (radians).
        max_iter: iteration limit.
        xtol: stop when every relative parameter step is below this.
        ftol: stop when the decrease of chi2 the (damped) model predicts is below ftol * chi2.
        covariance: compute the shape covariance (inverse Schur-reduced normal matrix).
        frame_weights: optional (N,) weights of the frames (robust reweighting); the
            returned residuals and chi2 are unweighted.
        pose_iterations: embedded pose iterations after each shape step (see refine_batch).
        frame_search: after convergence look for better pose basins frame by frame
            (:func:`_frame_search`) and iterate again from them while that lowers chi2.
    """
    meas = _measurements(obs)
    w8 = _weights(point_sigma, tangent_sigma)
    if frame_weights is not None:
        w8_fit = w8[None, :] * np.sqrt(np.asarray(frame_weights, float))[:, None]
    else:
        w8_fit = w8

    def run(s0: np.ndarray, p0: np.ndarray, n: int):
        out = refine_batch(
            meas,
            s0[None],
            p0[None],
            point_sigma,
            tangent_sigma,
            n,
            xtol,
            ftol,
            frame_weights=frame_weights,
            pose_iterations=pose_iterations,
        )
        return out[0][0], out[1][0], out[2][0], float(out[3][0]), int(out[4][0]), bool(out[5][0])

    g, p, r, chi2_fit, iters, conv = run(
        np.asarray(shape, float), np.asarray(poses, float), max_iter
    )
    for _ in range(3 if frame_search else 0):
        if iters >= max_iter:
            break
        p_sw = _frame_search(g, p, meas, w8_fit)
        if p_sw is None:
            break
        g2, p2, r2, chi2_2, it2, conv2 = run(g, p_sw, max_iter - iters)
        iters += it2
        if not chi2_2 < chi2_fit - 1e-9 * (1.0 + chi2_fit):
            break
        g, p, r, chi2_fit, conv = g2, p2, r2, chi2_2, conv2
    if frame_weights is not None:  # refine_batch's residuals are weighted
        r = standardised_residuals(g, p, meas, w8)
    chi2 = np.array([np.sum(r * r)])
    cov = None
    if covariance:
        _, jg, jl = _linearise(g, p, meas, w8)
        cov = schur_covariance(jg, jl)
    frame_chi2 = np.sum(r * r, axis=1)
    return RefineResult(g, p, float(chi2[0]), frame_chi2, r, cov, iters, conv)


def crlb_covariance(
    shape: np.ndarray, poses: np.ndarray, point_sigma: float, tangent_sigma: float
) -> np.ndarray | None:
    """(4, 4) Cramer-Rao bound of the shape's covariance at the true parameters.

    ``tangent_sigma`` in radians, ``point_sigma`` in input units; poses (N, 5) are nuisance
    parameters (their uncertainty is accounted for by the Schur complement).
    """
    w8 = _weights(point_sigma, tangent_sigma)
    p = np.asarray(poses, float)
    _, jg, jl = measurement_model.predict_with_jacobians(*np.asarray(shape, float), *p.T)
    return schur_covariance(jg * w8[None, :, None], jl * w8[None, :, None])


def crlb(
    shape: np.ndarray, poses: np.ndarray, point_sigma: float, tangent_sigma: float
) -> np.ndarray:
    """(4,) Cramer-Rao lower bounds on the standard deviations of c, alpha, beta, phi.

    ``shape`` (c, alpha, beta, phi) and ``poses`` (N, 5) are the true parameters; ``point_sigma``
    in input units, ``tangent_sigma`` in radians.  Infinite where the bound does not exist.
    """
    cov = crlb_covariance(shape, poses, point_sigma, tangent_sigma)
    if cov is None:
        return np.full(4, np.inf)
    return np.sqrt(np.clip(np.diag(cov), 0.0, None))
