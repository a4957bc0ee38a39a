"""Shape refinement by the marginal likelihood: every frame's pose integrated out (Laplace).

Why.  Each frame carries six measurements (A', B', two tangent angles) and five pose parameters
of its own (delta, tau, theta, tx, ty), so it tells the shape one number.  Maximising the
likelihood over the poses as well ("profile likelihood", ``refine.refine``) is then biased at
realistic noise, the Neyman-Scott effect of incidental parameters (the bias does not shrink as
frames are added, the bound does).  Measured on the benchmark's 1 px / 1 deg, 20-frame scenes
refined from the truth: the maximum-likelihood c comes out long (mean error +0.7 of its
Cramer-Rao bound) and its RMSE is 3.5 times the bound.

What.  Integrate each frame's pose out instead, over the invariant (Haar) measure of rotations
and a flat measure of the image translation, and maximise what is left over the shape alone.
Laplace's method around each frame's best pose p_i gives, up to a constant,

    F(g) = sum_i [ chi2_i(g, p_i) / kappa + log det H_i - 2 log |cos tau_i| ]

- ``chi2_i``: the frame's squared standardised residuals at its best pose for shape g;
- ``H_i``: the Hessian of chi2_i / 2 over the pose (``volume_terms``; 1/kappa scales it by a
  constant that drops out);
- ``|cos tau|``: the Haar density of R_z(theta) R_y(tau) R_x(delta) (tau is the middle angle);
- ``kappa = chi2_ML / (N - 4)``: the noise scale measured from the maximum-likelihood fit, so
  the estimate does not depend on the stated sigmas (only on their ratio), and noise-free data
  (kappa -> 0) keep the exact answer.

Two branches.  A frame's pose integral covers every pose, and equation (10) often has two
minima for one shape (the other sign of tau, another delta), a frame seen nearly in the image
plane or with phi near 0 or 180 degrees fitting both about equally.  Such a frame's term is the
mixture of its two Laplace terms, F_i = -2 log(exp(-F_ia / 2) + exp(-F_ib / 2)) (``alt_poses``:
the frames whose other branch fits within ``reconstruct.MIXTURE_DCHI2`` noise scales; a branch
that falls onto the other counts once).  With one branch per frame, chosen by chi2, the
estimate followed each frame's choice, and a choice made by the noise moved the shape:
``python -m bench.headline --from 0 --to 600`` (the headline cell: 1 px, 1 deg, 20 frames):
RMS of the errors in CRLB standard deviations c 1.26 -> 1.08, alpha 1.23 -> 1.13, beta
1.21 -> 1.13, phi 1.16 -> 1.15; 5 -> 2 scenes with an angle more than 5 degrees off; the
bench's RMSE/CRLB on scenes 0-199 alpha 1.09 -> 1.07, beta 1.07 -> 1.03, phi 1.23 -> 1.12; the
same mean time per scene (0.16 s on 2 workers).  (Merged branches must count once: with a
tolerance of 1e-6 on the poses, two starts that ended in one minimum a hair apart counted
twice, F jumped by 2 log 2 as the poses moved, and the line search stalled.)

How.  Quasi-Newton (BFGS) on the four shape parameters, in coordinates whitened by the chi2
part's Gauss-Newton Hessian (2 S / kappa, S the Schur-reduced information as in ``refine``), so
one unit is one standard deviation and the start has the right curvature.  Every evaluation of
F re-solves each frame's pose (``solve_poses``, Newton), warm-started from the poses of the
last accepted point moved to first order along dp/dg (a frame keeps its old pose where that
fits it better: a long step can carry the prediction past a fold).  The gradient is analytic
but for the volume terms (``_gradient``):

    dF/dg = sum_i [ dchi2_i/dg / kappa + dL_i/dg + dL_i/dp_i dp_i/dg ],   L_i = volume term,

chi2's own pose derivative vanishing at the best pose; dp_i/dg = -H_pp^-1 H_pg from the
frame's full Hessian of chi2_i / 2 over shape and pose (J^T J plus ``refine.curvature``, the
second-order term; it matches differences of re-solved poses, where Gauss-Newton's -V^-1 W^T is
off by tens of percent on frames seen near broadside).  L's total derivative along each axis
is a central difference with the poses moved along dp/dg, not re-solved (their error is of
second order, as is the difference's).  The line search's trial steps are evaluated a few at a
time in one batch, the gradient only at the accepted one.  (Before: a forward-difference
gradient of F, five shapes' poses re-solved per gradient, the trials one by one; the same
answers up to the path sensitivity below, at 1/3.5 of the cost.)  Tried and
dropped: a joint Levenberg-Marquardt over shape and poses (it crept without the volume terms'
Hessian).

What it does not do: the estimate is not unbiased either (c comes out slightly short, mean
-0.3 of its bound on the same scenes); the bench reports it next to maximum likelihood.  And F
is singular where a frame's pose Hessian H_i turns singular (a frame near the fold tau = 0
whose one minimum in tau splits in two as the shape changes): log det H_i -> -inf on one side,
the Gauss-Newton fallback (a jump) on the other.  BFGS walks into such a point until the line
search finds no decrease (``converged`` then, with a large gradient); about a third of the
calls on the 1 px / 1 deg, 20-frame scenes end so, at a point along that surface that depends
on the path (changing the old forward-difference step by 10% moved 37 of those 200 answers by
more than 0.2 standard deviations; where the end is a regular minimum, the answer does not
depend on the path).

Units: shapes (c, alpha, beta, phi) and poses (N, 5) as in ``refine``; radians.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.generated import measurement_model
from curverecon.model.observations import wrap_angle, wrap_line_angle
from curverecon.refine.ml import (
    FRAME_CHUNK,
    curvature,
    map_chunks,
    schur_information,
    split_params,
)

VOLUME_STEP = 1e-3
"""Central-difference step of the volume terms' gradient, in standard deviations of the shape."""

GTOL = 1e-2
"""BFGS stops when F's gradient (per standard deviation) is below this."""

MAX_ITER = 40
"""BFGS iterations at most."""

LINE_SEARCH_BATCHES = ((0, 1, 2, 3), tuple(range(4, 14)))
"""The line search's trial steps 2^-j, j = 0..13 (down to 1e-4), in the batches evaluated."""

BATCH_MAX_FRAMES = 200
"""Up to this many frames the line search's trial steps are evaluated in the batches of
``LINE_SEARCH_BATCHES``; beyond, one at a time (a batch of 10 trial shapes re-solved 10,000
frames' poses 10 times over: 17 of a 26-s reconstruction)."""

LONG_TRIALS = 4
"""Beyond ``BATCH_MAX_FRAMES`` frames the line search tries t = 1, 1/2, ... only this many
times (down to 1/8).  With thousands of frames F is resolved only to the jumps of frames whose
pose solve ends in another basin from another start (10,000 frames: F at one shape 58 apart
from two warm starts), far above what a shorter step could gain: on ``bench.stages``' 10,000
frames all 13 trials after the first step failed, 0.2 s each."""

POSE_ITERATIONS = 4
"""Newton iterations at most of each pose solve (warm-started, it stops earlier)."""

HALVINGS = 8
"""Step halvings of a frame's pose update before that frame gives up for this iteration."""

SAME_POSE = 1e-3
"""A frame's two branches that end within this (radians, in delta and in tau) are one minimum:
distinct branches of (10) differ in the sign of tau or in delta by degrees."""

KAPPA_MIN = 1e-12
"""Below this noise scale (chi2 per degree of freedom) the correction, proportional to kappa,
is beneath double precision of the shape: noise-free data keep the maximum-likelihood answer."""


@dataclass
class MarginalResult:
    """Outcome of :func:`refine_marginal`.

    Attributes:
        shape: (4,) c, alpha, beta, phi.
        poses: (N, 5) each frame's best pose for that shape.
        value: F at the answer (see the module docstring).
        kappa: the noise scale used (chi2 / (N - 4) of the start).
        other_poses: (N, 5) with ``alt_poses``: each frame's pose on the branch not in
            ``poses`` (NaN where the frame had one branch).
        iterations: BFGS iterations; converged: whether BFGS stopped by its gradient test,
            or because its line search found no decrease (F's resolution reached, or a
            singular point of F: module docstring), rather than at ``MAX_ITER``.
    """

    shape: np.ndarray
    poses: np.ndarray
    value: float
    kappa: float
    iterations: int
    converged: bool
    other_poses: np.ndarray | None = None


try:  # numpy's batched Cholesky gufunc: NaN factors (no exception) where a block is not PD
    from numpy.linalg import _umath_linalg

    _CHOLESKY_LO = _umath_linalg.cholesky_lo
except (ImportError, AttributeError):  # pragma: no cover - other numpy versions
    _CHOLESKY_LO = None


def _positive_definite(m: np.ndarray) -> np.ndarray:
    """(...,) whether each symmetric block of ``m`` (..., n, n) is positive definite: whether
    its Cholesky factorisation succeeds (a fraction of the cost of its eigenvalues)."""
    if _CHOLESKY_LO is None:  # pragma: no cover
        return np.linalg.eigvalsh(m)[..., 0] > 0
    with np.errstate(all="ignore"):
        factor = _CHOLESKY_LO(m, signature="d->d")
    return np.all(np.isfinite(factor), axis=(-2, -1))


def _residuals(g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """(K, N, 6) standardised residuals for shapes (K, 4) and poses (K, N, 5)."""
    return _standardise(measurement_model.predict(*split_params(g, p)), meas, w8)


def _standardise(pred: np.ndarray, meas: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """Standardised residuals of predictions (..., 6): tangent angles wrapped (lines)."""
    r = pred - meas
    r[..., 4:6] = wrap_line_angle(r[..., 4:6])
    return r * w8


def _linearise(
    g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Standardised residuals (K, N, 6) and Jacobians over shape (K, N, 6, 4) and pose
    (K, N, 6, 5) for shapes (K, 4) and poses (K, N, 5)."""
    pred, jg, jl = measurement_model.predict_with_jacobians(*split_params(g, p))
    return _standardise(pred, meas, w8), jg * w8[:, None], jl * w8[:, None]


def _solve(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    tol: float,
    n_total: int | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`solve_poses`, returning as well the shape Jacobians (K, N, 6, 4) and the
    second-order term (``curvature``, (K, N, 9, 9)) at the poses found (computed once there:
    the volume terms and the gradient use it too).

    Every (shape, frame) pair is a row of its own: the Newton steps, their halvings and the
    linearisations after a step are computed for the rows still moving only (a frame's
    arithmetic is its own, so the result is that of iterating every row; a long sequence's
    frames, warm-started, mostly stop after one or two steps)."""
    kk, n = p.shape[:2]
    r, jg, jl = _linearise(g, p, meas, w8)
    curv = curvature(g, p, r, w8)
    f = np.sum(r * r, axis=-1)
    eye5 = np.eye(5)
    per_frame_tol = tol / (n_total or n)  # (n_total: these frames a chunk of so many)
    # flat (K * N) views of the state, and every row's shape and measurements
    pf = np.array(p, dtype=float).reshape(kk * n, 5)
    rf, jgf, jlf = (np.reshape(a, (kk * n, *a.shape[2:])) for a in (r, jg, jl))
    cf, ff = curv.reshape(kk * n, 9, 9), f.reshape(kk * n)
    g_row = np.repeat(np.asarray(g, float), n, axis=0)  # (K * N, 4)
    m_row = np.tile(meas, (kk, 1))  # (K * N, 6)

    def lin_rows(rows: np.ndarray, pr: np.ndarray):
        """Residuals, Jacobians and second-order term of rows (M,) at poses pr (M, 5)."""
        gr, pr3 = g_row[rows], pr[:, None]
        rr, jgr, jlr = _linearise(gr, pr3, m_row[rows, None], w8)
        return rr[:, 0], jgr[:, 0], jlr[:, 0], curvature(gr, pr3, rr, w8)[:, 0]

    act = np.arange(kk * n)  # rows still improving
    for _ in range(n_iter):
        ja, ra, ca, pa = jlf[act], rf[act], cf[act], pf[act]
        v = np.einsum("...ki,...kj->...ij", ja, ja)
        v = v + 1e-12 * np.trace(v, axis1=-2, axis2=-1)[..., None, None] * eye5
        # Newton where the full Hessian (with the residuals' second derivatives, refine's
        # analytic ``curvature``) is positive definite, Gauss-Newton elsewhere: near the fold
        # tau = 0 Gauss-Newton alone converges slowly, and F's volume term is sensitive there
        hess = v + ca[..., 4:, 4:]
        floor = 1e-9 * np.trace(v, axis1=-2, axis2=-1)  # least eigenvalue for Newton
        newton = _positive_definite(hess - floor[..., None, None] * eye5)
        hess = np.where(newton[..., None, None], hess, v)
        grad = np.einsum("...ki,...k->...i", ja, ra)
        step = -np.linalg.solve(hess, grad[..., None])[..., 0]
        # a frame whose step promises (model: chi2 falls by -grad . step) less than the
        # tolerance is done: the step is not tried (saves the confirming evaluation)
        go = -np.sum(grad * step, axis=-1) > per_frame_tol
        act, pa, step = act[go], pa[go], step[go]
        if act.size == 0:
            break
        fa = ff[act]
        todo = np.arange(act.size)  # positions in act whose step is still being halved
        gain = np.zeros(act.size)
        for _ in range(HALVINGS):
            p_try = pa[todo] + step[todo]
            r_try = _residuals(g_row[act[todo]], p_try[:, None], m_row[act[todo], None], w8)
            f_try = np.sum(r_try[:, 0] * r_try[:, 0], axis=-1)
            take = f_try < fa[todo]
            done = todo[take]
            gain[done] = fa[done] - f_try[take]
            pa[done] = p_try[take]
            fa[done] = f_try[take]
            todo = todo[~take]
            if todo.size == 0:
                break
            step[todo] = 0.5 * step[todo]
        moved = gain > 0
        rows = act[moved]
        if rows.size:
            pf[rows], ff[rows] = pa[moved], fa[moved]
            rf[rows], jgf[rows], jlf[rows], cf[rows] = lin_rows(rows, pa[moved])
        act = act[gain > per_frame_tol]
        if act.size == 0:
            break
    return (
        pf.reshape(kk, n, 5),
        rf.reshape(kk, n, 6),
        jgf.reshape(kk, n, 6, 4),
        jlf.reshape(kk, n, 6, 5),
        cf.reshape(kk, n, 9, 9),
    )


def solve_poses(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    n_iter: int,
    tol: float = 1e-12,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every frame's best pose for each of K shapes (K, 4), from poses (K, N, 5).

    Newton (Gauss-Newton where the Hessian is not positive definite) with per-frame step
    halving: a plain step can overshoot on a frame seen near broadside (B' = c cos tau is flat
    in tau), and such a frame would then never move.  A frame stops when its step promises to
    lower its chi2 by less than ``tol / N`` (that step is not taken), or when a step taken
    lowered it by less.  At most ``n_iter`` steps per frame.  Vectorised over shapes and
    frames.  Returns poses (K, N, 5), standardised residuals (K, N, 6) and pose Jacobians
    (K, N, 6, 5).
    """
    p, r, _, jl, _ = _solve(g, p, meas, w8, n_iter, tol)
    return p, r, jl


def volume_terms(
    g: np.ndarray, p: np.ndarray, r: np.ndarray, jl: np.ndarray, w8: np.ndarray
) -> np.ndarray:
    """log det H - 2 log|cos tau| of every frame, (K, N): Laplace volume and Haar prior.

    H is the Hessian of the frame's chi2 / 2 over its pose, J^T J + sum_k r_k d2 r_k (the
    second-order part from ``refine.curvature``), or J^T J alone where H is not positive
    definite.  (With J^T J alone the estimate of c over-corrects: mean error -0.7 of its bound
    against -0.3 with H, on the bench's 1 px / 1 deg, 20-frame scenes.)  Shapes (K, 4), poses
    (K, N, 5), standardised residuals (K, N, 6) and pose Jacobians (K, N, 6, 5).
    """
    return _volume(p, jl, curvature(g, p, r, w8))


def _volume(p: np.ndarray, jl: np.ndarray, curv: np.ndarray, which: bool = False):
    """:func:`volume_terms` from the second-order term ``curv`` (K, N, 9, 9) at (g, p); with
    ``which``, also where the full Hessian H was used (K, N) (elsewhere J^T J)."""
    v = np.einsum("...ki,...kj->...ij", jl, jl)
    sign, logdet_h = np.linalg.slogdet(v + curv[..., 4:, 4:])
    logdet = np.where(sign > 0, logdet_h, np.linalg.slogdet(v)[1])
    out = logdet - 2.0 * np.log(np.maximum(np.abs(np.cos(p[..., 1])), 1e-300))
    return (out, sign > 0) if which else out


def shape_information(g: np.ndarray, p: np.ndarray, w8: np.ndarray) -> np.ndarray:
    """(4, 4) Schur-reduced Gauss-Newton information of the shape at (g, p), standardised."""
    _, jg, jl = measurement_model.predict_with_jacobians(*g, *p.T)
    return schur_information(jg * w8[None, :, None], jl * w8[None, :, None])


def _setup(
    meas: np.ndarray, point_sigma: float, tangent_sigma: float, chi2: float
) -> tuple[float, np.ndarray] | None:
    """(kappa, weights), or None where the marginal step does not apply."""
    n = meas.shape[0]
    if n < 5 or not chi2 > 0:
        return None
    kappa = chi2 / (n - 4)
    if kappa < KAPPA_MIN:
        return None
    return kappa, np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)


def _frame_values(
    gs: np.ndarray,
    start: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    kappa: float,
    n_total: int | None = None,
) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, ...]]:
    """Per-frame terms of F (K, N) for shapes (K, 4), poses re-solved from ``start`` (K, N, 5);
    those poses; and (residuals (K, N, 6), shape and pose Jacobians, second-order term) there.
    ``n_total``: the frames of the whole problem when these are a chunk of them (the pose
    solves' tolerance is per frame of the whole)."""
    n = start.shape[1]
    if n > FRAME_CHUNK:  # every frame is its own: in chunks (cache)
        parts = map_chunks(lambda c: _frame_values(gs, start[:, c], meas[c], w8, kappa, n), n)
        lins = [q[2] for q in parts]
        return (
            np.concatenate([q[0] for q in parts], axis=1),
            np.concatenate([q[1] for q in parts], axis=1),
            tuple(np.concatenate([lin[i] for lin in lins], axis=1) for i in range(4)),
        )
    ps, rs, jgs, jls, curv = _solve(gs, start, meas, w8, POSE_ITERATIONS, 1e-9 * kappa, n_total)
    frames = np.sum(rs * rs, axis=2) / kappa + _volume(ps, jls, curv)
    return frames, ps, (rs, jgs, jls, curv)


def _gradient(
    g: np.ndarray,
    p: np.ndarray,
    lin: tuple[np.ndarray, ...],
    meas: np.ndarray,
    w8: np.ndarray,
    kappa: float,
    dirs: np.ndarray,
    weights: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """F's gradient along the shape directions ``dirs`` (4, M) (columns), and dp/dx (N, 5, M).

    At one shape g (4,) with every frame's best pose p (N, 5) and ``lin`` = (residuals (N, 6),
    shape Jacobians (N, 6, 4), pose Jacobians (N, 6, 5), second-order term (N, 9, 9)) there.
    The pose follows the shape: dp/dg = -H_pp^-1 H_pg, H the frame's full Hessian of chi2 / 2
    over (shape, pose), J^T J plus the second-order term (``curvature``: exact, unlike
    Gauss-Newton's -V^-1 W^T, which is off by tens of percent on frames seen near broadside).
    Then
      - chi2 part: dchi2/dp = 0 at the best pose, so d(chi2 / kappa) = 2 J_g^T r / kappa;
      - volume part: central differences of ``volume_terms`` along (dg, dp/dg dg) with the
        poses moved to first order, not re-solved (the pose's error is second order, as is
        the central difference's); all 2M points in one batch.
    """
    r, jg, jl, curv = lin
    hpp = np.einsum("nki,nkj->nij", jl, jl) + curv[:, 4:, 4:]
    hpg = np.einsum("nki,nkj->nij", jl, jg) + curv[:, 4:, :4]
    # a tiny relative ridge: a frame exactly at a singular pose Hessian gets a finite answer
    hpp = hpp + 1e-13 * np.trace(hpp, axis1=-2, axis2=-1)[:, None, None] * np.eye(5)
    dpdx = -np.linalg.solve(hpp, hpg @ dirs)  # (N, 5, M)
    wts = np.ones(len(p)) if weights is None else weights
    grad_chi2 = 2.0 * np.einsum("nki,nk,n->i", jg, r, wts) @ dirs / kappa
    m = dirs.shape[1]
    h = VOLUME_STEP
    sgn = np.repeat([h, -h], m)  # (2M,)
    gs = g + sgn[:, None] * np.tile(dirs.T, (2, 1))
    ps = p + sgn[:, None, None] * np.tile(np.moveaxis(dpdx, 2, 0), (2, 1, 1))
    vt = np.empty((2 * m, len(p)))
    full = np.empty((2 * m, len(p)), dtype=bool)

    def part(c: slice) -> None:  # every frame is its own: in chunks (cache)
        rs, _, jls = _linearise(gs, ps[:, c], meas[c], w8)
        vt[:, c], full[:, c] = _volume(ps[:, c], jls, curvature(gs, ps[:, c], rs, w8), True)

    map_chunks(part, len(p))
    # a frame whose pose Hessian changes between positive definite and not among these points
    # has a jump in its term there (J^T J's determinant replaces H's), not a slope: it is left
    # out of the volume part (100,000 frames: four such frames gave -2,400 to +2,700 per
    # standard deviation each against about 60 for the sum of all others).  Only beyond
    # ``BATCH_MAX_FRAMES`` rows: with 20 frames it moved 2 of the headline's 200 answers by
    # 0.3 standard deviations, RMSE/CRLB unchanged to 0.01 (phi 1.123 -> 1.115)
    jump = np.any(full != full[:1], axis=0) & (len(p) > BATCH_MAX_FRAMES)
    wv = np.where(jump, 0.0, wts) if jump.any() else wts
    vol = np.where(wv > 0, vt, 0.0) @ wv
    return grad_chi2 + (vol[:m] - vol[m:]) / (2.0 * h), dpdx


def _stack(
    meas: np.ndarray, poses: np.ndarray, alt_poses: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Measurements and poses with the frames that have a second branch (finite rows of
    ``alt_poses``) appended once more, on that branch; and the indices of those frames."""
    if alt_poses is None:
        return meas, poses, np.zeros(0, int)
    two = np.flatnonzero(np.all(np.isfinite(alt_poses), axis=1))
    return np.concatenate([meas, meas[two]]), np.concatenate([poses, alt_poses[two]]), two


def _mixture(
    frames: np.ndarray, ps: np.ndarray, n1: int, two: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """F (K,) and the rows' weights (K, n1 + len(two)) from the rows' terms ``frames`` and
    poses ``ps`` (``_stack``'s layout): a frame with two branches contributes
    -2 log(exp(-Fa/2) + exp(-Fb/2)), its rows weighted by their shares of that sum (F's
    derivative along each row's term); where its second branch has fallen onto the first
    (delta and tau within ``SAME_POSE``) it counts once."""
    if two.size == 0:
        return np.sum(frames, axis=1), np.ones(frames.shape)
    fa, fb = frames[:, two], frames[:, n1:]
    same = np.max(np.abs(wrap_angle(ps[:, two, :2] - ps[:, n1:, :2])), axis=2) < SAME_POSE
    fb = np.where(same | ~np.isfinite(fb), np.inf, fb)
    lo = np.minimum(fa, fb)
    with np.errstate(all="ignore"):
        ea, eb = np.exp(-(fa - lo) / 2), np.exp(-(fb - lo) / 2)
    tot = ea + eb
    single = np.delete(frames[:, :n1], two, axis=1)
    f = np.sum(single, axis=1) + np.sum(lo - 2.0 * np.log(tot), axis=1)
    wts = np.ones(frames.shape)
    wts[:, two] = ea / tot
    wts[:, n1:] = eb / tot
    return f, wts


def marginal_value(
    meas: np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    chi2: float,
    alt_poses: np.ndarray | None = None,
) -> float | None:
    """F (module docstring) at a shape, every frame's pose re-solved from ``poses`` (and its
    second branch from ``alt_poses``, as in :func:`refine_marginal`).

    ``chi2`` sets the noise scale kappa = chi2 / (N - 4): pass the same one (the best fit's)
    to compare the basins of several fits.  None where the marginal step does not apply
    (see :func:`refine_marginal`).
    """
    setup = _setup(meas, point_sigma, tangent_sigma, chi2)
    if setup is None:
        return None
    kappa, w8 = setup
    n1 = meas.shape[0]
    meas, p, two = _stack(meas, np.array(poses, float), alt_poses)
    g = np.array(shape, float)[None]
    frames, ps, _ = _frame_values(g, p[None], meas, w8, kappa)
    value = float(_mixture(frames, ps, n1, two)[0][0])
    return value if np.isfinite(value) else None


def refine_marginal(
    meas: np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    chi2: float,
    alt_poses: np.ndarray | None = None,
) -> MarginalResult | None:
    """Maximise the marginal likelihood over the shape, from the maximum-likelihood fit.

    Args:
        meas: (N, 6) measurements (``Observations.measurements()``) of the inlier frames.
        shape, poses: the maximum-likelihood fit (``refine.refine``) on those frames.
        point_sigma (input units), tangent_sigma (radians): the stated noise; only their ratio
            matters (the scale is measured, ``kappa``).
        chi2: that fit's chi2.
        alt_poses: (N, 5) each frame's pose on its other branch of (10) (NaN rows: none);
            those frames enter F as two-component mixtures (module docstring).  None: every
            frame on its one branch.
    Returns:
        The result (``poses``: each frame on its branch of the larger weight), or None where it
        is not defined: fewer than 5 frames (no degree of freedom
        to measure the noise scale), a noise scale below ``KAPPA_MIN`` (noise-free data), or a
        singular information matrix at the start.
    """
    setup = _setup(meas, point_sigma, tangent_sigma, chi2)
    if setup is None:
        return None
    kappa, w8 = setup
    g0 = np.array(shape, float)
    p0 = np.array(poses, float)
    try:
        chol = np.linalg.cholesky(2.0 * shape_information(g0, p0, w8) / kappa)
    except np.linalg.LinAlgError:
        return None
    to_shape = np.linalg.inv(chol.T)  # whitened coordinates x: g = g0 + to_shape @ x
    n1 = meas.shape[0]
    meas, p0, two = _stack(meas, p0, alt_poses)
    n = meas.shape[0]

    def combine(frames: np.ndarray, ps: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _mixture(frames, ps, n1, two)

    def evaluate(xs: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray, tuple]:
        """F at K whitened points (K, 4), poses solved from ``starts`` (K, N, 5) (one batch);
        inf where c <= 0.  Also the poses and (residuals, Jacobians, second-order term)
        there."""
        gs = g0 + xs @ to_shape.T
        ok = gs[:, 0] > 0
        gs = np.where(ok[:, None], gs, g0)
        frames, ps, lin = _frame_values(gs, starts, meas, w8, kappa)
        fs, wts = combine(frames, ps)
        return np.where(ok & np.isfinite(fs), fs, np.inf), ps, (*lin, wts)

    def gradient(k: int, xs: np.ndarray, ps: np.ndarray, lin: tuple) -> tuple:
        """F's gradient (4,) and dp/dx (N, 5, 4) at point k of a batch from ``evaluate``."""
        g = g0 + to_shape @ xs[k]
        return _gradient(
            g, ps[k], tuple(a[k] for a in lin[:4]), meas, w8, kappa, to_shape, lin[4][k]
        )

    def predicted_starts(xs: np.ndarray) -> np.ndarray:
        """Poses to start from at K points (K, 4): each frame's pose at x moved along dp/dx
        (first order), or left where it is where that fits the frame worse (a long step can
        carry the prediction past a fold)."""
        gs = np.concatenate([g0 + xs @ to_shape.T] * 2)
        moved = p + np.einsum("nij,kj->kni", dpdx, xs - x)
        both = np.concatenate([moved, np.broadcast_to(p, moved.shape)])
        r = _residuals(gs, both, meas, w8)
        f2 = np.sum(r * r, axis=-1).reshape(2, len(xs), n)
        return np.where((f2[0] <= f2[1])[..., None], moved, p)

    # the trial steps in batches where a batch costs about one evaluation (few frames: numpy's
    # per-call overhead dominates); one at a time where the arithmetic does (many frames)
    batches = (
        LINE_SEARCH_BATCHES
        if n <= BATCH_MAX_FRAMES
        else tuple((j,) for levels in LINE_SEARCH_BATCHES for j in levels)[:LONG_TRIALS]
    )
    x = np.zeros(4)
    fs, ps, lin = evaluate(x[None], p0[None])
    f, p = float(fs[0]), ps[0]
    if not np.isfinite(f):
        return None
    grad, dpdx = gradient(0, x[None], ps, lin)
    if not np.all(np.isfinite(grad)):
        return None

    # quasi-Newton (BFGS update of the inverse Hessian, identity start: the whitened chi2
    # part) with a backtracking line search on F alone
    h_inv = np.eye(4)
    converged = False
    iterations = 0
    for _ in range(MAX_ITER):
        if np.max(np.abs(grad)) < GTOL:
            converged = True
            break
        step = -h_inv @ grad
        slope = float(grad @ step)
        if slope >= 0:  # not a descent direction: restart from steepest descent
            h_inv = np.eye(4)
            step, slope = -grad, -float(grad @ grad)
        # backtracking by halving: the first t = 1, 1/2, 1/4, ... above 1e-4 with enough
        # decrease (Armijo) and a finite gradient; the trial points are evaluated a few at a
        # time in one batch (about the cost of one: the cost is numpy's per-call overhead), the
        # gradient only at the accepted one
        accepted = None
        for levels in batches:
            ts = 0.5 ** np.asarray(levels, float)
            xs = x + ts[:, None] * step
            fs, ps, lin = evaluate(xs, predicted_starts(xs))
            for k in np.flatnonzero(fs <= f + 1e-4 * ts * slope):
                grad_new, dpdx_new = gradient(k, xs, ps, lin)
                if np.all(np.isfinite(grad_new)):
                    accepted = k
                    break
            if accepted is not None:
                break
        if accepted is None:
            # no decrease along a descent direction: F's resolution reached, or a singular
            # point of F (module docstring)
            converged = True
            break
        x_new = xs[accepted]
        s_k, y_k = x_new - x, grad_new - grad
        sy = float(s_k @ y_k)
        if sy > 1e-12:
            rho = 1.0 / sy
            m = np.eye(4) - rho * np.outer(s_k, y_k)
            h_inv = m @ h_inv @ m.T + rho * np.outer(s_k, s_k)
        x, f, p, grad, dpdx = x_new, float(fs[accepted]), ps[accepted], grad_new, dpdx_new
        iterations += 1
    others = None
    if two.size:  # each frame on its branch of the larger weight
        _, wts = combine(*_frame_values((g0 + to_shape @ x)[None], p[None], meas, w8, kappa)[:2])
        other = wts[0, n1:] > wts[0, two]
        pa, pb = p[two], p[n1:]
        p = np.array(p[:n1])
        p[two[other]] = pb[other]
        others = np.full_like(p, np.nan)
        others[two] = np.where(other[:, None], pa, pb)
    return MarginalResult(g0 + to_shape @ x, p, f, kappa, iterations, converged, others)
