"""A start for the maximum-likelihood fit that needs no truth: a global search over the shape.

For a candidate shape (c, alpha, beta) and frame i, equation (10) fixes delta_i: multiplied by
-u_x / c' (u = the unit tangent at B' in the paper's frame, so d' = -c' u_y / u_x), (10) reads

    -c tan(alpha) u_x cos(delta) + c tan(alpha) sin(tau) u_y sin(delta) = u_y c'

i.e. R cos(delta - w) = u_y c', finite even where d' is infinite.  That gives two deltas for each
sign of sin(tau) = +-sqrt(1 - (c'/c)^2): four candidates per frame (infeasible ones clipped, their
misfit at B kept).  Equation (11) multiplied likewise by the tangent at A is then LINEAR in
X = c tan(beta) cos(phi), Y = c tan(beta) sin(phi):

    r_A = c' v_y + X (sin(tau) sin(delta) v_y - cos(delta) v_x) + Y (sin(tau) cos(delta) v_y
          + sin(delta) v_x)  =  (c / cos(beta)) |P t_A| sin(angle error at A)

(v = the unit tangent at A' in the paper's frame, P t_A the projected unit tangent), so a whole
grid of (beta, phi) is one matrix product per (c, alpha).  The per-frame misfit is the minimum
over the four candidates of sin^2(angle error at A) + r_B^2 (r_B: misfit of (10) where it has no
real solution), truncated (robust to outlier frames) and summed over frames: a cost of the shape
alone, the poses eliminated exactly, zero at the truth on noise-free data.

Pipeline (``search_start``): coarse vectorised grid -> its best local minima -> a few compass
steps and a batched Levenberg-Marquardt on the same pose-free cost (``local_refine``) -> the best
distinct shapes get a short batched ML refinement (``refine.refine_batch``, poses from the
grid's branch per frame) -> the best few are refined to convergence -> every frame tries the
other branches of (10) with the shape fixed (``switch_branches``) -> random restarts around the
best two by robust cost (three, and more restarts, with few frames or an implausible chi2; with
plausible noisy data screened by Gauss-Newton, ``o.screen_iterations``, and only the
``o.restart_finalists`` best refined with the Newton phase).
More than 40 frames: the search runs on 40 evenly spread frames and the candidates are refined
on all (``robust_start``); more than ``o.medium_frames``: on that many first, and only those that
stay near the best go on to all.

Shortcuts that cannot change the answer's fit: with at least ``o.exact_stage_min_frames`` frames
the best ``o.exact_stage_starts`` grid minima are polished and refined first, and if one of them
fits exactly (noise-free data) the other minima are not searched; the restarts are skipped when
the best fit is already exact (``o.exact_cost``: they could not beat it by their margin).

Tuned numbers (``o.*`` in the text) are the fields of :class:`curverecon.options.SearchOptions`.

Symmetries let the grid cover alpha, beta in (0, 90) degrees and phi in [0, 180] only
(docs/CONVENTIONS.md); c = max(c') / cos(gamma) with gamma in [0, 80] degrees.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import ndimage

from curverecon.model.observations import Observations, wrap_angle
from curverecon.model.pose import normalise
from curverecon.options import SearchOptions
from curverecon.refine.ml import POSE_HALVINGS, RefineResult, optimise_poses, refine_batch


@dataclass
class GridSpec:
    """Grid resolution of the global search (counts of grid values)."""

    n_gamma: int = 16
    n_alpha: int = 18
    n_beta: int = 18
    n_phi: int = 19
    gamma_max_deg: float = 80.0
    truncate_deg: float = 12.0
    gamma_power: float = 1.0

    def gammas(self) -> np.ndarray:
        """The gamma grid (radians): ``gamma_max * (k / (n - 1)) ** gamma_power``; a power above
        1 packs the values near 0, where the frames with c' close to c (tau near 0) make the
        cost's minima narrow in gamma."""
        u = np.linspace(0.0, 1.0, self.n_gamma)
        return np.radians(self.gamma_max_deg) * u**self.gamma_power

    @classmethod
    def for_frames(cls, n_frames: int) -> GridSpec:
        """A grid whose size (cells x frames) stays about constant: finer for few frames."""
        if n_frames <= 8:
            return cls(12, 22, 22, 25)
        if n_frames <= 30:
            return cls(6, 20, 20, 21)
        return cls(5, 16, 16, 17)


@dataclass
class Candidate:
    """A refined start: the ML result and its robust cost."""

    result: RefineResult
    robust_cost: float
    grid_cost: float


def frame_terms(obs: Observations) -> dict[str, np.ndarray]:
    """The per-frame terms of the pose-free cost: c' and the unit tangent directions at A and B
    relative to A'B'."""
    return {
        "cp": obs.cp,
        "ua": np.column_stack([np.cos(obs.rel_a), np.sin(obs.rel_a)]),
        "ub": np.column_stack([np.cos(obs.rel_b), np.sin(obs.rel_b)]),
    }


def branch_candidates(
    cp: np.ndarray, ub: np.ndarray, c: np.ndarray, tan_alpha: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The four (delta, sin tau) solutions of (10) per frame, for shapes broadcast over frames.

    Args:
        cp: (N,) c'; ub: (N, 2) unit tangent at B' in the paper's frame.
        c, tan_alpha: arrays of shape S (broadcast against a trailing frame axis).
    Returns:
        cos_delta, sin_delta, sin_tau, r_b: arrays (*S, N, 4); r_b is the misfit of (10) (a sine
        of the angle error at B, nonzero only where (10) has no real solution and was clipped).
    """
    c = np.asarray(c, float)[..., None]
    ta = np.asarray(tan_alpha, float)[..., None]
    s_abs = np.sqrt(np.clip(1.0 - (cp / c) ** 2, 0.0, None))
    t_a = c * ta
    # R cos(delta - w) = rhs with (R cos w, R sin w) = (a, b s_abs sign(sin tau)): R, the root
    # offset arccos(rhs / R) and the misfit do not depend on the sign, w only flips its sign
    # (atan2 is odd in its first argument), so they are computed once per frame, not four times
    a_coef = -t_a * ub[:, 0]
    b_coef = t_a * ub[:, 1] * s_abs
    rhs = ub[:, 1] * cp
    big_r = np.hypot(a_coef, b_coef)
    w = np.arctan2(b_coef, a_coef)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(big_r > 0, rhs / big_r, 0.0)
    ratio_c = np.clip(ratio, -1.0, 1.0)
    off = np.arccos(ratio_c)
    # branches: (sign of sin tau, root) = (+, +), (+, -), (-, +), (-, -)
    delta = np.stack([w + off, w - off, off - w, -w - off], axis=-1)
    s = s_abs[..., None] * np.array([1.0, 1.0, -1.0, -1.0])
    r_b = (rhs - big_r * ratio_c) / (c * np.sqrt(1.0 + ta * ta))
    r_b = np.broadcast_to(r_b[..., None], delta.shape)
    return np.cos(delta), np.sin(delta), s, r_b


@dataclass
class GridTerms:
    """The pose-free cost's terms on the (gamma, alpha, beta, phi) grid of :class:`GridSpec`,
    each linear in (1, X, Y) with X = c tan(beta) cos(phi), Y = c tan(beta) sin(phi)."""

    lin_cross: np.ndarray  # (G, A, N * 4, 3) float32
    lin_px: np.ndarray
    lin_py: np.ndarray
    coef: np.ndarray  # (G, 1, 3, B*P) float32: (1, X, Y) per (beta, phi)
    rb2: np.ndarray  # (G, A, N, 4, 1) float32: the misfit at B of each branch, squared
    n: int
    axes: dict


def grid_terms(t: dict[str, np.ndarray], spec: GridSpec) -> GridTerms:
    """:class:`GridTerms` of the frames ``t`` (:func:`frame_terms`)."""
    cp, ua, ub = t["cp"], t["ua"], t["ub"]
    n = cp.size
    gam = spec.gammas()
    alp = np.radians((np.arange(spec.n_alpha) + 0.5) * 90.0 / spec.n_alpha)
    bet = np.radians((np.arange(spec.n_beta) + 0.5) * 90.0 / spec.n_beta)
    phi = np.radians(np.linspace(0.0, 180.0, spec.n_phi))
    c = np.max(cp) / np.cos(gam)  # (G,)
    cg, ag = np.meshgrid(c, np.tan(alp), indexing="ij")  # (G, A)
    cos_d, sin_d, s, r_b = branch_candidates(cp, ub, cg, ag)  # (G, A, N, 4)
    vx, vy = ua[:, 0][:, None], ua[:, 1][:, None]  # (N, 1)
    dt = np.float32
    # Projected tangent at A times cos(beta) / c, with X = c tan(beta) cos(phi), Y = ... sin(phi):
    #     P = (c' + s (X sin d + Y cos d), X cos d - Y sin d)
    # and its cross product with the observed unit direction v:
    #     r_A = c' v_y + X (s sin d v_y - cos d v_x) + Y (s cos d v_y + sin d v_x).
    # All three are linear in (1, X, Y): one matrix product each for the whole (beta, phi) grid.
    ones = np.ones(cos_d.shape)
    lin_cross = np.stack(
        [cp[:, None] * vy * ones, s * sin_d * vy - cos_d * vx, s * cos_d * vy + sin_d * vx], -1
    )
    lin_px = np.stack([cp[:, None] * ones, s * sin_d, s * cos_d], -1)
    lin_py = np.stack([0.0 * ones, cos_d, -sin_d], -1)
    tb = np.tan(bet)
    xy = np.stack([np.outer(tb, np.cos(phi)).ravel(), np.outer(tb, np.sin(phi)).ravel()])
    coef = np.concatenate([np.ones((c.size, 1, xy.shape[1])), c[:, None, None] * xy[None]], axis=1)[
        :, None
    ].astype(dt)  # (G, 1, 3, B*P)
    shp = (spec.n_gamma, spec.n_alpha, n * 4, 3)
    lin_cross, lin_px, lin_py = (m.reshape(shp).astype(dt) for m in (lin_cross, lin_px, lin_py))
    rb2 = (r_b * r_b).astype(dt)[..., None]  # (G, A, N, 4, 1)
    axes = {"c": c, "alpha": alp, "beta": bet, "phi": phi}
    return GridTerms(lin_cross, lin_px, lin_py, coef, rb2, n, axes)


def grid_frame_misfits(g: GridTerms, ig: int) -> np.ndarray:
    """(A, N, B*P) every frame's misfit (its best branch of (10)), untruncated, float32, on the
    grid's gamma number ``ig`` (one gamma at a time: the work arrays stay in cache)."""
    dt = np.float32
    cross = g.lin_cross[ig] @ g.coef[ig]  # (A, N * 4, B*P)
    px = g.lin_px[ig] @ g.coef[ig]
    py = g.lin_py[ig] @ g.coef[ig]
    np.multiply(cross, cross, out=cross)
    np.multiply(px, px, out=px)
    np.multiply(py, py, out=py)
    np.add(px, py, out=px)
    px += dt(1e-30)
    np.divide(cross, px, out=cross)  # sin^2 of the angle error at A
    r2 = cross.reshape(cross.shape[0], g.n, 4, -1)
    r2 += g.rb2[ig]
    return np.minimum(np.minimum(r2[:, :, 0], r2[:, :, 1]), np.minimum(r2[:, :, 2], r2[:, :, 3]))


def grid_costs(obs: Observations, spec: GridSpec | None = None) -> tuple[np.ndarray, dict]:
    """Robust cost on the (gamma, alpha, beta, phi) grid; returns (costs, grid axes)."""
    spec = spec or GridSpec()
    g = grid_terms(frame_terms(obs), spec)
    trunc = np.float32(np.sin(np.radians(spec.truncate_deg)) ** 2)
    cost = np.empty((spec.n_gamma, spec.n_alpha, g.coef.shape[-1]))
    for ig in range(spec.n_gamma):
        per_frame = grid_frame_misfits(g, ig)  # (A, N, B*P)
        np.minimum(per_frame, trunc, out=per_frame)
        cost[ig] = np.sum(per_frame, axis=1, dtype=np.float64)  # (A, B*P)
    cost = cost.reshape(spec.n_gamma, spec.n_alpha, spec.n_beta, spec.n_phi)
    return cost, g.axes


def frame_misfits(obs_terms: dict[str, np.ndarray], params: np.ndarray) -> np.ndarray:
    """(M, N) pose-free misfit of every frame for shapes (M, 4) given as (gamma, alpha, beta,
    phi); c = max(c') / cos(gamma).

    The poses are eliminated exactly: per frame the best of the four solutions of (10); the
    misfit is the squared sine of the tangent-angle error at A plus (where (10) has no solution)
    the misfit at B.
    """
    cp, ua, ub = obs_terms["cp"], obs_terms["ua"], obs_terms["ub"]
    c = np.max(cp) / np.cos(params[:, 0])
    tb = np.tan(params[:, 2])
    cos_d, sin_d, s, r_b = branch_candidates(cp, ub, c, np.tan(params[:, 1]))  # (M, N, 4)
    x = (c * tb * np.cos(params[:, 3]))[:, None, None]
    y = (c * tb * np.sin(params[:, 3]))[:, None, None]
    px = cp[:, None] + s * (x * sin_d + y * cos_d)
    py = x * cos_d - y * sin_d
    cross = px * ua[:, 1][:, None] - py * ua[:, 0][:, None]
    r2 = cross * cross / (px * px + py * py + 1e-300) + r_b * r_b
    return np.min(r2, axis=2)


def reduced_cost(
    obs_terms: dict[str, np.ndarray], params: np.ndarray, truncate: float
) -> np.ndarray:
    """Robust cost of shapes given as (M, 4) (gamma, alpha, beta, phi): every frame's
    :func:`frame_misfits` truncated at ``truncate``, summed.  Returns (M,)."""
    return np.sum(np.minimum(frame_misfits(obs_terms, params), truncate), axis=1)


def _branch_residuals(obs_terms: dict[str, np.ndarray], params: np.ndarray) -> np.ndarray:
    """(M, N, 4, 2) signed residuals (sine of the angle error at A, misfit of (10) at B) of every
    branch, for shapes (M, 4) given as (gamma, alpha, beta, phi)."""
    cp, ua, ub = obs_terms["cp"], obs_terms["ua"], obs_terms["ub"]
    c = np.max(cp) / np.cos(params[:, 0])
    tb = np.tan(params[:, 2])
    cos_d, sin_d, s, r_b = branch_candidates(cp, ub, c, np.tan(params[:, 1]))
    x = (c * tb * np.cos(params[:, 3]))[:, None, None]
    y = (c * tb * np.sin(params[:, 3]))[:, None, None]
    px = cp[:, None] + s * (x * sin_d + y * cos_d)
    py = x * cos_d - y * sin_d
    cross = px * ua[:, 1][:, None] - py * ua[:, 0][:, None]
    r_a = cross / np.sqrt(px * px + py * py + 1e-300)
    return np.stack([r_a, r_b], axis=-1)


def local_refine(
    obs_terms: dict[str, np.ndarray],
    params: np.ndarray,
    truncate: float,
    n_iter: int = 15,
) -> tuple[np.ndarray, np.ndarray]:
    """Levenberg-Marquardt on :func:`reduced_cost` from M starts at once (branch per frame fixed
    at the current point, frames above the truncation left out, forward-difference Jacobian).

    Returns (params (M, 4), reduced costs (M,)).
    """
    x = np.array(params, dtype=float)
    m = x.shape[0]
    lo = np.array([0.0, 1e-4, 1e-4, -np.pi])
    hi = np.array([np.radians(87.0), np.pi / 2 - 1e-4, np.pi / 2 - 1e-4, 2 * np.pi])
    f = reduced_cost(obs_terms, x, truncate)
    lam = np.full(m, 1e-2)
    h = 1e-7
    rows = np.arange(m)[:, None]
    for _ in range(n_iter):
        res = _branch_residuals(obs_terms, x)  # (M, N, 4, 2)
        r2 = np.sum(res * res, axis=-1)
        k = np.argmin(r2, axis=2)  # (M, N)
        cols = np.arange(res.shape[1])[None, :]
        r = res[rows, cols, k]  # (M, N, 2)
        w = (np.min(r2, axis=2) < truncate)[..., None]
        xp = (x[:, None, :] + h * np.eye(4)[None]).reshape(-1, 4)
        resp = _branch_residuals(obs_terms, xp).reshape(m, 4, *res.shape[1:])
        rp = resp[
            np.arange(m)[:, None, None],
            np.arange(4)[None, :, None],
            cols[:, None, :],
            k[:, None, :],
        ]
        jac = (rp - r[:, None]) / h * w[:, None]  # (M, 4, N, 2)
        jac = jac.reshape(m, 4, -1)
        rv = (r * w).reshape(m, -1)
        jtj = jac @ np.swapaxes(jac, 1, 2)
        g = np.einsum("mij,mj->mi", jac, rv)
        d = np.einsum("mii->mi", jtj)
        a = jtj + lam[:, None, None] * (d[:, :, None] * np.eye(4) + 1e-12 * np.eye(4))
        try:
            step = -np.linalg.solve(a, g[..., None])[..., 0]
        except np.linalg.LinAlgError:
            break
        xn = np.clip(x + step, lo, hi)
        fn = reduced_cost(obs_terms, xn, truncate)
        better = fn < f
        x = np.where(better[:, None], xn, x)
        f = np.where(better, fn, f)
        lam = np.where(better, lam * 0.3, lam * 10.0)
    return x, f


def pattern_search(
    obs_terms: dict[str, np.ndarray],
    params: np.ndarray,
    steps: np.ndarray,
    truncate: float,
    n_iter: int = 30,
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised compass search of :func:`reduced_cost` from M starts; returns (params, costs)."""
    x = np.array(params, dtype=float)
    h = np.broadcast_to(np.asarray(steps, float), x.shape).copy()
    lo = np.array([0.0, 1e-4, 1e-4, -np.pi])
    hi = np.array([np.radians(87.0), np.pi / 2 - 1e-4, np.pi / 2 - 1e-4, 2 * np.pi])
    f = reduced_cost(obs_terms, x, truncate)
    m = x.shape[0]
    dirs = np.concatenate([np.eye(4), -np.eye(4)])  # (8, 4)
    for _ in range(n_iter):
        trial = x[:, None, :] + dirs[None] * h[:, None, :]
        trial = np.clip(trial, lo, hi)
        ft = reduced_cost(obs_terms, trial.reshape(-1, 4), truncate).reshape(m, 8)
        j = np.argmin(ft, axis=1)
        better = ft[np.arange(m), j] < f
        x = np.where(better[:, None], trial[np.arange(m), j], x)
        f = np.where(better, ft[np.arange(m), j], f)
        h = np.where(better[:, None], h, h * 0.5)
    return x, f


def poses_from_branches(obs: Observations, shape: np.ndarray) -> np.ndarray:
    """(N, 5) poses for a shape: per frame the candidate of (10) that best fits the tangent at A.

    ``shape`` may also be (K, 4): then (K, N, 5) poses, one set per shape (vectorised).
    """
    shapes = np.asarray(shape, float)
    single = shapes.ndim == 1
    shapes = np.atleast_2d(shapes)
    c, alpha, beta, phi = (shapes[:, i] for i in range(4))
    t = frame_terms(obs)
    cp, ua, ub = t["cp"], t["ua"], t["ub"]
    cos_d, sin_d, s, r_b = branch_candidates(cp, ub, c, np.tan(alpha))  # (K, N, 4)
    x = (c * np.tan(beta) * np.cos(phi))[:, None, None]
    y = (c * np.tan(beta) * np.sin(phi))[:, None, None]
    vx, vy = ua[:, 0][:, None], ua[:, 1][:, None]
    r_a = cp[:, None] * vy + x * (s * sin_d * vy - cos_d * vx) + y * (s * cos_d * vy + sin_d * vx)
    r_a = r_a / (c * np.sqrt(1 + np.tan(beta) ** 2))[:, None, None]
    k = np.argmin(r_a**2 + r_b**2, axis=2)[..., None]  # (K, N, 1)
    sin_k, cos_k = np.take_along_axis(sin_d, k, axis=2), np.take_along_axis(cos_d, k, axis=2)
    delta = np.arctan2(sin_k, cos_k)[..., 0]
    tau = np.arcsin(np.clip(np.take_along_axis(s, k, axis=2)[..., 0], -1.0, 1.0))
    rest = np.broadcast_to(
        np.column_stack([obs.theta, obs.a[:, 0], obs.a[:, 1]]), (shapes.shape[0], cp.size, 3)
    )
    out = np.concatenate([delta[..., None], tau[..., None], rest], axis=2)
    return out[0] if single else out


def switch_branches(
    obs: Observations,
    shape: np.ndarray,
    poses: np.ndarray,
    w8: np.ndarray,
    rescue: bool = False,
    options: SearchOptions | None = None,
) -> np.ndarray:
    """Per frame, the best of the current pose and the four branches of (10), shape fixed.

    Each alternative is polished by a few pose-only Gauss-Newton steps before the comparison.
    ``rescue``: frames that still fit badly are re-solved from a grid of starts as well
    (``_rescue_poses``; before a frame is called an outlier).  Returns the new (N, 5) poses
    (identical to ``poses`` where nothing fits better).  Also vectorised over candidates:
    shapes (K, 4) and poses (K, N, 5) give (K, N, 5).
    """
    shapes = np.asarray(shape, float)
    single = shapes.ndim == 1
    shapes = np.atleast_2d(shapes)  # (K, 4)
    poses = np.asarray(poses, float).reshape(shapes.shape[0], -1, 5)  # (K, N, 5)
    kk, n = poses.shape[:2]
    t = frame_terms(obs)
    cos_d, sin_d, s, _ = branch_candidates(
        t["cp"], t["ub"], shapes[:, 0], np.tan(shapes[:, 1])
    )  # (K, N, 4)
    sets = [poses]
    for k in range(4):
        alt = np.array(poses)
        alt[..., 0] = np.arctan2(sin_d[..., k], cos_d[..., k])
        alt[..., 1] = np.arcsin(np.clip(s[..., k], -1.0, 1.0))
        sets.append(alt)
    allp = np.stack(sets, axis=1).reshape(-1, 5)  # (K * 5 * N, 5)
    meas = np.tile(obs.measurements(), (kk * len(sets), 1))
    rows_shape = np.repeat(shapes, len(sets) * n, axis=0)
    allp, res = optimise_poses(
        rows_shape, allp, meas, w8, 6, halvings=POSE_HALVINGS if rescue else 0
    )
    f = np.sum(res * res, axis=1).reshape(kk, len(sets), n)
    allp = allp.reshape(kk, len(sets), n, 5)
    ki, ni = np.arange(kk)[:, None], np.arange(n)[None, :]
    best = np.argmin(f, axis=1)  # (K, N)
    best = np.where(f[ki, best, ni] < f[:, 0] - 1e-9 * (1.0 + f[:, 0]), best, 0)
    out = allp[ki, best, ni]
    if rescue:
        out = _rescue_poses(obs, shapes, out, f[ki, best, ni], w8, options or SearchOptions())
    return out[0] if single else out


def _rescue_poses(
    obs: Observations,
    shapes: np.ndarray,
    poses: np.ndarray,
    f: np.ndarray,
    w8: np.ndarray,
    o: SearchOptions,
) -> np.ndarray:
    """Poses (K, N, 5) with every frame whose chi2 ``f`` (K, N) is still above ``o.rescue_chi2``
    re-solved from a grid of starts (``o.rescue_deltas`` values of delta, both signs of tau at its
    current magnitude), shape fixed; a frame takes the best if it fits better.

    Where (10) has no real solution for the shape (c' >= c with noise, or the tangent at B out
    of reach) its branches all start at the clipped point and can all polish into one wrong
    minimum: on a 4642-frame test scene, chi2 64 at delta 0 where the pose at delta -30 (the
    other sign of tau) gives 3.4, and the frame was flagged as an outlier.
    """
    kk, nn = np.nonzero(f > o.rescue_chi2)
    if kk.size == 0:
        return poses
    deltas = np.linspace(-np.pi, np.pi, o.rescue_deltas, endpoint=False)
    base = poses[kk, nn]  # (M, 5)
    starts = np.repeat(base[:, None], 2 * o.rescue_deltas, axis=1)  # (M, 2D, 5)
    starts[..., 0] = np.tile(deltas, 2)[None]
    tau = np.abs(base[:, 1])[:, None] * np.repeat([1.0, -1.0], o.rescue_deltas)[None]
    starts[..., 1] = tau
    m = kk.size * 2 * o.rescue_deltas
    meas = np.repeat(obs.measurements()[nn], 2 * o.rescue_deltas, axis=0)
    rows_shape = np.repeat(shapes[kk], 2 * o.rescue_deltas, axis=0)
    sol, res = optimise_poses(rows_shape, starts.reshape(m, 5), meas, w8, 8)
    fr = np.sum(res * res, axis=1).reshape(kk.size, 2 * o.rescue_deltas)
    j = np.argmin(fr, axis=1)
    better = fr[np.arange(kk.size), j] < f[kk, nn] - 1e-9 * (1.0 + f[kk, nn])
    out = np.array(poses)
    sol = sol.reshape(kk.size, 2 * o.rescue_deltas, 5)
    out[kk[better], nn[better]] = sol[np.arange(kk.size), j][better]
    return out


def branch_alternatives(
    obs: Observations, shape: np.ndarray, poses: np.ndarray, w8: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Per frame the best pose on a different branch of (10) than ``poses``, shape fixed.

    "Different": the other sign of tau, or delta more than 5 degrees away.  Returns
    (poses (N, 5), chi2 (N,)); chi2 is inf where no other branch exists.
    """
    c, alpha = float(shape[0]), float(shape[1])
    t = frame_terms(obs)
    cos_d, sin_d, s, _ = branch_candidates(t["cp"], t["ub"], np.array(c), np.array(np.tan(alpha)))
    n = obs.n_frames
    sets = []
    for k in range(4):
        alt = np.array(poses)
        alt[:, 0] = np.arctan2(sin_d[:, k], cos_d[:, k])
        alt[:, 1] = np.arcsin(np.clip(s[:, k], -1.0, 1.0))
        sets.append(alt)
    allp = np.concatenate(sets)
    meas = np.tile(obs.measurements(), (4, 1))
    allp, res = optimise_poses(shape, allp, meas, w8, 8, halvings=0)
    f = np.sum(res * res, axis=1).reshape(4, n)
    allp = allp.reshape(4, n, 5)
    same_sign = np.sign(allp[:, :, 1]) == np.sign(poses[None, :, 1])
    close = np.abs(wrap_angle(allp[:, :, 0] - poses[None, :, 0])) < np.radians(5.0)
    f = np.where(same_sign & close, np.inf, f)
    best = np.argmin(f, axis=0)
    return allp[best, np.arange(n)], f[best, np.arange(n)]


def _local_minima(cost: np.ndarray, n_best: int) -> list[tuple[int, ...]]:
    filt = ndimage.minimum_filter(cost, size=3, mode="nearest")
    idx = np.argwhere(cost <= filt)
    vals = cost[tuple(idx.T)]
    order = np.argsort(vals, kind="stable")
    return [tuple(int(v) for v in idx[i]) for i in order[:n_best]]


def robust_cost(frame_chi2: np.ndarray, truncate: float = 25.0) -> float:
    """Sum of per-frame chi2 truncated at ``truncate`` (outlier frames count at most that)."""
    return float(np.sum(np.minimum(frame_chi2, truncate)))


def robust_start(
    obs: Observations,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    options: SearchOptions | None = None,
    **kwargs,
) -> list[Candidate]:
    """Refined candidates from the global search, best (lowest robust cost) first.

    With more than ``max_frames`` frames the search runs on ``max_frames`` evenly spread frames
    (its cost grows with the frame count) and its candidates are then refined on all frames.
    With more than ``o.medium_frames`` frames they are refined on that many evenly spread frames
    first, and only those within ``o.medium_keep_cost`` of the best there go on to all frames
    (the others would lose by far more on all frames; this saves most of the time of a long
    sequence).  Other keyword arguments go to :func:`search_start`.
    """
    o = options or SearchOptions()
    n = obs.n_frames
    max_frames = o.max_search_frames
    if n <= max_frames:
        return search_start(obs, point_sigma, tangent_sigma, options=o, **kwargs)
    cands = search_start(
        obs.subset(_spread(n, max_frames)), point_sigma, tangent_sigma, options=o, **kwargs
    )
    if n > o.medium_frames and len(cands) > 1:
        cands = _refined_on(
            obs.subset(_spread(n, o.medium_frames)), cands, point_sigma, tangent_sigma, o
        )
        cands = [c for c in cands if c.robust_cost <= cands[0].robust_cost + o.medium_keep_cost]
        # candidates of one basin (the same shape within ``o.medium_merge_distance``) start
        # their refinement on all frames from the same poses (every frame's pose comes from the
        # shape): only the best of them goes on
        kept: list[Candidate] = []
        for c in cands:
            if all(
                shape_distance(c.result.shape, k.result.shape) >= o.medium_merge_distance
                for k in kept
            ):
                kept.append(c)
        cands = kept
    if n > o.medium_frames:
        # a ladder of ever larger spread subsets (each ``o.ladder_factor`` times the last):
        # every rung starts within a few of its own standard deviations of its optimum, so the
        # refinement on all frames takes a few iterations instead of a long creep along c
        size = o.medium_frames * o.ladder_factor
        while 2 * size <= n:
            cands = _refined_on(obs.subset(_spread(n, size)), cands, point_sigma, tangent_sigma, o)
            size *= o.ladder_factor
    return _refined_on(obs, cands, point_sigma, tangent_sigma, o)


def _spread(n: int, m: int) -> np.ndarray:
    """Indices of ``m`` frames spread evenly over ``n``."""
    return np.unique(np.linspace(0, n - 1, m).round().astype(int))


def _refined_on(
    obs: Observations,
    cands: list[Candidate],
    point_sigma: float,
    tangent_sigma: float,
    o: SearchOptions,
) -> list[Candidate]:
    """The candidates' shapes refined (maximum likelihood) on the frames of ``obs``: each frame
    starts on its best branch of (10) for the shape; best (lowest robust cost) first."""
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)
    meas = obs.measurements()
    shapes = np.array([c.result.shape for c in cands])
    poses = switch_branches(obs, shapes, poses_from_branches(obs, shapes), w8)
    # every frame's pose polished for the shape (with halvings): the branch switch's own
    # polish has none, and the frames it left off cost the refinement its first iterations
    # (30,000 frames: chi2 36,352 at the start against 28,218 at the optimum)
    kk, n = poses.shape[:2]
    polished, res = optimise_poses(
        np.repeat(shapes, n, axis=0), poses.reshape(-1, 5), np.tile(meas, (kk, 1)), w8, 10
    )
    poses = polished.reshape(kk, n, 5)
    if n >= o.rescue_before_fit_frames:
        # frames that fit badly at the start shape try every branch and a grid of starts now
        # (``o.rescue_before_fit_frames``): the start is near the optimum on a long sequence
        fs = np.sum(res * res, axis=1).reshape(kk, n)
        for k in range(kk):
            bad = np.flatnonzero(fs[k] > o.rescue_chi2)
            if bad.size:
                poses[k, bad] = switch_branches(
                    obs.subset(bad), shapes[k], poses[k, bad], w8, rescue=True, options=o
                )
    g, p, r, chi2, iters, conv = refine_batch(
        meas, shapes, poses, point_sigma, tangent_sigma, max_iter=60
    )
    # frames left on a wrong pose at the best candidate's refined shape (among thousands a few
    # are): those above ``o.rescue_chi2`` try every branch and a grid of starts (``rescue``),
    # and the candidate is refitted if any moved.  (On a 4642-frame test scene three frames at
    # chi2 500-1400 made the fit's chi2 implausible and sent it to the trimmed refits, which
    # then flagged good frames.)
    fc = np.sum(r * r, axis=2)
    k = int(np.argmin([robust_cost(f) for f in fc]))
    bad = np.flatnonzero(fc[k] > o.rescue_chi2)
    if bad.size:
        pk = np.array(p[k])
        pk[bad] = switch_branches(obs.subset(bad), g[k], p[k, bad], w8, rescue=True, options=o)
        if np.any(pk != p[k]):
            g2, p2, r2, chi22, it2, conv2 = refine_batch(
                meas, g[k : k + 1], pk[None], point_sigma, tangent_sigma, max_iter=60
            )
            if chi22[0] < chi2[k]:
                g[k], p[k], r[k], chi2[k] = g2[0], p2[0], r2[0], chi22[0]
                iters[k] += it2[0]
                conv[k] = conv2[0]
    out = []
    for k, cand in enumerate(cands):
        shape_n, poses_n = normalise(g[k], p[k])
        fc = np.sum(r[k] * r[k], axis=1)
        res = RefineResult(
            shape_n, poses_n, float(chi2[k]), fc, r[k], None, int(iters[k]), bool(conv[k])
        )
        out.append(Candidate(res, robust_cost(fc), cand.grid_cost))
    out.sort(key=lambda cand: cand.robust_cost)
    return out


def search_start(
    obs: Observations,
    point_sigma: float = 1.0,
    tangent_sigma: float = np.radians(1.0),
    n_candidates: int | None = None,
    n_final: int = 4,
    spec: GridSpec | None = None,
    extra_shapes: list[np.ndarray] | None = None,
    n_restarts: int | None = None,
    n_restart_centres: int | None = None,
    options: SearchOptions | None = None,
) -> list[Candidate]:
    """Refined candidates from the global grid search, best (lowest robust cost) first.

    The ``n_candidates`` best grid minima (plus ``extra_shapes``) get a short ML refinement,
    all at once (``refine.refine_batch``); the ``n_final`` best distinct ones are refined to
    convergence.  Exact stage (at least ``o.exact_stage_min_frames`` frames): the best
    ``o.exact_stage_starts`` grid minima go first; those that polish to a pose-free cost
    <= ``o.exact_reduced_cost`` are refined, and if the best ML chi2 is
    <= ``o.exact_cost`` their candidates are returned (nothing can fit better; the other shapes
    returned are other exact fits only); otherwise the search continues as if the stage had not
    been (the same candidates).

    Args:
        obs: observations (at least 4 frames).
        point_sigma, tangent_sigma: noise (input units; radians) used by the ML refinement.
        n_candidates: number of grid minima refined briefly (default ``o.candidates``,
            ``o.candidates_few`` below 12 frames, ``o.candidates_minimal`` with 4).
        n_final: number of distinct candidates refined to convergence.
        spec: grid resolution.
        extra_shapes: further start shapes (e.g. from the linearisation).
        n_restarts: random restarts around each of the best candidates (default ``o.restarts``;
            ``o.restarts_few`` with fewer than 12 frames; ``o.restarts_implausible`` when the best
            chi2 is implausibly high or nearly but not exactly zero, ``o.near_exact_chi2``); none
            once the best fit is exact (``o.exact_cost``).
        n_restart_centres: around how many of the best candidates (by robust cost) the random
            restarts are drawn (default 2; 3 with fewer than 12 frames or an implausible chi2).
    Returns:
        Candidates sorted by robust cost; each ``result.shape`` normalised (alpha, beta in
        [0, pi/2], phi in [0, pi]); ``result.covariance`` is None.
    """
    o = options or SearchOptions()
    n = obs.n_frames
    few = n < 12
    if n_candidates is None:
        n_candidates = (
            o.candidates_minimal if n <= 4 else (o.candidates_few if few else o.candidates)
        )
    spec = spec or GridSpec.for_frames(n)
    n_search = (4 if few else 2) * n_candidates
    trunc = np.sin(np.radians(spec.truncate_deg)) ** 2
    terms = frame_terms(obs)
    extra = [np.asarray(e, float) for e in (extra_shapes or []) if np.all(np.isfinite(e))]

    def polish(x: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x, f = pattern_search(terms, x, h, trunc, n_iter=8)
        return local_refine(terms, x, trunc, n_iter=12 if few else 8)

    def finish(xs: np.ndarray, fs: np.ndarray) -> list[Candidate]:
        return _refine_candidates(
            obs,
            xs,
            fs,
            extra,
            point_sigma,
            tangent_sigma,
            n_candidates,
            n_final,
            n_restarts,
            n_restart_centres,
            o,
        )

    # Exact stage (noise-free data, at least o.exact_stage_min_frames frames): the best
    # o.exact_stage_starts grid minima first; if some fit exactly (reduced cost ~0) they alone are
    # refined, and if the best ML chi2 is <= o.exact_cost nothing can fit better: the search ends
    # with those exact candidates.  Otherwise the search runs as without this stage (the first
    # minima's polish is reused).
    m = o.exact_stage_starts
    x0, h0 = _grid_starts(obs, spec, n_search)
    if n < o.exact_stage_min_frames or x0.shape[0] <= m:
        xs, fs = polish(x0, h0)
        return finish(xs, fs)
    xs1, fs1 = polish(x0[:m], h0[:m])
    exact = fs1 <= o.exact_reduced_cost
    if exact.any():
        out = finish(xs1[exact], fs1[exact])
        if out and out[0].robust_cost <= o.exact_cost:
            return out
    xs2, fs2 = polish(x0[m:], h0[m:])
    return finish(np.concatenate([xs1, xs2]), np.concatenate([fs1, fs2]))


def _grid_starts(obs: Observations, spec: GridSpec, n_search: int) -> tuple[np.ndarray, np.ndarray]:
    """The ``n_search`` best local minima of the grid as (gamma, alpha, beta, phi) rows, best
    first, and per row the compass steps (half a grid cell; in gamma the local spacing)."""
    cost, axes = grid_costs(obs, spec)
    cells = _local_minima(cost, n_search)
    gam = np.arccos(np.clip(np.max(obs.cp) / axes["c"], 0.0, 1.0))
    x0 = np.array(
        [
            [gam[ig], axes["alpha"][ia], axes["beta"][ib], axes["phi"][ip]]
            for ig, ia, ib, ip in cells
        ]
    ).reshape(-1, 4)
    gam_grid = spec.gammas()
    gam_step = np.diff(gam_grid) if gam_grid.size > 1 else np.radians([spec.gamma_max_deg])
    gam_step = np.maximum(np.r_[gam_step, gam_step[-1:]], np.r_[gam_step[:1], gam_step])
    steps = 0.5 * np.column_stack(
        [
            gam_step[[ig for ig, _, _, _ in cells]],
            np.full(len(cells), axes["alpha"][1] - axes["alpha"][0]),
            np.full(len(cells), axes["beta"][1] - axes["beta"][0]),
            np.full(len(cells), axes["phi"][1] - axes["phi"][0]),
        ]
    )
    return x0, steps


def _refine_candidates(
    obs: Observations,
    xs: np.ndarray,
    fs: np.ndarray,
    extra: list[np.ndarray],
    point_sigma: float,
    tangent_sigma: float,
    n_candidates: int,
    n_final: int,
    n_restarts: int | None,
    n_restart_centres: int | None,
    o: SearchOptions,
) -> list[Candidate]:
    """The ML part of :func:`search_start` from polished grid minima ``xs`` (gamma, alpha, beta,
    phi) with reduced costs ``fs``: short batched refinement of the best distinct ones (and
    ``extra`` shapes), the best distinct refined to convergence, branch switching, restarts."""
    pr = _Problem(obs, obs.measurements(), point_sigma, tangent_sigma)
    shapes, grid_cost = _start_shapes(obs, xs, fs, extra, n_candidates)
    g, p, r, _, _, _ = pr.refine(
        shapes, poses_from_branches(obs, shapes), max_iter=15, drop_factor=3.0
    )
    chosen = _distinct_best(g, p, r, n_final)
    fits = _Fits(*pr.refine(g[chosen], p[chosen], max_iter=40, drop_factor=3.0))
    _switch_and_refit(pr, fits)
    _restart_around_best(pr, fits, n_restarts, n_restart_centres, o)
    out = []
    for k, i in enumerate(chosen):
        shape_n, poses_n = normalise(fits.g[k], fits.p[k])
        fc = np.sum(fits.r[k] * fits.r[k], axis=1)
        res = RefineResult(
            shape_n,
            poses_n,
            float(fits.chi2[k]),
            fc,
            fits.r[k],
            None,
            int(fits.iters[k]),
            bool(fits.conv[k]),
        )
        out.append(Candidate(res, robust_cost(fc), grid_cost[i]))
    out.sort(key=lambda cand: cand.robust_cost)
    return out


@dataclass(frozen=True)
class _Problem:
    """What every refinement of :func:`_refine_candidates` fits: the frames, their
    measurements and noise."""

    obs: Observations
    meas: np.ndarray
    point_sigma: float
    tangent_sigma: float

    @property
    def w8(self) -> np.ndarray:
        """The residuals' weights (1 / sigma) for ``switch_branches``."""
        return np.array([1.0 / self.point_sigma] * 4 + [1.0 / self.tangent_sigma] * 2)

    def refine(self, shapes: np.ndarray, poses: np.ndarray, **kwargs) -> tuple[np.ndarray, ...]:
        """``refine_batch`` from these starts on the frames (keyword arguments passed on)."""
        return refine_batch(
            self.meas, shapes, poses, self.point_sigma, self.tangent_sigma, **kwargs
        )


@dataclass
class _Fits:
    """Refined candidates as ``refine_batch`` returns them: shapes g (K, 4), poses p (K, N, 5),
    residuals r (K, N, 6), chi2, iterations and convergence (K,)."""

    g: np.ndarray
    p: np.ndarray
    r: np.ndarray
    chi2: np.ndarray
    iters: np.ndarray
    conv: np.ndarray

    def robust_costs(self) -> np.ndarray:
        """Every candidate's robust cost (:func:`robust_cost` of its frames' chi2)."""
        return np.array([robust_cost(f) for f in np.sum(self.r * self.r, axis=2)])


def _start_shapes(
    obs: Observations, xs: np.ndarray, fs: np.ndarray, extra: list[np.ndarray], n_candidates: int
) -> tuple[np.ndarray, list[float]]:
    """The start shapes (c, alpha, beta, phi) of the ``n_candidates`` best distinct minima (all
    four parameters within 1e-3 rad of a kept one: the same), best first, then ``extra``; and
    each one's grid cost (NaN for ``extra``)."""
    order = np.argsort(fs, kind="stable")
    keep = np.zeros(order.size, bool)
    for j, i in enumerate(order):
        if np.count_nonzero(keep) >= n_candidates:
            break
        prev = xs[order[:j][keep[:j]]]
        keep[j] = prev.size == 0 or np.min(np.max(np.abs(prev - xs[i]), axis=1)) >= 1e-3
    sel = order[keep]
    cmax = np.max(obs.cp)
    starts = [np.array([cmax / np.cos(xs[i, 0]), *xs[i, 1:]]) for i in sel]
    grid_cost = [float(fs[i]) for i in sel]
    for e in extra:
        starts.append(e)
        grid_cost.append(float("nan"))
    return np.array(starts), grid_cost


def _distinct_best(g: np.ndarray, p: np.ndarray, r: np.ndarray, n_final: int) -> list[int]:
    """The ``n_final`` best (lowest robust cost) refined starts with distinct normalised
    shapes (``shape_distance`` above 1e-3)."""
    fchi2 = np.sum(r * r, axis=2)
    rc = np.array([robust_cost(f) for f in fchi2])
    order = np.argsort(rc, kind="stable")
    chosen: list[int] = []
    normed = [normalise(g[i], p[i])[0] for i in range(len(g))]
    for i in order:
        if len(chosen) >= n_final:
            break
        if all(shape_distance(normed[i], normed[j]) > 1e-3 for j in chosen):
            chosen.append(int(i))
    return chosen


def _switch_and_refit(pr: _Problem, fits: _Fits) -> None:
    """Branch switching: a frame may sit on the wrong solution of (10) (sign of tau, root);
    every branch is tried per frame with the shape fixed, and the candidates refitted where
    that helps (in place)."""
    p_sw = switch_branches(pr.obs, fits.g, fits.p, pr.w8)
    changed = np.any(p_sw != fits.p, axis=(1, 2))
    if not changed.any():
        return
    g2, p2, r2, chi22, it2, conv2 = pr.refine(
        fits.g[changed], p_sw[changed], max_iter=40, drop_factor=3.0
    )
    better = chi22 < fits.chi2[changed]
    idx = np.flatnonzero(changed)[better]
    fits.g[idx], fits.p[idx], fits.r[idx] = g2[better], p2[better], r2[better]
    fits.chi2[idx] = chi22[better]
    fits.iters[idx] += it2[better]
    fits.conv[idx] = conv2[better]


def _restart_around_best(
    pr: _Problem,
    fits: _Fits,
    n_restarts: int | None,
    n_restart_centres: int | None,
    o: SearchOptions,
) -> None:
    """Local restarts around the best candidates (few frames: many shallow minima nearby); the
    best restart replaces the worst candidate (in place) if its robust cost is lower than the
    best one's.

    That needs it below the best one's by a relative 1e-9: impossible (costs are >= 0) once the
    best fit is exact (noise-free data, or 4 frames, where every refined start fits exactly) -
    the restarts are then skipped.  They are ranked by the robust cost (as the candidates are):
    with outlier frames the raw chi2 can prefer a wrong shape that spreads the outliers' misfit
    over all frames."""
    n = pr.obs.n_frames
    few = n < 12
    dof = max(n - 4, 1)
    implausible = np.min(fits.chi2) > dof + 5.0 * np.sqrt(2.0 * dof) + 10.0
    near_exact = np.min(fits.chi2) < o.near_exact_chi2 * dof  # nearly noise-free: search harder
    if n_restarts is None:
        n_restarts = (
            o.restarts_implausible
            if implausible or near_exact
            else (o.restarts_few if few else o.restarts)
        )
    rc = fits.robust_costs()
    if not (n_restarts > 0 and np.min(rc) > o.exact_cost):
        return
    if n_restart_centres is None:
        n_restart_centres = 3 if (few or implausible) else 2
    starts = _restart_starts(fits, rc, n_restarts, n_restart_centres)
    best, best_cost = _best_restart(pr, starts, not (implausible or near_exact), o)
    k_worst = int(np.argmax(rc))
    if best_cost < np.min(rc) - 1e-9 * (1 + np.min(rc)):
        fits.g[k_worst], fits.p[k_worst], fits.r[k_worst] = best.g[0], best.p[0], best.r[0]
        fits.chi2[k_worst] = best.chi2[0]
        fits.iters[k_worst], fits.conv[k_worst] = best.iters[0], best.conv[0]


def _restart_starts(fits: _Fits, rc: np.ndarray, n_restarts: int, n_centres: int) -> np.ndarray:
    """``n_restarts`` random shapes around each of the ``n_centres`` best candidates (by
    robust cost), alternately at 1 and 2.5 times the spread (seeded: the same every call)."""
    rng = np.random.default_rng(12345)
    top = np.argsort(rc, kind="stable")[:n_centres]
    starts = []
    spread = np.where(np.arange(n_restarts) % 2 == 0, 1.0, 2.5)[:, None]
    for k in top:
        pert = fits.g[k] + spread * rng.normal(size=(n_restarts, 4)) * np.array(
            [0.04 * fits.g[k][0], 0.06, 0.06, 0.1]
        )
        pert[:, 0] = np.abs(pert[:, 0])
        starts.append(pert)
    return np.concatenate(starts)


def _best_restart(
    pr: _Problem, starts: np.ndarray, screen: bool, o: SearchOptions
) -> tuple[_Fits, float]:
    """The best restart (robust cost) refined to convergence, branch switching included, and
    its robust cost.

    ``screen`` (plausible noisy data): the restarts are screened by Gauss-Newton alone (cheap
    iterations that keep a start's basin); the ``o.restart_finalists`` best by robust cost are
    then refined from their starts as every restart is otherwise (Newton phase, to
    convergence): the same results whenever the best restart is among them.  Implausible or
    nearly noise-free data (a missed minimum, an exact fit to find): no screening."""
    sp = poses_from_branches(pr.obs, starts)
    fin = np.arange(len(starts))
    if screen:
        _, _, r3, _, _, _ = pr.refine(
            starts,
            sp,
            max_iter=o.screen_iterations,
            ftol=o.screen_ftol,
            drop_factor=3.0,
            newton_phase=False,
        )
        rc3 = np.array([robust_cost(f) for f in np.sum(r3 * r3, axis=2)])
        fin = np.sort(np.argsort(rc3, kind="stable")[: o.restart_finalists])
    g3, p3, r3, chi23, it3, conv3 = pr.refine(starts[fin], sp[fin], max_iter=40, drop_factor=3.0)
    rc3 = np.array([robust_cost(f) for f in np.sum(r3 * r3, axis=2)])
    j = int(np.argmin(rc3))
    best = _Fits(
        g3[j : j + 1],
        p3[j : j + 1],
        r3[j : j + 1],
        chi23[j : j + 1],
        it3[j : j + 1],
        conv3[j : j + 1],
    )
    p_sw = switch_branches(pr.obs, g3[j], p3[j], pr.w8)
    if np.any(p_sw != p3[j]):
        g4, p4, r4, chi24, it4, conv4 = pr.refine(g3[j : j + 1], p_sw[None], max_iter=40)
        rc4 = robust_cost(np.sum(r4[0] * r4[0], axis=1))
        if rc4 < rc3[j]:
            best.g[0], best.p[0], best.r[0] = g4[0], p4[0], r4[0]
            best.chi2[0], best.conv[0] = chi24[0], conv4[0]
            rc3[j] = rc4
    return best, rc3[j]


def shape_distance(a: np.ndarray, b: np.ndarray) -> float:
    """Distance between normalised shapes: relative c difference and angle differences (rad)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = np.abs(wrap_angle(a[1:] - b[1:]))
    return float(max(abs(a[0] - b[0]) / max(a[0], b[0]), np.max(d)))
