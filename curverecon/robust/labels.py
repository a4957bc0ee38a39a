"""Which end is A in each frame, when the input does not say (``"ends_identified": false``).

Frames taken apart in time (images in any order, a curve moving free) may name the two
traceable points differently from frame to frame.  A frame whose labels are exchanged is a
frame of the shape (c, beta, alpha, phi) instead of (c, alpha, beta, phi) (phi, the angle
between AS and BT, is the same for both), its polyline running from B to A: the labelling is a
discrete unknown per frame, like its pose branch.  This stage decides it and hands the ordinary
pipeline consistently labelled frames:

1. the label search (:func:`label_search`): the global search's grid of the pose-free cost
   (``robust.search``'s, :func:`_grid_costs`; with polylines at least
   ``LabelOptions.curve_grid``) with every frame's misfit the better of its two labellings;
   its best local minima polished by compass steps on that cost; the distinct results, in
   order, refined by maximum likelihood with every frame in its better labelling
   (:func:`_refined`) and scored by their truncated chi2 with the shape held fixed
   (``robust.frame_samples.fixed_shape_fit``) in the better labelling per frame, plus a penalty
   for every frame that fits both about equally (a shape fitting most frames either way, alpha
   and beta near 0 seen along the chord, fits by the labels' freedom, not by the data); without
   polylines each is refined again from its own labels, and where none scores as the noise
   allows, the minima of a finer grid are scored too; with polylines the best is refined again
   from its own labels.  That cost is symmetric under the exchange of
   alpha and beta with every frame's labels, so frame 0 is held unexchanged: the answer names
   A and B as in frame 0;
2. with polylines (``curve.labels``): section 4's curve on every frame's pose at the label
   search's shape (:func:`_quick_curve`) is fitted to every polyline in either direction;
   where one direction fits clearly closer it decides that frame, and frame 0 is tried against
   all the others (its end points alone often leave its labelling open), the labelling whose
   curve fits the polylines closer kept; where even that curve fits the polylines poorly
   (``LabelOptions.unsettled_fit``), the labels are judged again at the pipeline's end-point
   answer with section 4's curve (:func:`_settled`) before the first full run;
3. the ordinary pipeline on the relabelled frames (A and B, tangent_A and tangent_B swapped,
   the polyline reversed); at its answer every frame's labelling is checked again (chi2 in
   either labelling at the answer's shape; with polylines the answer's curve fitted to them),
   and the pipeline reruns if one changed (``LabelOptions.max_rounds``);
4. exactly four frames: every real solution of the minimal solver for every relative
   labelling (eight, frame 0 fixed) joins the alternatives, with its labelling.

A frame whose labellings fit about equally at the answer (chi2 within
``LabelOptions.undecided_dchi2``, and with polylines neither direction clearly closer: A and B
look alike, alpha ~ beta) is named in a warning; where that is frame 0, the answer's A and B may
be named the other way round, and a second warning says so.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np
from scipy import ndimage

from curverecon.curve import section4
from curverecon.curve.labels import polyline_misfits
from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations
from curverecon.model.pose import normalise, rotations, translations
from curverecon.model.reconstruction import Alternative, Reconstruction
from curverecon.options import LabelOptions, ReconstructOptions
from curverecon.refine.ml import RefineResult, refine
from curverecon.robust.frame_samples import fixed_shape_fit
from curverecon.robust.search import (
    GridSpec,
    frame_misfits,
    frame_terms,
    grid_frame_misfits,
    grid_terms,
    shape_distance,
)
from curverecon.solvers import minimal


@dataclass
class LabelSearch:
    """The label search's best shape (normalised), every frame's labelling, its cost."""

    shape: np.ndarray
    exchanged: np.ndarray
    cost: float
    settled: bool = False
    """The refinement converged and left every frame's labelling as it started: refining
    again from this shape and labelling would change nothing."""
    fit: RefineResult | None = None
    """Every frame's fit at ``shape`` held fixed, as labelled then exchanged (2N frames)."""


def exchange(obs: Observations, mask: np.ndarray) -> Observations:
    """``obs`` with the labels of the frames in ``mask`` exchanged: A and B, tangent_A and
    tangent_B swapped, the polyline reversed."""
    m = np.asarray(mask, bool)
    col = m[:, None]
    curves = None
    if obs.curves is not None:
        curves = [c[::-1].copy() if f else c for c, f in zip(obs.curves, m, strict=True)]
    return replace(
        obs,
        a=np.where(col, obs.b, obs.a),
        b=np.where(col, obs.a, obs.b),
        tangent_a=np.where(col, obs.tangent_b, obs.tangent_a),
        tangent_b=np.where(col, obs.tangent_a, obs.tangent_b),
        curves=curves,
        warnings=list(obs.warnings),
    )


def _both(obs: Observations) -> Observations:
    """Every frame twice: as labelled, then with its labels exchanged."""
    return Observations(
        np.concatenate([obs.a, obs.b]),
        np.concatenate([obs.b, obs.a]),
        np.concatenate([obs.tangent_a, obs.tangent_b]),
        np.concatenate([obs.tangent_b, obs.tangent_a]),
    )


def _grid_costs(obs: Observations, spec: GridSpec) -> tuple[np.ndarray, dict]:
    """``robust.search.grid_costs`` with every frame in its better labelling: the per-frame
    misfit the better of the frame's two labellings, truncated, summed over frames."""
    g = grid_terms(frame_terms(_both(obs)), spec)
    half = g.n // 2
    trunc = np.float32(math.sin(math.radians(spec.truncate_deg)) ** 2)
    cost = np.empty((spec.n_gamma, spec.n_alpha, g.coef.shape[-1]))
    for ig in range(spec.n_gamma):
        per_frame = grid_frame_misfits(g, ig)  # (A, 2N, B*P)
        per_frame = np.minimum(per_frame[:, :half], per_frame[:, half:])
        cost[ig] = np.sum(np.minimum(per_frame, trunc), axis=1, dtype=np.float64)
    cost = cost.reshape(spec.n_gamma, spec.n_alpha, spec.n_beta, spec.n_phi)
    return cost, g.axes


def _grid_minima(obs: Observations, spec: GridSpec, count: int) -> np.ndarray:
    """The ``count`` best local minima of :func:`_grid_costs`, as (gamma, alpha, beta, phi)
    rows."""
    cost, axes = _grid_costs(obs, spec)
    filt = ndimage.minimum_filter(cost, size=3, mode="nearest")
    idx = np.argwhere(cost <= filt)
    idx = idx[np.argsort(cost[tuple(idx.T)], kind="stable")[:count]]
    gam = np.arccos(np.clip(np.max(obs.cp) / axes["c"], 0.0, 1.0))
    return np.array(
        [[gam[g], axes["alpha"][a], axes["beta"][b], axes["phi"][p]] for g, a, b, p in idx]
    ).reshape(-1, 4)


def _cost(terms: tuple[dict, dict], x: np.ndarray, trunc: float) -> np.ndarray:
    """(M,) pose-free cost of shapes (M, 4), every frame in its better labelling."""
    f = np.minimum(frame_misfits(terms[0], x), frame_misfits(terms[1], x))
    return np.sum(np.minimum(f, trunc), axis=1)


def _compass(
    terms: tuple[dict, dict], x: np.ndarray, steps: np.ndarray, trunc: float, n_iter: int
) -> tuple[np.ndarray, np.ndarray]:
    """Vectorised compass search of :func:`_cost` from M starts (``robust.search``'s
    ``pattern_search`` on this cost); returns (params, costs)."""
    x = np.array(x, float)
    h = np.broadcast_to(np.asarray(steps, float), x.shape).copy()
    lo = np.array([0.0, 1e-4, 1e-4, -np.pi])
    hi = np.array([np.radians(87.0), np.pi / 2 - 1e-4, np.pi / 2 - 1e-4, 2 * np.pi])
    f = _cost(terms, x, trunc)
    m = x.shape[0]
    dirs = np.concatenate([np.eye(4), -np.eye(4)])
    with np.errstate(all="ignore"):
        for _ in range(n_iter):
            trial = np.clip(x[:, None, :] + dirs[None] * h[:, None, :], lo, hi)
            ft = _cost(terms, trial.reshape(-1, 4), trunc).reshape(m, 8)
            j = np.argmin(ft, axis=1)
            better = ft[np.arange(m), j] < f
            x = np.where(better[:, None], trial[np.arange(m), j], x)
            f = np.where(better, ft[np.arange(m), j], f)
            h = np.where(better[:, None], h, h * 0.5)
    return x, f


def label_search(
    obs: Observations, point_sigma: float, tangent_sigma: float, o: LabelOptions | None = None
) -> LabelSearch:
    """The shape and labelling that fit the frames best, each frame in its better labelling
    (module docstring, steps 1-2); frame 0 unexchanged."""
    o = o or LabelOptions()
    spec = GridSpec.for_frames(o.grid_frames_factor * obs.n_frames)
    size = (spec.n_gamma, spec.n_alpha, spec.n_beta, spec.n_phi)
    finer = GridSpec(*(int(v) for v in np.maximum(o.curve_grid, size)))
    shapes = _candidate_shapes(obs, finer if obs.curves is not None else spec, o, [])
    # with polylines every candidate is scored: where the noise is below the stated sigma a
    # wrong labelling's refined shape can score below the plausible level and stop the scoring
    # (held-out curve scenes of seed 7, 0.5 px, 16 frames: the stop at 40 kept labellings at
    # 18-29 that the polylines could not repair; with the polyline placement, 8 misses among
    # 48 scenes with the stop, 7 without; the candidates' refinements take about 5 ms each)
    enough = o.plausible_score * obs.n_frames if obs.curves is None else -np.inf
    best = _best_candidate(obs, shapes, None, point_sigma, tangent_sigma, o, enough)
    if obs.curves is None and best.cost > enough:
        # no candidate fits as the noise allows: the truth's basin may lie between the
        # coarse grid's points; the finer grid's minima are scored too
        more = _candidate_shapes(obs, finer, o, shapes)
        best = _best_candidate(obs, more, best, point_sigma, tangent_sigma, o, enough)
    if obs.curves is not None:
        best = _again(obs, best, point_sigma, tangent_sigma, o, o.final_rounds, settle=False)
    if best.exchanged[0]:  # the same fit named from frame 0: alpha and beta exchanged
        shape, _ = normalise(best.shape[[0, 2, 1, 3]], np.zeros((1, 5)))
        best = LabelSearch(shape, ~best.exchanged, best.cost)
    return best


def _candidate_shapes(
    obs: Observations, spec: GridSpec, o: LabelOptions, known: list[np.ndarray]
) -> list[np.ndarray]:
    """Up to ``o.candidates`` distinct polished shapes (normalised) from the best minima of
    :func:`_grid_costs` on ``spec``, in the order of their pose-free cost, none within
    ``o.distinct`` of a shape in ``known``."""
    trunc = math.sin(math.radians(spec.truncate_deg)) ** 2
    x = _grid_minima(obs, spec, o.starts)
    steps = 0.5 * np.radians(
        [80.0 / max(spec.n_gamma - 1, 1), 90.0 / spec.n_alpha, 90.0 / spec.n_beta, 10.0]
    )
    terms = (frame_terms(obs), frame_terms(exchange(obs, np.ones(obs.n_frames, bool))))
    x, f = _compass(terms, x, steps, trunc, o.compass_iterations)
    shapes: list[np.ndarray] = []
    for k in np.argsort(f):
        shape = np.array([np.max(obs.cp) / math.cos(x[k, 0]), *x[k, 1:]])
        shape, _ = normalise(shape, np.zeros((1, 5)))
        if all(shape_distance(shape, s) >= o.distinct for s in [*known, *shapes]):
            shapes.append(shape)
        if len(shapes) == o.candidates:
            break
    return shapes


def _best_candidate(
    obs: Observations,
    shapes: list[np.ndarray],
    best: LabelSearch | None,
    point_sigma: float,
    tangent_sigma: float,
    o: LabelOptions,
    enough: float,
) -> LabelSearch:
    """The best of ``best`` and ``shapes`` refined (:func:`_refined`; without polylines each
    refined again from its own labels, :func:`_again`), scored in order until one scores at
    most ``enough``."""
    rounds = o.final_rounds if obs.curves is None else 0
    for shape in shapes:
        if best is not None and best.cost <= enough:
            break  # a fit as close as the noise allows: the next candidates cannot do much better
        found = _refined(obs, shape, point_sigma, tangent_sigma, o)
        found = _again(obs, found, point_sigma, tangent_sigma, o, rounds)
        if best is None or found.cost < best.cost:
            best = found
    if best is None:
        raise CurveReconError("the label search found no candidate shape")
    return best


def _again(
    obs: Observations,
    found: LabelSearch,
    point_sigma: float,
    tangent_sigma: float,
    o: LabelOptions,
    rounds: int,
    settle: bool = True,
) -> LabelSearch:
    """``found`` refined again from its own shape and labels (:func:`_refined`) up to
    ``rounds`` times, while its score falls; with ``settle``, not once its refinement has
    settled (``LabelSearch.settled``)."""
    for _ in range(rounds):
        if settle and found.settled:
            break
        again = _refined(obs, found.shape, point_sigma, tangent_sigma, o, found.fit)
        if not again.cost < found.cost:
            break
        found = again
    return found


def _refined(
    obs: Observations,
    shape: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    o: LabelOptions,
    fit: RefineResult | None = None,
) -> LabelSearch:
    """A polished shape refined by maximum likelihood, every frame in its better labelling at
    the start (frames past ``o.truncate_chi2`` in both weighted down), labelled again at the
    refined shape and scored by its truncated chi2.  ``fit``: the frames' fit at ``shape``
    in both labellings where known (``LabelSearch.fit``)."""
    n = obs.n_frames
    if fit is None:
        fit = fixed_shape_fit(_both(obs), shape, point_sigma, tangent_sigma)
    same, other = fit.frame_chi2[:n], fit.frame_chi2[n:]
    ex = other < same
    poses = np.where(ex[:, None], fit.poses[n:], fit.poses[:n])
    weights = np.where(np.minimum(same, other) < o.truncate_chi2, 1.0, 1e-3)
    with np.errstate(all="ignore"):
        ref = refine(
            exchange(obs, ex),
            shape,
            poses,
            point_sigma,
            tangent_sigma,
            max_iter=o.refine_iterations,
            covariance=False,
            frame_weights=weights,
        )
    finite = bool(np.all(np.isfinite(ref.shape)))
    if finite:
        shape, _ = normalise(ref.shape, ref.poses)
    fit = fixed_shape_fit(_both(obs), shape, point_sigma, tangent_sigma)
    same, other = fit.frame_chi2[:n], fit.frame_chi2[n:]
    cost = float(np.sum(np.minimum(np.minimum(same, other), o.truncate_chi2)))
    # a shape that fits most frames in either labelling (alpha and beta near 0 seen along the
    # chord: the shape barely determined) fits by the labels' freedom, not by the data
    cost += float(np.sum(np.maximum(o.undecided_dchi2 - np.abs(other - same), 0.0)))
    settled = finite and ref.converged and np.array_equal(other < same, ex)
    return LabelSearch(shape, other < same, cost, bool(settled), fit)


def frame_labels(
    obs: Observations, shape: np.ndarray, point_sigma: float, tangent_sigma: float
) -> tuple[np.ndarray, np.ndarray]:
    """Every frame's chi2 at ``shape`` (held fixed, every frame at its best pose) as labelled
    in ``obs`` and with its labels exchanged: (N,), (N,)."""
    fit = fixed_shape_fit(_both(obs), shape, point_sigma, tangent_sigma)
    n = obs.n_frames
    return fit.frame_chi2[:n], fit.frame_chi2[n:]


Runner = Callable[[Observations, ReconstructOptions], Reconstruction]

_ANY_TANGENTS = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))


def reconstruct_any_labels(
    obs: Observations,
    opts: ReconstructOptions,
    run: Runner,
) -> Reconstruction:
    """The reconstruction of frames whose labels A and B may differ from frame to frame
    (module docstring): ``run`` reconstructs consistently labelled frames (the pipeline);
    the stage's numbers are ``opts.labels``."""
    o = opts.labels
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    found = label_search(obs, ps, ts, o)
    exchanged = found.exchanged
    consistent = replace(exchange(obs, exchanged), ends_identified=True)
    if obs.curves is not None and o.polyline_check and opts.curve.bundle:
        same, other = frame_labels(consistent, found.shape, ps, ts)
        # frame 0 tried against the others unless its end points decide it clearly
        weak = obs.tangents_from_curve or not obs.ends_given
        swap = weak or abs(other[0] - same[0]) < o.polyline_dchi2
        consistent, exchanged, fit = _polyline_start(
            consistent, exchanged, found.shape, opts, run, o, swap
        )
        if fit > o.unsettled_fit * section4.polyline_sigma(consistent.curves):
            consistent, exchanged = _settled(consistent, exchanged, opts, run, o)
    rec = run(consistent, opts)
    for _ in range(o.max_rounds):
        flip, decided, _ = _label_flips(rec, consistent, ps, ts, o)
        if not flip.any():
            break
        exchanged ^= flip
        consistent = exchange(consistent, flip)
        rec = run(consistent, opts)
    undecided = [int(i) for i in np.flatnonzero(~decided)]
    warnings = list(rec.warnings)
    if undecided:
        warnings.append(
            f"frames {undecided[:20]}: which end is A could not be decided (both labellings "
            f"fit about equally; A and B look alike: alpha {math.degrees(rec.alpha):.1f}, "
            f"beta {math.degrees(rec.beta):.1f} degrees)"
        )
    if undecided and undecided[0] == 0:
        warnings.append(
            "frame 0 fits both labellings: the answer's A and B may be named the other way "
            "round (alpha and beta exchanged)"
        )
    if opts.method == "auto" and obs.n_frames == minimal.FRAMES:
        rec = replace(rec, alternatives=_four_frame_labellings(obs, rec, exchanged, ps, ts, opts))
    return replace(rec, warnings=warnings, ends_exchanged=exchanged)


def _polyline_start(
    obs: Observations,
    exchanged: np.ndarray,
    shape: np.ndarray,
    opts: ReconstructOptions,
    run: Runner,
    o: LabelOptions,
    try_swap: bool = True,
) -> tuple[Observations, np.ndarray, float]:
    """The label search's labelling, or (``try_swap``) the same with frame 0 exchanged against
    the others, whichever section 4's curve fits the polylines closer (mean over frames of the
    closer direction's RMS), then every frame relabelled where its polyline clearly says so
    (:func:`_label_flips`).  Frame 0's end points alone often leave its labelling open, and a
    wrong one sets it against every other frame.  The curve is placed on the poses that fit
    ``shape`` (the label search's, held fixed; with frame 0 exchanged against the others the
    same shape with alpha and beta exchanged) (:func:`_quick_curve`), or where section 4
    fails there, comes from the pipeline without the bundle.  Returns the frames relabelled,
    their labelling, and the kept curve's fit to the polylines (px; inf where no curve was
    placed)."""
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    others = np.arange(obs.n_frames) > 0
    best = None
    for swap in (False, True)[: 1 + try_swap]:
        cand = exchange(obs, others) if swap else obs
        start = _renamed(shape) if swap else shape
        rec = _quick_curve(cand, start, opts, run)
        if rec is None:
            continue
        flip, _, score = _label_flips(rec, cand, ps, ts, o, every_frame=True)
        if best is None or score < best[0]:
            best = (score, cand, exchanged ^ (others & swap), flip)
    if best is None:
        return obs, exchanged, np.inf
    score, cand, exchanged, flip = best
    return exchange(cand, flip), exchanged ^ flip, score


def _settled(
    obs: Observations, exchanged: np.ndarray, opts: ReconstructOptions, run: Runner, o: LabelOptions
) -> tuple[Observations, np.ndarray]:
    """Where the quick curve fits the polylines poorly (frames still labelled wrong): the
    pipeline's end-point answer with section 4's curve (no bundle, no four-frame samples:
    0.1-0.2 s, the frames labelled wrong its outliers) and every frame relabelled where its
    polyline clearly says so.  A first full run on frames labelled wrong costs 1.3-1.8 s (the
    curve bundle restarts from every frame where some frame does not fit, and LO-RANSAC)."""
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    quick = replace(
        opts,
        curve=replace(opts.curve, bundle=False),
        frame_samples=replace(opts.frame_samples, enabled=False),
    )
    try:
        rec = run(obs, quick)
    except CurveReconError:
        return obs, exchanged
    if rec.curve3d is None:
        return obs, exchanged
    flip, _, _ = _label_flips(rec, obs, ps, ts, o, every_frame=True)
    return exchange(obs, flip), exchanged ^ flip


def _renamed(shape: np.ndarray) -> np.ndarray:
    """``shape`` with alpha and beta exchanged (A and B named the other way round), normalised."""
    return normalise(shape[[0, 2, 1, 3]], np.zeros((1, 5)))[0]


def _quick_curve(
    obs: Observations, shape: np.ndarray, opts: ReconstructOptions, run: Runner
) -> Reconstruction | None:
    """Section 4's curve (``curve.section4``) on every frame's pose at ``shape`` held fixed
    (``fixed_shape_fit``: each frame's best branch), as a reconstruction with that shape and
    those poses; where section 4 cannot place it, the pipeline's without the bundle; None
    where that fails too."""
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    fit = fixed_shape_fit(obs, shape, ps, ts)
    try:
        # only the points are used: any tangents spare the coplanarity check's end tangents
        # estimated from every polyline (half of section 4's time here)
        res = section4.reconstruct_curve(
            obs.curves, rotations(fit.poses), translations(fit.poses), tangents=_ANY_TANGENTS
        )
        return Reconstruction(
            shape=shape,
            poses=fit.poses,
            std=None,
            inliers=np.ones(obs.n_frames, bool),
            curve3d=res.points,
        )
    except CurveReconError:
        pass
    quick = replace(  # section 4's curve; no LO-RANSAC for a wrong labelling's odd frame
        opts,
        curve=replace(opts.curve, bundle=False),
        frame_samples=replace(opts.frame_samples, enabled=False),
    )
    try:
        return run(obs, quick)
    except CurveReconError:
        return None


def _label_flips(
    rec: Reconstruction,
    obs: Observations,
    point_sigma: float,
    tangent_sigma: float,
    o: LabelOptions,
    every_frame: bool = False,
) -> tuple[np.ndarray, np.ndarray, float]:
    """The frames whose labels to exchange at ``rec`` (frame 0 never: when frame 0 clearly
    prefers the other labelling, every other frame is exchanged instead), the frames whose
    labelling is decided, and the polylines' mean fit (px, the closer direction's RMS; inf
    without polylines): by the chi2 at ``rec.shape`` in either labelling (``frame_labels``),
    and with polylines by the curve's fit to them (``curve.labels.polyline_misfits``; every
    frame with ``every_frame``) where one direction fits clearly closer
    (``LabelOptions.polyline_ratio``)."""
    n = obs.n_frames
    fit = fixed_shape_fit(_both(obs), rec.shape, point_sigma, tangent_sigma)
    same, other = fit.frame_chi2[:n], fit.frame_chi2[n:]
    prefer = other < same - o.switch_dchi2
    decided = np.abs(other - same) >= o.undecided_dchi2
    score = np.inf
    if obs.curves is not None and rec.curve3d is not None and o.polyline_check:
        check = np.abs(other - same) < o.polyline_dchi2
        if every_frame or obs.tangents_from_curve or not obs.ends_given:
            check[:] = True  # tangents fitted to the polylines: weak evidence of their own
        check[0] = True
        rms_same, rms_other = polyline_misfits(rec, obs, check)
        with np.errstate(invalid="ignore"):
            low = np.minimum(rms_same, rms_other)
            clear = low < o.polyline_ratio * np.maximum(rms_same, rms_other)
        prefer = np.where(clear, rms_other < rms_same, prefer)
        decided |= clear
        score = float(np.nanmean(low))
    return prefer ^ (prefer[0] & decided[0]), decided, score


def _four_frame_labellings(
    obs: Observations,
    rec: Reconstruction,
    exchanged: np.ndarray,
    point_sigma: float,
    tangent_sigma: float,
    opts: ReconstructOptions,
) -> list[Alternative]:
    """``rec``'s alternatives and every real minimal solution of every other relative
    labelling of four frames (frame 0 unexchanged), each with its labelling."""
    alts = [
        replace(a, ends_exchanged=exchanged.copy()) if a.ends_exchanged is None else a
        for a in rec.alternatives
    ]
    for code in range(1 << (obs.n_frames - 1)):
        ex = np.array([False] + [bool(code >> k & 1) for k in range(obs.n_frames - 1)])
        if np.array_equal(ex, exchanged):
            continue
        sub = exchange(obs, ex)
        try:
            result = minimal.solve(sub, opts.minimal)
        except (ArithmeticError, ValueError, np.linalg.LinAlgError):
            continue
        for shape, poses in zip(result.shapes, result.poses, strict=True):
            shape_n, poses_n = normalise(shape, poses)
            fit = refine(sub, shape_n, poses_n, point_sigma, tangent_sigma, max_iter=0)
            alts.append(Alternative(shape_n, poses_n, float(fit.chi2), fit.std, ex))
    kept: list[Alternative] = []
    for a in sorted(alts, key=lambda a: a.chi2):
        same_label = [k for k in kept if np.array_equal(k.ends_exchanged, a.ends_exchanged)]
        if all(shape_distance(a.shape, k.shape) >= 1e-6 for k in same_label):
            kept.append(a)
    return kept
