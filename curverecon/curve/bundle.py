"""The curve bundle's answer: poses and one 3-D B-spline fitted to every polyline, kept only
when never worse than the end points' answer (:func:`refine_reconstruction`).

The curve stage reads as a sequence of modules:

- ``curve.spline``: the curve model (a clamped cubic B-spline), a fit's result and its shape;
- ``curve.residuals``: the residual model (``Problem``: residual rows, Jacobians, the normal
  equations in blocks);
- ``curve.lm``: the solvers (Levenberg-Marquardt with a Schur complement on the poses);
- ``curve.pose_search``: every frame's pose searched again against a fixed curve;
- ``curve.joint``: the joint fit in stages (:func:`bundle_adjust`) and the polylines-only refits;
- ``curve.starts``: start curves and poses, the further starts, the lowest cost kept;
- ``curve.fixed_poses``: the curve alone with every pose fixed (exact end points, long
  sequences, a refused bundle);
- ``curve.gate``: the never-worse gate;
- ``curve.uncertainty``: the std of the shape and of every output curve point.

:func:`refine_reconstruction` is these steps in order: the run's data (:func:`_prepared`); the
fixed-pose answer where no joint fit is made; the bundle from its starts, frames that contradict
the given end points flagged and left out (:func:`_fitted_bundle`); the gate; the refused
bundle's answer (:func:`_refused_answer`) or the accepted one (:func:`_accepted_answer`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve.fixed_poses import fit_curve_fixed_poses, fixed_pose_answer
from curverecon.curve.gate import (
    band_keeps_bundle,
    band_warning,
    end_point_chi2,
    gate,
    gate_reference_chi2,
    never_worse_limit,
    polylines_reject_fixed_poses,
)
from curverecon.curve.joint import (
    N_CONTROL,
    bundle_adjust,
    resect_uneven_frames,
)
from curverecon.curve.residuals import SIGMA_FLOOR
from curverecon.curve.section4 import noise_level
from curverecon.curve.spline import (
    Basis,
    BundleResult,
    arc_parameters,
    bundle_error,
    fit_spline,
    shape_and_poses,
)
from curverecon.curve.starts import bundle_from_frame, extra_start_frames, flat_start, run_starts
from curverecon.curve.uncertainty import (
    accepted_std,
    curve_point_std,
    refused_std,
    rival_minima_std,
)
from curverecon.options import CurveOptions

__all__ = [
    "BundleResult",
    "CurveRun",
    "bundle_adjust",
    "bundle_from_frame",
    "curve_point_std",
    "end_point_chi2",
    "extra_start_frames",
    "fit_curve_fixed_poses",
    "fit_spline",
    "flat_start",
    "gate_reference_chi2",
    "never_worse_limit",
    "polylines_reject_fixed_poses",
    "refine_reconstruction",
    "resect_uneven_frames",
    "shape_and_poses",
]


@dataclass
class CurveRun:
    """What the steps of :func:`refine_reconstruction` share: its arguments, the bundle's
    keyword arguments (``kw``), the end-point fit's weights and variance factor, the polylines'
    noise level, the answer's warnings (appended to by the steps), every completed start of the
    last run of starts (``tried``) and the start curve of frame 0's other branch once made."""

    rec: Any
    obs: Any
    curves: list
    o: CurveOptions
    flat: bool
    curve_start: np.ndarray
    use_given: bool
    point_sigma: float
    tangent_sigma_deg: float
    n_out: int | None
    curve_frames: np.ndarray | None
    fixed_start: Callable[[], np.ndarray | None] | None
    start_for: Callable[[np.ndarray, np.ndarray], np.ndarray | None] | None
    ends: np.ndarray | None
    tangents: np.ndarray | None
    kw: dict
    w8: np.ndarray
    inl: np.ndarray
    dof: int
    chi2_ep: float | None
    s2: float | None
    sigma: float
    limit: float
    warnings: list[str]
    tried: list[BundleResult] = field(default_factory=list)
    flipped_start: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(self.curves)

    def fixed_curve_start(self) -> np.ndarray:
        """The start of the fits with every pose fixed (``fixed_start``, else ``curve_start``)."""
        made = self.fixed_start() if self.fixed_start is not None else None
        return np.asarray(self.curve_start if made is None else made, float)

    def flag_warning(self, flagged: list[int], rms: np.ndarray) -> None:
        self.warnings.append(
            f"frames {flagged}: the polyline contradicts the end points and tangents (RMS "
            f"{', '.join(f'{rms[i]:.1f}' for i in flagged)} px from the curve they fix, limit "
            f"{self.limit:.1f} px): left out of the curve fit"
        )


def refine_reconstruction(
    rec,
    obs,
    curve_start: np.ndarray | None,
    *,
    use_given: bool = False,
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    n_out: int | None = None,
    options=None,
    curve_frames: np.ndarray | None = None,
    fixed_start: Callable[[], np.ndarray | None] | None = None,
    start_for: Callable[[np.ndarray, np.ndarray], np.ndarray | None] | None = None,
):
    """Run the curve bundle on a reconstruction and return the updated answer.

    rec: a ``reconstruct.Reconstruction`` (its poses are the start); obs: the observations
    (with curves); curve_start: the start curve in frame 0's camera coordinates (``curve3d``),
    or None for :func:`flat_start`.  use_given: the input gave A', B' and the tangents (they
    join the fit as measurements with ``point_sigma``, ``tangent_sigma_deg``; tangents of
    frames the end-point fit marked as outliers are left out).  options: ``CurveOptions``.

    With given end points and tangents, two more steps (``CurveOptions``):

    - a frame whose polyline stays far from the fitted curve (``flag_rms_*``) while its end
      points fit is flagged: its polyline contradicts the end points (another curve, a tracking
      error) and is left out of a second fit, not averaged in (``curve_bundle.flagged_frames``);
    - never worse: the bundle's shape and poses are kept only if their end-point chi2 exceeds
      the end-point answer's by at most :func:`never_worse_limit` (``never_worse_dchi2``, or
      with ``never_worse_f_test`` its F-distribution counterpart for a variance estimated from
      the fit) in units of the end-point fit's own variance factor (chi2 / dof, the noise
      level the end points show).  Beyond that the
      polylines (or the curve model) pull the answer outside the end points' confidence region,
      so the end-point answer stays and the curve alone is fitted to the polylines with every
      pose fixed and the ends and end tangent lines pinned (:func:`fit_curve_fixed_poses`).
      Noise-free end points have a variance factor of float rounding: any curve-model error
      moves the bundle out of that region, and the exact answer stays exact.

    Returns ``(reconstruction, curve3d (n_out, 3), info)``: the shape and every pose from the
    fitted curve (normalised as in ``pose.normalise``), ``std`` from the bundle's covariance,
    ``chi2`` / per-frame ``chi2`` recomputed for the end points and tangents, the branch
    alternatives recomputed for the new shape; ``curve3d`` in frame 0's camera coordinates
    with A at z = 0 (the mirror image consistent with the frames' ``A3``, ``B3``, tangents);
    ``info`` the ``curve_bundle`` key of the output (see docs/file-formats.md).

    ``curve_frames`` (long sequences with given end points, ``CurveOptions.bundle_max_frames``):
    no joint fit; the end-point answer stays and the curve alone is fitted with every pose
    fixed (as when the never-worse test refuses the bundle) to the polylines of these frames;
    ``frame_rms_px`` is then measured on every frame.

    ``fixed_start``: the start curve of the fits with every pose fixed (exact end points, long
    sequences, a refused bundle), made only when one of them runs (None, or a None result:
    ``curve_start``).  That fit has local minima, so its start must be good, while the bundle
    itself starts well from a coarser curve (``curve.stage``: section 4's 60-sample curve of
    the branch search for the bundle, its full reconstruction made here only when needed).

    ``start_for(rotations, translations)``: a start curve (frame 0's camera coordinates) for
    other poses, for the bundle from frame 0's other pose branch
    (``CurveOptions.frame0_branch_dchi2``); None, or a None result: ``curve_start`` turned with
    frame 0.
    """
    run = _prepared(
        rec,
        obs,
        curve_start,
        use_given=use_given,
        point_sigma=point_sigma,
        tangent_sigma_deg=tangent_sigma_deg,
        n_out=n_out,
        options=options,
        curve_frames=curve_frames,
        fixed_start=fixed_start,
        start_for=start_for,
    )
    o, all_frames = run.o, np.ones(run.n, bool)
    if run.s2 is not None and run.s2 < o.exact_variance_factor:
        # exact end points (noise-free): the bundle could only move the answer out of their
        # confidence region, which has shrunk to float rounding
        start = run.fixed_curve_start()
        return fixed_pose_answer(run, start, o.exact_start_control_points, all_frames, {}, True)
    if curve_frames is not None and not run.flat:
        return fixed_pose_answer(run, run.fixed_curve_start(), N_CONTROL, all_frames, {})
    br, mask, flagged = _fitted_bundle(run)
    verdict = gate(run, br)
    if not verdict.accepted:
        refused = _refused_answer(run, br, verdict, mask, flagged)
        if refused is not None:
            return refused
    return _accepted_answer(run, br, verdict, mask, flagged)


def _prepared(
    rec,
    obs,
    curve_start: np.ndarray | None,
    *,
    use_given: bool,
    point_sigma: float,
    tangent_sigma_deg: float,
    n_out: int | None,
    options,
    curve_frames: np.ndarray | None,
    fixed_start,
    start_for,
) -> CurveRun:
    """The data the steps of :func:`refine_reconstruction` share (:class:`CurveRun`)."""
    o = options if options is not None else CurveOptions()
    curves = obs.curves
    if curves is None:
        raise bundle_error("the curve bundle needs a polyline in every frame")
    flat = curve_start is None
    if flat:
        curve_start = flat_start(curves[0])
    ends = tangents = None
    if use_given:
        ends = np.stack([obs.a, obs.b], axis=1)
        tangents = np.stack([obs.tangent_a, obs.tangent_b], axis=1)
        tangents[~np.asarray(rec.inliers, bool)] = np.nan  # gross tangent errors: left out
    kw = {
        "ends": ends,
        "tangents": tangents,
        "point_sigma": point_sigma,
        "tangent_sigma_deg": tangent_sigma_deg,
        "smooth_weight": o.bundle_smooth_weight,
        "order_tol": o.bundle_order_tol,
    }
    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / np.radians(tangent_sigma_deg)] * 2)
    inl = np.asarray(rec.inliers, bool)
    s2 = chi2_ep = None
    # the end-point fit's degrees of freedom: one per inlier frame (6 measurements, 5 pose
    # parameters) less the 4 of the shape
    dof = max(int(inl.sum()) - 4, 1)
    if use_given and rec.poses is not None:
        # the end-point fit's variance factor: the noise level its end points show
        chi2_ep = float(np.sum(end_point_chi2(rec.shape, rec.poses, obs, inl, w8)[inl]))
        s2 = max(chi2_ep / dof, o.variance_floor)
    # the polylines' noise level from the frames the curve is fitted to (long sequences: the
    # ``curve_frames`` subset; all 1,000 frames' estimates took a fifth of the curve stage)
    measured = curves if curve_frames is None else [curves[i] for i in curve_frames]
    sigma = max(float(np.median([noise_level(pl.as_polyline(p)) for p in measured])), SIGMA_FLOOR)
    return CurveRun(
        rec=rec,
        obs=obs,
        curves=curves,
        o=o,
        flat=flat,
        curve_start=curve_start,
        use_given=use_given,
        point_sigma=point_sigma,
        tangent_sigma_deg=tangent_sigma_deg,
        n_out=n_out,
        curve_frames=curve_frames,
        fixed_start=fixed_start,
        start_for=start_for,
        ends=ends,
        tangents=tangents,
        kw=kw,
        w8=w8,
        inl=inl,
        dof=dof,
        chi2_ep=chi2_ep,
        s2=s2,
        sigma=sigma,
        limit=o.flag_rms_sigma * sigma + o.flag_rms_px,
        warnings=list(rec.warnings),
    )


def _fitted_bundle(run: CurveRun) -> tuple[BundleResult, np.ndarray, list[int]]:
    """The bundle from its starts (``starts.run_starts``); with given end points, frames whose
    polylines stay beyond ``run.limit`` from the curve are flagged and the bundle run again
    without their polylines; polylines only, frames left on a wrong pose branch searched again
    and the number of control points chosen by the data.  Returns (bundle, the frames whose
    polylines it fits, the flagged frames)."""
    o, n = run.o, run.n
    br = run_starts(run)
    flagged: list[int] = []
    mask = np.ones(n, bool)
    if run.use_given:
        bad = br.rms > run.limit
        if bad.any() and bad.sum() <= o.max_flagged_fraction * n:
            flagged = [int(i) for i in np.flatnonzero(bad)]
            run.flag_warning(flagged, br.rms)
            mask = ~bad
            br = run_starts(run, mask)
    if not run.use_given:
        # polylines only: a few frames left on a wrong pose branch searched again against the
        # curve the others fit (the end tangents are the curve's own: one such frame bends them)
        br = resect_uneven_frames(br, run.curves, smooth_weight=o.bundle_smooth_weight)
    return br, mask, flagged


def _refused_answer(run: CurveRun, br: BundleResult, verdict, mask: np.ndarray, flagged: list):
    """The gate refused the bundle: the end-point answer stays and the curve alone is fitted
    with its poses and ends (``fixed_poses.fixed_pose_answer``), its std widened by the two
    answers' disagreement; in the gate's band the bundle is kept after all when the polylines
    reject the end-point answer's poses (then None: the accepted answer follows)."""
    rec, warnings = run.rec, run.warnings
    a3, _, ta3, _ = rec.points_3d()
    start = np.asarray(run.curve_start, float) if run.flat else run.fixed_curve_start()
    if run.flat:
        start = br.curve_points(200)
        d0 = start[min(5, len(start) - 1)] - start[0]
        if d0 @ ta3[0] < (d0 * [1.0, 1.0, -1.0]) @ ta3[0]:
            start = start * [1.0, 1.0, -1.0]
    extra = {
        "iterations": int(br.iterations),
        "converged": bool(br.converged),
        "end_point_dchi2": float(verdict.dchi2),
        "flagged_frames": flagged,
    }
    n_warnings = len(warnings)
    out, curve3d, info = fixed_pose_answer(run, start, br.control.shape[0], mask, extra)
    if verdict.band:
        # the band (CurveOptions.never_worse_f_test): the bundle's shape is kept when the
        # polylines reject the end-point answer's poses (the curve fitted on them stays
        # beyond the noise from the polylines the bundle fits)
        kept, tail = band_keeps_bundle(run, br, verdict, info, mask)
        if kept:
            del warnings[n_warnings:]  # the fixed-pose fit's own flags: not the answer's
            warnings.append(band_warning(run, verdict, tail))
            return None
    return refused_std(run, out, curve3d, br, verdict), curve3d, info


def _accepted_answer(run: CurveRun, br: BundleResult, verdict, mask: np.ndarray, flagged: list):
    """The bundle's answer: the shape and every pose from the fitted curve, its std, the
    branch alternatives for the new shape, curve3d equally spaced in 3-D arc length, the
    warnings of frames that stay far from the curve."""
    from curverecon.robust.search import branch_alternatives

    rec, o, warnings = run.rec, run.o, run.warnings
    k = br.control.shape[0]
    # curve samples equally spaced in 3-D arc length, in the curve frame
    u_out = arc_parameters(br.control, int(run.n_out) if run.n_out is not None else 200)
    pts = Basis(len(br.control)).values(u_out) @ br.control
    # normalise changes the curve frame by rotations (no change in camera coordinates) and,
    # for phi < 0, by the mirror image z -> -z (camera depth negated; A stays at z = 0)
    curve3d = pts * [1.0, 1.0, -1.0] if verdict.shape[3] < 0 else pts
    alt_poses, alt_chi2 = branch_alternatives(run.obs, verdict.shape_n, verdict.poses_n, run.w8)
    stds = accepted_std(run, br, mask, u_out)
    std, point_std, normal_std = rival_minima_std(run, br, pts, verdict.shape_n, stds)
    limit = o.flag_rms_sigma * br.sigma + o.flag_rms_px
    bad = [int(i) for i in np.flatnonzero((br.rms > limit) & mask)]
    if bad:
        warnings.append(
            f"frames {bad}: the fitted curve stays up to {float(br.rms[bad].max()):.1f} px (RMS) "
            f"from their polylines (limit {limit:.1f} px)"
        )
    if not run.use_given:
        warnings.append(
            "alpha, beta, phi come from the fitted curve's end tangents (no tangents were given): "
            "ends of noisy polylines fix them less well than their std says"
        )
    new = replace(
        rec,
        estimator="curve-bundle",
        shape=verdict.shape_n,
        poses=verdict.poses_n,
        std=std if std is not None else rec.std,
        warnings=warnings,
        chi2=float(np.sum(verdict.frame_chi2[run.inl])),
        frame_chi2=verdict.frame_chi2,
        branch_alternatives=alt_poses,
        branch_alternative_chi2=alt_chi2,
        curve3d_std=point_std,
        curve3d_normal_std=normal_std,
    )
    info = {
        "control_points": int(k),
        "sigma_px": float(br.sigma),
        "frame_rms_px": [float(v) for v in br.rms],
        "iterations": int(br.iterations),
        "converged": bool(br.converged),
        "accepted": True,
        "end_point_dchi2": None if verdict.dchi2 is None else float(verdict.dchi2),
        "flagged_frames": flagged,
    }
    return new, curve3d, info
