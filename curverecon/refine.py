"""Maximum-likelihood refinement over all frames (Levenberg-Marquardt with a Schur complement).

Parameters: the shape (c, alpha, beta, phi) shared by all frames and per frame the pose
(delta, tau, theta, tx, ty) (input units, radians).  Residuals per frame, in units of their
standard deviation: the image points A', B' (``(pred - obs) / point_sigma``) and the tangent
angles (``wrap(pred - obs) / tangent_sigma``, wrapped to (-pi/2, pi/2]: a tangent is a line).
Predictions and their analytic Jacobians come from ``measurement_model.predict_with_jacobians``.

The normal matrix is block-arrow shaped: a 4x4 shape block U, per-frame 5x5 pose blocks V_i and
4x5 couplings W_i.  Each step eliminates the pose blocks (batched 5x5 inverses, einsum; no Python
loop over frames) and solves the 4x4 Schur complement S = U - sum W_i V_i^-1 W_i^T.  The shape's
covariance is S^-1 at the solution (undamped, Gauss-Newton); at the true parameters it is the
Cramer-Rao bound.  ``refine_batch`` runs K independent starts at once (a leading axis).

Two phases per start.  Far from a minimum the model is Gauss-Newton (convex; its short steps
keep the start's basin, as plain LM always did).  Once an accepted Gauss-Newton step predicts a
decrease below ``NEWTON_SWITCH`` times chi2 the model becomes Newton's: the blocks get the
second-order term sum_k r_k d2 r_k (``_curvature``, analytic: B' = A' + c cos(tau) (cos theta,
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

from dataclasses import dataclass

import numpy as np

from curverecon.generated import measurement_model
from curverecon.observations import Observations, wrap_line_angle


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


def optimise_poses(
    g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray, n_iter: int
) -> tuple[np.ndarray, np.ndarray]:
    """A few Gauss-Newton steps on every frame's pose with the shape held fixed (vectorised).

    "Embedded point iterations": keeping the poses at their optimum for the current shape makes
    the outer iteration follow the curved valley (c against every tau) in a few steps.  A frame
    keeps a step only if it lowers that frame's chi2.  ``g`` is one shape (4,) or one per row of
    ``p`` (N, 4).  Returns (poses, standardised residuals).
    """
    g = np.asarray(g, float)
    gargs = list(g.T) if g.ndim == 2 else list(g)  # (N, 4): one shape per row

    def resid(poses):
        r = measurement_model.predict(*gargs, *poses.T) - meas
        r[:, 4:6] = wrap_line_angle(r[:, 4:6])
        return r * w8

    r = resid(p)
    f = np.sum(r * r, axis=1)
    for _ in range(n_iter):
        pred, _, jl = measurement_model.predict_with_jacobians(*gargs, *p.T)
        jl = jl * w8[None, :, None]
        v = np.einsum("nki,nkj->nij", jl, jl)
        v = v + 1e-9 * np.einsum("nii->ni", v)[:, :, None] * np.eye(5)
        el = np.einsum("nki,nk->ni", jl, r)
        dl = -np.einsum("nij,nj->ni", _batched_inverse(v), el)
        p_try = p + dl
        r_try = resid(p_try)
        f_try = np.sum(r_try * r_try, axis=1)
        take = f_try < f
        if not take.any():
            break
        p = np.where(take[:, None], p_try, p)
        r = np.where(take[:, None], r_try, r)
        f = np.where(take, f_try, f)
    return p, r


def _batched_inverse(v: np.ndarray) -> np.ndarray:
    """Inverse of each 5x5 block; nearly singular blocks get a tiny relative ridge."""
    m = v.shape[-1]
    vr = np.array(v, dtype=float, copy=True).reshape(*v.shape[:-2], m * m)
    diag = vr[..., :: m + 1]  # a view: the diagonal of each block
    diag += 1e-13 * np.maximum(np.sum(diag, axis=-1), 1e-300)[..., None]
    return np.linalg.inv(vr.reshape(v.shape))


def schur_information(jg: np.ndarray, jl: np.ndarray) -> np.ndarray:
    """(4, 4) Schur-reduced normal matrix of the shape, the poses eliminated: U - sum W V^-1 W^T
    from the standardised Jacobians (N, 6, 4) and (N, 6, 5)."""
    u = np.einsum("nki,nkj->ij", jg, jg)
    v = np.einsum("nki,nkj->nij", jl, jl)
    w = np.einsum("nki,nkj->nij", jg, jl)
    vinv = _batched_inverse(v)
    s = u - np.einsum("nij,njk,nlk->il", w, vinv, w)
    return 0.5 * (s + s.T)


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


def _split(g: np.ndarray, p: np.ndarray) -> list[np.ndarray]:
    """Arguments of the generated functions for batched shapes (K, 4) and poses (K, N, 5)."""
    return [g[:, i : i + 1] for i in range(4)] + [p[..., i] for i in range(5)]


def _lin_batch(g, p, meas, w8):
    pred, jg, jl = measurement_model.predict_with_jacobians(*_split(g, p))
    r = pred - meas
    r[..., 4:6] = wrap_line_angle(r[..., 4:6])
    r *= w8
    return r, jg * w8[..., None], jl * w8[..., None]


def _angle_hessian(
    sgn: float | np.ndarray, tau: np.ndarray, a: np.ndarray, gam: np.ndarray
) -> tuple[np.ndarray, ...]:
    """Second derivatives of atan2(m1, m0) over (tau, a, gamma) of a projected tangent.

    m0 = sgn cos(tau) cos(a) + sin(tau) sin(a) sin(gamma), m1 = sin(a) cos(gamma) is the
    direction R_y(tau) R_x(delta) t up to the rotation theta (which only adds to the angle):
    tangent at B: sgn = -1, a = alpha, gamma = delta; at A: sgn = 1, a = beta, gamma = delta + phi.
    Returns the entries (tt, ta, tg, aa, ag, gg) of the symmetric 3x3 Hessian.
    """
    ct, st = np.cos(tau), np.sin(tau)
    ca, sa = np.cos(a), np.sin(a)
    cg, sg = np.cos(gam), np.sin(gam)
    m0 = sgn * ct * ca + st * sa * sg
    m1 = sa * cg
    # first derivatives of m0 (m0_t, m0_a, m0_g) and m1 (m1_t = 0, m1_a, m1_g)
    d0 = (-sgn * st * ca + ct * sa * sg, -sgn * ct * sa + st * ca * sg, st * sa * cg)
    d1a, d1g = ca * cg, -sa * sg
    # second derivatives of m0 and m1 (m1 does not depend on tau)
    h0tt = -sgn * ct * ca - st * sa * sg
    h0 = {"tt": h0tt, "ta": sgn * st * sa + ct * ca * sg, "tg": ct * sa * cg}
    h0.update(aa=h0tt, ag=st * ca * cg, gg=-st * sa * sg)
    h1 = {"aa": -m1, "ag": -ca * sg, "gg": -m1}
    inv = 1.0 / (m0 * m0 + m1 * m1)
    d1 = (0.0, d1a, d1g)
    grad = [(m0 * d1[i] - m1 * d0[i]) * inv for i in range(3)]
    dden = [2.0 * (m0 * d0[i] + m1 * d1[i]) for i in range(3)]
    out = []
    for key, i, j in (("tt", 0, 0), ("ta", 0, 1), ("tg", 0, 2), ("aa", 1, 1), ("ag", 1, 2)):
        # symmetric part of (m0 h1 - m1 h0) / den - grad_i dden_j / den
        num = m0 * h1.get(key, 0.0) - m1 * h0[key]
        out.append((num - 0.5 * (grad[i] * dden[j] + grad[j] * dden[i])) * inv)
    out.append((m0 * h1["gg"] - m1 * h0["gg"] - grad[2] * dden[2]) * inv)
    return tuple(out)


def _curvature_map() -> np.ndarray:
    """(17, 81) map of the terms of :func:`_curvature` onto a flattened symmetric 9x9 block."""
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


def _curvature(g: np.ndarray, p: np.ndarray, r: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """Second-order term sum_k r_k d2 r_k of the residuals of every frame, (K, N, 9, 9).

    Over (c, alpha, beta, phi, delta, tau, theta, tx, ty).  Gauss-Newton drops it; here it is
    not small: near the fold tau = 0 (c' close to c, often c' > c with noise) the B' residual's
    curvature c cos(tau) dwarfs the Gauss-Newton term in tau (Gauss-Newton overshoots, zig-zag),
    and the tangent angles' curvature is of the order of their Gauss-Newton term where a
    projected tangent is short.  With it the iteration is Newton's method (quadratic
    convergence); the damping and the positive-definiteness test keep it safe.
    """
    c = g[:, 0, None]
    tau, theta = p[..., 1], p[..., 2]
    ct, st = np.cos(tau), np.sin(tau)
    cth, sth = np.cos(theta), np.sin(theta)
    wp = w8[..., 2]
    q = wp * (r[..., 2] * cth + r[..., 3] * sth)  # B' residual along A'B'
    qp = wp * (r[..., 3] * cth - r[..., 2] * sth)  # and across
    qcc = -q * c * ct
    # both tangents at once (last axis: A, B)
    a = np.stack([g[:, 2], g[:, 1]], -1)[:, None, :]  # (K, 1, 2): the same in every frame
    gam = p[..., 0, None] + np.stack(
        [np.broadcast_to(g[:, 3, None], tau.shape), np.zeros_like(tau)], -1
    )
    h = _angle_hessian(np.array([1.0, -1.0]), tau[..., None], a, gam)
    wr = w8[..., 4:6] * r[..., 4:6]
    terms = np.empty((*q.shape, 17))
    terms[..., 0] = -q * st
    terms[..., 1] = qp * ct
    terms[..., 2] = qcc
    terms[..., 3] = qcc
    terms[..., 4] = -qp * c * st
    for k in range(6):
        hk = h[k] * wr
        terms[..., 5 + k] = hk[..., 0]
        terms[..., 11 + k] = hk[..., 1]
    out = np.zeros((*q.shape, 81))
    out[..., _CURVATURE_COPY[0]] = terms[..., _CURVATURE_COPY[1]]
    for j, ks in _CURVATURE_SUMS:
        out[..., j] = np.sum(terms[..., ks], axis=-1)
    return out.reshape(*q.shape, 9, 9)


def _add_curvature(
    u: np.ndarray | None, v: np.ndarray, w: np.ndarray | None, s: np.ndarray
) -> None:
    """Add the per-frame second-order blocks ``s`` (K, N, 9, 9) to U, V and W."""
    v += s[..., 4:, 4:]
    if w is not None:
        w += s[..., :4, 4:]
        u += np.sum(s[..., :4, :4], axis=-3)


try:  # numpy's batched Cholesky gufunc: NaN factors (no exception) where a block is not PD
    from numpy.linalg import _umath_linalg

    _CHOLESKY_LO = _umath_linalg.cholesky_lo
except (ImportError, AttributeError):  # pragma: no cover - other numpy versions
    _CHOLESKY_LO = None


def _positive_definite(m: np.ndarray) -> np.ndarray:
    """(...,) whether each symmetric block of ``m`` (..., n, n) is positive definite.

    The test is whether a Cholesky factorisation succeeds.  If one block of the batch fails,
    the blocks are told apart by numpy's Cholesky gufunc (failed factors are NaN), which costs a
    fraction of the eigenvalue fallback (used where that gufunc is not available).
    """
    try:
        np.linalg.cholesky(m)
        return np.ones(m.shape[:-2], dtype=bool)
    except np.linalg.LinAlgError:
        if _CHOLESKY_LO is None:  # pragma: no cover
            return np.linalg.eigvalsh(m)[..., 0] > 0
    with np.errstate(invalid="ignore", over="ignore", divide="ignore", under="ignore"):
        factor = _CHOLESKY_LO(m, signature="d->d")
    return np.all(np.isfinite(factor), axis=(-2, -1))


def _pose_steps(
    g: np.ndarray,
    p: np.ndarray,
    r: np.ndarray,
    jg: np.ndarray,
    jl: np.ndarray,
    f: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    rtol: float,
    lam: np.ndarray | None = None,
    mask: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Damped Gauss-Newton steps on every frame's pose, shape ``g`` (K, 4) fixed; batched (K, N).

    Damped like the outer iteration: ``lam`` (K,) times the Gauss-Newton diagonal (None:
    undamped).  Each frame keeps its step only if the step lowers that frame's
    chi2 ``f`` (K, N) (and, given ``mask`` (K,), only in the starts it marks).  Stops after
    ``n_iter`` steps or when the steps gain less than ``rtol``
    times the total chi2.  Returns the updated (p, r, jg, jl, f), linearised at the new poses.
    """
    for _ in range(n_iter):
        jlt = np.swapaxes(jl, -1, -2)
        v = jlt @ jl
        if lam is not None:
            dv = np.einsum("...ii->...i", v)
            v = v.reshape(*v.shape[:-2], 25).copy()
            v[..., ::6] += lam[:, None, None] * dv
            v = v.reshape(*v.shape[:-1], 5, 5)
        el = jlt @ r[..., None]
        dl = -(_batched_inverse(v) @ el)[..., 0]
        descent = np.sum(dl * el[..., 0], axis=-1) < 0
        p_try = p + dl
        r_t, jg_t, jl_t = _lin_batch(g, p_try, meas, w8)
        f_t = np.sum(r_t * r_t, axis=-1)
        take = (f_t < f) & descent
        if mask is not None:
            take &= mask[:, None]
        if not take.any():
            break
        gain = np.sum(np.where(take, f - f_t, 0.0))
        p = np.where(take[..., None], p_try, p)
        r = np.where(take[..., None], r_t, r)
        jg = np.where(take[..., None, None], jg_t, jg)
        jl = np.where(take[..., None, None], jl_t, jl)
        f = np.where(take, f_t, f)
        if gain <= rtol * np.sum(f):
            break
    return p, r, jg, jl, f


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
    Returns:
        shapes (K, 4), poses (K, N, 5), residuals (K, N, 6) standardised, chi2 (K,),
        iterations (K,), converged (K,) bool.
    """
    meas = _measurements(obs)
    w8 = _weights(point_sigma, tangent_sigma)
    if frame_weights is not None:
        w8 = w8[None, :] * np.sqrt(np.asarray(frame_weights, float))[:, None]
    g = np.array(shapes, dtype=float, ndmin=2)
    p = np.array(poses, dtype=float, ndmin=3)
    k = g.shape[0]
    r, jg, jl = _lin_batch(g, p, meas, w8)
    chi2 = np.einsum("kna,kna->k", r, r)
    lam = np.full(k, 1e-3)
    # Gauss-Newton while far from a minimum (convex model, short steps: the start's basin is
    # kept); Newton with embedded pose steps once a Gauss-Newton step predicts little
    newton = np.zeros(k, dtype=bool)
    done = np.zeros(k, dtype=bool)
    converged = np.zeros(k, dtype=bool)
    iters = np.zeros(k, dtype=int)
    for it in range(max_iter):
        act = np.flatnonzero(~done)
        if act.size == 0:
            break
        if it >= drop_after and drop_factor is not None and act.size > 1:
            # give up on starts far worse than the best one (they are not the answer)
            hopeless = chi2[act] > drop_factor * (np.min(chi2) + act_floor)
            done[act[hopeless]] = True
            act = act[~hopeless]
        iters[act] += 1
        if act.size == k:  # all active: views, no copies
            ga, pa, ra, jga, jla, lama, c2 = g, p, r, jg, jl, lam.copy(), chi2.copy()
        else:
            ga, pa, ra, jga, jla, lama, c2 = (
                g[act],
                p[act],
                r[act],
                jg[act],
                jl[act],
                lam[act],
                chi2[act],
            )
        jgt = np.swapaxes(jga, -1, -2)
        jlt = np.swapaxes(jla, -1, -2)
        u = np.sum(jgt @ jga, axis=1)
        v = jlt @ jla
        w = jgt @ jla
        eg = np.sum(jgt @ ra[..., None], axis=1)[..., 0]
        el = (jlt @ ra[..., None])[..., 0]
        du = np.einsum("kii->ki", u).copy()
        dv = np.einsum("knii->kni", v).copy()
        nwt = newton[act]
        if nwt.all():
            _add_curvature(u, v, w, _curvature(ga, pa, ra, w8))
        elif nwt.any():
            i = np.flatnonzero(nwt)
            un, vn, wn = u[i], v[i], w[i]
            _add_curvature(un, vn, wn, _curvature(ga[i], pa[i], ra[i], w8))
            u[i], v[i], w[i] = un, vn, wn
        # Newton (or Gauss-Newton) model; an indefinite damped model gets more damping at once
        check = bool(nwt.any())  # a damped Gauss-Newton matrix is positive definite
        dg, dl, predicted, pd = _damped_step(u, v, w, eg, el, du, dv, lama, check)
        saddle = np.zeros(act.size, dtype=bool)  # the Newton model was indefinite
        for _ in range(12):
            bad = ~(pd & (predicted > 0)) & (lama <= 1e12)
            if not bad.any():
                break
            saddle |= bad
            lama = np.where(bad, np.maximum(lama * 10.0, 1e-4), lama)
            dg2, dl2, pred2, pd2 = _damped_step(u, v, w, eg, el, du, dv, lama, check)
            dg = np.where(bad[:, None], dg2, dg)
            dl = np.where(bad[:, None, None], dl2, dl)
            predicted = np.where(bad, pred2, predicted)
            pd = np.where(bad, pd2, pd)
        step = np.maximum(
            np.max(np.abs(dg) / np.maximum(np.abs(ga), 1.0), axis=1),
            np.max(np.abs(dl) / np.maximum(np.abs(pa), 1.0), axis=(1, 2)),
        )
        indefinite = ~(predicted > 0) | ~pd
        small = (step < xtol) | (predicted <= ftol * np.maximum(c2, 1e-300)) | (lama > 1e12)
        small &= ~saddle | (lama > 1e12)  # a tiny damped step near a saddle is no convergence
        small &= ~indefinite | (lama > 1e12)
        converged[act[small & (lama <= 1e12)]] = True
        done[act[small]] = True
        g_new, p_new = ga + dg, pa + dl
        ok = np.all(np.isfinite(g_new), axis=1) & np.all(np.isfinite(p_new), axis=(1, 2))
        ok &= (g_new[:, 0] > 0) & ~small & ~indefinite
        g_new = np.where(ok[:, None], g_new, ga)
        p_new = np.where(ok[:, None, None], p_new, pa)
        r_new, jg_new, jl_new = _lin_batch(g_new, p_new, meas, w8)
        if pose_iterations > 0 and nwt.any():
            # variable projection: the poses follow the new shape (the curved valley)
            f_new = np.sum(r_new * r_new, axis=-1)
            p_new, r_new, jg_new, jl_new, f_new = _pose_steps(
                g_new,
                p_new,
                r_new,
                jg_new,
                jl_new,
                f_new,
                meas,
                w8,
                pose_iterations,
                1e-6,
                lama,
                nwt,
            )
            chi2_new = np.sum(f_new, axis=-1)
        else:
            chi2_new = np.einsum("kna,kna->k", r_new, r_new)
        accept = ok & (chi2_new < c2)
        rho = (c2 - chi2_new) / np.maximum(predicted, 1e-300)
        factor = np.maximum(1.0 / 3.0, 1.0 - (2.0 * np.clip(rho, 0.0, 1.0) - 1.0) ** 3)
        lam[act] = np.where(accept, np.maximum(lama * factor, 1e-15), lama * 4.0)
        switch = ~nwt & accept & (predicted <= NEWTON_SWITCH * c2) & newton_phase
        newton[act] = nwt | switch
        lam[act[switch]] = np.minimum(lam[act[switch]], 1e-3)  # a new model: trust it afresh
        if act.size == k and accept.all():
            g, p, r, jg, jl, chi2 = g_new, p_new, r_new, jg_new, jl_new, chi2_new
            continue
        acc = act[accept]
        g[acc], p[acc], r[acc] = g_new[accept], p_new[accept], r_new[accept]
        jg[acc], jl[acc], chi2[acc] = jg_new[accept], jl_new[accept], chi2_new[accept]
    return g, p, r, chi2, iters, converged


NEWTON_SWITCH = 1e-2
"""Switch to Newton once a Gauss-Newton step predicts a decrease below this times chi2."""


def _damped_step(
    u: np.ndarray,
    v: np.ndarray,
    w: np.ndarray,
    eg: np.ndarray,
    el: np.ndarray,
    du: np.ndarray,
    dv: np.ndarray,
    lam: np.ndarray,
    check: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Solve the damped block-arrow system by the Schur complement.

    (H + lam D) d = -e with H = [[U, W], [W^T, V]] (Gauss-Newton plus the second-order blocks)
    and D its Gauss-Newton diagonal (``du``, ``dv``).  Returns the shape step (K, 4), the pose
    steps (K, N, 5), the decrease of chi2 the quadratic model predicts (K,) and whether the
    damped matrix was positive definite (K,) (``check`` False: not tested, True).
    """
    ud = u.reshape(-1, 16).copy()
    ud[:, ::5] += lam[:, None] * (du + 1e-12 * np.max(du, axis=1)[:, None])
    ud = ud.reshape(u.shape)
    vd = v.reshape(*v.shape[:2], 25).copy()
    vd[..., ::6] += lam[:, None, None] * (dv + 1e-12 * np.max(dv, axis=2)[..., None])
    vd = vd.reshape(v.shape)
    pd = np.all(_positive_definite(vd), axis=-1) if check else np.ones(len(lam), dtype=bool)
    vinv = _batched_inverse(vd)
    y = w @ vinv
    wt = np.swapaxes(w, -1, -2)
    sc = ud - np.sum(y @ wt, axis=1)
    rhs = -eg + np.sum(y @ el[..., None], axis=1)[..., 0]
    sc = sc + 1e-14 * np.einsum("kii->k", sc)[:, None, None] * np.eye(4)
    sc = 0.5 * (sc + np.swapaxes(sc, -1, -2))
    if check:
        pd &= _positive_definite(sc)
    try:
        dg = np.linalg.solve(sc, rhs[..., None])[..., 0]
    except np.linalg.LinAlgError:
        dg = (np.linalg.pinv(sc) @ rhs[..., None])[..., 0]
    dl = (vinv @ (-el - (wt @ dg[:, None, :, None])[..., 0])[..., None])[..., 0]
    # model decrease: -e.d + lam d^T D d (exact for the solved system)
    predicted = -(np.einsum("ki,ki->k", eg, dg) + np.einsum("kni,kni->k", el, dl))
    predicted += lam * (np.einsum("ki,ki->k", du, dg * dg) + np.einsum("kni,kni->k", dv, dl * dl))
    return dg, dl, predicted, pd


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
    r, jg, jl = _lin_batch(gm, cands, meas, w8)
    f = np.sum(r * r, axis=-1)
    f_now = f[0].copy()
    cands, r, jg, jl, f = _pose_steps(gm, cands, r, jg, jl, f, meas, w8, n_iter, 0.0)
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
