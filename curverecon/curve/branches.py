"""Pose branches chosen by the curve: where the end points and tangents fit two branches of
(10) about equally well, the frames' polylines tell them apart.

``resolve_branches_with_curves`` switches single frames with the shape fixed;
``refit_branches_with_curves`` chooses among equally good maximum-likelihood optima.  Both score
a trial by the total reprojection distance of the section-4 curve (``curve.section4``) over the
frames.  Tuned numbers: :class:`curverecon.options.CurveOptions`.
"""

from __future__ import annotations

import functools
import inspect
import math
from dataclasses import replace

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.generated import frame_equations
from curverecon.model.observations import Observations
from curverecon.model.pose import normalise, rotations, translations
from curverecon.model.reconstruction import Alternative, Reconstruction
from curverecon.options import CurveOptions
from curverecon.refine.ml import refine, refine_batch
from curverecon.robust.search import branch_alternatives


def resolve_branches_with_curves(
    rec: Reconstruction,
    curves: list[np.ndarray],
    reconstruct_curve,
    o: CurveOptions | None = None,
    full: bool = True,
) -> tuple[Reconstruction, object]:
    """Use the frames' polylines to choose the pose branch of ambiguous frames.

    The end points and tangents alone fit two branches of (10) about equally well in some frames
    (other branch within ``o.flip_dchi2``, ``Reconstruction.ambiguous_frames``).  The whole
    curve tells them apart: a frame on the wrong branch makes the recovered 3-D curve reproject
    badly onto the polylines.  Greedy search: in each round every ambiguous frame is tried on
    its other branch and the single switch that lowers the total reprojection distance (sum of
    ``frame_residual`` over the inlier frames) most is kept, if it lowers it by at least
    ``o.flip_gain``; repeat until no switch helps.

    The total is used, not the switched frame's own residual, because the curve is built along
    frame 0's lines of sight: frame 0 always reprojects well, and when frame 0 itself is on the
    wrong branch it is the *other* frames that reproject badly (switching frame 0 repairs them).
    The curve stays in frame 0's camera coordinates (with frame 0's chosen pose).  The shape is
    kept.

    Args:
        rec: an "auto" reconstruction with branch alternatives.
        curves: the frames' polylines (A' to B').
        reconstruct_curve: ``curverecon.curve.section4.reconstruct_curve`` (its result has
            ``frame_residual``, the per-frame median reprojection distance).
        full: the curve result is ``reconstruct_curve``'s on the chosen poses; False: the
            search's own (``o.search_samples`` samples, unsmoothed) when it has one - a start
            for the curve bundle, which fits its own spline to it (one reconstruction of the
            whole curve on every frame saved).
    Returns:
        (reconstruction, curve result) - the input reconstruction if nothing changed.
    """
    o = o or CurveOptions()
    search = coarse_search(reconstruct_curve, o)
    limited = _limited(search)
    if not full:
        # the search's results stand for the reconstruction's (the same poses, coarser)
        reconstruct_curve = search
    cand: list[int] = []
    if not (
        rec.branch_alternatives is None
        or rec.branch_alternative_chi2 is None
        or rec.frame_chi2 is None
    ):
        dchi2 = rec.branch_alternative_chi2 - rec.frame_chi2
        cand = [int(i) for i in np.flatnonzero(np.isfinite(dchi2) & (dchi2 < o.flip_dchi2))]
    # the full reconstruction of the start poses only where it is kept (nothing to try, or
    # nothing switched) or scores the search itself: a switch replaces it (one section-4
    # reconstruction saved in the scenes with a switch)
    res = None
    if search is reconstruct_curve or not cand:
        res = reconstruct_curve(curves, rec.rotations(), rec.translations())
        if getattr(res, "frame_residual", None) is None or not cand:
            return rec, res
    inl = np.asarray(rec.inliers, bool)

    def total(r) -> float:
        f = np.asarray(getattr(r, "frame_residual", None), float)
        return float(np.sum(f[inl])) if f.shape == inl.shape else np.inf

    switched = np.zeros(len(rec.poses), bool)
    if res is None:  # the search is coarser than the reconstruction: its own start
        res = search(curves, *_rt(rec.poses))
    best_total = total(res)
    # the totals of the switch states scored so far (inf: beyond the bound then).  A state comes
    # again two rounds on (switching back the frame switched last, or the last two switches in
    # the other order): its total then decides the same - a finite total is exact, and an inf
    # one exceeded a bound at least as high as any later round's
    scored = {switched.tobytes(): best_total}
    # the search's result of each state scored (a state kept has a finite total: complete)
    results = {switched.tobytes(): res}
    for _ in range(o.flip_max_switches):
        round_best = None
        for i in cand:
            trial = switched.copy()
            trial[i] = ~trial[i]
            key = trial.tobytes()
            t = scored.get(key)
            if t is None:
                poses = np.where(trial[:, None], rec.branch_alternatives, rec.poses)
                # only a total below the round's best and below the gain's threshold matters:
                # the residuals stop once they exceed both (inf; the same switches)
                bound = (1.0 - o.flip_gain) * best_total
                if round_best is not None:
                    bound = min(bound, round_best[0])
                r = limited(curves, *_rt(poses), limit=bound, frames=inl)
                t = total(r)
                scored[key], results[key] = t, r
            if round_best is None or t < round_best[0]:
                round_best = (t, i)
        t, i = round_best
        if not t < (1.0 - o.flip_gain) * best_total:
            break
        switched[i] = ~switched[i]
        best_total = t
    take = [int(i) for i in np.flatnonzero(switched)]
    if not take:
        if search is not reconstruct_curve:
            res = reconstruct_curve(curves, rec.rotations(), rec.translations())
        return rec, res
    poses = np.array(rec.poses)
    poses[take] = rec.branch_alternatives[take]
    alt = np.array(rec.branch_alternatives)
    alt[take] = rec.poses[take]
    fchi2 = np.array(rec.frame_chi2)
    achi2 = np.array(rec.branch_alternative_chi2)
    fchi2[take], achi2[take] = rec.branch_alternative_chi2[take], rec.frame_chi2[take]
    # the answer's chi2 with them: the switched inlier frames' own chi2 replaced (it was left
    # at the start's, below the sum of frame_chi2 over the inliers: helix 1105 0.83 for 1.27)
    inl_take = [i for i in take if rec.inliers[i]]
    chi2 = float(rec.chi2) + float(np.sum(fchi2[inl_take] - achi2[inl_take]))
    warnings = list(rec.warnings) + [
        f"frames {take}: pose branch chosen by the curve (their end points and tangents fit "
        "two branches about equally well)"
    ]
    new = replace(
        rec,
        poses=poses,
        warnings=warnings,
        chi2=chi2,
        frame_chi2=fchi2,
        branch_alternatives=alt,
        branch_alternative_chi2=achi2,
    )
    if not full:
        return new, results[switched.tobytes()]
    return new, reconstruct_curve(curves, new.rotations(), new.translations())


def _rt(poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return rotations(poses), translations(poses)


def _limited(search):
    """``search(curves, rotations, translations, limit=, frames=)``: ``search`` with its
    ``residual_limit`` and ``residual_frames`` when it takes them (``section4.reconstruct_curve``
    stops measuring frame residuals once their sum over ``frames`` exceeds ``limit``: their
    total is then inf, and a search that keeps only totals below ``limit`` decides the same);
    otherwise ``search`` without them.

    A trial's poses that cannot carry the curve at all (section 4 refuses them, e.g. no frame
    views it from another direction than frame 0) give None: no ``frame_residual``, a total of
    inf, the trial never chosen.  Such a trial ended the whole reconstruction before (helix
    seed 1105 at 0.5 px, 12 frames, ``--curve-bundle off``).  The start poses are not scored
    through it: when they cannot carry the curve, the end-point answer cannot, and
    ``stage.fit_curve`` says so."""
    try:
        params = inspect.signature(search).parameters
    except (TypeError, ValueError):
        params = {}
    if {"residual_limit", "residual_frames"} <= set(params):

        def call(curves, rot, tra, limit, frames):
            return search(curves, rot, tra, residual_limit=limit, residual_frames=frames)

    else:

        def call(curves, rot, tra, limit, frames):
            return search(curves, rot, tra)

    def run(curves, rot, tra, *, limit: float = np.inf, frames=None):
        try:
            return call(curves, rot, tra, limit, frames)
        except CurveReconError:
            return None

    return run


def coarse_search(reconstruct_curve, o: CurveOptions):
    """A cheaper variant of ``reconstruct_curve`` for the branch search (fewer samples, no
    smoothing, fixed dummy end tangents so that the coplanarity check - irrelevant to
    ``frame_residual`` - does not estimate them from every polyline) when it accepts those
    keywords; otherwise the callable itself."""
    try:
        params = inspect.signature(reconstruct_curve).parameters
    except (TypeError, ValueError):
        return reconstruct_curve
    if {"n_samples", "smooth", "tangents"} <= set(params):
        dummy = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
        return functools.partial(
            reconstruct_curve, n_samples=o.search_samples, smooth=False, tangents=dummy
        )
    return reconstruct_curve


def _distinct_optima(cands: list[int], shapes: np.ndarray, poses: np.ndarray, tol: float):
    """The candidates (indices of ``shapes`` (M, 4), ``poses`` (M, N, P)) that are not the
    same optimum as an earlier one (every shape and pose parameter within ``tol``; all of
    them for ``tol`` <= 0)."""
    if tol <= 0:
        return cands
    x = np.concatenate([shapes, poses.reshape(len(poses), -1)], axis=1)
    kept: list[int] = []
    for k in cands:
        if not any(np.max(np.abs(x[k] - x[j])) <= tol for j in kept):
            kept.append(k)
    return kept


def refit_branches_with_curves(
    rec: Reconstruction,
    obs: Observations,
    reconstruct_curve,
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    curve=None,
    o: CurveOptions | None = None,
) -> tuple[Reconstruction, object]:
    """Among about equally good maximum-likelihood optima, take the one the curve fits best.

    First the other shapes that fit about equally well (``rec.alternatives``; they usually
    differ from the answer in the pose branch of several frames at once): if one makes the
    recovered curve reproject much better (total ``frame_residual`` lower by
    ``o.refit_gain``), it is refitted and becomes the answer (the old answer becomes an
    alternative).  Then joint refits with single frames started on the other sign of tau:

    ``resolve_branches_with_curves`` switches frames with the shape held fixed.  With noisy end
    points and tangents the maximum-likelihood fit can also have a nearby local optimum in which
    one frame (often frame 0, whose pose fixes the coordinates of ``curve3d``) has the other sign
    of tau and the shape and the other poses move a little: its chi2 is about as low, but with the
    shape held fixed that branch fits badly, so it is not among the branch alternatives.  Here
    every frame in turn is started on the other sign of tau (delta from (10) and (11) for the
    current shape) and the shape and all poses are refitted jointly (one batched refinement);
    refits whose chi2 is within ``o.refit_dchi2`` of the answer's are scored by the total
    curve reprojection distance (sum of ``frame_residual``), and the best is kept if it lowers
    that total by at least ``o.refit_gain``.  Up to ``o.refit_rounds`` rounds.

    Only for "auto" reconstructions without outlier frames (otherwise returned unchanged).
    ``curve``: the curve result for ``rec`` if already computed (saves one reconstruction).

    Returns:
        (reconstruction, curve result) - the input reconstruction if nothing changed.
    """
    o = o or CurveOptions()
    res = curve
    if res is None:
        res = reconstruct_curve(obs.curves, rec.rotations(), rec.translations())
    if rec.method != "auto" or rec.chi2 is None or not np.all(rec.inliers):
        return rec, res
    ps, ts = float(point_sigma), math.radians(tangent_sigma_deg)
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    search = _limited(coarse_search(reconstruct_curve, o))
    n = obs.n_frames

    def total(poses: np.ndarray, limit: float = np.inf) -> float:
        """The total residual of the curve from ``poses``; inf once beyond ``limit`` (only
        totals below it are kept: the same choices)."""
        r = search(obs.curves, *_rt(poses), limit=limit)
        f = np.asarray(getattr(r, "frame_residual", None), float)
        return float(np.sum(f)) if f.shape == (n,) else np.inf

    shape, poses = rec.shape, np.array(rec.poses)
    best_total = total(poses)
    fit = None
    alternatives = list(rec.alternatives)
    # The other shapes that fit about equally well (``rec.alternatives``, each with its own pose
    # branches in many frames at once - out of reach of single-frame switches): the curve picks.
    scored_alts: list[tuple[float, int]] = []
    for j, a in enumerate(alternatives):
        gain_limit = (1.0 - o.refit_gain) * best_total
        scored_alts.append((total(a.poses, min([gain_limit, *(t for t, _ in scored_alts)])), j))
    if scored_alts and min(scored_alts)[0] < (1.0 - o.refit_gain) * best_total:
        j = min(scored_alts)[1]
        trial = refine(obs, alternatives[j].shape, alternatives[j].poses, ps, ts, covariance=True)
        trial_shape, trial_poses = normalise(trial.shape, trial.poses)
        t = total(trial_poses, (1.0 - o.refit_gain) * best_total)
        if t < (1.0 - o.refit_gain) * best_total:
            alternatives[j] = Alternative(rec.shape, rec.poses, float(rec.chi2), rec.std)
            fit, shape, poses, best_total = trial, trial_shape, trial_poses, t
    for _ in range(o.refit_rounds):
        c, alpha, beta, phi = (float(v) for v in shape)
        with np.errstate(all="ignore"):
            cos_d, sin_d = frame_equations.pose_from_shape(
                c, np.tan(alpha), np.tan(beta), phi, obs.cp, obs.dp, obs.ep, -np.sin(poses[:, 1])
            )
        delta = np.arctan2(np.broadcast_to(sin_d, (n,)), np.broadcast_to(cos_d, (n,)))
        frames = np.flatnonzero(np.isfinite(delta))
        if frames.size == 0:
            break
        starts = np.repeat(poses[None], frames.size, axis=0)
        starts[np.arange(frames.size), frames, 0] = delta[frames]
        starts[np.arange(frames.size), frames, 1] = -poses[frames, 1]
        shapes = np.repeat(np.asarray(shape, float)[None], frames.size, axis=0)
        g, p, _, chi2, _, _ = refine_batch(obs, shapes, starts, ps, ts, max_iter=60)
        cands = [k for k in range(frames.size) if chi2[k] < rec.chi2 + o.refit_dchi2]
        cands = _distinct_optima(cands, g, p, o.refit_same_tol)
        scored: list[tuple[float, int]] = []
        for k in cands:
            gain_limit = (1.0 - o.refit_gain) * best_total
            scored.append((total(p[k], min([gain_limit, *(t for t, _ in scored)])), k))
        if not scored:
            break
        t, k = min(scored)
        if not t < (1.0 - o.refit_gain) * best_total:
            break
        trial = refine(obs, g[k], p[k], ps, ts, covariance=True)
        trial_shape, trial_poses = normalise(trial.shape, trial.poses)
        # the full refinement may move on: check again
        t = total(trial_poses, (1.0 - o.refit_gain) * best_total)
        if not (t < (1.0 - o.refit_gain) * best_total and trial.chi2 < rec.chi2 + o.refit_dchi2):
            break
        fit, shape, poses, best_total = trial, trial_shape, trial_poses, t
    if fit is None:
        return rec, res
    alt_poses, alt_chi2 = branch_alternatives(obs, shape, poses, w8)
    std = fit.std if fit.std is not None and np.all(np.isfinite(fit.std)) else rec.std
    warnings = list(rec.warnings) + [
        "the curve chose between nearby maximum-likelihood optima (pose branches refitted "
        f"jointly; chi2 {rec.chi2:.2f} -> {fit.chi2:.2f})"
    ]
    new = replace(  # a joint maximum-likelihood refit: its estimator "ml"
        rec,
        shape=shape,
        poses=poses,
        std=std,
        alternatives=alternatives,
        warnings=warnings,
        chi2=fit.chi2,
        frame_chi2=fit.frame_chi2,
        branch_alternatives=alt_poses,
        branch_alternative_chi2=alt_chi2,
        estimator="ml",
    )
    return new, reconstruct_curve(obs.curves, new.rotations(), new.translations())
