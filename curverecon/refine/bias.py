"""The maximum-likelihood shape's bias, estimated by simulation at the estimate and subtracted.

Why.  Each frame has five pose parameters of its own for six measurements (Neyman-Scott): the
maximum-likelihood shape carries a bias of order sigma^2 that does not shrink with more frames,
while its standard deviation shrinks as 1/sqrt(N).  On 1 px / 1 deg ``make_scene`` scenes c
came out 3-6.5 standard deviations long at 1,000 frames and 5-18 at 10,000.  The bias comes
from frames seen near the fold tau = 0 of (10) (|A'B'| = c cos tau is flat there: a noisy |A'B'|
above c pins the frame at the fold and pulls c long) and from frames whose two branches of (10)
fit alike (each takes the branch its noise prefers).  A second-order expansion (Kanatani's
hyper-accurate correction) fails on exactly those frames: fitted from the truth at 10,000
frames, 99.7 % of its bias sat in the 11 % of frames where its second-order residual is not
small against the first-order one, and there it diverged.

What.  The estimate solves sum_i U_i(g) = 0, U_i = J_g,i^T r_i at frame i's best pose for shape g
(the profile score, standardised residuals); to first order the bias is -S^-1 sum_i E[U_i], S
the Schur-reduced information (the fit's covariance is S^-1).  Each frame's E[U_i] is simulated
(``_simulated``): ``DRAWS`` noisy copies of the frame predicted at (g, its pose), each copy's
pose solved from the frame's pose and from its other branch's (the better kept, as the fit
does), and U minus its first-order part B^T (P - I) e averaged (that part has mean zero and
carries nearly all of U's variance: a control variate; A, B the frame's standardised pose and
shape Jacobians, P = A (A^T A)^-1 A^T).  A frame whose other branch fits within a few noise
scales enters as the mixture of both, weighted 1 / (1 + exp(dchi2 / (2 kappa))) for the other
(``_branch_mixture``).  Frames whose average stays uncertain get ``TAIL_DRAWS`` draws.  Beyond
``MAX_SIMULATED`` frames a random subset is simulated and the sum scaled up.  The noise scale is
the one whose simulation reproduces the frames' chi2 (chi2 / (N - 4) of the fit is low: every
frame takes the better of its branches).

Where.  Evaluated at the fit the bias comes out short: the fit's poses belong to its biased
shape (with c long, frames near the fold come out away from it).  So it is evaluated twice
(``ITERATIONS``): at the fit, and at the fit minus that bias with the simulated frames' poses
re-solved for it; the answer subtracts the mean of the two.  (Iterating further did not settle:
on some scenes the evaluation ran away.)

The error bar.  The returned covariance (the answer adds it to its own) holds the simulation's
error (the draws' spread, the subset's sampling), half the difference of the two evaluations
squared, and ``SYSTEMATIC_FRACTION`` of the correction along it, times ``_fold_gain``: what the
correction does not know is in the error bar, not hidden.  The gain: the fit is g + bias(g) at
the true g, so an error e of the bias moves the answer by e / lambda, lambda the slope of that
map along the correction, measured from the two evaluations (below 1 where the bias grows as the
shape moves against it).  It matters at a fold: with phi near 0 (the mirror phi -> -phi) the
maximum-likelihood phi comes out about 3 degrees at 1 px / 1 deg whatever the frames, the map
is flat there (phi + bias(phi) 0.048 at phi = 0, 0.048 at 0.012, 0.051 at 0.024, 0.056 at 0.035
on one 10,000-frame scene) and the simulation finds a quarter of the bias: phi 5.1 standard
deviations off without the gain, 2.9 with it (gain 1.8).  Draws come from a fixed seed: the same
input gives the same answer.  docs/accuracy.md has the figures (``python -m bench.honest``).

References: J. Neyman and E. L. Scott, Econometrica 16 (1948) 1-32 (incidental parameters);
K. Kanatani, "Statistical Optimization for Geometric Computation", Elsevier 1996, ch. 14 (the
second-order bias of maximum likelihood in geometric fitting); B. Efron and R. J. Tibshirani, "An
Introduction to the Bootstrap", Chapman & Hall 1993, ch. 10 (bias correction by the bootstrap).

Units: shapes (c, alpha, beta, phi) and poses (N, 5) as in ``refine``; radians.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from curverecon.generated import measurement_model
from curverecon.model.observations import wrap_angle, wrap_line_angle
from curverecon.refine.marginal import KAPPA_MIN
from curverecon.refine.ml import optimise_poses, split_params
from curverecon.robust.search import branch_alternatives, switch_branches

BIAS_CORRECTED_FRAMES = 300
"""From this many inlier frames on, the default answer (``estimator="marginal"``) is the
maximum-likelihood fit minus its estimated bias, not the marginal likelihood's optimum: that
optimum carries an O(sigma^2) bias of its own.  On 16 ``make_scene`` scenes (1 px, 1 deg) at 300
frames, |z| > 3 in 8 of the 64 (scene, parameter) pairs with the marginal optimum (the largest
6.3), 1 with the correction (3.06); at 100 frames the two alike (1 of 96 pairs each, 4.7 on one
scene's phi); at 1,000 frames on 24 scenes the marginal optimum 85 % within 3, the
largest 20.9 (``python -m bench.honest`` for the corrected answer's figures)."""

DRAWS = 8
"""Simulated draws per frame (1,000 frames: 0.3 s of CPU time for the correction; its
simulation error, in the covariance, about 0.2 standard deviations of c)."""

TAIL_DRAWS = 256
"""Draws for a frame whose ``DRAWS``-draw average is uncertain by more than ``TAIL_STD``."""

MAX_TAIL = 50
"""At most this many frames (the most uncertain) get ``TAIL_DRAWS`` draws: with a subset of
100,000 frames every simulated term counts 33 times, and hundreds passed ``TAIL_STD`` (the
correction took 4.6 s of CPU time, 1.2 s with this limit)."""

TAIL_STD = 0.05
"""A frame's simulated term whose uncertainty moves the shape by more than this many of the
shape's standard deviations gets ``TAIL_DRAWS`` draws."""

MAX_SIMULATED = 3000
"""At most this many frames are simulated (beyond, a random subset, the sum scaled up and the
subset's sampling error added to the covariance): the correction's time does not grow with the
frames beyond it (100,000 frames: 1.2 s of CPU time)."""

ITERATIONS = 2
"""Evaluations of the bias: first at the fit, then at the fit minus the bias found, every
simulated frame's pose re-solved for that shape (the fit's poses belong to its biased shape:
with c too long, frames seen near the fold tau = 0 of (10) come out away from it, and the bias
they make is missed; 1,000 frames, one scene: c's bias 2.4 standard deviations at the fit,
7.0 at the true shape with the poses re-solved for it, 7.3 at the true poses)."""

SYSTEMATIC_FRACTION = 0.6
"""The correction's systematic error, as a fraction of the correction (a standard deviation
along it, added to the covariance).  Evaluated at the fit the bias comes out short (the fit's
poses are not a sample of the true poses: with c too long the frames near the fold come out away
from it, and a frame whose two branches fit alike sits on the one its noise prefers); measured
on ``make_scene`` 1 px / 1 deg scenes, the true error over the correction was 0.4 to 2.5
(``python -m bench.honest``)."""

MIN_SLOPE = 0.25
"""The smallest slope of g -> g + bias(g) along the correction that ``_fold_gain`` believes (at
most a factor 4 on the correction's systematic error)."""

MIN_WEIGHT = 0.02
"""A frame's other branch whose weight is below this is not simulated."""

POSE_ITERATIONS = 8
"""Gauss-Newton iterations of each simulated frame's pose solve (``ml.optimise_poses``)."""

SEED = 20261128
"""Seed of the simulation's draws."""


@dataclass
class BiasCorrection:
    """Outcome of :func:`ml_bias`.

    Attributes:
        bias: (4,) the estimated bias of the maximum-likelihood shape (subtract it).
        covariance: (4, 4) covariance of that estimate's own error (the simulation's), in the
            shape's units (add it to the shape's covariance).
        simulated: frames whose bias term was simulated (before any subset).
        seconds: wall time.
        gain: the factor on the correction's systematic error (``_fold_gain``; 1 where the
            bias does not grow along the correction).
    """

    bias: np.ndarray
    covariance: np.ndarray
    simulated: int
    seconds: float
    gain: float = 1.0


def _frame_jacobians(
    g: np.ndarray, p: np.ndarray, w8: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Standardised shape (N, 6, 4) and pose (N, 6, 5) Jacobians, and C = (A^T A)^-1 (N, 5, 5)."""
    _, jg, jl = measurement_model.predict_with_jacobians(*split_params(g[None], p[None]))
    jg, jl = jg[0] * w8[:, None], jl[0] * w8[:, None]
    v = np.einsum("nki,nkj->nij", jl, jl)
    # a tiny relative ridge: a frame exactly at the fold (a singular pose block) stays finite
    v = v + 1e-12 * np.trace(v, axis1=-2, axis2=-1)[:, None, None] * np.eye(5)
    return jg, jl, np.linalg.inv(v)


class _Frames:
    """Simulated frames as ``robust.search.switch_branches`` reads them (c', the tangents'
    angles relative to A'B', the measurements), without ``Observations``' validation (a draw
    may put a tangent anywhere)."""

    def __init__(self, meas: np.ndarray) -> None:
        self._meas = meas
        chord = meas[:, 2:4] - meas[:, 0:2]
        self.cp = np.hypot(chord[:, 0], chord[:, 1])
        theta = np.arctan2(chord[:, 1], chord[:, 0])
        self.rel_a = wrap_line_angle(meas[:, 4] - theta)
        self.rel_b = wrap_line_angle(meas[:, 5] - theta)

    @property
    def n_frames(self) -> int:
        return len(self._meas)

    def measurements(self) -> np.ndarray:
        return self._meas


def _simulated(
    g: np.ndarray,
    p: np.ndarray,
    w8: np.ndarray,
    kappa: float,
    draws: int,
    rng: np.random.Generator,
    other: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The frames' (poses p (M, 5); ``other``: each one's other branch, NaN rows where none)
    score bias by simulation at (g, p): mean (M, 4), the
    mean's covariance (M, 4, 4) over ``draws`` draws each, and each frame's mean chi2 at its
    simulated best pose (M,) (module docstring)."""
    m = len(p)
    pred = measurement_model.predict(*split_params(g[None], p[None]))[0]
    e = rng.standard_normal((draws, m, 6)) * np.sqrt(kappa)  # standardised noise
    meas = (pred[None] + e / w8).reshape(draws * m, 6)
    meas[:, 4:6] = wrap_angle(meas[:, 4:6])
    # every draw on the better of its two branches of (10), as the fit puts it: solved from
    # the frame's pose and from its other branch's (where it has one)
    best_p, best_r = optimise_poses(g, np.tile(p, (draws, 1)), meas, w8, POSE_ITERATIONS)
    if other is not None:
        rows = np.flatnonzero(np.all(np.isfinite(np.tile(other, (draws, 1))), axis=1))
        if rows.size:
            alt_start = np.tile(other, (draws, 1))[rows]
            ap, ar = optimise_poses(g, alt_start, meas[rows], w8, POSE_ITERATIONS)
            take = np.sum(ar * ar, axis=1) < np.sum(best_r[rows] ** 2, axis=1)
            best_p[rows[take]], best_r[rows[take]] = ap[take], ar[take]
    _, jg_hat, _ = measurement_model.predict_with_jacobians(*split_params(g[None], best_p[None]))
    u = np.einsum("mki,mk->mi", jg_hat[0] * w8[:, None], best_r).reshape(draws, m, 4)
    jg, jl, cov = _frame_jacobians(g, p, w8)
    pe = np.einsum("mki,mij,mlj,dml->dmk", jl, cov, jl, e)
    u = u - np.einsum("mki,dmk->dmi", jg, pe - e)  # minus the first-order part (mean zero)
    mean = u.mean(axis=0)
    dev = u - mean
    chi2 = np.sum(best_r * best_r, axis=1).reshape(draws, m).mean(axis=0)
    return mean, np.einsum("dmi,dmj->mij", dev, dev) / (draws * max(draws - 1, 1)), chi2


def _branch_mixture(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    kappa: float,
    frame_chi2: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Each frame's pose on its other branch of (10) (NaN where none) and that branch's weight
    (M,): 1 / (1 + exp(dchi2 / (2 kappa))), the probability that the truth lies on it when
    both are equally likely a priori (the marginal likelihood's mixture, ``refine.marginal``)."""
    alt, alt_chi2 = branch_alternatives(_Frames(meas), g, p, w8)  # type: ignore[arg-type]
    with np.errstate(over="ignore", invalid="ignore"):
        wt = 1.0 / (1.0 + np.exp((alt_chi2 - frame_chi2) / (2.0 * kappa)))
    wt = np.where(np.isfinite(alt_chi2) & (wt > MIN_WEIGHT), wt, 0.0)
    return alt, wt


def _frame_terms(
    g: np.ndarray,
    p: np.ndarray,
    meas: np.ndarray,
    w8: np.ndarray,
    kappa: float,
    frame_chi2: np.ndarray,
    rng: np.random.Generator,
    spread_scale: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The frames' simulated score bias (M, 4), its covariance (M, 4, 4) and mean chi2 (M,),
    mixed over each frame's two branches (``_branch_mixture``); frames whose term is uncertain
    by more than ``TAIL_STD`` (``spread_scale`` (4, 4): the map from a frame's term to the
    shape in standard deviations) simulated again with ``TAIL_DRAWS`` draws."""
    alt, wt = _branch_mixture(g, p, meas, w8, kappa, frame_chi2)
    two = np.flatnonzero(wt > 0)
    rows = np.concatenate([p, alt[two]])
    other = np.concatenate([alt, p[two]])
    mean, mcov, chi2 = _simulated(g, rows, w8, kappa, DRAWS, rng, other)
    spread = np.sqrt(np.einsum("ij,mjk,ik->mi", spread_scale, mcov, spread_scale))
    worst = np.max(spread, axis=1)
    tail = np.flatnonzero(worst > TAIL_STD)
    tail = tail[np.argsort(-worst[tail])[:MAX_TAIL]]
    if tail.size:
        mean[tail], mcov[tail], chi2[tail] = _simulated(
            g, rows[tail], w8, kappa, TAIL_DRAWS, rng, other[tail]
        )
    m = len(p)
    w = np.ones(m)
    w[two] = 1.0 - wt[two]
    out = [a[:m] * w.reshape(-1, *([1] * (a.ndim - 1))) for a in (mean, mcov, chi2)]
    for o, a in zip(out, (mean, mcov, chi2), strict=True):
        o[two] += a[m:] * wt[two].reshape(-1, *([1] * (a.ndim - 1)))
    return out[0], out[1], out[2]


def _best_poses(
    g: np.ndarray, p: np.ndarray, meas: np.ndarray, w8: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Every frame's best pose for shape g (4,) from poses p (M, 5), over the branches of (10)
    as the fit chooses them, and its chi2 (M,)."""
    best = switch_branches(_Frames(meas), g, p, w8)  # type: ignore[arg-type]
    ps, rs = optimise_poses(g, best, meas, w8, POSE_ITERATIONS)
    return ps, np.sum(rs * rs, axis=1)


def ml_bias(
    meas: np.ndarray,
    shape: np.ndarray,
    poses: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    frame_chi2: np.ndarray,
    covariance: np.ndarray,
) -> BiasCorrection | None:
    """The bias of a maximum-likelihood fit's shape, estimated at that fit (module docstring).

    Args:
        meas: (N, 6) measurements of the frames fitted.
        shape, poses: the fit (``refine.refine``).
        point_sigma (input units), tangent_sigma (radians): the stated noise (the scale is
            measured from the fit's chi2).
        frame_chi2: (N,) the fit's chi2 of every frame.
        covariance: (4, 4) the fit's shape covariance (from the stated noise).
    Returns:
        The correction, or None where it does not apply: fewer than 5 frames, or a noise scale
        below ``KAPPA_MIN`` (noise-free data: no bias to remove).
    """
    t0 = time.perf_counter()
    n = len(meas)
    if n < 5 or not float(np.sum(frame_chi2)) / (n - 4) >= KAPPA_MIN:
        return None
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)
    g_fit = np.asarray(shape, float)
    s_inv = np.asarray(covariance, float)
    pick_rng = np.random.default_rng(SEED)
    pick = np.arange(n) if n <= MAX_SIMULATED else np.sort(pick_rng.choice(n, MAX_SIMULATED, False))
    scale = n / pick.size
    to_std = scale * s_inv / np.sqrt(np.diag(s_inv))[:, None]
    m_meas, p, f = meas[pick], np.asarray(poses, float)[pick], np.asarray(frame_chi2)[pick]
    # the noise scale: the fit's chi2 / (N - 4) understates it (every frame takes the better of
    # its branches); the first evaluation is scaled to the scale whose simulation gives the
    # frames' chi2, the second simulated at that scale
    kappa = float(np.sum(frame_chi2)) / (n - 4)
    biases, covs = [], []
    g = g_fit
    for k in range(ITERATIONS):
        if k:  # the picked frames' best poses for the shape corrected by the first evaluation
            p, f = _best_poses(g, p, m_meas, w8)
        # common random numbers: the same draws at every evaluation
        mean, mcov, sim_chi2 = _frame_terms(
            g, p, m_meas, w8, kappa, f, np.random.default_rng(SEED + 1), to_std
        )
        ratio = float(np.mean(f)) / max(float(np.mean(sim_chi2)), 1e-300) if k == 0 else 1.0
        var = (ratio * scale) ** 2 * mcov.sum(axis=0)
        if pick.size < n:  # the subset's sampling error of the scaled sum
            dev = ratio * (mean - mean.mean(axis=0))
            var = var + n * n * (1 - 1 / scale) * (dev.T @ dev) / ((pick.size - 1) * pick.size)
        biases.append(-s_inv @ (ratio * scale * mean.sum(axis=0)))
        covs.append(s_inv @ var @ s_inv.T)
        kappa *= ratio
        g = g_fit - biases[-1]
    # the bias lies between its values at the fit and at the corrected shape (module
    # docstring): their mean, and half their difference as a systematic error
    bias = np.mean(biases, axis=0)
    half = 0.5 * (biases[-1] - biases[0])
    cov = np.mean(covs, axis=0) + np.outer(half, half)
    gain = _fold_gain(biases[0], biases[-1], np.sqrt(np.diag(s_inv)))
    cov = cov + (gain * SYSTEMATIC_FRACTION) ** 2 * np.outer(bias, bias)
    return BiasCorrection(bias, cov, int(pick.size), time.perf_counter() - t0, gain)


def _fold_gain(b_fit: np.ndarray, b_corrected: np.ndarray, sd: np.ndarray) -> float:
    """1 / lambda, lambda the slope of g -> g + bias(g) along the correction (standardised by
    the fit's standard deviations ``sd``), from the bias at the fit ``b_fit`` and at the fit minus
    it ``b_corrected``; lambda clipped to [``MIN_SLOPE``, 1].  The fit is g + bias(g) at the true
    g: an error e of the bias moves the answer by e / lambda (module docstring, "The error
    bar")."""
    u, v = b_fit / sd, (b_corrected - b_fit) / sd
    uu = float(u @ u)
    if not uu > 0.0 or not np.all(np.isfinite(v)):
        return 1.0
    return 1.0 / float(np.clip(1.0 - float(v @ u) / uu, MIN_SLOPE, 1.0))
