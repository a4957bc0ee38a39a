"""Maximum-likelihood refinement over all frames (Levenberg-Marquardt with a Schur complement).

Parameters: the shape (c, alpha, beta, phi) shared by all frames and per frame the pose
(delta, tau, theta, tx, ty) (input units, radians).  Residuals per frame, in units of their
standard deviation: the image points A', B' (``(pred - obs) / point_sigma``) and the tangent
angles (``wrap(pred - obs) / tangent_sigma``, wrapped to (-pi/2, pi/2]: a tangent is a line).
Predictions and their analytic Jacobians come from ``measurement_model.predict_with_jacobians``.

The normal matrix is block-arrow shaped: a 4x4 shape block U, per-frame 5x5 pose blocks V_i and
4x5 couplings W_i.  Each step eliminates the pose blocks (batched 5x5 inverses, einsum; no Python
loop over frames) and solves the 4x4 Schur complement S = U - sum W_i V_i^-1 W_i^T.  The shape's
covariance is S^-1 at the solution (undamped); at the true parameters it is the Cramer-Rao bound.
``refine_batch`` runs K independent starts at once (the same algebra with a leading axis).

Damping: Nielsen's update (lambda times max(1/3, 1 - (2 rho - 1)^3) after an accepted step,
times 4 after a rejected one), so lambda shrinks geometrically while the linear model predicts
well and the iteration becomes Gauss-Newton near the optimum.  (The update once read
(rho - 1)^3, which never shrinks lambda: ill-conditioned fits, e.g. a frame with c' close to c
where the B' prediction c cos(tau) is flat in tau, then crept along the valley to ``max_iter``.)
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


def schur_covariance(jg: np.ndarray, jl: np.ndarray) -> np.ndarray | None:
    """(4, 4) shape covariance: inverse of the Schur-reduced normal matrix (or None)."""
    u = np.einsum("nki,nkj->ij", jg, jg)
    v = np.einsum("nki,nkj->nij", jl, jl)
    w = np.einsum("nki,nkj->nij", jg, jl)
    vinv = _batched_inverse(v)
    s = u - np.einsum("nij,njk,nlk->il", w, vinv, w)
    s = 0.5 * (s + s.T)
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


def refine_batch(
    obs: Observations | np.ndarray,
    shapes: np.ndarray,
    poses: np.ndarray,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    max_iter: int = 100,
    xtol: float = 1e-11,
    ftol: float = 1e-13,
    drop_factor: float | None = None,
    act_floor: float = 10.0,
    frame_weights: np.ndarray | None = None,
    drop_after: int = 8,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Levenberg-Marquardt on K independent starts at once (all vectorised, no loop over frames).

    Args:
        obs: observations or (N, 6) measurements.
        shapes: (K, 4) start shapes; poses: (K, N, 5) start poses.
        point_sigma (input units), tangent_sigma (radians): noise of the measurements.
        drop_factor: after ``drop_after`` iterations stop starts whose chi2 exceeds
            drop_factor * (best chi2 + act_floor) (screening many starts); None keeps all.
        frame_weights: (N,) optional weights of the frames' squared residuals (robust IRLS);
            residuals and chi2 returned are then weighted too.
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
    done = np.zeros(k, dtype=bool)
    converged = np.zeros(k, dtype=bool)
    iters = np.zeros(k, dtype=int)
    eye4 = np.eye(4)
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
        du = np.einsum("kii->ki", u)
        dv = np.einsum("knii->kni", v)
        ud = u.reshape(-1, 16).copy()
        ud[:, ::5] += lama[:, None] * (du + 1e-12 * np.max(du, axis=1)[:, None])
        ud = ud.reshape(u.shape)
        vd = v.reshape(*v.shape[:2], 25).copy()
        vd[..., ::6] += lama[:, None, None] * (dv + 1e-12 * np.max(dv, axis=2)[..., None])
        vd = vd.reshape(v.shape)
        vinv = _batched_inverse(vd)
        y = w @ vinv
        sc = ud - np.sum(y @ np.swapaxes(w, -1, -2), axis=1)
        rhs = -eg + np.sum(y @ el[..., None], axis=1)[..., 0]
        sc = sc + 1e-14 * np.einsum("kii->k", sc)[:, None, None] * eye4
        try:
            dg = np.linalg.solve(sc, rhs[..., None])[..., 0]
        except np.linalg.LinAlgError:
            dg = (np.linalg.pinv(sc) @ rhs[..., None])[..., 0]
        dl = (vinv @ (-el - (np.swapaxes(w, -1, -2) @ dg[:, None, :, None])[..., 0])[..., None])[
            ..., 0
        ]
        step = np.maximum(
            np.max(np.abs(dg) / np.maximum(np.abs(ga), 1.0), axis=1),
            np.max(np.abs(dl) / np.maximum(np.abs(pa), 1.0), axis=(1, 2)),
        )
        # decrease of chi2 predicted by the damped linear model (>= 0)
        predicted = -(np.einsum("ki,ki->k", eg, dg) + np.einsum("kni,kni->k", el, dl))
        small = (step < xtol) | (predicted <= ftol * np.maximum(c2, 1e-300)) | (lama > 1e12)
        converged[act[small & (lama <= 1e12)]] = True
        done[act[small]] = True
        g_new, p_new = ga + dg, pa + dl
        ok = np.all(np.isfinite(g_new), axis=1) & np.all(np.isfinite(p_new), axis=(1, 2))
        ok &= (g_new[:, 0] > 0) & ~small
        g_new = np.where(ok[:, None], g_new, ga)
        p_new = np.where(ok[:, None, None], p_new, pa)
        r_new, jg_new, jl_new = _lin_batch(g_new, p_new, meas, w8)
        chi2_new = np.einsum("kna,kna->k", r_new, r_new)
        accept = ok & (chi2_new < c2)
        rho = (c2 - chi2_new) / np.maximum(predicted, 1e-300)
        factor = np.maximum(1.0 / 3.0, 1.0 - (2.0 * np.clip(rho, 0.0, 1.0) - 1.0) ** 3)
        lam[act] = np.where(accept, np.maximum(lama * factor, 1e-15), lama * 4.0)
        if act.size == k and accept.all():
            g, p, r, jg, jl, chi2 = g_new, p_new, r_new, jg_new, jl_new, chi2_new
            continue
        acc = act[accept]
        g[acc], p[acc], r[acc] = g_new[accept], p_new[accept], r_new[accept]
        jg[acc], jl[acc], chi2[acc] = jg_new[accept], jl_new[accept], chi2_new[accept]
    return g, p, r, chi2, iters, converged


def refine(
    obs: Observations | np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    max_iter: int = 100,
    xtol: float = 1e-11,
    ftol: float = 1e-13,
    covariance: bool = True,
    frame_weights: np.ndarray | None = None,
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
        ftol: stop when the decrease of chi2 the linear model predicts is below ftol * chi2.
        covariance: compute the shape covariance (inverse Schur-reduced normal matrix).
        frame_weights: optional (N,) weights of the frames (robust reweighting); the
            returned residuals and chi2 are unweighted.
    """
    meas = _measurements(obs)
    g, p, r, chi2, iters, conv = refine_batch(
        meas,
        np.asarray(shape, float)[None],
        np.asarray(poses, float)[None],
        point_sigma,
        tangent_sigma,
        max_iter,
        xtol,
        ftol,
        frame_weights=frame_weights,
    )
    g, p = g[0], p[0]
    w8 = _weights(point_sigma, tangent_sigma)
    r = standardised_residuals(g, p, meas, w8)
    chi2 = np.array([np.sum(r * r)])
    cov = None
    if covariance:
        _, jg, jl = _linearise(g, p, meas, w8)
        cov = schur_covariance(jg, jl)
    frame_chi2 = np.sum(r * r, axis=1)
    return RefineResult(g, p, float(chi2[0]), frame_chi2, r, cov, int(iters[0]), bool(conv[0]))


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
