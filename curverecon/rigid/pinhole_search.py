"""A global search over frame 0's depths (``perspective``, ``free``, four points or more).

Under a pinhole the body is fixed by the depths of its points in frame 0: with A's depth 1
(the gauge) and every point on its known ray m = (x, y, 1) (normalised coordinates), the depths
(lambda_B, lambda_C, lambda_D) of B, C, D give X_k = lambda_k m_k0.  For such a body every other
frame's pose follows in closed form: perspective-three-point (P3P, Grunert's distances along the
rays of A, B, C, every real root) places A, B and C, and D = A + alpha u + beta v + gamma u x v
(u = B - A, v = C - A; alpha, beta, gamma the coefficients of frame 0's D - A in that basis, which
a rotation keeps) chooses the root whose D reprojects nearest to its image.  A frame's misfit is
that squared distance (pixels^2; frame 0 has none), capped at ``CAP_PX``^2, and a body's score
the trimmed sum over the frames (``rigid.starts.TRIM``: outlier frames do not decide).

The grid is over B's and C's depths only (``GRID`` each, within ``REACH`` times the point's
longest image distance from A in any frame, normalised units), every cell at once
(vectorised): its poses place D on a line P_fr + lambda_D Q_fr in each frame f and root r,
each (frame, root) proposes the lambda_D whose point is nearest D's ray, and the best-scoring
proposal is the cell's (exact on noise-free scenes, where no grid in D's depth would be); points
beyond D (five or more) likewise, each on its own.  The cells are scored on ``SEARCH_FRAMES``
frames; the best ``KEEP`` distinct cells are polished by Nelder-Mead on the score over all of
B, C, D's depths, and the best ``count`` become starts (every frame's points from its chosen
root, the rotations by Kabsch), which the consensus fit and maximum likelihood of
``rigid.estimate`` then refine.

The depth reversal (:func:`other_valleys`): a nearly flat body seen from afar images almost
alike when its depths are reversed (the orthographic mirror, which the perspective only
weakly breaks); at 1 px and 1000 units the two valleys' chi2 often differ by less than the
noise (bench seed 0, 20 accuracy scenes: the answer's valley had the lower chi2 than the
truth's on 9).  The answer's fit on its inlier frames is mirrored (body z -> -z, R_f -> S R_f
S) and refined: a lower chi2 becomes the answer, one within ``ALTERNATIVE_DCHI2`` of the
answer's and apart from it by more than its std is reported beside it and widens its
covariance (:func:`widened_covariance`).
"""

from __future__ import annotations

import numpy as np

from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState
from curverecon.rigid.refinement import RigidFit, refine
from curverecon.rigid.starts import TRIM

GRID = 40
"""Depths of B and of C on the coarse grid (GRID^2 cells; D's depth proposed per cell): the
noise-free six-frame scenes 0-9 of the bench (seed 0) all found first; a 14^3 grid over B, C
and D missed 3 of them (the true valley about 0.005 wide in depth)."""
SEARCH_FRAMES = 10
"""Frames (frame 0 and others spread evenly) that score and polish the cells (the cost grows
with the square of the frames: all 20 took 2.3 s under load); the chosen bodies are posed in
every frame."""
BLOCK = 100
"""Cells scored at once (memory: BLOCK * 4 N * N * 4 * 3 floats)."""
REACH = 1.6
"""Half-width of each point's depth range, in units of its longest image distance from A
(normalised coordinates): a body vector's length is about the longest of its images."""
KEEP = 4
"""Coarse cells polished by Nelder-Mead."""
POLISH_ITERATIONS = 200
"""Nelder-Mead iterations per polished cell (the maximum likelihood polishes further)."""
CAP_PX = 30.0
"""A frame's misfit is capped at this many pixels (an outlier frame, or no valid root)."""
NEWTON_STEPS = 2
"""Newton steps on each root of the quartic after the companion matrix's eigenvalues."""
MIN_DEPTH = 0.05
"""Depths below this (relative to A's) are not tried."""
ALTERNATIVE_DCHI2 = 4.0
"""The depth-reversed valley is an alternative when its chi2 is at most this above the
answer's (two standard deviations of a one-parameter likelihood ratio)."""
VALLEY_ITERATIONS = 400
"""Levenberg-Marquardt iterations of the depth-reversed refit (``estimate.PINHOLE_ITERATIONS``)."""


def _poly_mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Coefficients (lowest degree first, along the last axis, padded to degree 4) of the
    product of a and b (total degree at most 4)."""
    shape = np.broadcast_shapes(a.shape[:-1], b.shape[:-1])
    out = np.zeros(shape + (5,))
    for i in range(a.shape[-1]):
        m = min(b.shape[-1], 5 - i)
        out[..., i : i + m] += a[..., i : i + 1] * b[..., :m]
    return out


def p3p(rays: np.ndarray, body: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every pose of three points: rays (..., 3, 3) (any length, points A, B, C) and their body
    positions (..., 3, 3) (any frame).  Returns (camera points (..., 4, 3, 3), valid (..., 4)):
    Grunert's distances s_k along the unit rays j_k with s_B = u s_A, s_C = v s_A; the
    difference of two of the three cosine-law equations is linear in u, u = p(v) / q(v), and
    substituted into the third a quartic in v, solved by its companion matrix.  A root is valid
    when real, every distance positive and the three side lengths met to 1e-6 relative."""
    j = rays / np.linalg.norm(rays, axis=-1, keepdims=True)
    ca = np.sum(j[..., 1, :] * j[..., 2, :], axis=-1)  # between B and C
    cb = np.sum(j[..., 0, :] * j[..., 2, :], axis=-1)  # A and C
    cg = np.sum(j[..., 0, :] * j[..., 1, :], axis=-1)  # A and B
    a2 = np.sum((body[..., 1, :] - body[..., 2, :]) ** 2, axis=-1)
    b2 = np.sum((body[..., 0, :] - body[..., 2, :]) ** 2, axis=-1)
    c2 = np.sum((body[..., 0, :] - body[..., 1, :]) ** 2, axis=-1)
    one, zero = np.ones_like(ca), np.zeros_like(ca)
    w = np.stack([one, -2.0 * cb, one], axis=-1)  # 1 + v^2 - 2 v cb
    # b2 (u^2 + v^2 - 2 u v ca) = a2 w  and  b2 (1 + u^2 - 2 u cg) = c2 w; their difference:
    # u * 2 b2 (v ca - cg) = b2 (v^2 - 1) - (a2 - c2) w
    p = b2[..., None] * np.stack([-one, zero, one], axis=-1) - (a2 - c2)[..., None] * w
    q = 2.0 * b2[..., None] * np.stack([-cg, ca], axis=-1)
    qq = _poly_mul(q, q)
    quart = b2[..., None] * (qq + _poly_mul(p, p) - 2.0 * cg[..., None] * _poly_mul(p, q))
    quart = quart - c2[..., None] * _poly_mul(w, qq)
    lead = quart[..., 4:5]
    lead = np.where(np.abs(lead) > 1e-300, lead, 1e-300)
    comp = np.zeros(ca.shape + (4, 4))
    comp[..., 1:, :3] = np.eye(3)
    comp[..., :, 3] = -quart[..., :4] / lead
    with np.errstate(all="ignore"):
        roots = np.linalg.eigvals(np.nan_to_num(comp))
        v = roots.real
        c4 = quart[..., None, :]  # (..., 1, 5) against the roots (..., 4)
        for _ in range(NEWTON_STEPS):
            val = (((c4[..., 4] * v + c4[..., 3]) * v + c4[..., 2]) * v + c4[..., 1]) * v
            val = val + c4[..., 0]
            der = ((4.0 * c4[..., 4] * v + 3.0 * c4[..., 3]) * v + 2.0 * c4[..., 2]) * v
            der = der + c4[..., 1]
            step = val / der
            v = np.where(np.isfinite(step), v - step, v)
        pv = p[..., None, 0] + p[..., None, 1] * v + p[..., None, 2] * v * v
        qv = q[..., None, 0] + q[..., None, 1] * v
        u = pv / qv
        sa = np.sqrt(c2[..., None] / (1.0 + u * u - 2.0 * u * cg[..., None]))
        s = _refine_distances(
            np.stack([sa, u * sa, v * sa], axis=-1),  # (..., 4, 3)
            np.stack([ca, cb, cg], axis=-1)[..., None, :],
            np.stack([a2, b2, c2], axis=-1)[..., None, :],
        )
        pts = s[..., None] * j[..., None, :, :]
        err = np.stack(
            [
                np.sum((pts[..., 1, :] - pts[..., 2, :]) ** 2, -1) / a2[..., None],
                np.sum((pts[..., 0, :] - pts[..., 2, :]) ** 2, -1) / b2[..., None],
                np.sum((pts[..., 0, :] - pts[..., 1, :]) ** 2, -1) / c2[..., None],
            ],
            axis=-1,
        )
        valid = (
            np.all(s > 0, axis=-1)
            & np.all(np.abs(err - 1.0) < 1e-6, axis=-1)
            & (np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(v)))
        )
    return pts, valid


def _refine_distances(s: np.ndarray, cos: np.ndarray, sides2: np.ndarray) -> np.ndarray:
    """Newton steps on the three cosine-law equations in the distances s (..., 3) (A, B, C;
    cos and sides2 (..., 3) opposite A, B, C): the quartic's roots lose digits when the rays
    are nearly parallel (a distant object)."""
    ca, cb, cg = (cos[..., i] for i in range(3))
    for _ in range(NEWTON_STEPS):
        s1, s2, s3 = (s[..., i] for i in range(3))
        f = (
            np.stack(
                [
                    s2 * s2 + s3 * s3 - 2.0 * s2 * s3 * ca,
                    s1 * s1 + s3 * s3 - 2.0 * s1 * s3 * cb,
                    s1 * s1 + s2 * s2 - 2.0 * s1 * s2 * cg,
                ],
                axis=-1,
            )
            - sides2
        )
        zero = np.zeros_like(s1)
        jac = 2.0 * np.stack(
            [
                np.stack([zero, s2 - s3 * ca, s3 - s2 * ca], axis=-1),
                np.stack([s1 - s3 * cb, zero, s3 - s1 * cb], axis=-1),
                np.stack([s1 - s2 * cg, s2 - s1 * cg, zero], axis=-1),
            ],
            axis=-2,
        )
        ok = np.isfinite(f).all(-1) & np.isfinite(jac).all((-1, -2))
        ok &= np.abs(np.linalg.det(np.where(ok[..., None, None], jac, np.eye(3)))) > 1e-300
        safe = np.where(ok[..., None, None], jac, np.eye(3))
        step = np.linalg.solve(safe, np.where(ok[..., None], f, 0.0)[..., None])[..., 0]
        s = s - step
    return s


def _others(x0: np.ndarray) -> np.ndarray:
    """(..., P - 3, 3) the coefficients (alpha, beta, gamma) of every point beyond C in the basis
    (u, v, u x v) of frame 0's points x0 (..., P, 3)."""
    u, v = x0[..., 1, :] - x0[..., 0, :], x0[..., 2, :] - x0[..., 0, :]
    basis = np.stack([u, v, np.cross(u, v)], axis=-1)  # columns
    rel = x0[..., 3:, :] - x0[..., :1, :]
    return np.linalg.solve(basis[..., None, :, :], rel[..., None])[..., 0]


def _frame_points(pts: np.ndarray, coef: np.ndarray) -> np.ndarray:
    """(..., R, P, 3) every root's points: A, B, C from P3P (..., R, 3, 3), the rest by their
    coefficients (..., P - 3, 3)."""
    u, v = pts[..., 1, :] - pts[..., 0, :], pts[..., 2, :] - pts[..., 0, :]
    w = np.cross(u, v)
    c = coef[..., None, :, :]
    rest = (
        pts[..., None, 0, :]
        + c[..., 0:1] * u[..., None, :]
        + c[..., 1:2] * v[..., None, :]
        + c[..., 2:3] * w[..., None, :]
    )
    return np.concatenate([pts, rest], axis=-2)


def _misfits(rays: np.ndarray, pix: np.ndarray, focal: float, lam: np.ndarray):
    """For bodies of frame-0 depths lam (K, P) (A's first, 1): (per-frame squared misfit in
    pixels^2 (K, N), every frame's points of the best root (K, N, P, 3))."""
    x0 = lam[..., None] * rays[0][None]  # (K, P, 3)
    coef = _others(x0)  # (K, P-3, 3)
    k, n = len(lam), len(rays)
    pts, valid = p3p(
        np.broadcast_to(rays[None, :, :3], (k, n, 3, 3)),
        np.broadcast_to(x0[:, None, :3], (k, n, 3, 3)),
    )
    full = _frame_points(pts, coef[:, None])  # (K, N, 4, P, 3)
    with np.errstate(all="ignore"):
        proj = full[..., 3:, :2] / full[..., 3:, 2:]
        d2 = focal**2 * np.sum((proj - pix[None, :, None, 3:]) ** 2, axis=(-1, -2))
        ok = valid & np.all(full[..., 3:, 2] > 0, axis=-1)
    d2 = np.where(ok & np.isfinite(d2), d2, np.inf)
    best = np.argmin(d2, axis=-1)  # (K, N)
    mis = np.minimum(np.take_along_axis(d2, best[..., None], -1)[..., 0], CAP_PX**2)
    mis[:, 0] = 0.0
    chosen = np.take_along_axis(full, best[..., None, None, None], axis=2)[:, :, 0]
    chosen[:, 0] = x0
    found = np.isfinite(np.take_along_axis(d2, best[..., None], -1)[..., 0])
    found[:, 0] = True
    # a frame without a valid root keeps the pose of the last frame before it that has one
    for f in range(1, n):
        chosen[~found[:, f], f] = chosen[~found[:, f], f - 1]
    return mis, chosen


def _score(mis: np.ndarray) -> np.ndarray:
    """(K,) the trimmed sum of the frames' misfits (K, N) (frame 0 counted as a kept zero)."""
    n = mis.shape[1]
    keep = max(1, int(np.ceil((1.0 - TRIM) * n)))
    return np.sum(np.sort(mis, axis=1)[:, :keep], axis=1)


def _grid(rays: np.ndarray) -> np.ndarray:
    """(GRID^2, 3) the coarse cells' depths (A's 1) of B and C."""
    img = np.linalg.norm(rays[:, 1:3, :2] - rays[:, :1, :2], axis=-1)  # (N, 2)
    reach = REACH * np.max(img, axis=0)
    axes = [np.linspace(max(1.0 - r, MIN_DEPTH), 1.0 + r, GRID) for r in reach]
    mesh = np.meshgrid(*axes, indexing="ij")
    return np.stack([np.ones(mesh[0].size)] + [m.ravel() for m in mesh], axis=1)


def _further_depths(rays: np.ndarray, pix: np.ndarray, focal: float, abc: np.ndarray):
    """For bodies whose A, B, C have frame-0 depths abc (K, 3): (the depth of every further
    point (K, P - 3), score (K,)).  Each frame's root places A, B, C; a further point at depth
    lambda in frame 0 is then at P_fr + lambda Q_fr in frame f (a line), and each (frame, root)
    proposes the lambda whose point is nearest its ray (linear least squares); every proposal
    is scored over all frames (misfit of the nearest root, capped, trimmed sum) and the best
    kept, point by point."""
    k, n, p = len(abc), len(rays), rays.shape[1]
    x0 = abc[..., None] * rays[0, :3][None]  # (K, 3, 3)
    pts, valid = p3p(
        np.broadcast_to(rays[None, :, :3], (k, n, 3, 3)),
        np.broadcast_to(x0[:, None], (k, n, 3, 3)),
    )
    u0, v0 = x0[:, 1] - x0[:, 0], x0[:, 2] - x0[:, 0]
    basis0 = np.stack([u0, v0, np.cross(u0, v0)], axis=-1)  # (K, 3, 3) columns
    u, v = pts[..., 1, :] - pts[..., 0, :], pts[..., 2, :] - pts[..., 0, :]
    basis = np.stack([u, v, np.cross(u, v)], axis=-1)  # (K, N, 4, 3, 3)
    lam = np.ones((k, p - 3))
    total = np.zeros(k)
    for j in range(3, p):
        g = np.linalg.solve(basis0, np.broadcast_to(rays[0, j], (k, 3))[..., None])[..., 0]
        h = np.linalg.solve(basis0, x0[:, 0, :, None])[..., 0]
        q = np.einsum("knrij,kj->knri", basis, g)
        base = pts[..., 0, :] - np.einsum("knrij,kj->knri", basis, h)
        m = rays[None, :, None, j]  # (1, N, 1, 3)
        c, e = np.cross(m, base), np.cross(m, q)
        with np.errstate(all="ignore"):
            prop = -np.sum(c * e, -1) / np.sum(e * e, -1)  # (K, N, 4)
        prop = np.where(valid, prop, np.nan)[:, 1:].reshape(k, -1)  # (K, C)
        with np.errstate(all="ignore"):
            pt = base[:, None] + prop[:, :, None, None, None] * q[:, None]  # (K, C, N, 4, 3)
            proj = pt[..., :2] / pt[..., 2:]
            d2 = focal**2 * np.sum((proj - pix[None, None, :, None, j]) ** 2, -1)
        d2 = np.where(valid[:, None] & (pt[..., 2] > 0) & np.isfinite(d2), d2, np.inf)
        mis = np.minimum(np.min(d2, axis=-1), CAP_PX**2)  # (K, C, N)
        mis[..., 0] = 0.0
        keep = max(1, int(np.ceil((1.0 - TRIM) * n)))
        sc = np.sum(np.sort(mis, axis=-1)[..., :keep], axis=-1)
        sc = np.where(np.isfinite(prop) & (prop > MIN_DEPTH), sc, np.inf)
        best = np.argmin(sc, axis=1)
        lam[:, j - 3] = np.take_along_axis(prop, best[:, None], 1)[:, 0]
        total += np.take_along_axis(sc, best[:, None], 1)[:, 0]
    return lam, total


def _cells(rays: np.ndarray, pix: np.ndarray, focal: float) -> tuple[np.ndarray, np.ndarray]:
    """(every cell's depths (K, P), score (K,)): the (B, C) grid, the further points' depths
    by :func:`_further_depths`, in blocks of ``BLOCK`` cells."""
    abc = _grid(rays)
    lams, scores = [], []
    for i in range(0, len(abc), BLOCK):
        lam, sc = _further_depths(rays, pix, focal, abc[i : i + BLOCK])
        lams.append(lam)
        scores.append(sc)
    return np.concatenate([abc, np.concatenate(lams)], axis=1), np.concatenate(scores)


def _polish(rays, pix, focal, lam0: np.ndarray) -> tuple[np.ndarray, float]:
    """(depths (P,), score) after Nelder-Mead on the score from lam0 (A's depth held at 1)."""
    from scipy.optimize import minimize

    def cost(x):
        lam = np.concatenate([[1.0], np.maximum(x, MIN_DEPTH)])[None]
        return float(_score(_misfits(rays, pix, focal, lam)[0])[0])

    res = minimize(
        cost,
        lam0[1:],
        method="Nelder-Mead",
        options={"xatol": 1e-5, "fatol": 1e-6, "maxiter": POLISH_ITERATIONS},
    )
    return np.concatenate([[1.0], np.maximum(res.x, MIN_DEPTH)]), float(res.fun)


def depth_search(data: RigidData, count: int = 2) -> list[np.ndarray]:
    """The ``count`` best bodies' every-frame points (N, P, 3), A's depth in frame 0 = 1
    (module docstring)."""
    cam = data.camera
    focal = float(cam.focal_px)
    rays = cam.rays(data.points)  # (N, P, 3)
    pix = rays[..., :2]
    sub = np.unique(np.round(np.linspace(0, len(rays) - 1, min(len(rays), SEARCH_FRAMES))))
    sub = sub.astype(int)
    cells, score = _cells(rays[sub], pix[sub], focal)
    spacing = np.ptp(cells[:, 1:3], axis=0) / (GRID - 1)
    picked: list[int] = []
    for i in np.argsort(score, kind="stable"):
        if not np.isfinite(score[i]):
            break
        if all(np.any(np.abs(cells[i, 1:3] - cells[j, 1:3]) > 1.5 * spacing) for j in picked):
            picked.append(int(i))
        if len(picked) == KEEP:
            break
    polished = [_polish(rays[sub], pix[sub], focal, cells[i]) for i in picked]
    polished.sort(key=lambda t: t[1])
    bodies: list[np.ndarray] = []
    for lam, _ in polished:
        if not any(np.max(np.abs(lam - b)) < 1e-3 for b in bodies):
            bodies.append(lam)
        if len(bodies) == count:
            break
    return [_misfits(rays, pix, focal, lam[None])[1][0] for lam in bodies]


def search_starts(layout: Layout, data: RigidData, count: int = 2) -> list[RigidState]:
    """Starts of the perspective free row with four points or more (module docstring)."""
    from curverecon.rigid.pinhole_starts import state_from_points3

    out = []
    for p3 in depth_search(data, count):
        try:
            out.append(state_from_points3(layout, data, p3))
        except (np.linalg.LinAlgError, ValueError):
            continue
    return out


def depth_reversed(state: RigidState) -> RigidState:
    """The state mirrored in depth about A: body z -> -z, every R_f -> S R_f S (S = diag(1, 1,
    -1)), A's positions kept; exact under orthographic projection, a start under a pinhole."""
    flip = np.diag([1.0, 1.0, -1.0])
    out = state.copy()
    out.body = out.body * np.array([1.0, 1.0, -1.0])
    out.rotations = flip @ out.rotations @ flip
    return out


def other_valleys(layout: Layout, data: RigidData, fit: RigidFit) -> tuple[RigidFit, list]:
    """(the answer's fit, the alternatives' fits) of the perspective free row with four points
    or more: ``fit`` (on the frames ``data``, with its covariance) and its depth-reversed refit
    (module docstring); the lower chi2 is the answer, the other an alternative when within
    ``ALTERNATIVE_DCHI2`` and some body coordinate differs by more than the answer's std.
    Every other row: (fit, [])."""
    free4 = layout.projection == "perspective" and layout.motion == "free"
    if not free4 or len(layout.points) < 4 or fit.covariance is None:
        return fit, []
    try:
        alt = refine(layout, depth_reversed(fit.state), data, max_iter=VALLEY_ITERATIONS)
    except (np.linalg.LinAlgError, FloatingPointError, ValueError):
        return fit, []
    if alt.covariance is None or not np.isfinite(alt.chi2):
        return fit, []
    best, other = (alt, fit) if alt.chi2 < fit.chi2 else (fit, alt)
    sd = np.sqrt(np.maximum(np.diag(best.covariance), 0.0))[: best.state.body.size]
    apart = np.abs(other.state.body - best.state.body).ravel() > sd
    if other.chi2 - best.chi2 > ALTERNATIVE_DCHI2 or not np.any(apart):
        return best, []
    return best, [other]


def answer_valleys(
    layout: Layout, data: RigidData, fit: RigidFit, idx: np.ndarray
) -> tuple[RigidFit, list]:
    """:func:`other_valleys` on the inlier frames ``idx`` of ``data`` (every frame): when the
    depth-reversed refit becomes the answer, its ``full_state`` carries the outlier frames
    mirrored too (their parameters are the answer's last over every frame).  The force field:
    the valleys its search settled in (``pinhole_branches.force_field_valleys``)."""
    if layout.motion == "force-field":
        from curverecon.rigid.pinhole_branches import force_field_valleys

        return force_field_valleys(layout, data, fit, idx)
    best, alts = other_valleys(layout, data.subset(idx), fit)
    if best is fit:
        return fit, alts
    full = depth_reversed(fit.full_state or fit.state)
    full.body = np.array(best.state.body, float)
    full.rotations[idx] = best.state.rotations
    full.translations[idx] = best.state.translations
    best.full_state = full
    return best, alts


def widened_covariance(fit: RigidFit, alternatives: list) -> np.ndarray | None:
    """The globals' covariance with every alternative's body offset d added (cov + d d^T): the
    answer's std then reaches each valley that fits about as well (free motion: the globals
    are the body; the force field: the body and the parabola)."""
    if fit.covariance is None:
        return None
    cov = np.array(fit.covariance, float)
    n = fit.state.body.size
    if fit.state.parabola is not None:  # the force field: the parabola follows the body
        n += fit.state.parabola.size
    for alt in alternatives:
        d = _globals_of(alt.state) - _globals_of(fit.state)
        cov[:n, :n] += np.outer(d, d)
    return cov


def _globals_of(state: RigidState) -> np.ndarray:
    """The body, then the force field's parabola (the globals' order of the fit)."""
    parts = [np.ravel(state.body)]
    if state.parabola is not None:
        parts.append(np.ravel(state.parabola))
    return np.concatenate(parts)


__all__ = [
    "depth_reversed",
    "answer_valleys",
    "depth_search",
    "other_valleys",
    "p3p",
    "search_starts",
    "widened_covariance",
]
