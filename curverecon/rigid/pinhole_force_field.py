"""The perspective force field's global search: the mass centre's 3-D parabola and the body's
invariants, every frame's depths eliminated without choosing a branch.

A and B seen by a pinhole, the mass centre G unseen on G(t) = g0 + g1 t + g2 t^2 / 2 (camera
coordinates, the gauge g0_z = 1).  In a frame with unit rays m_A, m_B, A = lam m_A and
B = mu m_B come from a body with |A - G|^2 = aa, |B - G|^2 = bb, (A - G).(B - G) = ab exactly
when depths lam, mu exist.  With alpha = m_A.G, beta = m_B.G, k = m_A.m_B, x = lam - alpha,
y = mu - beta:

    x^2 = P = aa - |G|^2 + alpha^2,     y^2 = Q = bb - |G|^2 + beta^2,
    k x y + a1 x + b1 y + C = 0,        a1 = k beta - alpha, b1 = k alpha - beta,
                                        C = k alpha beta - alpha^2 - beta^2 + |G|^2 - ab.

Solving the last for y, squaring with y^2 = Q, solving for x and squaring with x^2 = P leaves
one polynomial equation a frame, free of the roots' signs:

    E = (a1^2 P + C^2 - k^2 P Q - b1^2 Q)^2 - 4 P (k b1 Q - a1 C)^2 = 0.

Eleven unknowns (g0_x, g0_y, g1, g2, aa, bb, ab), one equation a frame: the row's count (11
frames).  Choosing each frame's branch instead (two roots a point) makes the cost jump where a
ray grazes a sphere, and a fit over the same eleven globals reaches the truth only from 0.1 %
off it; E is smooth.  The search (as ``rigid.parabola``'s orthographic one):

* the residual is E over its gradient in the four normalised image coordinates (the Sampson
  distance, about normalised image units), with the depths' existence min(P, 0) and min(Q, 0)
  (E also holds for imaginary depths); damped Gauss-Newton on a batch of starts, the largest
  ``TRIM`` fraction of the frames without weight at each step (outlier frames);
* the starts: G's image on the parabola through the points' mean image, moved at three times by
  the mean image's scatter, at depths 1 and exp(N(0, DEPTH_SPREAD)) at the middle and last time;
  the invariants from the largest image chord (aa = bb about (c / 2)^2, ab about -(c / 2)^2);
* ``CANDIDATES`` distinct minima are polished together and each becomes a state: the body from
  frame 0's best root pair, every frame's rotation from the triangle A, B, G of each of the
  four root pairs (``rigid.starts.kabsch``) refitted with the globals held, the pair of least
  chi2 kept per frame; each state is settled over every frame (``rigid.pinhole_branches``:
  the frames' root pairs chosen again), the best ``WALKED`` walked along their weakest
  direction.

:func:`force_field_starts` returns the ``KEEP`` best for ``rigid.pinhole_starts``; the consensus
fit and maximum likelihood over every frame's rotation follow.  The search's cost does not rank
the candidates (near-solutions abound), the refined chi2 does; the full fit's basin about the
truth is narrow, so some noise-free scenes still end in another minimum (docs/accuracy.md).
"""

from __future__ import annotations

import numpy as np

from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState

STARTS = 256
"""Starts of the batch (the first the mean image's parabola at depth 1)."""
ITERATIONS = 80
"""Gauss-Newton iterations of every start."""
TRIM = 0.2
"""Fraction of frames without weight at each step (outlier frames do not pull the search)."""
DEPTH_SPREAD = 0.3
"""Log-normal spread of the starts' depths of G at the middle and last time (the bench's scenes
move G by up to about 0.3 of its distance in depth)."""


def _design(t: np.ndarray) -> np.ndarray:
    return np.column_stack([np.ones_like(t), t, 0.5 * t * t])


def _unpack(x: np.ndarray, t: np.ndarray):
    """(G (K, N, 3), aa, bb, ab (K, 1)) of parameter rows x (K, 11): g0_x, g0_y, g1, g2, aa,
    bb, ab (g0_z = 1)."""
    par = np.concatenate([x[:, :2], np.ones((len(x), 1)), x[:, 2:8]], axis=1).reshape(-1, 3, 3)
    g = np.einsum("fj,kjd->kfd", _design(t), par)
    return g, x[:, 8:9], x[:, 9:10], x[:, 10:11]


def _terms(ma: np.ndarray, mb: np.ndarray, g, aa, bb, ab):
    """(E, P, Q) per (start, frame) for unit rays ma, mb (K or 1, N, 3) (module docstring)."""
    alpha, beta = np.sum(ma * g, -1), np.sum(mb * g, -1)
    k = np.sum(ma * mb, -1)
    gg = np.sum(g * g, -1)
    p = aa - gg + alpha**2
    q = bb - gg + beta**2
    c = k * alpha * beta - alpha**2 - beta**2 + gg - ab
    a1, b1 = k * beta - alpha, k * alpha - beta
    lhs = a1 * a1 * p + c * c - k * k * p * q - b1 * b1 * q
    e = lhs * lhs - 4.0 * p * (k * b1 * q - a1 * c) ** 2
    return e, p, q


def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _residuals(u: np.ndarray, t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(K, N, 3) residuals of parameter rows x (K, 11) at normalised image points u (N, 2, 2):
    E's Sampson distance and the depths' existence (module docstring)."""
    g, aa, bb, ab = _unpack(x, t)
    rays = _unit(np.concatenate([u, np.ones(u.shape[:-1] + (1,))], axis=-1))
    e, p, q = _terms(rays[None, :, 0], rays[None, :, 1], g, aa, bb, ab)
    h = 1e-6
    grad2 = np.zeros_like(e)
    for j in range(2):
        for d in range(2):
            v = u.copy()
            v[:, j, d] += h
            r2 = _unit(np.concatenate([v, np.ones(v.shape[:-1] + (1,))], axis=-1))
            ed = _terms(r2[None, :, 0], r2[None, :, 1], g, aa, bb, ab)[0]
            grad2 += ((ed - e) / h) ** 2
    scale = np.sqrt(np.maximum(np.abs(aa) + np.abs(bb), 1e-300))
    floor = 1e-8 * np.maximum(np.abs(aa) + np.abs(bb), 1e-300) ** 4
    out = np.empty(e.shape + (3,))
    out[..., 0] = e / np.sqrt(grad2 + floor)
    out[..., 1] = np.minimum(p, 0.0) / scale
    out[..., 2] = np.minimum(q, 0.0) / scale
    return out


def _jacobian(u, t, x, res) -> np.ndarray:
    """(K, N, 3, 11) forward differences of :func:`_residuals`, each step relative to its
    parameter's size."""
    jac = np.zeros(res.shape + (x.shape[1],))
    for i in range(x.shape[1]):
        h = 1e-7 * np.maximum(np.abs(x[:, i]), 1e-4)
        xi = x.copy()
        xi[:, i] += h
        jac[..., i] = (_residuals(u, t, xi) - res) / h[:, None, None]
    return jac


def _weights(res: np.ndarray, trim: float) -> np.ndarray:
    """(K, N) weights 1 on the smallest (1 - trim) of every row's frame residuals, else 0."""
    norm = np.sum(res * res, -1)
    keep = max(1, int(np.ceil((1.0 - trim) * norm.shape[1])))
    order = np.argsort(norm, axis=1)
    w = np.zeros_like(norm)
    np.put_along_axis(w, order[:, :keep], 1.0, axis=1)
    return w


def _gauss_newton(u, t, x, trim: float, iterations: int):
    """Damped Gauss-Newton on the trimmed residuals for every row of x (K, 11): (x, cost)."""

    def evaluate(x):
        with np.errstate(all="ignore"):
            res = _residuals(u, t, x)
        res = np.where(np.isfinite(res), res, 1e6)
        return res * _weights(res, trim)[..., None]

    res = evaluate(x)
    cost = np.sum(res * res, (1, 2))
    lam = np.full(len(x), 1e-3)
    n = x.shape[1]
    for _ in range(iterations):
        with np.errstate(all="ignore"):
            jac = _jacobian(u, t, x, res) * (res != 0)[..., None]
        jac = np.where(np.isfinite(jac), jac, 0.0)
        h = np.einsum("knmi,knmj->kij", jac, jac)
        b = np.einsum("knmi,knm->ki", jac, res)
        d = np.einsum("kii->ki", h)
        hd = h + (lam[:, None] * np.maximum(d, 1e-30))[:, :, None] * np.eye(n)[None]
        try:
            step = -np.linalg.solve(hd, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            break
        trial = x + np.where(np.isfinite(step), step, 0.0)
        r_t = evaluate(trial)
        c_t = np.sum(r_t * r_t, (1, 2))
        better = np.isfinite(c_t) & (c_t < cost)
        x = np.where(better[:, None], trial, x)
        res = np.where(better[:, None, None], r_t, res)
        cost = np.where(better, c_t, cost)
        lam = np.where(better, np.maximum(lam / 10.0, 1e-12), np.minimum(lam * 10.0, 1e12))
    return x, cost


def _starts(u: np.ndarray, t: np.ndarray, count: int, seed: int) -> np.ndarray:
    """(count, 11) start rows (module docstring)."""
    design = _design(t)
    mean = u.mean(axis=1)
    base = np.linalg.lstsq(design, mean, rcond=None)[0]
    spread = max(float(np.sqrt(np.mean(np.sum((mean - design @ base) ** 2, 1)))), 1e-9)
    tk = np.array([t[0], 0.5 * (t[0] + t[-1]), t[-1]])
    dk = _design(tk)
    rng = np.random.default_rng(seed)
    img = dk @ base + rng.normal(0.0, spread, (count, 3, 2))
    depth = np.exp(rng.normal(0.0, DEPTH_SPREAD, (count, 3)))
    img[0], depth[0] = dk @ base, 1.0
    depth[:, 0] = 1.0
    knots = np.concatenate([img, np.ones((count, 3, 1))], axis=2) * depth[..., None]
    par = np.linalg.solve(dk[None], knots)  # (count, 3, 3) g0, g1, g2
    par /= par[:, :1, 2:3]  # the gauge g0_z = 1 (a scale of the whole scene)
    chord = float(np.max(np.linalg.norm(u[:, 0] - u[:, 1], axis=1)))
    half = (0.5 * chord * np.exp(rng.normal(0.0, 0.3, (count, 1)))) ** 2
    aa = half * np.exp(rng.normal(0.0, 0.3, (count, 1)))
    bb = half * np.exp(rng.normal(0.0, 0.3, (count, 1)))
    ab = -np.sqrt(aa * bb) * rng.uniform(0.5, 1.0, (count, 1))
    aa[0], bb[0], ab[0] = half[0], half[0], -0.9 * half[0]
    flat = par.reshape(count, 9)
    return np.concatenate([flat[:, :2], flat[:, 3:], aa, bb, ab], axis=1)


def search(
    u: np.ndarray, times: np.ndarray, seed: int = 0, count: int = 12
) -> list[tuple[np.ndarray, float]]:
    """The distinct minima of the trimmed Sampson cost, best first: up to ``count`` of
    (parameter row (11,), cost).  ``u`` (N, 2, 2): A's and B's normalised image coordinates
    ((pixels - principal point) / focal length), ``times`` (N,)."""
    t = np.asarray(times, float)
    x, cost = _gauss_newton(u, t, _starts(u, t, STARTS, seed), TRIM, ITERATIONS)
    out: list[tuple[np.ndarray, float]] = []
    for k in np.argsort(cost):
        if not np.isfinite(cost[k]):
            break
        g = _unpack(x[k : k + 1], t)[0][0]
        if any(np.max(np.abs(g - _unpack(o[None], t)[0][0])) < 1e-3 for o, _ in out):
            continue
        out.append((x[k].copy(), float(cost[k])))
        if len(out) == count:
            break
    return out


def branches(u: np.ndarray, times: np.ndarray, row: np.ndarray):
    """(A and B in every frame for each of the four root pairs (4, N, 2, 3), G (N, 3), the pair
    whose y = -(a1 x + C) / (k x + b1) fits best (N,)): pair (i, j) takes x = (-1)^i sqrt(P),
    y = (-1)^j sqrt(Q) (negative P, Q clipped to 0)."""
    t = np.asarray(times, float)
    g, aa, bb, ab = (v[0] for v in _unpack(row[None], t))
    rays = _unit(np.concatenate([u, np.ones(u.shape[:-1] + (1,))], axis=-1))
    ma, mb = rays[:, 0], rays[:, 1]
    alpha, beta = np.sum(ma * g, -1), np.sum(mb * g, -1)
    k = np.sum(ma * mb, -1)
    gg = np.sum(g * g, -1)
    p = np.sqrt(np.maximum(aa - gg + alpha**2, 0.0))
    q = np.sqrt(np.maximum(bb - gg + beta**2, 0.0))
    c = k * alpha * beta - alpha**2 - beta**2 + gg - ab
    a1, b1 = k * beta - alpha, k * alpha - beta
    pts, miss = [], []
    for sx in (1.0, -1.0):
        for sy in (1.0, -1.0):
            x, y = sx * p, sy * q
            miss.append(np.abs(k * x * y + a1 * x + b1 * y + c))
            lam, mu = x + alpha, y + beta
            pts.append(np.stack([lam[:, None] * ma, mu[:, None] * mb], axis=1))
    return np.array(pts), g, np.argmin(np.array(miss), axis=0)


BRANCH_ITERATIONS = 30
"""Levenberg-Marquardt iterations of every frame's own rotation per root pair (globals held)."""


def state_of(layout: Layout, data: RigidData, row: np.ndarray) -> RigidState:
    """The row's state from one parameter row: the body from frame 0's best root pair, the
    parabola from the row; every frame's rotation from the triangle A, B, G of each root pair
    (``rigid.starts.kabsch``), refitted with the globals held, the pair of least chi2 kept
    per frame (a root pair of an inexact row can be the wrong one where a ray grazes a
    sphere)."""
    from curverecon.rigid.refinement import refine
    from curverecon.rigid.starts import kabsch

    cam = data.camera
    u = (data.points - np.asarray(cam.principal_point, float)) / float(cam.focal_px)
    pts, g, pick = branches(u, data.times, row)
    tri = []
    for k in range(4):
        a, b = pts[k, :, 0] - g, pts[k, :, 1] - g
        tri.append(np.stack([a, b, np.cross(a, b)], axis=1))
    ref = tri[pick[0]][0]
    parabola = np.concatenate([row[:2], [1.0], row[2:8]]).reshape(3, 3)
    best_chi2, best_rots = None, None
    for k in range(4):
        rots = kabsch(ref, tri[k])
        rots[0] = np.eye(3)
        state = RigidState(body=ref[:2].copy(), parabola=parabola.copy(), rotations=rots)
        try:
            fit = refine(layout, state, data, max_iter=BRANCH_ITERATIONS, covariance=False,
                         fix_globals=True)  # fmt: skip
        except (np.linalg.LinAlgError, ValueError):
            continue
        chi2 = np.where(np.isfinite(fit.frame_chi2), fit.frame_chi2, np.inf)
        if best_chi2 is None:
            best_chi2, best_rots = chi2, fit.state.rotations.copy()
            continue
        take = chi2 < best_chi2
        best_chi2 = np.where(take, chi2, best_chi2)
        best_rots[take] = fit.state.rotations[take]
    if best_rots is None:
        raise ValueError("no root pair could be refitted")
    return RigidState(body=ref[:2].copy(), parabola=parabola, rotations=best_rots)


CANDIDATES = 12
"""Distinct minima of the search polished and refined over every frame: noise-free, 30 frames,
the truth reached on 9 of 10 scenes of bench seed 0 and 4 of 10 of seed 1 (with 16 candidates
and 4 kept the same scenes)."""
KEEP = 3
"""Refined candidates of least trimmed chi2 handed on as starts."""
POLISH_ITERATIONS = 100
"""Gauss-Newton iterations polishing the candidates together."""
WALKED = 2
"""Settled candidates of least trimmed chi2 walked along their weakest direction."""


def force_field_starts(layout: Layout, data: RigidData) -> list[RigidState]:
    """Start states of the perspective force field with A and B (no tangents: the search's
    equation has none; else an empty list): the search's ``CANDIDATES`` distinct minima,
    polished, each made a state (:func:`state_of`) and settled over every frame
    (``pinhole_branches.settle``: the frames' root pairs chosen again); the ``WALKED`` best
    walked along their weakest direction (``pinhole_branches.walk``); the ``KEEP`` of least
    trimmed chi2 (``rigid.starts.trimmed_sum``: outlier frames do not decide), fits of a
    singular information last.  Every settled
    valley is remembered for the answer's alternatives."""
    from curverecon.rigid.pinhole_branches import admit, remember, settle, walk

    if layout.tangents or layout.projection != "perspective" or len(layout.points) != 2:
        return []
    cam = data.camera
    u = (data.points - np.asarray(cam.principal_point, float)) / float(cam.focal_px)
    found = search(u, data.times, count=CANDIDATES)
    if not found:
        return []
    rows = _gauss_newton(u, data.times, np.array([r for r, _ in found]), TRIM, POLISH_ITERATIONS)[0]
    scored: list = []
    for row in rows:
        try:
            with np.errstate(all="ignore"):
                scored += admit(layout, data, settle(layout, data, state_of(layout, data, row)))
        except (np.linalg.LinAlgError, ValueError, FloatingPointError):
            continue
    scored.sort(key=lambda item: item[:2])  # regular fits first, then by trimmed chi2
    for singular, _, state, cov in list(scored[:WALKED]):
        if not singular:
            for fit in walk(layout, data, state, cov):
                scored += admit(layout, data, fit)
    scored.sort(key=lambda item: item[:2])
    remember(data, [item[2] for item in scored if not item[0]])
    return [item[2] for item in scored[:KEEP]]


__all__ = ["force_field_starts", "search"]
