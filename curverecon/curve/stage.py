"""The curve stage: the whole 3-D curve from every frame's polyline, given the end-point answer.

With polylines in every frame: where a frame fits two pose branches about equally well, the
curve chooses (``curve.branches``); section 4 reconstructs the non-traceable points
(``curve.section4``); then, for ``method="auto"`` with ``CurveOptions.bundle``, the curve
bundle fits the poses and one 3-D curve to every polyline together and the shape comes from
the fitted curve (``curve.bundle``).  ``curve3d`` is in frame 0's camera coordinates, A at z = 0.

Long sequences (``CurveOptions.curve_search_max_frames``, ``bundle_max_frames``): the branch
choice and section 4 run on a fixed number of frames spread over the sequence (they cost
O(N^2) on all); from ``bundle_max_frames`` frames on, with end points given, the end-point
answer stays and the curve alone is fitted to those frames' polylines with every pose fixed.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import replace

import numpy as np

from curverecon.curve import section4
from curverecon.curve.branches import (
    coarse_search,
    refit_branches_with_curves,
    resolve_branches_with_curves,
)
from curverecon.curve.bundle import refine_reconstruction
from curverecon.curve.polyline import end_tangents
from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import ReconstructOptions

#: end tangents for section 4's coplanarity check when its result feeds the bundle
_ANY_TANGENTS = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))


def fit_curve(
    rec: Reconstruction, obs: Observations, options: ReconstructOptions
) -> Reconstruction:
    """``rec`` with ``curve3d`` (and, with the bundle, the bundle's shape, poses and
    ``curve_bundle`` summary); ``rec`` itself when the frames carry no polylines."""
    if obs.curves is None:
        return rec
    o = options.curve
    reconstruct_curve = section4.reconstruct_curve
    bundle = o.bundle and rec.method == "auto"
    if bundle:
        # the bundle takes section 4's points only: its coplanarity check (a warning and a
        # field of the section-4 result) needs no end tangents estimated from every polyline
        reconstruct_curve = functools.partial(reconstruct_curve, tangents=_ANY_TANGENTS)
    warnings: list[str] = []
    n = len(obs.curves)
    # long sequences with given end points: the end-point answer stays, the curve alone is
    # fitted (CurveOptions.bundle_max_frames)
    fixed = bundle and obs.ends_given and n >= o.bundle_max_frames
    if not o.bundle and rec.method == "auto" and rec.std is None:
        # section 4 works on the end-point answer's poses alone: where the end points do not
        # determine the shape (singular information) neither are the poses, and a curve placed
        # on them is the start's accident (helix seed 2104, 1 px, 12 frames: c 9,142 for 297,
        # every frame reprojecting 95 px off)
        raise CurveReconError(
            "section 4 cannot place the curve on the end-point answer's poses (the end points "
            "do not determine the shape: singular information); the curve bundle "
            "(--curve-bundle on) fits the polylines themselves"
        )
    coarse_start = False
    try:
        if bundle and n > o.curve_search_max_frames:
            # long sequences: the branch choice and the start curve from a fixed-size subset
            # of the frames (section 4 costs O(N^2): every frame's crossings scored in every
            # frame); the bundle then fits every frame and searches every pose itself
            rec, res = _search_on_subset(rec, obs.curves, reconstruct_curve, o)
        elif rec.branch_alternatives is not None:
            # fixed-shape branch switches first, then (without the bundle) the other equally
            # good optima (alternative shapes, joint refits from the other sign of tau); each
            # change is kept only if the recovered curve reprojects clearly better
            # with the bundle on given end points (and no joint refits after it) the search's
            # coarse curve of the chosen poses is the bundle's start
            # (CurveOptions.bundle_start_from_search)
            coarse_start = bundle and obs.ends_given and o.bundle_start_from_search
            rec, res = resolve_branches_with_curves(
                rec, obs.curves, reconstruct_curve, o, full=not coarse_start
            )
            if not bundle:
                # the joint refits (the bundle refits the shape and every pose itself)
                rec, res = refit_branches_with_curves(
                    rec,
                    obs,
                    reconstruct_curve,
                    options.point_sigma,
                    options.tangent_sigma_deg,
                    curve=res,
                    o=o,
                )
        else:
            res = reconstruct_curve(obs.curves, rec.rotations(), rec.translations())
    except CurveReconError as exc:
        if not bundle:
            # section 4 works on the end-point answer's poses alone: say that it is the answer
            # (often a shape the end points do not determine) that cannot carry the curve
            hint = "; the curve bundle (--curve-bundle on) fits the polylines themselves"
            raise CurveReconError(
                f"section 4 cannot place the curve on the end-point answer's poses ({exc})"
                + (hint if not o.bundle else "")
            ) from exc
        # e.g. a degenerate shape whose poses all look along one direction: the bundle
        # starts from frame 0's polyline and searches every frame's pose again
        res = None
        warnings.append(f"section 4 failed on the end-point answer ({exc})")
    if not bundle:
        return replace(
            rec,
            curve3d=np.asarray(res.points, float),
            warnings=list(rec.warnings) + list(res.warnings),
        )
    fixed_start = None
    if coarse_start and res is not None:
        # the fits with every pose fixed (a refused bundle, exact end points) start from the
        # full section-4 curve of the chosen poses, made only when one runs
        # (CurveOptions.bundle_start_from_search)
        rot, tra, coarse_points = rec.rotations(), rec.translations(), res.points

        def fixed_start() -> np.ndarray:
            try:
                return reconstruct_curve(obs.curves, rot, tra).points
            except CurveReconError:
                return coarse_points

    coarse = coarse_search(reconstruct_curve, o)
    sub = subset_frames(n, o.curve_search_max_frames)

    def start_for(rot: np.ndarray, tra: np.ndarray) -> np.ndarray | None:
        """The branch search's coarse section-4 curve for other poses (on its frames)."""
        try:
            return coarse([obs.curves[i] for i in sub], rot[sub], tra[sub]).points
        except CurveReconError:
            return None

    rec, curve3d, info = refine_reconstruction(
        rec,
        obs,
        None if res is None else res.points,
        use_given=obs.ends_given,
        point_sigma=options.point_sigma,
        tangent_sigma_deg=options.tangent_sigma_deg,
        # curve3d's samples: section 4's default number (its start may be the coarser search's)
        n_out=None if res is None else section4.default_samples(obs.curves[0]),
        options=o,
        curve_frames=sub if fixed else None,
        fixed_start=fixed_start,
        start_for=start_for,
    )
    return replace(rec, curve3d=curve3d, curve_bundle=info, warnings=list(rec.warnings) + warnings)


def subset_frames(n: int, count: int) -> np.ndarray:
    """``count`` frames spread evenly over a sequence of ``n`` (frame 0 first, the curve's
    reference frame; all of them when ``n <= count``)."""
    if n <= count:
        return np.arange(n)
    return np.unique(np.round(np.linspace(0.0, n - 1, count)).astype(int))


def _search_on_subset(rec: Reconstruction, curves, reconstruct_curve, o) -> tuple:
    """The branch choice by the curve (single-frame switches, shape fixed) and section 4 on
    ``o.curve_search_max_frames`` frames spread over the sequence; the switches found are
    applied to the whole reconstruction.  The joint refits (``refit_branches_with_curves``:
    one refinement of all N frames per frame, O(N^2)) are left out: with this many frames one
    frame's branch moves the maximum-likelihood shape little, and the curve bundle searches
    every frame's pose against the curve.  Returns (reconstruction, section-4 result of the
    subset: its curve is in frame 0's camera coordinates like the whole one's)."""
    sub = subset_frames(len(curves), o.curve_search_max_frames)
    sub_curves = [curves[i] for i in sub]

    def pick(a):
        return None if a is None else np.asarray(a)[sub]

    if rec.branch_alternatives is None:
        return rec, reconstruct_curve(sub_curves, rec.rotations()[sub], rec.translations()[sub])
    alt_chi2 = pick(rec.branch_alternative_chi2)
    if rec.frame_chi2 is not None and np.isfinite(alt_chi2[0]):
        # frame 0's pose fixes curve3d's coordinates: its other branch is tried by the curve
        # however its end points rank it (1,000 frames, helix, seed 2001: the other branch at
        # chi2 + 4.08, just beyond flip_dchi2, was the right one; the curve was 17 % off)
        alt_chi2 = np.array(alt_chi2, float)
        alt_chi2[0] = min(alt_chi2[0], float(rec.frame_chi2[0]))
    part = replace(
        rec,
        poses=np.asarray(rec.poses)[sub],
        inliers=np.asarray(rec.inliers)[sub],
        frame_chi2=pick(rec.frame_chi2),
        branch_alternatives=pick(rec.branch_alternatives),
        branch_alternative_chi2=alt_chi2,
    )
    new, res = resolve_branches_with_curves(part, sub_curves, reconstruct_curve, o)
    if new is part:
        return rec, res
    take = sub[np.any(np.asarray(new.poses) != np.asarray(part.poses), axis=1)]
    poses = np.array(rec.poses)
    alt = np.array(rec.branch_alternatives)
    poses[take], alt[take] = rec.branch_alternatives[take], rec.poses[take]
    fchi2, achi2 = np.array(rec.frame_chi2), np.array(rec.branch_alternative_chi2)
    fchi2[take], achi2[take] = rec.branch_alternative_chi2[take], rec.frame_chi2[take]
    out = replace(
        rec,
        poses=poses,
        frame_chi2=fchi2,
        branch_alternatives=alt,
        branch_alternative_chi2=achi2,
        warnings=list(rec.warnings)
        + [
            f"frames {[int(i) for i in take]}: pose branch chosen by the curve (their end "
            "points and tangents fit two branches about equally well)"
        ],
    )
    return out, res


def _mean_frame_rms(rec: Reconstruction) -> float:
    info = rec.curve_bundle or {}
    rms = info.get("frame_rms_px")
    return float(np.mean(rms)) if rms else math.inf


def better_fit_to_polylines(
    rec: Reconstruction,
    obs: Observations,
    opts: ReconstructOptions,
    end_points: Callable[[Observations, ReconstructOptions], Reconstruction],
) -> Reconstruction:
    """Tangents estimated from the polylines (``CurveOptions.traced_tangents_retry``): the
    answer again with the adaptive end-tangent fit as a start only, the polylines alone fixing
    the shape (``end_points``: the pipeline's end-point stages, then :func:`fit_curve`); the
    answer whose curve reprojects closer to the polylines is kept."""
    try:
        ends = [end_tangents(c) for c in obs.curves]
        alt = Observations(
            obs.a,
            obs.b,
            np.array([e[0] for e in ends]),
            np.array([e[1] for e in ends]),
            obs.curves,
            False,
            [],
        )
        other = fit_curve(end_points(alt, opts), alt, opts)
    except (CurveReconError, ArithmeticError, ValueError, np.linalg.LinAlgError):
        return rec
    mine, theirs = _mean_frame_rms(rec), _mean_frame_rms(other)
    if not theirs < mine:
        return rec
    note = (
        f"the traced tangents (estimated from the polylines) left the curve {mine:.2f} px "
        f"(mean frame RMS) from the polylines, the polylines alone {theirs:.2f} px: "
        "the answer is the polylines' (tangents as a start only)"
    )
    return replace(other, warnings=[*other.warnings, note])


__all__ = ["better_fit_to_polylines", "fit_curve", "subset_frames"]
