"""Outlier frames: which frames do not fit the best hypothesis, and the fit without them.

The test is on each frame's studentised chi2 (chi2 / (1 - leverage), ``refine.ml.frame_leverages``)
against the chi2(1) quantile of ``OutlierOptions.false_alarm``, scaled up if the noise looks
larger than stated (median-scaled).  Before it: a frame-level Cauchy reweighting so that outliers
stand out, and, when the fit's chi2 is implausible, trimmed refits (least trimmed squares'
concentration steps) so that outlier frames cannot mask themselves.  Then the worst frame above
the threshold is dropped and the fit redone until none is left; a frame is first re-solved
from a grid of pose starts (a good frame left on a wrong pose is not an outlier).

Tuned numbers: :class:`curverecon.options.OutlierOptions`.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations
from curverecon.options import OutlierOptions, SearchOptions
from curverecon.refine.ml import (
    RefineResult,
    frame_leverages,
    refine,
    standardised_residuals,
)
from curverecon.robust.search import robust_start, switch_branches

MEDIAN_CHI2_1 = 0.4549364231195724
"""Median of chi2 with one degree of freedom."""


def chi2_tail(chi2: float, n_frames: int) -> float:
    """P(a chi2 of n_frames - 4 degrees of freedom exceeds ``chi2``): how surprising a fit of
    ``n_frames`` frames (one degree of freedom each, four shape parameters) is for the noise."""
    return float(chi2_dist.sf(chi2, max(n_frames - 4, 1)))


def chi2_lower_tail(chi2: float, n_frames: int) -> float:
    """P(a chi2 of n_frames - 4 degrees of freedom is below ``chi2``): small when the fit is
    far closer than the noise given allows (the data are more precise than it says)."""
    return float(chi2_dist.cdf(chi2, max(n_frames - 4, 1)))


def implausible_chi2(chi2: float, n_frames: int) -> bool:
    """A fit's chi2 too high for the noise: above its n_frames - 4 degrees of freedom by five
    of their standard deviations plus 10 (outlier frames, or a wrong basin)."""
    dof = max(n_frames - 4, 1)
    return chi2 > dof + 5.0 * math.sqrt(2.0 * dof) + 10.0


def find_outlier_frames(
    obs: Observations,
    fit: RefineResult,
    ps: float,
    ts: float,
    o: OutlierOptions | None = None,
    search: SearchOptions | None = None,
    start_inliers: np.ndarray | None = None,
) -> tuple[np.ndarray, RefineResult]:
    """(N,) inlier mask and the maximum-likelihood fit on the inliers (no covariance).

    Args:
        obs: all frames; fit: the best hypothesis refined on all frames (or, with
            ``start_inliers``, a fit of all frames' poses to a shape estimated without the
            frames outside it).
        ps, ts: point noise (input units) and tangent noise (radians).
        start_inliers: (N,) frames known to fit (LO-RANSAC's consensus set): the fit starts on
            them (:func:`consensus_start`) instead of the robust reweighting of all frames.
    At most (N - 5) // 2 frames are flagged.
    """
    o = o or OutlierOptions()
    search = search or SearchOptions()
    n = obs.n_frames
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    max_out = max(0, (n - 5) // 2)
    if start_inliers is not None and 0 < int((~start_inliers).sum()) <= max_out:
        inliers, fit = consensus_start(obs, fit, start_inliers, ps, ts, w8, o, search)
        return _drop_loop(obs, inliers, fit, ps, ts, w8, max_out, False, o, search)
    # Robust fit (frame-level Cauchy reweighting) so that outlier frames stand out; with an
    # implausible chi2, trimmed refits; then the outlier test on the unweighted, studentised
    # per-frame chi2: drop the worst frame above the threshold, refit, repeat.
    implausible = implausible_chi2(fit.chi2, n)
    long = n >= o.batch_frames
    st = studentised(obs, fit, w8, o)
    # (a long sequence with a plausible chi2: a frame's pull on the shape is ~4/N of its own,
    # no outlier can hide behind the others, and the frames above the threshold are the
    # false alarms ``o.false_alarm`` predicts: the reweighting would change nothing)
    robust_rounds = 3 if np.max(st) > threshold(st, o) and (implausible or not long) else 0
    for _ in range(robust_rounds):
        scale2 = o.cauchy_k**2 * max(1.0, float(np.median(st)) / MEDIAN_CHI2_1)
        weights = 1.0 / (1.0 + st / scale2)
        poses_sw = switch_branches(obs, fit.shape, fit.poses, w8, rescue=True, options=search)
        fit = refine(obs, fit.shape, poses_sw, ps, ts, covariance=False, frame_weights=weights)
        st = studentised(obs, fit, w8, o)
    inliers = np.ones(n, dtype=bool)
    if max_out > 0 and implausible:
        inliers, fit = trimmed_inliers(obs, fit, ps, ts, w8, max_out, o, search)
    return _drop_loop(obs, inliers, fit, ps, ts, w8, max_out, long, o, search)


def consensus_start(
    obs: Observations,
    fit: RefineResult,
    start: np.ndarray,
    ps: float,
    ts: float,
    w8: np.ndarray,
    o: OutlierOptions,
    search: SearchOptions,
) -> tuple[np.ndarray, RefineResult]:
    """The inliers and fit the outlier test starts from when a consensus set is known.

    The shape is refined on the frames of ``start``; every frame left out is then fitted to that
    shape (its pose at its best branch of (10)) and taken back when its chi2 is below the
    outlier test's threshold (a good frame a rough sample shape left just above its truncation);
    the fit is redone on the frames kept.  The frames left out are never refitted together with
    the others, so those that do not fit cannot pull the shape.
    """
    inliers = np.array(start, bool)
    sub = refine(obs.subset(inliers), fit.shape, fit.poses[inliers], ps, ts, covariance=False)
    poses = np.array(fit.poses)
    poses[inliers] = sub.poses
    poses = switch_branches(obs, sub.shape, poses, w8, options=search)
    r = standardised_residuals(sub.shape, poses, obs.measurements(), w8)
    chi2 = np.sum(r * r, axis=1)
    thr = threshold(studentised(obs.subset(inliers), sub, w8, o), o)
    back = ~inliers & (chi2 <= min(thr, o.take_back_chi2))
    if not back.any():
        return inliers, sub
    inliers |= back
    return inliers, refine(obs.subset(inliers), sub.shape, poses[inliers], ps, ts, covariance=False)


def _drop_loop(
    obs: Observations,
    inliers: np.ndarray,
    fit: RefineResult,
    ps: float,
    ts: float,
    w8: np.ndarray,
    max_out: int,
    long: bool,
    o: OutlierOptions,
    search: SearchOptions,
) -> tuple[np.ndarray, RefineResult]:
    """The outlier test's loop from ``inliers`` and the fit on them: the worst inlier frame
    above the threshold is re-solved from a grid of pose starts or dropped, and the shape
    refitted, until none is above it or ``max_out`` frames are out (long sequences: every
    frame above it per round, ``_drop_all_over``)."""
    n = obs.n_frames
    rescued = 0
    while True:
        idx = np.flatnonzero(inliers)
        st = studentised(obs.subset(inliers), fit, w8, o)
        j = int(np.argmax(st))
        thr = threshold(st, o)
        if st[j] <= thr or (~inliers).sum() >= max_out:
            break
        if long:
            inliers, fit, rescued = _drop_all_over(
                obs, inliers, fit, st, thr, max_out, rescued, ps, ts, w8, search
            )
            continue
        # a frame on a wrong pose (a minimum of its own that no branch of (10) led out of)
        # is not an outlier: its pose re-solved from a grid of starts first, and kept if
        # that brings it under the threshold (``search.switch_branches(..., rescue=True)``)
        one = obs.subset(np.array([idx[j]]))
        pj = switch_branches(one, fit.shape, fit.poses[j : j + 1], w8, rescue=True, options=search)
        if rescued < n and not np.array_equal(pj, fit.poses[j : j + 1]):
            rj = standardised_residuals(fit.shape, pj, one.measurements(), w8)
            chi2_j = float(np.sum(rj * rj))
            if chi2_j < fit.frame_chi2[j] and chi2_j <= thr:
                poses = np.array(fit.poses)
                poses[j] = pj[0]
                fit = refine(obs.subset(inliers), fit.shape, poses, ps, ts, covariance=False)
                rescued += 1
                continue
        inliers[idx[j]] = False
        keep = np.arange(idx.size) != j
        fit = refine(obs.subset(inliers), fit.shape, fit.poses[keep], ps, ts, covariance=False)
    return inliers, fit


def _drop_all_over(
    obs: Observations,
    inliers: np.ndarray,
    fit: RefineResult,
    st: np.ndarray,
    thr: float,
    max_out: int,
    rescued: int,
    ps: float,
    ts: float,
    w8: np.ndarray,
    search: SearchOptions,
) -> tuple[np.ndarray, RefineResult, int]:
    """One round of the outlier loop of a long sequence: every inlier frame above the
    threshold at once (rather than the worst, refit, repeat: O(N) per frame flagged).

    As the loop does for its worst frame: each is first re-solved from a grid of pose starts
    (kept if that brings it under the threshold); the others are dropped, the worst first, at
    most up to ``max_out`` frames left out in all; then one refit on the inliers.  Returns the
    new mask, fit and count of rescued frames."""
    n = obs.n_frames
    idx = np.flatnonzero(inliers)
    over = np.flatnonzero(st > thr)
    over = over[np.argsort(-st[over], kind="stable")]
    poses = np.array(fit.poses)
    if rescued < n:
        sub = obs.subset(idx[over])
        pj = switch_branches(sub, fit.shape, poses[over], w8, rescue=True, options=search)
        rj = standardised_residuals(fit.shape, pj, sub.measurements(), w8)
        chi2_j = np.sum(rj * rj, axis=1)
        moved = np.any(pj != poses[over], axis=1)
        ok = moved & (chi2_j < fit.frame_chi2[over]) & (chi2_j <= thr)
        poses[over[ok]] = pj[ok]
        rescued += int(ok.sum())
        over = over[~ok]
    drop = over[: max(0, max_out - int((~inliers).sum()))]
    inliers = np.array(inliers)
    inliers[idx[drop]] = False
    keep = np.ones(idx.size, bool)
    keep[drop] = False
    fit = refine(obs.subset(inliers), fit.shape, poses[keep], ps, ts, covariance=False)
    return inliers, fit, rescued


def trimmed_inliers(
    obs: Observations,
    fit: RefineResult,
    ps: float,
    ts: float,
    w8: np.ndarray,
    max_out: int,
    o: OutlierOptions,
    search: SearchOptions,
) -> tuple[np.ndarray, RefineResult]:
    """Outlier frames by trimmed refits (least trimmed squares' concentration steps).

    When the best fit's chi2 is implausible, outlier frames have pulled the shape, every frame's
    misfit has grown, and the median-scaled threshold hides them (masking).  So: refit the shape
    on all but the ``max_out`` frames of largest studentised chi2; test every frame against that
    fit, the left-out ones by their deleted residual (their pose fitted to the trimmed shape,
    chi2 / (1 + h), h = tr(S_kept^-1 S_i)) and the others by chi2 / (1 - l); flag those above
    the threshold; repeat from the new shape (``o.trim_steps``).  Returns the inliers (at least
    N - ``max_out``) and the fit on them; all frames and ``fit`` itself when none is flagged.
    """
    n = obs.n_frames
    meas = obs.measurements()
    shape, poses = fit.shape, np.array(fit.poses)
    flagged = np.zeros(n, bool)
    base = float(chi2_dist.isf(o.false_alarm, 1))
    for step in range(o.trim_steps):
        trial = refine(obs, shape, poses, ps, ts, max_iter=0, covariance=False)
        st = studentised(obs, trial, w8, o)
        keep = np.zeros(n, bool)
        keep[np.argsort(st, kind="stable")[: n - max_out]] = True
        tf = refine(obs.subset(keep), shape, poses[keep], ps, ts, covariance=False)
        if step == 0:  # the kept frames searched again: the outliers may have moved the basin
            try:
                cands = robust_start(obs.subset(keep), ps, ts, options=search)
            except CurveReconError:  # e.g. the kept frames alone are degenerate: keep tf
                cands = []
            if cands and cands[0].result.chi2 < tf.chi2:
                tf = cands[0].result
        poses[keep] = tf.poses
        poses = switch_branches(obs, tf.shape, poses, w8, options=search)
        poses[keep] = tf.poses
        r = standardised_residuals(tf.shape, poses, meas, w8)
        chi2 = np.sum(r * r, axis=1)
        lev = frame_leverages(tf.shape, poses, meas, w8, among=keep)
        t2 = np.where(keep, chi2 / np.maximum(1.0 - lev, o.leverage_floor), chi2 / (1.0 + lev))
        scale = max(1.0, float(np.median(t2)) / MEDIAN_CHI2_1)
        over = t2 > base * scale
        worst = np.argsort(-t2, kind="stable")[:max_out]
        flagged = np.zeros(n, bool)
        flagged[worst[over[worst]]] = True
        shape = tf.shape
    if not flagged.any():  # nothing found: the fit stays as it was
        return np.ones(n, bool), fit
    inl = ~flagged
    return inl, refine(obs.subset(inl), shape, poses[inl], ps, ts, covariance=False)


def studentised(
    obs: Observations, fit: RefineResult, w8: np.ndarray, o: OutlierOptions
) -> np.ndarray:
    """(N,) per-frame chi2 / (1 - leverage) (``refine.frame_leverages``): what the outlier test
    compares with its threshold, so that a frame that pins the shape cannot hide its misfit."""
    lev = frame_leverages(fit.shape, fit.poses, obs.measurements(), w8)
    return fit.frame_chi2 / np.maximum(1.0 - lev, o.leverage_floor)


def threshold(frame_chi2: np.ndarray, o: OutlierOptions) -> float:
    """Per-frame chi2 threshold: chi2(1) quantile, scaled up if the noise looks larger."""
    base = float(chi2_dist.isf(o.false_alarm, 1))
    scale = max(1.0, float(np.median(frame_chi2)) / MEDIAN_CHI2_1)
    return base * scale
