"""The curve bundle's solvers, separate from its residual model (``curve.residuals``).

Levenberg-Marquardt on the joint problem (:func:`lm_bundle`; a few hundred residuals per frame
and 3K + 5(N - 1) parameters): the normal equations in blocks, the 5 x 5 pose blocks (a frame's
rows see only its own pose) eliminated by their Schur complement (:func:`_schur_solve`): O(N) per
step, no dense Jacobian of all the poses (the same steps as the dense solve, to rounding).
:func:`lm_poses`: the same loop on every frame's pose alone, the curve fixed (the pose search).
:func:`gauss_newton_tsvd`: truncated-SVD Gauss-Newton for the curve with every pose fixed.
"""

from __future__ import annotations

import numpy as np

from curverecon.curve.residuals import Problem, expm_so3_batch

#: Iteration cap of each Levenberg-Marquardt run (the full-curve stage).
MAX_ITER = 60


#: Relative decrease of the cost below which LM stops.
REL_TOL = 1e-6


#: LM (:func:`lm_bundle`): a Gauss-Newton step (damping at most LM_GN_LAMBDA) that does not
#: lower the cost while the linearisation predicts less than LM_STOP_DCHI2 (chi2 units) ends the
#: run.  (Up to rounding, :func:`_gauss_newton_damping`: at first the damping reached from 1e-3 by
#: tenfold decreases, 1.0000000000000002e-06, was not "at most 1e-6", and a run whose first
#: Gauss-Newton trial came there went on to damp it up to 10 times for gains of 0.005-0.07 chi2;
#: bench seed 1400, 20 frames: 57 of the LM's 847 cost evaluations; held out 2000 and 2100: 37 of
#: 487, 16 of 437; of 191 scenes of curve_05 and never_worse, 41 moved within noise, the counts,
#: rates and coverages the same.)  Measured and left off: Nielsen's damping update (gain ratio;
#: 912 evaluations, more iterations); the stop on a rejected damped step's own predicted decrease
#: (a damped step predicts little far from the minimum too: the noise-free polylines-only fit of
#: tests/test_curve_polylines_only.py stopped at 0.79 chi2 for 0.07); damped retries left
#: unevaluated while the step moves by under a tenth (sharp-ends 6001 of tests/test_curve_std.py
#: took another basin); the full fit and the robust-ends polish as one robust run (final costs
#: 0.1-3.4 chi2 higher on 11 of 12 scenes: seeds 1400 and 2000, every family).  Before, such a
#: step started a tail of 3-10 steps at damping raised up to 1e9-fold, each lowering the cost
#: by 0.001-0.02 and moving the shape by under 0.004 of its std (bench seed 1400, 20 frames,
#: fourier: the GN prediction there 0.2-0.5, the cost rough at that scale); a fifth of the LM's
#: evaluations.
#: The final polish then starts elsewhere and can settle in another dip of the rough floor: on
#: 30 scenes (1 px, 20 frames, seeds 1400, 2000-2003, every family; with the matrix products'
#: rounding) the shapes moved by a median 0.002 and at most 0.12 of their std, the curve errors
#: of 14 both ways (-0.11 to +0.07 % of the length); seed 1400 fourier's curve 0.22 of its std
#: across the curve (median point) from the tight solve's.  Also in the final polish with robust
#: ends (``END_POLISH``; it was left out there at first): its runs spent 9-21 trial steps of
#: predicted decreases 0.00-0.1 on the floor (time_20 seeds 1400); on 84 scenes (1 px, 20
#: frames, seeds 1400-1407, 2000-2005, every family) 21 answers moved, the shapes by a median
#: 0.000 and at most 0.03 of their std, the curve errors by -0.004 to +0.12 % of the length
#: (the +0.12 on fourier 1403, 2.4 % off either way), 5 % of the curve bundle's time saved.
LM_GN_LAMBDA = 1e-6


LM_STOP_DCHI2 = 0.5


def sum_products(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``sum_n w[n] @ x[n]`` for w (N, C, P), x (N, P, K): one matrix product (C, N P) (N P, K)
    (an einsum of these shapes took several times longer)."""
    n, c, p = w.shape
    return np.transpose(w, (1, 0, 2)).reshape(c, n * p) @ x.reshape(n * p, -1)


def _schur_solve(blocks, lam: float) -> np.ndarray:
    """The LM step ``-(J^T J + lam D)^-1 J^T r`` (D: Marquardt's diagonal of J^T J, floored
    at 1e-12 of its largest entry) from the normal equations' blocks of
    :meth:`Problem.normal_equations`: the per-frame 5 x 5 pose blocks eliminated (Schur
    complement on the curve's parameters), then back-substituted.  The same step as the
    dense solve (to rounding) at O(N) cost instead of O(N^3).  Raises LinAlgError if singular."""
    u, gc, v, w, gp = blocks
    du = np.diag(u)
    dv = np.einsum("nii->ni", v[1:])
    top = max(float(np.max(du)), float(np.max(dv)) if dv.size else 0.0, 1e-300)
    floor = 1e-12 * top
    a = u + lam * np.diag(np.maximum(du, floor))
    vd = v[1:] + lam * np.maximum(dv, floor)[:, :, None] * np.eye(5)
    # (V + lam D)^-1 [W^T | gp] for every frame at once
    rhs = np.concatenate([np.transpose(w[1:], (0, 2, 1)), gp[1:, :, None]], axis=2)
    sol = np.linalg.solve(vd, rhs)  # (N - 1, 5, n_curve + 1)
    s = a - sum_products(w[1:], sol[:, :, :-1])
    rc = gc - np.einsum("ncp,np->c", w[1:], sol[:, :, -1])
    dc = -np.linalg.solve(s, rc)
    dp = -(sol[:, :, -1] + np.einsum("npk,k->np", sol[:, :, :-1], dc))
    return np.concatenate([dc, dp.reshape(-1)])


def _model_decrease(blocks, dx: np.ndarray) -> float:
    """The decrease of the cost ``|r|^2`` (chi2: residuals in units of sigma) that the
    linearisation predicts for the step dx, ``-(2 g^T dx + dx^T H dx)`` with H = J^T J and
    g = J^T r from the blocks of :meth:`Problem.normal_equations` (frame 0's pose is the
    gauge: no parameters)."""
    u, gc, v, w, gp = blocks
    nc = len(gc)
    dc, dp = dx[:nc], dx[nc:].reshape(-1, 5)
    hc = u @ dc + np.einsum("ncp,np->c", w[1:], dp)
    hp = np.transpose(w[1:], (0, 2, 1)) @ dc + (v[1:] @ dp[:, :, None])[:, :, 0]
    g_dx = float(gc @ dc + np.sum(gp[1:] * dp))
    return -(2.0 * g_dx + float(dc @ hc + np.sum(dp * hp)))


def _gauss_newton_damping(lam: float) -> bool:
    """Whether the damping ``lam`` is at most ``LM_GN_LAMBDA`` (the Gauss-Newton step), up to
    the rounding of the tenfold steps that reach it (1e-3 / 10 / 10 / 10 is
    1.0000000000000002e-06)."""
    return lam <= LM_GN_LAMBDA * (1.0 + 1e-9)


def lm_bundle(prob, state, max_iter: int, lam: float = 1e-3, rel_tol: float = REL_TOL):
    """Levenberg-Marquardt (Marquardt's diagonal scaling) on the bundle's joint problem (curve
    and every pose), the steps from the normal equations' blocks (:func:`_schur_solve`): no
    dense Jacobian of all the poses.  A step is taken when it lowers the cost (lambda times 10
    until it does, at most 10 times; then converged), lambda / 10 after it; stops when the cost
    falls by less than ``rel_tol`` of itself, or when a step at the least damping (``lambda <=
    LM_GN_LAMBDA``: the Gauss-Newton step) does not lower the cost although the linearisation
    predicts a decrease below ``LM_STOP_DCHI2``: the cost is then at its floor (the foot points,
    the reverse term's polyline segments and Huber make it rough at that scale).  Returns
    (state, cost, iterations, converged)."""
    r, blocks, _ = prob.normal_equations(*state)
    cost = float(r @ r)
    it, converged = 0, False
    while it < max_iter:
        it += 1
        improved = floor = False
        for attempt in range(10):
            try:
                dx = _schur_solve(blocks, lam)
            except np.linalg.LinAlgError:
                lam *= 10.0
                continue
            new = prob.apply(*state, dx)
            r2 = prob.evaluate(*new, jac=False)[0]
            cost2 = float(r2 @ r2)
            if np.isfinite(cost2) and cost2 < cost:
                improved = True
                break
            if (
                attempt == 0
                and _gauss_newton_damping(lam)
                and _model_decrease(blocks, dx) < LM_STOP_DCHI2
            ):
                floor = True
                break
            lam *= 10.0
        if floor:
            converged = True
            break
        if not improved:
            converged = True
            break
        rel = (cost - cost2) / max(cost, 1e-300)
        state = new
        lam = max(lam / 10.0, 1e-9)
        if rel < rel_tol or it >= max_iter:
            # the last step: its cost is the trial's (the same residuals), no linearisation
            converged = rel < rel_tol
            cost = cost2
            break
        r, blocks, _ = prob.normal_equations(*state)
        cost = float(r @ r)
    return state, cost, it, converged


def gauss_newton_tsvd(residual, p, max_iter: int, rcond: float, abs_tol: float):
    """Gauss-Newton with truncated-SVD steps on ``residual(p, jac) -> (r, J, ...)``.

    The curve's parametrisation is nearly free (sliding control points along the curve changes
    it only to second order): full steps along those near-null directions are huge and leave
    the linearisation (the cost rose tenfold per step, seen).  Singular directions below
    ``rcond`` times the largest are dropped from each step (they change the cost by nothing
    that matters), so the steps stay in the determined part and converge in a few iterations.
    Step halving (by 4) when a step does not lower the cost; stops when the cost falls by less
    than ``abs_tol`` per residual (or a relative ``REL_TOL``).  Returns (p, cost)."""
    r, jac, *_ = residual(p)
    cost = float(r @ r)
    for _ in range(max_iter):
        dx = -np.linalg.lstsq(jac, r, rcond=rcond)[0]
        step, new = 1.0, None
        for _ in range(8):
            r2 = residual(p + step * dx, jac=False)[0]
            cost2 = float(r2 @ r2)
            if np.isfinite(cost2) and cost2 < cost:
                new = p + step * dx
                break
            step /= 4.0
        if new is None:
            break
        drop = cost - cost2
        p = new
        r, jac, *_ = residual(p)
        cost = float(r @ r)
        if drop < abs_tol * len(r) or drop < REL_TOL * cost:
            break
    return p, cost


def lm_poses(prob: Problem, ctrl, m, b, max_iter: int, rel_tol: float, lam0: float = 1e-3):
    """Levenberg-Marquardt (as :func:`lm_bundle`) on each frame's pose alone (the curve
    fixed), every frame of ``prob`` at once: the frames are independent, so each keeps its own
    damping, iteration count and
    stopping test, exactly as separate runs would (the frames still running are evaluated,
    in a smaller problem once half have stopped).  Returns (m, b, cost per frame)."""
    n = prob.n
    m, b = m.copy(), b.copy()
    lam = np.full(n, lam0)
    it = np.zeros(n, int)
    active = np.ones(n, bool)
    sub, sel = prob, np.arange(n)

    def normal(mm, bb):
        c_s, v_s, g_s = sub.pose_normal_equations(ctrl, mm[sel], bb[sel])
        c, v, g = np.full(n, np.inf), np.zeros((n, 5, 5)), np.zeros((n, 5))
        c[sel], v[sel], g[sel] = c_s, v_s, g_s
        return c, v, g

    cost, v, gp = normal(m, b)
    eye5 = np.eye(5)
    while active.any():
        if active.sum() <= len(sel) // 2:
            sel = np.flatnonzero(active)
            sub = prob.subset(sel)
        it[active] += 1
        dv = np.einsum("nii->ni", v)
        diag = np.maximum(dv, 1e-12 * np.maximum(dv.max(axis=1), 1e-300)[:, None])
        inner = active.copy()
        improved = np.zeros(n, bool)
        tries = np.zeros(n, int)
        m_new, b_new, cost2 = m.copy(), b.copy(), cost.copy()
        while inner.any():
            idx = np.flatnonzero(inner)
            a = v[idx] + lam[idx, None, None] * diag[idx][:, :, None] * eye5
            dx = np.full((len(idx), 5), np.nan)
            try:
                dx = -np.linalg.solve(a, gp[idx][:, :, None])[:, :, 0]
            except np.linalg.LinAlgError:
                for j, ii in enumerate(idx):
                    try:
                        dx[j] = -np.linalg.solve(a[j], gp[ii])
                    except np.linalg.LinAlgError:
                        pass
            solved = np.all(np.isfinite(dx), axis=1)
            mt, bt = m.copy(), b.copy()
            ok_idx = idx[solved]
            mt[ok_idx] = expm_so3_batch(dx[solved, :3]) @ m[ok_idx]
            bt[ok_idx, :2] += dx[solved, 3:5]
            r2, _, _, rows, _ = sub.evaluate(ctrl, mt[sel], bt[sel], jac=False)
            c2 = np.full(n, np.inf)
            c2[sel] = sub.frame_costs(r2, rows)
            good = np.zeros(n, bool)
            good[ok_idx] = np.isfinite(c2[ok_idx]) & (c2[ok_idx] < cost[ok_idx])
            m_new[good], b_new[good], cost2[good] = mt[good], bt[good], c2[good]
            improved |= good
            bad = inner & ~good
            lam[bad] *= 10.0
            tries[bad] += 1
            inner &= ~good & (tries < 10)
        active &= improved  # a frame no step improves has converged
        rel = (cost - cost2) / np.maximum(cost, 1e-300)
        m[active], b[active] = m_new[active], b_new[active]
        lam[active] = np.maximum(lam[active] / 10.0, 1e-9)
        cost_all, v_all, gp_all = normal(m, b)
        cost[active], v[active], gp[active] = cost_all[active], v_all[active], gp_all[active]
        active &= ~(rel < rel_tol) & (it < max_iter)
    return m, b, cost
