"""Hypotheses from four-frame samples: LO-RANSAC on the complete minimal solver.

With outlier frames the global search (``robust.search``) refines its candidates on all frames,
and the outliers pull every candidate: on 30 % outlier scenes its best candidate was 40-50
degrees off where the truth, refined on the inlier frames alone, had the lower robust cost.  A
four-frame sample of inliers is not pulled: :class:`FrameSampleEstimator` gives the generic
loop (:func:`curverecon.robust.ransac.lo_ransac`, PoseLib's calling convention) every real
shape of a sample (:func:`curverecon.solvers.minimal.solve`), scores a shape on all frames by
its truncated per-frame chi2 with the shape held fixed (:func:`fixed_shape_fit`, the measure
the answer is then accepted by; ``FrameSampleOptions.score``), and refines the best on the
frames it explains (``refine.start.refine_hypothesis``, the local optimisation; then c moves
to the minimum of that fit's chi2 plus the score's chord term, :func:`chord_prior_step`).

:func:`frame_sample_hypothesis` runs the loop and returns the answer as a :class:`Candidate`:
the shape held fixed and every frame's pose at its best branch, so that its robust cost
(``robust.search.robust_cost``) compares with another shape's computed the same way
(:func:`fixed_shape_fit`).  The pipeline runs it only when the search's answer flags outlier
frames or its chi2 is improbable (``FrameSampleOptions``): each sample costs one minimal solve
(about 0.17 s).

With few frames (5 to ``FewFrameSampleOptions.max_frames``) :func:`few_frame_hypotheses` adds
the shapes of a few samples spread over the frames (:func:`spread_samples`), refined on all
frames, to the search's candidates when the search found no exact fit: on exact data each
sample's solutions contain the truth, which fits every frame exactly.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator, Sequence

import numpy as np
from scipy.optimize import minimize_scalar

from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations, wrap_angle
from curverecon.model.pose import normalise
from curverecon.options import (
    FewFrameSampleOptions,
    FrameSampleOptions,
    MinimalOptions,
    SearchOptions,
)
from curverecon.refine.ml import RefineResult, refine, refine_batch
from curverecon.refine.start import refine_hypothesis
from curverecon.robust.ransac import RansacOptions, RansacStats, lo_ransac
from curverecon.robust.search import Candidate, poses_from_branches, robust_cost, switch_branches
from curverecon.solvers import minimal
from curverecon.solvers.pose import poses_from_shape


def fixed_shape_fit(
    obs: Observations,
    shape: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    search: SearchOptions | None = None,
) -> RefineResult:
    """Every frame's pose at its best branch of (10) for ``shape``, the shape not moved: its
    ``frame_chi2`` is what each frame says of this shape alone (no covariance)."""
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)
    poses = switch_branches(obs, shape, poses_from_branches(obs, shape), w8, options=search)
    return refine(obs, shape, poses, point_sigma, tangent_sigma, max_iter=0, covariance=False)


MIN_REFINE_FRAMES = 6
"""Frames a shape must explain before the local optimisation refines it on them (a fit on
fewer is barely determined; 0 gave the same output on the 13 scenes of
``bench.options_audit`` that run the samples: ``docs/options-audit.md``)."""

CHORD_BINS = 64
"""Bins of the chord-length convolution in :func:`chord_costs` (each a quarter of the chord's
noise standard deviation wide, over +-8 of them)."""


def chord_costs(obs: Observations, c: float, point_sigma: float) -> np.ndarray:
    """(N,) -2 log p(|A'B'| | c) of every frame: the density of the observed chord length when
    AB's direction is uniform on the sphere (the Haar measure of rotations that the marginal
    likelihood, ``refine.marginal``, integrates the poses over), so that its length in the image
    is c cos(u), P(length <= L) = 1 - sqrt(1 - L^2 / c^2), convolved with the noise of the
    chord's length (sd sqrt(2) point_sigma).  The end points stay right in frames whose tangents
    are outliers, so every frame says this about c, which the fixed-shape chi2 does not (any
    pose fits A', B' exactly when |A'B'| <= c).  Each frame's term is capped at the median
    frame's plus ``FrameSampleOptions.truncate`` (a frame whose end points are wrong)."""
    length = np.linalg.norm(obs.b - obs.a, axis=1)
    c = abs(float(c))
    s = math.sqrt(2.0) * point_sigma
    lo = np.clip(length - 8.0 * s, 0.0, c)
    hi = np.clip(length + 8.0 * s, 0.0, c)
    k = np.linspace(0.0, 1.0, CHORD_BINS + 1)
    edges = lo[:, None] + (hi - lo)[:, None] * k[None, :]
    cdf = 1.0 - np.sqrt(np.maximum(0.0, 1.0 - (edges / max(c, 1e-300)) ** 2))
    mass = np.diff(cdf, axis=1)
    mid = 0.5 * (edges[:, 1:] + edges[:, :-1])
    z = (length[:, None] - mid) / s
    p = np.sum(mass * np.exp(-0.5 * z * z), axis=1) / (math.sqrt(2.0 * math.pi) * s)
    return -2.0 * np.log(np.maximum(p, 1e-300))


def chord_cost(obs: Observations, c: float, point_sigma: float, truncate: float) -> float:
    """The sum of :func:`chord_costs`, each frame's capped at the median frame's plus
    ``truncate``."""
    costs = chord_costs(obs, c, point_sigma)
    return float(np.sum(np.minimum(costs, float(np.median(costs)) + truncate)))


CHORD_PRIOR_SPAN = 4.0
""":func:`chord_prior_step` searches c within this many standard deviations of the fit's."""
CHORD_PRIOR_GRID = 81
"""Grid points of that search (then a bounded scalar minimisation around the best one)."""


def chord_prior_step(
    obs: Observations,
    shape: np.ndarray,
    covariance: np.ndarray,
    point_sigma: float,
    weight: float,
    truncate: float,
) -> np.ndarray:
    """The shape that minimises a fit's chi2 plus ``weight`` times :func:`chord_cost`, the chi2
    in the Gaussian approximation of the fit (shape (4,) at its minimum, shape covariance (4, 4)
    from the same frames).

    The chi2 of the shape with c held at a value is, to second order, (c - c0)^2 / var(c)
    above its minimum, with the other parameters at their conditional optimum, shape0 +
    cov[:, 0] / var(c) (c - c0) (the regression of the shape on c).  So c minimises
    q(c) = (c - c0)^2 / var(c) + weight * chord_cost(c) (1-D: a grid over
    +-``CHORD_PRIOR_SPAN`` standard deviations, then a bounded scalar minimisation around its
    best point) and the rest follow.  The chord term is the prior on c that every frame's
    |A'B'| gives, outlier tangents or not; the fit alone does not see it.  Returns ``shape``
    when var(c) is not positive and finite."""
    shape = np.asarray(shape, float)
    cov = np.asarray(covariance, float)
    c0, var = float(shape[0]), float(cov[0, 0])
    if not (math.isfinite(var) and var > 0.0 and np.all(np.isfinite(cov[:, 0]))):
        return shape
    sd = math.sqrt(var)
    lo, hi = max(c0 - CHORD_PRIOR_SPAN * sd, 0.5 * c0), c0 + CHORD_PRIOR_SPAN * sd

    def q(c: float) -> float:
        return (c - c0) ** 2 / var + weight * chord_cost(obs, c, point_sigma, truncate)

    grid = np.linspace(lo, hi, CHORD_PRIOR_GRID)
    values = np.array([q(float(c)) for c in grid])
    k = int(np.argmin(values))
    a, b = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    best_c, best_q = float(grid[k]), float(values[k])
    res = minimize_scalar(q, bounds=(float(a), float(b)), method="bounded")
    if res.success and float(res.fun) < best_q:
        best_c = float(res.x)
    q0 = q(c0)
    if not best_q < q0 and not (res.success and float(res.fun) < q0):
        return shape
    return shape + cov[:, 0] / var * (best_c - c0)


def sample_score(
    obs: Observations,
    shape: np.ndarray,
    frame_chi2: np.ndarray,
    point_sigma: float,
    options: FrameSampleOptions,
) -> float:
    """What the samples' shapes are compared by: the per-frame chi2 truncated at
    ``options.truncate``, plus ``options.chord_weight`` times :func:`chord_cost`."""
    cost = float(np.sum(np.minimum(frame_chi2, options.truncate)))
    if options.chord_weight > 0.0:
        cost += options.chord_weight * chord_cost(obs, shape[0], point_sigma, options.truncate)
    return cost


class FrameSampleEstimator:
    """The curve's estimator for :func:`lo_ransac`: data items are frames, samples four."""

    sample_size = minimal.FRAMES

    def __init__(
        self,
        obs: Observations,
        point_sigma: float,
        tangent_sigma: float,
        options: FrameSampleOptions,
        minimal_options: MinimalOptions | None = None,
        search: SearchOptions | None = None,
    ) -> None:
        if options.score not in ("fixed_shape", "tangent"):
            raise CurveReconError(
                "FrameSampleOptions.score must be 'fixed_shape' or 'tangent', not "
                f"{options.score!r}"
            )
        self.obs = obs
        self.num_data = obs.n_frames
        self.point_sigma = point_sigma
        self.tangent_sigma = tangent_sigma
        self.options = options
        self.minimal_options = minimal_options
        self.search = search
        self.solves = 0

    def generate_models(self, sample: np.ndarray) -> list[np.ndarray]:
        """Every real shape that fits the four sampled frames exactly (none for a degenerate
        sample: two equal views, a tangent along A'B')."""
        self.solves += 1
        try:
            result = minimal.solve(self.obs.subset(sample), self.minimal_options)
        except CurveReconError:
            return []
        return list(result.shapes)

    def _frame_cost(self, shape: np.ndarray) -> np.ndarray:
        _, misfit = poses_from_shape(self.obs, shape)
        return np.where(np.isfinite(misfit), (misfit / self.tangent_sigma) ** 2, np.inf)

    def score_model(self, shape: np.ndarray) -> tuple[float, int]:
        """(sum of per-frame chi2 truncated at ``options.truncate``, frames below it): the
        chi2 of :func:`fixed_shape_fit`, or the tangent misfit alone (``options.score``)."""
        t = self.options.truncate
        if self.options.score == "fixed_shape":
            fit = fixed_shape_fit(
                self.obs, shape, self.point_sigma, self.tangent_sigma, self.search
            )
            cost = fit.frame_chi2
        else:
            cost = self._frame_cost(shape)
        score = sample_score(self.obs, shape, cost, self.point_sigma, self.options)
        return score, int(np.sum(cost < t))

    def refine_model(self, shape: np.ndarray) -> np.ndarray:
        """Maximum likelihood on the frames the shape explains (full chi2 below the truncation
        at the shape's best poses), when there are enough of them; repeated on the frames the
        refined shape explains while that set changes (at most ``options.lo_rounds`` fits)."""
        shape = self._annealed(shape)
        previous = None
        for _ in range(max(1, self.options.lo_rounds)):
            fit = fixed_shape_fit(
                self.obs, shape, self.point_sigma, self.tangent_sigma, self.search
            )
            inliers = fit.frame_chi2 < self.options.truncate
            if int(inliers.sum()) < MIN_REFINE_FRAMES:
                return shape
            if previous is not None and np.array_equal(inliers, previous):
                break
            previous = inliers
            sub = self.obs.subset(inliers)
            fit_sub = refine_hypothesis(
                sub, shape, self.point_sigma, self.tangent_sigma, options=self.search
            )
            shape = fit_sub.shape
        if self.options.chord_prior and self.options.chord_weight > 0.0 and previous is not None:
            # the chord term of the score as a prior on c (the fit above ignores it)
            shape = self._better_scored(shape, self._chord_prior_shape(sub, fit_sub))
        return shape

    def _annealed(self, shape: np.ndarray) -> np.ndarray:
        """``shape`` refitted on the frames below ``options.anneal_start`` times the truncation,
        then below lower multiples of it (``options.anneal_steps`` fits, the multiple falling
        geometrically towards 1): the local optimisation's fits at a decreasing threshold
        (Lebeda, Matas and Chum 2012), so that a rough sample's shape first takes in the
        good frames it misses by a little, not only those it already explains."""
        o = self.options
        steps = max(0, o.anneal_steps)
        for j in range(steps):
            mult = o.anneal_start ** (1.0 - j / steps)
            fit = fixed_shape_fit(
                self.obs, shape, self.point_sigma, self.tangent_sigma, self.search
            )
            inliers = fit.frame_chi2 < mult * o.truncate
            if int(inliers.sum()) < MIN_REFINE_FRAMES:
                break
            shape = refine_hypothesis(
                self.obs.subset(inliers),
                shape,
                self.point_sigma,
                self.tangent_sigma,
                options=self.search,
            ).shape
        return shape

    def _chord_prior_shape(self, sub: Observations, fit: RefineResult) -> np.ndarray:
        """``fit``'s shape moved to the minimum of its chi2 on ``sub`` plus the score's chord
        term (:func:`chord_prior_step`, the chi2 in its Gaussian approximation)."""
        cov = refine(
            sub, fit.shape, fit.poses, self.point_sigma, self.tangent_sigma, max_iter=0
        ).covariance
        if cov is None:
            return fit.shape
        return chord_prior_step(
            self.obs,
            fit.shape,
            cov,
            self.point_sigma,
            self.options.chord_weight,
            self.options.truncate,
        )

    def _better_scored(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Of shapes ``a`` and ``b`` the one of lower :meth:`score_model` (``a`` on a tie)."""
        if np.array_equal(a, b):
            return a
        return b if self.score_model(b)[0] < self.score_model(a)[0] else a

    def same_model(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Two shapes within ``options.distinct_deg`` in every angle and that fraction of a
        radian in relative c, after normalisation (``model.pose.normalise``: the symmetries
        of the shape give equal predictions)."""
        na = normalise(np.asarray(a, float), np.zeros((0, 5)))[0]
        nb = normalise(np.asarray(b, float), np.zeros((0, 5)))[0]
        tol = math.radians(self.options.distinct_deg)
        d_angles = np.abs(wrap_angle(na[1:] - nb[1:]))
        return bool(np.all(d_angles < tol) and abs(na[0] - nb[0]) < tol * abs(nb[0]))


def frame_sample_hypothesis(
    obs: Observations,
    point_sigma: float,
    tangent_sigma: float,
    options: FrameSampleOptions | None = None,
    minimal_options: MinimalOptions | None = None,
    search: SearchOptions | None = None,
    initial_shapes: Sequence[np.ndarray] = (),
) -> tuple[Candidate | None, RansacStats]:
    """LO-RANSAC over four-frame samples: the best shape as a fixed-shape :class:`Candidate`
    (its ``robust_cost`` from :func:`fixed_shape_fit`), or None when no sample gave a shape.
    ``initial_shapes`` (e.g. the search's answer) compete with the samples' shapes from the
    start, polished by the same local optimisation (``lo_ransac``'s ``initial_models``)."""
    o = options or FrameSampleOptions()
    est = FrameSampleEstimator(obs, point_sigma, tangent_sigma, o, minimal_options, search)
    ransac = RansacOptions(
        max_iterations=o.max_samples,
        min_iterations=o.min_samples,
        success_prob=o.success_prob,
        dyn_num_trials_mult=o.dyn_num_trials_mult,
        seed=o.seed,
        final_refinements=o.final_refinements,
    )
    best, stats = lo_ransac(est, ransac, [np.asarray(s, float) for s in initial_shapes])
    if best is None:
        return None, stats
    fit = fixed_shape_fit(obs, best, point_sigma, tangent_sigma, search)
    return Candidate(fit, robust_cost(fit.frame_chi2, o.truncate), math.nan), stats


def iter_spread_samples(n_frames: int) -> Iterator[np.ndarray]:
    """Distinct four-frame samples spread over the frames, deterministically and lazily:
    sample j takes frames floor(i n / 4) + j (mod n), i = 0..3 (a quarter of the sequence
    apart), repeats skipped; then the other samples in lexicographic order."""
    base = np.arange(minimal.FRAMES) * n_frames // minimal.FRAMES
    rotations = (tuple(np.sort((base + j) % n_frames)) for j in range(n_frames))
    others = itertools.combinations(range(n_frames), minimal.FRAMES)
    seen: set[tuple[int, ...]] = set()
    for sample in itertools.chain(rotations, others):
        key = tuple(int(i) for i in sample)
        if key not in seen:
            seen.add(key)
            yield np.array(key)


def spread_samples(n_frames: int, count: int) -> list[np.ndarray]:
    """The first ``count`` samples of :func:`iter_spread_samples`."""
    return list(itertools.islice(iter_spread_samples(n_frames), count))


def few_frame_hypotheses(
    obs: Observations,
    point_sigma: float,
    tangent_sigma: float,
    options: FewFrameSampleOptions | None = None,
    minimal_options: MinimalOptions | None = None,
    search: SearchOptions | None = None,
) -> list[Candidate]:
    """Candidates from the real minimal solutions of the first ``options.samples`` spread
    samples (:func:`spread_samples`; a degenerate one gives none): of each sample's shapes the
    ``options.refine_per_sample`` with the lowest chi2 on all frames (shape fixed, every frame
    at its best branch of (10)) are refined on all frames (``refine.start.refine_hypothesis``);
    best (lowest robust cost) first."""
    o = options or FewFrameSampleOptions()
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / tangent_sigma] * 2)
    meas = obs.measurements()
    starts: list[np.ndarray] = []
    for sample in itertools.islice(iter_spread_samples(obs.n_frames), o.samples):
        try:
            shapes = minimal.solve(obs.subset(sample), minimal_options).shapes
        except CurveReconError:  # a degenerate sample (two equal views, a tangent along A'B')
            continue
        if shapes.shape[0] == 0:
            continue
        poses = switch_branches(obs, shapes, poses_from_branches(obs, shapes), w8)
        chi2 = refine_batch(meas, shapes, poses, point_sigma, tangent_sigma, max_iter=0)[3]
        starts += [shapes[k] for k in np.argsort(chi2, kind="stable")[: o.refine_per_sample]]
    cands = []
    for shape in starts:
        fit = refine_hypothesis(obs, shape, point_sigma, tangent_sigma, options=search)
        cands.append(Candidate(fit, robust_cost(fit.frame_chi2), math.nan))
    return sorted(cands, key=lambda c: c.robust_cost)
