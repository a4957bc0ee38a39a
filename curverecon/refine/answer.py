"""The answer: the final shape estimate among the equally good fits, and every frame's pose.

Maximum likelihood takes the best fit.  The marginal likelihood (the default) takes every fit
that is about as good by chi2 to its basin's marginal optimum (``refine.marginal``; every
frame's pose integrated out, one noise scale for all) and keeps the highest optimum; from
``refine.bias.BIAS_CORRECTED_FRAMES`` frames the default is instead the best fit minus its
simulated bias, its covariance widened by the correction's uncertainty.  Then the
outlier frames get their best pose for the answer's shape, the shape is normalised, and the
warnings and alternatives are written.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from curverecon.model.observations import Observations
from curverecon.model.pose import normalise
from curverecon.model.reconstruction import Alternative, Reconstruction, alternatives_warning
from curverecon.options import BranchOptions, SearchOptions
from curverecon.refine.bias import ml_bias
from curverecon.refine.marginal import KAPPA_MIN, refine_marginal
from curverecon.refine.ml import RefineResult, optimise_poses, refine
from curverecon.robust.branches import second_branches
from curverecon.robust.search import branch_alternatives, switch_branches
from curverecon.solvers.pose import poses_from_shape

BIAS_WARNING_FRAMES = 3000
"""From this many inlier frames on, the uncorrected maximum-likelihood answer
(``estimator="ml"``) warns that its standard deviations understate its error: its bias does not
shrink with more frames while the standard deviations do (``python -m bench --only scale``
before the correction: c off by 14.3 standard deviations at 30,000 frames and 27.1 at 100,000).
The default answer from ``refine.bias.BIAS_CORRECTED_FRAMES`` frames on is corrected for its bias
and its standard deviations include the correction's uncertainty: no warning."""


def _bias_corrected(
    sub: Observations, fit: RefineResult, ps: float, ts: float
) -> tuple[RefineResult, str]:
    """The fit with its shape's estimated bias subtracted and the estimate's own covariance
    added (``refine.bias``), and the estimator's name; the fit itself where no correction
    applies (noise-free data, singular information)."""
    if fit.covariance is None:
        return fit, "ml"
    bc = ml_bias(sub.measurements(), fit.shape, fit.poses, ps, ts, fit.frame_chi2, fit.covariance)
    if bc is None or not np.all(np.isfinite(bc.bias)):
        return fit, "ml"
    out = dataclasses.replace(
        fit, shape=fit.shape - bc.bias, covariance=fit.covariance + bc.covariance
    )
    return out, "ml-bias-corrected"


def final_estimate(
    obs: Observations,
    inliers: np.ndarray,
    fits: list[tuple[np.ndarray, RefineResult]],
    ps: float,
    ts: float,
    marginal: bool,
    warnings: list[str],
    branches: BranchOptions | None = None,
    search: SearchOptions | None = None,
    correct_bias: bool = False,
) -> Reconstruction:
    """The reconstruction from the equally good fits on the inlier frames (best first).

    Args:
        obs: all frames; inliers: (N,) mask; fits: [(normalised shape, fit on the inliers)].
        ps, ts: point noise (input units), tangent noise (radians).
        marginal: the marginal-likelihood estimate (else maximum likelihood).
        warnings: the warnings so far (extended here).
        correct_bias: (with ``marginal`` False) the maximum-likelihood shape minus its
            estimated bias, its covariance plus that estimate's (``refine.bias``).
    """
    branches = branches or BranchOptions()
    search = search or SearchOptions()
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    sub = obs.subset(inliers)
    final = fits[0][1]
    ml_chi2 = final.chi2
    # The answer.  Maximum likelihood: the best fit.  Marginal: every fit that is about as
    # good by chi2 is taken to its basin's marginal optimum (one noise scale for all), and the
    # highest of those optima is the answer.  (At 1 px, 1 deg and 20 frames the lowest chi2 is
    # sometimes a spurious basin, c off by 10-30 standard deviations, while F prefers the basin
    # of the truth by 20-80; see curverecon.refine.marginal.  Comparing F at the optima rather than
    # at the fits' ML points matters where the ML points sit on either side of a fold: F at
    # the ML point of the truth's basin was 2 higher on one headline scene, its optimum 2
    # lower.  On the bench's 200 headline scenes: alpha's RMSE/CRLB 1.26 -> 1.09, phi's 1.25
    # -> 1.23, with 3 answers changed, at the same time per scene: ``python -m bench.headline``.
    # Each frame whose other branch of (10) fits about as well enters F as a mixture of both,
    # ``robust.branches.second_branches``: phi's 1.23 -> 1.12, see curverecon.refine.marginal.)
    estimator = "ml"
    chosen = 0
    if marginal:
        meas_in = sub.measurements()
        kappa = ml_chi2 / max(sub.n_frames - 4, 1)
        mixture = sub.n_frames >= 5 and kappa >= KAPPA_MIN  # where the marginal step applies
        mgs = [
            refine_marginal(
                meas_in,
                f.shape,
                f.poses,
                ps,
                ts,
                ml_chi2,
                second_branches(sub, f, w8, kappa, branches) if mixture else None,
            )
            for _, f in fits
        ]
        if all(m is not None for m in mgs):
            chosen = int(np.argmin([m.value for m in mgs]))
        r0 = fits[chosen][1]
        mg = mgs[chosen]
        if mg is not None:
            # every frame on its best branch of (10) for the answer's shape (the mixture put it
            # on its branch of the larger weight, which can differ where the two fit alike)
            mg.poses = switch_branches(sub, mg.shape, mg.poses, w8, options=search)
            final = refine(sub, mg.shape, mg.poses, ps, ts, max_iter=0, covariance=True)
            estimator = "marginal"
        else:
            final = r0
    elif correct_bias:
        final, estimator = _bias_corrected(sub, final, ps, ts)

    # Poses of outlier frames: best pose for the final shape (shape held fixed).
    poses = np.array(poses_from_shape(obs, final.shape)[0])
    poses[inliers] = final.poses
    meas = obs.measurements()
    poses, resid = optimise_poses(final.shape, poses, meas, w8, 10)
    frame_chi2 = np.sum(resid * resid, axis=1)
    frame_chi2[inliers] = final.frame_chi2
    shape, poses = normalise(final.shape, poses)
    alt_poses, alt_chi2 = branch_alternatives(obs, shape, poses, w8)
    std = final.std
    if std is None or not np.all(np.isfinite(std)):
        std = None
        warnings.append("the shape is not determined by these frames (singular information matrix)")
    elif std[0] > 0.5 * shape[0] or np.any(std[1:] > math.radians(30.0)):
        warnings.append(
            "the shape is poorly determined by these frames (standard deviation "
            f"c {std[0]:.3g}, angles {', '.join(f'{math.degrees(s):.1f}' for s in std[1:])} deg)"
        )
    if std is not None and not correct_bias and int(inliers.sum()) >= BIAS_WARNING_FRAMES:
        warnings.append(
            f"with {int(inliers.sum())} frames the standard deviations are below the "
            "maximum-likelihood estimator's bias (the poses are nuisance parameters; on "
            "simulated 1 px / 1 deg scenes c came out 6 to 37 standard deviations off at 10,000 "
            "to 100,000 frames; the default estimator corrects it): read them as the precision, "
            "not the accuracy"
        )
    outliers = np.flatnonzero(~inliers)
    if outliers.size:
        warnings.append(
            f"{outliers.size} frame(s) do not fit and were left out of the shape estimate: "
            + ", ".join(str(int(i)) for i in outliers)
        )
    alternatives: list[Alternative] = []
    for k, (alt_shape, alt) in enumerate(fits):
        if k == chosen:
            continue
        other_poses = np.array(poses_from_shape(obs, alt_shape)[0])
        other_poses[inliers] = normalise(alt.shape, alt.poses)[1]
        alternatives.append(Alternative(alt_shape, other_poses, alt.chi2, alt.std))
    if alternatives:
        warnings.append(alternatives_warning(shape, std, alternatives))
    return Reconstruction(
        shape=shape,
        poses=poses,
        std=std,
        inliers=inliers,
        alternatives=alternatives,
        warnings=warnings,
        method="auto",
        chi2=final.chi2,
        frame_chi2=frame_chi2,
        branch_alternatives=alt_poses,
        branch_alternative_chi2=alt_chi2,
        estimator=estimator,
        ambiguous_dchi2=branches.ambiguous_dchi2,
    )
