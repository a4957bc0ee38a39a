"""Other hypotheses that fit the inlier frames about as well as the best (``alternatives``).

The search's other candidates within four times ``BranchOptions.alternative_dchi2`` of the
best robust cost are refined on the inliers in one batch; those whose chi2 is within
``alternative_dchi2`` of the best fit and whose shape differs (``shape_distance`` >= 0.02) are
kept, with their covariance.
"""

from __future__ import annotations

import numpy as np

from curverecon.model.observations import Observations
from curverecon.model.pose import normalise
from curverecon.options import BranchOptions
from curverecon.refine.ml import RefineResult, refine, refine_batch
from curverecon.robust.search import Candidate, shape_distance


def equally_good_fits(
    obs: Observations,
    inliers: np.ndarray,
    cands: list[Candidate],
    final: RefineResult,
    ps: float,
    ts: float,
    o: BranchOptions | None = None,
) -> list[tuple[np.ndarray, RefineResult]]:
    """[(normalised shape, fit on the inliers)], the best fit ``final`` first."""
    o = o or BranchOptions()
    sub = obs.subset(inliers)
    ml_chi2 = final.chi2
    fits = [(normalise(final.shape, final.poses)[0], final)]  # (normalised shape, fit)
    pending = [
        cand.result
        for cand in cands[1:]
        if cand.robust_cost - cands[0].robust_cost <= 4 * o.alternative_dchi2
        and shape_distance(cand.result.shape, fits[0][0]) >= 0.02
    ]
    if pending:
        g_alt, p_alt, _, _, _, _ = refine_batch(
            sub,
            np.array([r.shape for r in pending]),
            np.array([r.poses[inliers] for r in pending]),
            ps,
            ts,
        )
    for k, r in enumerate(pending):
        if any(shape_distance(r.shape, f[0]) < 0.02 for f in fits):
            continue
        alt = refine(sub, g_alt[k], p_alt[k], ps, ts, max_iter=0, covariance=True)
        if alt.chi2 - ml_chi2 > o.alternative_dchi2:
            continue
        alt_shape = normalise(alt.shape, alt.poses)[0]
        if any(shape_distance(alt_shape, f[0]) < 0.02 for f in fits):
            continue
        fits.append((alt_shape, alt))

    return fits
