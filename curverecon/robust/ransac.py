"""A generic LO-RANSAC loop (as PoseLib's ``robust/ransac_impl.h`` structures it).

An estimator draws a minimal sample and returns every model it determines
(``generate_models``), scores a model on all the data (``score_model``: a robust cost, lower is
better, and the number of inliers), and polishes a model on its inliers (``refine_model``, the
local optimisation).  The loop keeps the best model; whenever a sample improves on it, the new
best is refined at once (LO) and re-scored.  It stops adaptively once it has drawn k samples in
all, where k is the number that draws at least one all-inlier sample with probability
``success_prob`` at the best model's inlier ratio (times ``dyn_num_trials_mult``), between
``min_iterations`` and ``max_iterations``.  Then (``final_refinements``) the best-scoring
unrefined models that differ from every model refined so far (the estimator's optional
``same_model``) are refined too, and the best of all refined models is returned: a sample
near the truth may score below a wrong model until it is polished.  Hypotheses from elsewhere
(``initial_models``, e.g. another method's answer) enter before the first sample, scored and
refined like a sample's models.

The loop knows nothing about curves (tests/test_ransac.py runs it on a line-fitting
estimator); the curve's estimator draws four-frame samples for the minimal solver.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Generic, Protocol, TypeVar

import numpy as np

Model = TypeVar("Model")


class Estimator(Protocol[Model]):
    """What the loop needs of an estimator (PoseLib's calling convention)."""

    sample_size: int
    """Number of data items in a minimal sample."""

    num_data: int
    """Number of data items."""

    def generate_models(self, sample: np.ndarray) -> list[Model]:
        """Every model the minimal sample (indices into the data) determines."""
        ...

    def score_model(self, model: Model) -> tuple[float, int]:
        """(robust cost on all the data, lower is better; number of inliers)."""
        ...

    def refine_model(self, model: Model) -> Model:
        """The model polished on its inliers (local optimisation)."""
        ...


@dataclass
class RansacOptions:
    """Options of :func:`lo_ransac` (defaults as PoseLib's ``RansacOptions`` where they apply).

    Attributes:
        max_iterations: hard cap on samples (a cap on time with few inliers).
        min_iterations: samples drawn at least, whatever the inlier ratio (guards against an
            early lucky but wrong best model).
        success_prob: probability that some sample was all inliers when the loop stops.
        dyn_num_trials_mult: safety factor on the adaptive number of samples.
        seed: the sampler's seed (same input, same output).
        final_refinements: after the loop, this many more of the best-scoring distinct
            unrefined models are refined and re-scored (0: PoseLib's loop alone).
    """

    max_iterations: int = 1000
    min_iterations: int = 20
    success_prob: float = 0.9999
    dyn_num_trials_mult: float = 3.0
    seed: int = 0
    final_refinements: int = 0


@dataclass
class RansacStats(Generic[Model]):
    """What :func:`lo_ransac` did: samples drawn, models scored, refinements, best inliers."""

    iterations: int = 0
    models: int = 0
    refinements: int = 0
    num_inliers: int = 0
    inlier_ratio: float = 0.0
    cost: float = math.inf
    history: list[float] = field(default_factory=list)


def required_iterations(inlier_ratio: float, sample_size: int, o: RansacOptions) -> int:
    """Samples needed to draw one all-inlier sample with probability ``o.success_prob``."""
    if inlier_ratio >= 1.0:
        return o.min_iterations
    p_good = inlier_ratio**sample_size
    if p_good <= 0.0:
        return o.max_iterations
    k = math.log(1.0 - o.success_prob) / math.log1p(-p_good)
    k = int(math.ceil(o.dyn_num_trials_mult * k))
    return int(min(max(k, o.min_iterations), o.max_iterations))


def lo_ransac(
    estimator: Estimator[Model],
    options: RansacOptions | None = None,
    initial_models: Sequence[Model] = (),
) -> tuple[Model | None, RansacStats]:
    """The best model (refined) and the loop's statistics; None if no sample gave a model.

    ``initial_models``: hypotheses from elsewhere (e.g. another method's answer), scored and
    the best of them refined before the first sample, as if a sample had given them (they
    count as models, not as samples; ``min_iterations`` samples are drawn all the same)."""
    o = options or RansacOptions()
    rng = np.random.default_rng(o.seed)
    stats: RansacStats = RansacStats()
    best: Model | None = None
    n, m = estimator.num_data, estimator.sample_size
    if n < m:
        return None, stats
    limit = o.max_iterations
    scored: list[tuple[float, int, Model]] = []  # every model's score, for the final refinements
    refined_from: list[Model] = []

    def consider(models: Sequence[Model]) -> None:
        """Score ``models``; if one is the new best, refine it (LO) and update the limit."""
        nonlocal best, limit
        improved = False
        for model in models:
            stats.models += 1
            cost, inl = estimator.score_model(model)
            scored.append((cost, len(scored), model))
            if cost < stats.cost:
                best, stats.cost, stats.num_inliers = model, cost, inl
                improved = True
        if improved and best is not None:
            # local optimisation of the new best, kept if it scores better
            stats.refinements += 1
            refined_from.append(best)
            refined = estimator.refine_model(best)
            cost, inl = estimator.score_model(refined)
            if cost < stats.cost:
                best, stats.cost, stats.num_inliers = refined, cost, inl
            stats.inlier_ratio = stats.num_inliers / n
            limit = required_iterations(stats.inlier_ratio, m, o)

    if len(initial_models):
        consider(initial_models)
    while stats.iterations < limit:
        stats.iterations += 1
        sample = np.sort(rng.choice(n, size=m, replace=False))
        consider(estimator.generate_models(sample))
        stats.history.append(stats.cost)
    if o.final_refinements > 0:
        best = _final_refinements(estimator, scored, refined_from, best, stats, o)
    return best, stats


def _final_refinements(
    estimator: Estimator[Model],
    scored: list[tuple[float, int, Model]],
    refined_from: list[Model],
    best: Model | None,
    stats: RansacStats,
    o: RansacOptions,
) -> Model | None:
    """The best model after refining the ``o.final_refinements`` best-scoring unrefined models
    that differ from every model refined before (``estimator.same_model(a, b)`` when the
    estimator has it; otherwise every model counts as distinct)."""
    same = getattr(estimator, "same_model", None)
    done = list(refined_from)
    count = 0
    for _, _, model in sorted(scored, key=lambda t: (t[0], t[1])):
        if count >= o.final_refinements:
            break
        if any(model is d for d in done) or (
            same is not None and any(same(model, d) for d in done)
        ):
            continue
        done.append(model)
        count += 1
        stats.refinements += 1
        refined = estimator.refine_model(model)
        cost, inl = estimator.score_model(refined)
        if cost < stats.cost:
            best, stats.cost, stats.num_inliers = refined, cost, inl
            stats.inlier_ratio = inl / estimator.num_data
    return best
