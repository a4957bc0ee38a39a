"""The force field's global search: the mass centre's parabola and the body's invariants.

With A and B seen and the mass centre G unseen, a frame's images p = A' - xy(G) and
q = B' - xy(G) (xy(G) = g0 + g1 t + g2 t^2 / 2) come from a body with |a|^2 = aa, |b|^2 = bb,
a.b = ab (a = A - G, b = B - G) exactly when (aa - |p|^2)(bb - |q|^2) = (ab - p.q)^2 (the
depths exist; ``solvers/ortho_force_field.residuals``, generated).  Nine unknowns, one equation a
frame, and no practical minimal solver; but the equation is cheap, so a batch of starts is
refined at once:

* the equation divided by its gradient in the measured A', B' (the Sampson distance, about
  input units) is the residual; Gauss-Newton with Marquardt damping, every start in one array;
  the largest ``trim`` fraction of the frames' residuals get no weight at each step (outlier
  frames), so the score is the trimmed sum of squares;
* the starts: the parabola through the points' mean image (G lies within the body's size of
  it), then that parabola moved at three times (the first, middle and last frame) by normal
  draws of the mean image's scatter about it; the invariants by linear least squares given the
  parabola (the equation is linear in aa, bb, ab and aa bb - ab^2).

:func:`search` returns the distinct minima, best first; ``rigid.starts`` turns them into states
(depths from the invariants, rotations aligned).  The bench's 30 noise-free scenes of 14
frames (seed 2026) all come out within 1e-14 of the chord (docs/accuracy.md).
"""

from __future__ import annotations

import numpy as np

from curverecon.solvers.ortho_force_field import residuals as equation

STARTS = 96
"""Starts of the batch (the first the mean image's parabola)."""
ITERATIONS = 60
"""Gauss-Newton iterations of every start."""


def _design(t: np.ndarray) -> np.ndarray:
    return np.column_stack([np.ones_like(t), t, 0.5 * t * t])


def sampson(points: np.ndarray, times: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(K, N, 3) residuals (input units) of K parameter vectors x (K, 9) in the order of
    ``ortho_force_field.UNKNOWNS`` and their (K, N, 3, 9) Jacobians: per frame the Sampson
    distance of the equation (its normalising gradient held, as in Gauss-Newton on it) and
    the depths' existence, min(aa - |p|^2, 0) / (2 |p|) and the same for b (about the distance
    A' or B' would have to move): the equation alone also holds for imaginary depths, and a
    nearly straight body (G near the line AB) leaves its length to these two."""
    pts, t = np.asarray(points, float), np.asarray(times, float)
    design = _design(t)
    r, grad = equation(pts[:, :2], t, x.T[:, :, None])
    centre = np.einsum("fj,kjd->kfd", design, x[:, :6].reshape(-1, 3, 2))
    p, q = pts[None, :, 0] - centre, pts[None, :, 1] - centre
    aa, bb, ab = (x[:, i : i + 1] for i in (6, 7, 8))
    za2, zb2 = aa - np.sum(p * p, 2), bb - np.sum(q * q, 2)
    zab = ab - np.sum(p * q, 2)
    dp = -2.0 * p * zb2[..., None] + 2.0 * zab[..., None] * q
    dq = -2.0 * q * za2[..., None] + 2.0 * zab[..., None] * p
    floor = 1e-4 * np.maximum(np.abs(aa) + np.abs(bb), 1e-300) ** 3
    den = np.sqrt(np.sum(dp * dp, 2) + np.sum(dq * dq, 2) + floor)
    res = np.zeros((len(x), len(t), 3))
    jac = np.zeros((len(x), len(t), 3, 9))
    res[..., 0] = r / den
    jac[..., 0, :] = np.asarray(grad).reshape(len(x), len(t), 9) / den[..., None]
    for j, (v, z2) in enumerate(((p, za2), (q, zb2))):
        norm = np.sqrt(np.sum(v * v, 2)) + 1e-12
        on = z2 < 0
        res[..., 1 + j] = np.where(on, z2 / (2.0 * norm), 0.0)
        dg = np.where(on[..., None], v / norm[..., None], 0.0)  # d(-|v|^2)/dg / (2 |v|)
        jac[..., 1 + j, :6] = np.einsum("kfd,fj->kfjd", dg, design).reshape(len(x), len(t), 6)
        jac[..., 1 + j, 6 + j] = np.where(on, 1.0 / (2.0 * norm), 0.0)
    return res, jac


def invariants(points: np.ndarray, times: np.ndarray, parabola: np.ndarray) -> np.ndarray:
    """(aa, bb, ab) given the parabola (3, 2): linear least squares of
    D - aa |q|^2 - bb |p|^2 + 2 ab p.q = -(p x q)^2 in (D, aa, bb, ab), D = aa bb - ab^2."""
    centre = _design(np.asarray(times, float)) @ parabola
    p, q = points[:, 0] - centre, points[:, 1] - centre
    cross = p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]
    ones = np.ones(len(p))
    a = np.column_stack([ones, -np.sum(q * q, 1), -np.sum(p * p, 1), 2 * np.sum(p * q, 1)])
    scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
    sol = np.linalg.lstsq(a / scale, -(cross**2), rcond=None)[0] / scale
    return sol[1:]


def _trimmed_weights(res: np.ndarray, trim: float) -> np.ndarray:
    """(K, N) weights 1 on the smallest (1 - trim) of every row's squared residuals, else 0."""
    n = res.shape[1]
    keep = max(1, int(np.ceil((1.0 - trim) * n)))
    order = np.argsort(res * res, axis=1)
    w = np.zeros_like(res)
    np.put_along_axis(w, order[:, :keep], 1.0, axis=1)
    return w


def _gauss_newton(points, times, x, trim, iterations):
    """Damped Gauss-Newton on the trimmed residuals of :func:`sampson` for every row of x
    (K, 9): a frame's weight is 1 or 0 by its squared residuals' sum."""

    def evaluate(x):
        res, jac = sampson(points, times, x)
        w = _trimmed_weights(np.sqrt(np.sum(res * res, 2)), trim)
        return res * w[..., None], jac * w[..., None, None]

    res, jac = evaluate(x)
    cost = np.sum(res * res, (1, 2))
    lam = np.full(len(x), 1e-3)
    for _ in range(iterations):
        h = np.einsum("knmi,knmj->kij", jac, jac)
        b = np.einsum("knmi,knm->ki", jac, res)
        d = np.einsum("kii->ki", h)
        hd = h + (lam[:, None] * np.maximum(d, 1e-12))[:, :, None] * np.eye(9)[None]
        try:
            step = -np.linalg.solve(hd, b[..., None])[..., 0]
        except np.linalg.LinAlgError:
            break
        trial = x + np.where(np.isfinite(step), step, 0.0)
        r_t, j_t = evaluate(trial)
        c_t = np.sum(r_t * r_t, (1, 2))
        better = np.isfinite(c_t) & (c_t < cost)
        x = np.where(better[:, None], trial, x)
        res = np.where(better[:, None, None], r_t, res)
        jac = np.where(better[:, None, None, None], j_t, jac)
        cost = np.where(better, c_t, cost)
        lam = np.where(better, np.maximum(lam / 10.0, 1e-12), np.minimum(lam * 10.0, 1e12))
    return x, cost


def search(
    points: np.ndarray,
    times: np.ndarray,
    trim: float = 0.2,
    count: int = 3,
    seed: int = 0,
) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """The distinct minima of the trimmed Sampson cost, best first: up to ``count`` of
    (parabola (3, 2), invariants (aa, bb, ab), trimmed cost).  ``points`` (N, 2, 2) the images
    of A and B (input units), ``times`` (N,); ``seed`` fixes the starts."""
    pts, t = np.asarray(points, float)[:, :2], np.asarray(times, float)
    design = _design(t)
    mean = pts.mean(axis=1)
    base = np.linalg.lstsq(design, mean, rcond=None)[0]
    spread = max(float(np.sqrt(np.mean(np.sum((mean - design @ base) ** 2, 1)))), 1e-9)
    tk = np.array([t[0], 0.5 * (t[0] + t[-1]), t[-1]])
    dk = _design(tk)
    rng = np.random.default_rng(seed)
    knots = dk @ base + rng.normal(0.0, spread, (STARTS, 3, 2))
    knots[0] = dk @ base
    x = np.zeros((STARTS, 9))
    for k in range(STARTS):
        par = np.linalg.solve(dk, knots[k])
        x[k, :6] = par.ravel()
        x[k, 6:] = invariants(pts, t, par)
    x, cost = _gauss_newton(pts, t, x, trim, ITERATIONS)
    out: list[tuple[np.ndarray, np.ndarray, float]] = []
    for k in np.argsort(cost):
        if not np.isfinite(cost[k]):
            break
        par = x[k, :6].reshape(3, 2)
        if any(np.max(np.abs(dk @ (par - o[0]))) < 0.05 * spread + 1e-9 for o in out):
            continue
        out.append((par, x[k, 6:].copy(), float(cost[k])))
        if len(out) == count:
            break
    return out
