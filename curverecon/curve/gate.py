"""The never-worse gate of the curve bundle: the bundle's shape is kept only when it stays inside
the end points' confidence region (the end-point answer's profile chi2, in units of its own
variance factor; :func:`gate_reference_chi2`, :func:`never_worse_limit`), or, in the band
between the known-variance and the estimated-variance limits, when the polylines reject the
end-point answer's poses (:func:`polylines_reject_fixed_poses`).  :func:`gate` decides for one
bundle.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from curverecon.curve.spline import BundleResult, shape_and_poses
from curverecon.options import CurveOptions

if TYPE_CHECKING:
    from curverecon.curve.bundle import CurveRun


def end_point_chi2(shape: np.ndarray, poses: np.ndarray, obs, inliers, w8) -> np.ndarray:
    """(N,) per-frame chi2 of a shape and poses against the end points and tangents."""
    from curverecon.refine.ml import standardised_residuals

    resid = standardised_residuals(shape, poses, obs.measurements(), w8)
    return np.sum(resid * resid, axis=1)


def gate_reference_chi2(chi2_answer: float, alternatives, options=None) -> float:
    """The end-point chi2 the never-worse gate measures the bundle's shape from.

    ``chi2_answer``: the end-point answer's chi2 on its inlier frames; ``alternatives``: its
    equally good ``Reconstruction.alternatives`` (each refitted on the same inlier frames with
    the same sigmas, so their chi2 compare).  With ``CurveOptions.never_worse_alternatives``
    the least of these chi2, else the answer's.  The end points' likelihood-ratio confidence
    region is then the set of shapes within :func:`never_worse_limit` (in units of the variance
    factor) of the best fit: the union of the regions about every hypothesis that fits about
    as well, which takes a bundle that chose one of them by the curve and refuses a shape
    outside all of them."""
    o = options if options is not None else CurveOptions()
    chi2 = float(chi2_answer)
    if o.never_worse_alternatives:
        for alt in alternatives or []:
            if np.isfinite(alt.chi2):
                chi2 = min(chi2, float(alt.chi2))
    return chi2


def never_worse_limit(dof: int, options=None) -> float:
    """The upper end of the never-worse gate's band (``CurveOptions.never_worse_f_test``): the
    limit on ``end_point_dchi2`` (the bundle shape's end-point chi2 above the reference, in
    units of the variance factor s2 = chi2 / ``dof`` of the end-point fit, ``dof`` = inlier
    frames - 4) when s2 is estimated from the fit itself, 4 F(4, dof) at the probability of
    ``CurveOptions.never_worse_dchi2`` under chi2 with 4 degrees of freedom (the known-variance
    limit, 99 %), which it tends to as dof grows: 28.0 at 12 frames, 19.1 at 20."""
    o = options if options is not None else CurveOptions()
    limit = float(o.never_worse_dchi2)
    if dof < 1 or not np.isfinite(limit) or limit <= 0.0:
        return limit
    from scipy.stats import chi2, f

    return float(4.0 * f.ppf(chi2.cdf(limit, 4), 4, int(dof)))


def polylines_reject_fixed_poses(
    counts: np.ndarray,
    rms_fixed: np.ndarray,
    rms_bundle: np.ndarray,
    k: int,
    level: float,
) -> tuple[bool, float]:
    """Whether the polylines reject the end-point answer's poses: the nested-model F test of
    the curve fitted with every pose fixed and its ends pinned (:func:`fit_curve_fixed_poses`,
    per-frame RMS ``rms_fixed`` px) against the bundle (``rms_bundle``; both on the frames
    whose polylines the fits use).  ``counts``: polyline points of those frames (each less 2,
    as :func:`bic` counts them); ``k``: the bundle's control points.  The bundle has 5 N + 4
    more parameters than the pinned fixed-pose curve (3 K - 1 + 5 (N - 1) against
    2 + 3 (K - 4)), the noise level is the bundle's own RSS over its residual degrees of
    freedom (scale-free, like :func:`bic`).  Returns (rejected at ``level``, the upper-tail
    probability)."""
    from scipy.stats import f

    counts = np.asarray(counts, float)
    n_fr = len(counts)
    n_obs = float(counts.sum())
    p = 5 * n_fr + 4
    dof2 = n_obs - (3 * k - 1 + 5 * (n_fr - 1))
    rss_f = float(np.sum(counts * np.asarray(rms_fixed, float) ** 2))
    rss_b = float(np.sum(counts * np.asarray(rms_bundle, float) ** 2))
    if dof2 < 1 or not (np.isfinite(rss_f) and np.isfinite(rss_b)) or rss_b <= 0.0:
        return False, 1.0
    stat = ((rss_f - rss_b) / p) / (rss_b / dof2)
    tail = float(f.sf(stat, p, dof2))
    return tail < 1.0 - level, tail


@dataclass
class Verdict:
    """The gate's decision on one bundle: its shape and poses (normalised, ``pose.normalise``)
    with their end-point chi2 per frame, whether the bundle is kept, its ``end_point_dchi2``
    (None without given end points) and whether it lies in the band where the polylines decide
    (:func:`band_keeps_bundle`)."""

    shape: np.ndarray
    shape_n: np.ndarray
    poses_n: np.ndarray
    frame_chi2: np.ndarray
    accepted: bool
    dchi2: float | None
    band: bool


def gate(run: CurveRun, br: BundleResult) -> Verdict:
    """The never-worse gate on the bundle ``br``: its shape is kept when its end points'
    profile chi2 (every pose at its best for that shape) exceeds the reference
    (:func:`gate_reference_chi2`) by at most ``CurveOptions.never_worse_dchi2`` in units of the
    end-point fit's variance factor, or when the end points leave the shape undetermined."""
    from curverecon.model.pose import normalise

    o, obs, inl, w8, rec = run.o, run.obs, run.inl, run.w8, run.rec
    shape, poses, _ = shape_and_poses(br)
    shape_n, poses_n = normalise(shape, poses)
    frame_chi2 = end_point_chi2(shape_n, poses_n, obs, inl, w8)
    accepted, dchi2, band = True, None, False
    if run.s2 is not None:
        # the end points' profile chi2 of the bundle's shape (every pose at its best for that
        # shape): the shape's own distance from the end-point answer, in 4 dimensions
        from curverecon.refine.ml import optimise_poses

        _, resid = optimise_poses(shape_n, poses_n, obs.measurements(), w8, 10)
        profile = float(np.sum((resid * resid).sum(axis=1)[inl]))
        dchi2 = (
            min(profile, float(np.sum(frame_chi2[inl])))
            - gate_reference_chi2(run.chi2_ep, rec.alternatives, o)
        ) / run.s2
        # the gate guards a determined end-point answer; where the end points leave the shape
        # undetermined (singular information; with ``o.never_worse_alternatives`` off also
        # other shapes fitting as well) the curve decides
        undetermined = rec.std is None or (
            bool(rec.alternatives) and not o.never_worse_alternatives
        )
        accepted = undetermined or dchi2 <= o.never_worse_dchi2
        # between the known-variance limit and the estimated-variance one the end points leave
        # it open whether the shape is inside their 99 % region: the polylines decide below
        band = not accepted and o.never_worse_f_test and dchi2 <= never_worse_limit(run.dof, o)
    return Verdict(shape, shape_n, poses_n, frame_chi2, accepted, dchi2, band)


def band_keeps_bundle(
    run: CurveRun, br: BundleResult, verdict: Verdict, info: dict, mask: np.ndarray
) -> tuple[bool, float]:
    """In the band (``CurveOptions.never_worse_f_test``): whether the bundle's shape is kept
    because the polylines reject the end-point answer's poses (the curve fitted on them, per
    frame ``info["frame_rms_px"]``, stays beyond the noise from the polylines the bundle fits).
    Returns (kept, the F test's upper-tail probability)."""
    counts = np.array([max(len(c) - 2, 1) for c in run.curves], float)[mask]
    rms_fixed = np.asarray(info["frame_rms_px"], float)[mask]
    k = br.control.shape[0]
    return polylines_reject_fixed_poses(
        counts, rms_fixed, br.rms[mask], k, run.o.never_worse_polyline_level
    )


def band_warning(run: CurveRun, verdict: Verdict, tail: float) -> str:
    """The warning of a bundle kept in the band (:func:`band_keeps_bundle`)."""
    o = run.o
    return (
        f"the curve bundle's shape is {float(verdict.dchi2):.1f} (variance factors) above the "
        "end points' best fit, beyond the 99 % limit for a known noise level "
        f"({o.never_worse_dchi2:g}) but within it for the level the end points show "
        f"({run.dof} degrees of freedom); the polylines reject the "
        f"end-point answer's poses (probability {tail:.1e}): the bundle's answer kept"
    )
