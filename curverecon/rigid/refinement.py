"""Maximum likelihood for a row: Levenberg-Marquardt with a Schur complement over the frames.

The normal equations of the standardised residuals (``rigid.measurements``) have a global block
U (body, tangents, motion), one small block V_f per frame (its shift, rotation or angle) and the
cross blocks W_f.  Each step eliminates the frames (S = U - sum W_f V_f^-1 W_f^T, as
``refine/ml.py`` does for the paper's row), solves for the global step and back-substitutes the
frames' steps.  Marquardt damping scales the diagonal; frame 0's gauge-fixed rotation parameters
get a unit diagonal and a zero gradient, so they never move.

Covariance of the globals: S^-1 at the optimum (the noise levels are taken as given, not rescaled
by chi2).  The Cramer-Rao bound is the same matrix at the truth (``fisher_information``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.rigid.measurements import (
    RigidData,
    apply_step,
    fixed_globals,
    fixed_locals,
    residuals,
    residuals_and_jacobians,
)
from curverecon.rigid.model import Layout, RigidState


@dataclass
class RigidFit:
    """A fitted state: chi2, per-frame chi2 (N,), the globals' covariance (G, G) or None,
    the per-frame leverage of the globals (N,) or None, iterations, converged."""

    state: RigidState
    chi2: float
    frame_chi2: np.ndarray
    covariance: np.ndarray | None = None
    leverage: np.ndarray | None = None
    iterations: int = 0
    converged: bool = False
    full_state: RigidState | None = None
    """With outlier frames left out: the state over every frame (the outlier frames keep their
    parameters from before they were left out)."""


def _blocks(layout: Layout, jg: np.ndarray, jl: np.ndarray, r: np.ndarray):
    """U (G, G), W (N, G, L), V (N, L, L), b_g (G,), b_l (N, L); a gauge-fixed global (zero
    Jacobian column) gets a unit diagonal in U so that it never moves."""
    u = np.einsum("fmi,fmj->ij", jg, jg)
    gf = np.flatnonzero(fixed_globals(layout))
    u[gf, gf] = 1.0
    w = np.einsum("fmi,fmj->fij", jg, jl)
    v = np.einsum("fmi,fmj->fij", jl, jl)
    bg = np.einsum("fmi,fm->i", jg, r)
    bl = np.einsum("fmi,fm->fi", jl, r)
    return u, w, v, bg, bl


RIDGE = 1e-12
"""Relative ridge on every frame's block: a frame parameter the data do not see (a two-point
body's turn about its own chord under free motion) stays where it is; the globals' information
is unchanged (their cross terms with it vanish)."""


def _fix_gauge(v: np.ndarray, fixed: np.ndarray) -> np.ndarray:
    v = v.copy()
    f, k = np.nonzero(fixed)
    v[f, k, k] = 1.0
    idx = np.arange(v.shape[1])
    v[:, idx, idx] += RIDGE * np.max(np.abs(v[:, idx, idx]), axis=1, keepdims=True)
    return v


def schur(u, w, v, fixed):
    """(S, V^-1): the Schur complement of the frames' blocks and their inverses."""
    vinv = np.linalg.inv(_fix_gauge(v, fixed))
    s = u - np.einsum("fij,fjk,flk->il", w, vinv, w)
    return 0.5 * (s + s.T), vinv


def _step(u, w, v, bg, bl, fixed, lam, fix_globals=False):
    """The damped Gauss-Newton step (dg, dl) or None when the system is singular
    (``fix_globals``: the frames' parameters alone, dg = 0)."""
    if fix_globals:
        idx = np.arange(v.shape[1])
        vd = _fix_gauge(v, fixed)
        vd[:, idx, idx] += lam * np.maximum(vd[:, idx, idx], 1e-12)
        dl = -np.linalg.solve(vd, bl[..., None])[..., 0]
        dl[fixed] = 0.0
        return np.zeros(u.shape[0]), dl
    ud = u + lam * np.diag(np.maximum(np.diag(u), 1e-12))
    idx = np.arange(v.shape[1])
    vd = v.copy()
    vd[:, idx, idx] += lam * np.maximum(v[:, idx, idx], 1e-12)
    s, vinv = schur(ud, w, vd, fixed)
    rhs = -bg + np.einsum("fij,fjk,fk->i", w, vinv, bl)
    try:
        dg = np.linalg.solve(s, rhs)
    except np.linalg.LinAlgError:
        return None
    dl = -np.einsum("fij,fj->fi", vinv, bl + np.einsum("fji,j->fi", w, dg))
    dl[fixed] = 0.0
    return dg, dl


def refine(
    layout: Layout,
    state: RigidState,
    data: RigidData,
    *,
    max_iter: int = 100,
    covariance: bool = True,
    tol: float = 1e-10,
    fix_globals: bool = False,
) -> RigidFit:
    """The maximum-likelihood state from ``state`` (Levenberg-Marquardt, Schur complement);
    ``fix_globals``: the frames' own parameters alone (body and motion held)."""
    fixed = fixed_locals(layout, data.n_frames)
    r, jg, jl = residuals_and_jacobians(layout, state, data)
    cost = float(np.sum(r * r))
    lam, it, converged = 1e-4, 0, False
    while it < max_iter:
        it += 1
        u, w, v, bg, bl = _blocks(layout, jg, jl, r)
        step = _step(u, w, v, bg, bl, fixed, lam, fix_globals)
        if step is None:
            lam *= 10.0
            if lam > 1e12:
                break
            continue
        trial = apply_step(layout, state, step[0], step[1], data.times)
        r_new = residuals(layout, trial, data)
        new_cost = float(np.sum(r_new * r_new)) if np.all(np.isfinite(r_new)) else np.inf
        if new_cost <= cost:
            small = cost - new_cost <= tol * max(cost, 1e-300) or new_cost < 1e-28
            state, cost = trial, new_cost
            r, jg, jl = residuals_and_jacobians(layout, state, data)
            lam = max(lam / 10.0, 1e-12)
            if small:
                converged = True
                break
        else:
            lam *= 10.0
            if lam > 1e12:
                converged = True  # no descent left at this precision
                break
    frame_chi2 = np.sum(r * r, axis=1)
    fit = RigidFit(state, float(np.sum(frame_chi2)), frame_chi2, iterations=it, converged=converged)
    if covariance:
        fit.covariance, fit.leverage = information_inverse(layout, state, data)
    return fit


def fisher_information(layout: Layout, state: RigidState, data: RigidData) -> np.ndarray:
    """(G, G) Fisher information of the globals with the frames' parameters eliminated (the
    Schur complement of J^T J of the standardised residuals); at the truth, its inverse is the
    Cramer-Rao bound."""
    _, jg, jl = residuals_and_jacobians(layout, state, data)
    u, w, v, _, _ = _blocks(layout, jg, jl, np.zeros(jg.shape[:2]))
    s, _ = schur(u, w, v, fixed_locals(layout, data.n_frames))
    return s


def information_inverse(
    layout: Layout, state: RigidState, data: RigidData
) -> tuple[np.ndarray | None, np.ndarray | None]:
    """(covariance of the globals, per-frame leverage) at ``state``; (None, None) when the
    information is singular (a degenerate motion or too few frames)."""
    _, jg, jl = residuals_and_jacobians(layout, state, data)
    fixed = fixed_locals(layout, data.n_frames)
    u, w, v, _, _ = _blocks(layout, jg, jl, np.zeros(jg.shape[:2]))
    s, vinv = schur(u, w, v, fixed)
    if not is_regular(s):
        return None, None
    cov = np.linalg.inv(s)
    gf = fixed_globals(layout)
    cov[gf, :], cov[:, gf] = 0.0, 0.0
    # leverage of frame f: trace of its rows of the hat matrix J (J^T J)^-1 J^T
    eff = jg - np.einsum("fmk,fkl,fil->fmi", jl, vinv, w)
    lev_g = np.einsum("fmi,ij,fmj->f", eff, cov, eff)
    lev_l = np.einsum("fmk,fkl,fml->f", jl, vinv, jl)
    return 0.5 * (cov + cov.T), lev_g + lev_l


def is_regular(s: np.ndarray, rcond: float = 1e-10) -> bool:
    """True when the information matrix is invertible at a sensible condition (scaled by its
    diagonal, the smallest eigenvalue above ``rcond`` times the largest)."""
    if not np.all(np.isfinite(s)):
        return False
    d = np.sqrt(np.maximum(np.diag(s), 1e-300))
    scaled = s / np.outer(d, d)
    try:
        ev = np.linalg.eigvalsh(scaled)
    except np.linalg.LinAlgError:
        return False
    return bool(np.all(np.isfinite(ev)) and ev[0] > rcond * max(ev[-1], 1e-300))
