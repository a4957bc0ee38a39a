"""Pose branches of (10): frames whose other branch fits about as well as their pose.

Equation (10) has several solutions per frame for one shape (the sign of tau, another delta).
``flip_ambiguous_frames`` refits the shape with such frames switched (a local optimisation over
the discrete branches); ``second_branches`` gives each frame's other branch for the marginal
likelihood's mixture.  The per-frame switching itself (shape fixed) is
``robust.search.switch_branches`` / ``branch_alternatives``.

Tuned numbers: :class:`curverecon.options.BranchOptions`.
"""

from __future__ import annotations

import numpy as np

from curverecon.model.observations import Observations
from curverecon.options import BranchOptions, SearchOptions
from curverecon.refine.ml import RefineResult, refine, refine_batch
from curverecon.robust.search import branch_alternatives


def flip_ambiguous_frames(
    obs: Observations,
    fit: RefineResult,
    ps: float,
    ts: float,
    w8: np.ndarray,
    o: BranchOptions,
    search: SearchOptions,
    rounds: int = 2,
) -> RefineResult:
    """Refit with single frames moved to their other branch of (10) where that lowers chi2.

    A frame whose other branch (other sign of tau / other delta) fits about as well for the
    current shape (within ``o.flip_dchi2``) can hold the joint fit in a nearby local minimum: e.g.
    a frame with c' close to c (tau near 0), or phi near 0 or 180 degrees where a single frame's
    mirror image fits almost as well.  Each such frame is switched in turn (one batched
    refinement, one start per frame) and the best refit is kept if it lowers chi2.  Skipped
    once the fit is exact (``search.exact_cost``: no refit can beat it by the required margin).
    """
    for _ in range(rounds):
        if (
            fit.chi2 <= search.exact_cost
        ):  # an exact fit: no refit can lower chi2 by the margin below
            return fit
        alt, alt_chi2 = branch_alternatives(obs, fit.shape, fit.poses, w8)
        frames = np.flatnonzero(alt_chi2 - fit.frame_chi2 < o.flip_dchi2)
        if frames.size == 0:
            return fit
        combos = [(int(i),) for i in frames]
        g, p, chi2 = _refit_switched(obs, fit, alt, combos, ps, ts)
        k = int(np.argmin(chi2))
        if not chi2[k] < fit.chi2 - 1e-9 * (1.0 + fit.chi2):
            return fit
        fit = refine(obs, g[k], p[k], ps, ts, covariance=True)
    return fit


def _refit_switched(
    obs: Observations,
    fit: RefineResult,
    alt: np.ndarray,
    combos: list[tuple[int, ...]],
    ps: float,
    ts: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Joint refits (one batch) with the frames of each combination on their other branch."""
    poses = np.repeat(fit.poses[None], len(combos), axis=0)
    for j, c in enumerate(combos):
        poses[j, list(c)] = alt[list(c)]
    shapes = np.repeat(fit.shape[None], len(combos), axis=0)
    g, p, _, chi2, _, _ = refine_batch(obs, shapes, poses, ps, ts, max_iter=60)
    return g, p, chi2


def second_branches(
    obs: Observations, fit: RefineResult, w8: np.ndarray, kappa: float, o: BranchOptions
) -> np.ndarray:
    """(N, 5) each frame's pose on its other branch of (10) for the fit's shape, the second
    component of the marginal likelihood's mixture (``marginal.refine_marginal``), or NaN
    where there is none or it fits worse by more than ``o.mixture_dchi2`` noise scales (its
    weight would be below exp(-20))."""
    alt, alt_chi2 = branch_alternatives(obs, fit.shape, fit.poses, w8)
    keep = np.isfinite(alt_chi2) & (alt_chi2 - fit.frame_chi2 < o.mixture_dchi2 * kappa)
    return np.where(keep[:, None], alt, np.nan)
