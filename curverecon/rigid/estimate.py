"""One row's estimate: starts, maximum likelihood, outlier frames, degenerate fits refused.

Hypotheses come from every frame at once (``rigid.starts``: robust, trimmed scores, so outlier
frames do not decide); each is refined by maximum likelihood (``rigid.refinement``) and the
lowest chi2 kept.  Outlier frames are found as for the paper's row (``robust/outliers.py``):
each frame's studentised chi2 (chi2 / (1 - leverage)) against the chi-square quantile of its
degrees of freedom (measurements minus its own parameters) at ``OutlierOptions.false_alarm``,
scaled up when the median says the noise is larger; the worst frame above it is dropped and the
fit redone, at most (N - FRAMES) // 2 frames.

A fitted motion that does not determine the body is refused with one line
(:func:`check_degenerate`): an axis along the viewing direction, a zero rate, a singular
Fisher information.
"""

from __future__ import annotations

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.errors import CurveReconError
from curverecon.options import OutlierOptions
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import (
    AXIS_MOTIONS,
    Layout,
    RigidState,
    axis_vector,
    normalise,
    with_frames,
)
from curverecon.rigid.refinement import RigidFit, information_inverse, refine
from curverecon.rigid.starts import reset_rotations, starts

MIN_AXIS_TILT_DEG = 2.0
"""An axis within this of the viewing direction shows no depth: refused."""

MIN_TURN_DEG = 1.0
"""A fitted motion whose frames turn less than this in all (the largest angle from frame 0) is
refused: a zero rate, all frames alike."""


INTERMEDIATE_ITERATIONS = 60
"""Levenberg-Marquardt iterations of each consensus step (the outlier test's fits then run to
convergence, at most 200): the free row's steps crawl for about 100 iterations near the
optimum, where the consensus only needs the frames' misfits."""

AXIS_ITERATIONS = 200
"""Levenberg-Marquardt iterations of the axis rows' last consensus step (``axis_polish``):
their robust costs decide between basins, and along the ridge of a small turn (depth against
angle) the steps crawl for about 100 iterations."""


PINHOLE_ITERATIONS = 400
"""The same for the perspective rows: from a weak-perspective start the depth and the size
trade along a long valley (the free four-point row took 290 iterations from its start at
1000 units, seed 0)."""


def _refine(layout, state, data, **kw) -> RigidFit | None:
    try:
        iters = PINHOLE_ITERATIONS if layout.pinhole else INTERMEDIATE_ITERATIONS
        kw = {"max_iter": iters, **kw}
        fit = refine(layout, state, data, covariance=False, **kw)
    except (np.linalg.LinAlgError, FloatingPointError, ValueError):
        return None
    return fit if np.isfinite(fit.chi2) else None


def consensus_fit(
    layout: Layout, data: RigidData, state, threshold: float, keep: float = 0.7
) -> tuple[RigidFit, np.ndarray, float] | None:
    """(fit over every frame, its consensus frames (N,), robust cost) from one hypothesis:
    every frame's own parameters fitted to its body and motion; the frames below ``threshold``
    (at least the ``keep`` fraction that fit best; frame 0 always) refined together; again
    every frame's own parameters to that, the consensus the frames below ``threshold``, twice.
    The outlier frames never pull the body.  The robust cost is sum_f min(chi2_f, threshold)."""
    n = data.n_frames
    if layout.pinhole:
        from curverecon.rigid.pinhole_starts import flip_frames

        state = flip_frames(
            layout, state, data, lambda s: _refine(layout, s, data, fix_globals=True)
        )
    fit = _refine(layout, state, data, fix_globals=True)
    if fit is None:
        return None
    cons = np.ones(n, bool)
    for _ in range(2):
        order = np.argsort(fit.frame_chi2, kind="stable")
        sub = fit.frame_chi2 <= threshold
        sub[order[: max(int(np.ceil(keep * n)), 1)]] = True
        sub[0] = True
        idx = np.flatnonzero(sub)
        part = _refine(layout, with_frames(fit.state, idx), data.subset(idx))
        if part is None:
            break
        moved = expand_state(layout, part.state, idx, fit.state)
        if layout.pinhole:
            from curverecon.rigid.pinhole_starts import flip_frames

            refine_locals = lambda s: _refine(layout, s, data, fix_globals=True)  # noqa: E731
            moved = flip_frames(layout, moved, data, refine_locals)
        else:
            moved = reset_rotations(layout, moved, data)
        fit_all = _refine(layout, moved, data, fix_globals=True)
        if fit_all is None:
            break
        fit = fit_all
        new = fit.frame_chi2 <= threshold
        new[0] = True
        if np.array_equal(new, cons):
            break
        cons = new
    cons = fit.frame_chi2 <= threshold
    cons[0] = True
    cost = float(np.sum(np.minimum(fit.frame_chi2, threshold)))
    return fit, cons, cost


def best_fit(layout: Layout, data: RigidData, threshold: float) -> tuple[RigidFit, np.ndarray]:
    """The lowest robust cost over LO-RANSAC's minimal samples (``rigid.hypotheses``, where the
    row has a solver) and the all-frame starts: (fit over every frame, its consensus frames)."""
    from curverecon.rigid.hypotheses import RANSAC, FrameSampleEstimator, Hypothesis, solver_for
    from curverecon.robust.ransac import lo_ransac

    if layout.pinhole:
        from curverecon.rigid.pinhole_ransac import sample_loop
        from curverecon.rigid.pinhole_starts import pinhole_starts

        initial = [Hypothesis(s) for s in pinhole_starts(layout, data)]
        solver = None
        got = sample_loop(layout, data, threshold, initial, consensus_fit)
        if got is not None:
            return got
    else:
        initial = [Hypothesis(s) for s in starts(layout, data)]
        solver = solver_for(layout)
    best = None
    if solver is not None and data.n_frames >= solver.FRAMES:
        polish = axis_polish if layout.motion in AXIS_MOTIONS else consensus_fit
        est = FrameSampleEstimator(layout, data, solver, threshold, polish)
        polished = axis_initial(layout, data, est, initial) if polish is axis_polish else []
        model, _ = lo_ransac(est, RANSAC, initial_models=initial)
        if model is not None and model.fit is None:
            model = est.refine_model(model)
        if model is not None and model.fit is not None:
            best = (model.fit, model.consensus, model.cost)
        for h in polished:  # beside the loop, which ranks its models unpolished
            if h.fit is not None and (best is None or h.cost < best[2]):
                best = (h.fit, h.consensus, h.cost)
    else:
        fits = [consensus_fit(layout, data, h.state, threshold) for h in initial]
        best = _lowest_determined([got for got in fits if got is not None], layout, data)
    if best is None:
        raise CurveReconError(f"motion {layout.motion}: no start converged")
    return best[0], best[1]


def _lowest_determined(fits: list, layout: Layout, data: RigidData):
    """The lowest-cost (fit, consensus, cost) whose Fisher information on its consensus frames
    is regular, else the lowest (refused later by :func:`check_degenerate`); None for none.
    A fit run into a degenerate motion can sit a fraction of a chi2 below a determined one
    (perspective force field, ``bench.persp_auto`` seed 1 scene 4: 28.6 against 28.9 over 30
    frames), and the row would be refused though a start fits it."""
    fits = sorted(fits, key=lambda got: got[2])
    for fit, consensus, cost in fits:
        idx = np.flatnonzero(consensus)
        cov = information_inverse(layout, with_frames(fit.state, idx), data.subset(idx))[0]
        if cov is not None:
            return fit, consensus, cost
    return fits[0] if fits else None


def axis_polish(
    layout: Layout, data: RigidData, state, threshold: float
) -> tuple[RigidFit, np.ndarray, float] | None:
    """The axis rows' polish: :func:`consensus_fit`, then the body and motion refined on its
    consensus frames to convergence and every frame's own parameters fitted to them, kept if
    the robust cost falls.  The consensus fit's body comes from the frames below the threshold
    at the start's own parameters; when the consensus then takes every frame it stops there,
    and a basin left 7 above its minimum in chi2 lost to a wrong one (bench seed 2026).  An
    axis the answer would refuse (within ``MIN_AXIS_TILT_DEG`` of the viewing direction) costs
    every frame's threshold more: a circle about the line of sight that takes in an outlier
    frame no longer beats the scene's own axis (it is still the answer, and refused, when no
    other fits)."""
    got = consensus_fit(layout, data, state, threshold)
    if got is None:
        return None
    fit, cons, cost = got
    idx = np.flatnonzero(cons)
    part = _refine(layout, with_frames(fit.state, idx), data.subset(idx), max_iter=AXIS_ITERATIONS)
    if part is None:
        return got
    moved = expand_state(layout, part.state, idx, fit.state)
    full = _refine(layout, moved, data, fix_globals=True, max_iter=AXIS_ITERATIONS)
    if full is None:
        return got
    new_cost = float(np.sum(np.minimum(full.frame_chi2, threshold)))
    if new_cost < cost:
        new = full.frame_chi2 <= threshold
        new[0] = True
        fit, cons, cost = full, new, new_cost
    if _axis_tilt_deg(fit.state) < MIN_AXIS_TILT_DEG:  # refused if chosen: last in line
        cost += data.n_frames * threshold
    return fit, cons, cost


def _axis_tilt_deg(state) -> float:
    """The axis's angle from the viewing direction (degrees)."""
    return float(np.degrees(np.arccos(min(abs(float(axis_vector(state.axis)[2])), 1.0))))


def axis_initial(layout: Layout, data: RigidData, est, initial: list) -> list:
    """The axis rows' starts polished, compared with the loop's answer by their robust costs:
    the all-frame starts and the global search over the axis and B's depth
    (``rigid.axis_search``).  The loop polishes a model only when its unpolished cost beats
    the best so far: a start from a grid cell scores worse unpolished than a minimal sample's
    exact fit of four frames in a wrong basin.  Given to the loop polished, they left no
    sample's unpolished cost below theirs, and a sample the loop had polished into the
    scene's basin was never polished (uniform rotation, bench seed 2026)."""
    from curverecon.rigid.axis_search import ellipse_starts
    from curverecon.rigid.hypotheses import Hypothesis

    kept: list[RigidState] = []
    for s in [h.state for h in initial] + ellipse_starts(layout, data):
        s = normalise(layout, s, data.times)
        if not any(_same_start(s, k) for k in kept):
            kept.append(s)
    return [est.refine_model(Hypothesis(s)) for s in kept]


def _same_start(a: RigidState, b: RigidState) -> bool:
    """Two normalised axis starts within 2 degrees of axis and 2 % of B's length."""
    close = float(np.dot(axis_vector(a.axis), axis_vector(b.axis))) > np.cos(np.radians(2.0))
    scale = 0.02 * float(np.linalg.norm(a.body[0]))
    return close and float(np.max(np.abs(a.body - b.body))) <= scale


def frame_dof(layout: Layout) -> int:
    """Degrees of freedom of one frame's residuals: measurements minus its own parameters."""
    return max(layout.n_measurements - layout.n_local, 1)


def outlier_frames(
    layout: Layout,
    data: RigidData,
    fit: RigidFit,
    min_frames: int,
    o: OutlierOptions,
    start: np.ndarray | None = None,
) -> tuple[np.ndarray, RigidFit]:
    """(N,) inlier mask and the fit on the inliers (see the module docstring); ``start``: the
    frames the test starts from (a consensus set; all frames by default)."""
    n = data.n_frames
    max_out = max(0, (n - min_frames) // 2)
    inliers = np.ones(n, bool)
    if start is not None and np.count_nonzero(~start) <= max_out:
        inliers = np.array(start, bool)
    dof = frame_dof(layout)
    base = float(chi2_dist.isf(o.false_alarm, dof))
    median = float(chi2_dist.median(dof))
    state = fit.state  # over every frame
    best: tuple[np.ndarray, RigidFit] | None = None
    while True:
        idx = np.flatnonzero(inliers)
        cur = refine(layout, with_frames(state, idx), data.subset(idx), max_iter=200)
        if cur.leverage is None:  # these frames do not determine the body: the last fit stays
            break
        state = expand_state(layout, cur.state, idx, state)
        cur.full_state = state
        best = (inliers.copy(), cur)
        if np.count_nonzero(~inliers) >= max_out:
            break
        expected = np.maximum(layout.n_measurements - cur.leverage, 0.05 * dof)
        st = cur.frame_chi2 * dof / expected
        thr = base * max(1.0, float(np.median(st)) / median)
        worst = int(np.argmax(st))
        if st[worst] <= thr or idx[worst] == 0:
            break
        inliers[idx[worst]] = False
    if best is None:
        idx = np.flatnonzero(inliers)
        cur = refine(layout, with_frames(state, idx), data.subset(idx), covariance=False)
        cur.full_state = expand_state(layout, cur.state, idx, state)
        best = (inliers, cur)
    return best


def readmit(
    layout: Layout, data: RigidData, fit: RigidFit, inliers: np.ndarray, o: OutlierOptions
) -> tuple[np.ndarray, RigidFit]:
    """(inliers, fit): every frame refitted from the inliers' answer (the flagged frames'
    rotations aligned again, ``rigid.starts.reset_rotations``); that fit replaces the answer,
    every frame an inlier, when no frame fails the outlier test at the stated noise and its
    robust cost sum_f min(chi2_f, T) is below the answer's (flagged frames at T).  Free
    rotations: a search that settled on a wrong minimum misfits a few good frames by far, the
    test drops them and the fit on the rest stays on that minimum; refitted with them it
    leaves it.  Real outlier frames pull such a refit, so it costs more and they stay out."""
    from curverecon.rigid.measurements import residuals

    state = fit.full_state or fit.state
    best = None
    for start in (state, reset_rotations(layout, state, data)):
        try:
            cur = refine(layout, start, data, max_iter=200)
        except (np.linalg.LinAlgError, FloatingPointError, ValueError):
            continue
        if cur.leverage is not None and (best is None or cur.chi2 < best.chi2):
            best = cur
    if best is None:
        return inliers, fit
    dof = frame_dof(layout)
    thr = float(chi2_dist.isf(o.false_alarm, dof))
    r = residuals(layout, state, data)
    old = np.where(inliers, np.sum(r * r, axis=1), thr)
    if np.sum(np.minimum(best.frame_chi2, thr)) >= np.sum(np.minimum(old, thr)):
        return inliers, fit
    expected = np.maximum(layout.n_measurements - best.leverage, 0.05 * dof)
    if np.max(best.frame_chi2 * dof / expected) > thr:
        return inliers, fit
    best.full_state = best.state
    return np.ones(data.n_frames, bool), best


def expand_state(layout, sub_state, idx, full_state):
    """The full-length state with the subset's values at frames ``idx`` (the global values and
    those frames' own; every other frame keeps its values in ``full_state``)."""
    s = full_state.copy()
    s.body, s.directions, s.axis = sub_state.body, sub_state.directions, sub_state.axis
    s.rate, s.parabola = sub_state.rate, sub_state.parabola
    for name in ("angles", "rotations", "shifts", "translations"):
        v = getattr(sub_state, name)
        if v is not None:
            arr = np.array(getattr(s, name))
            arr[idx] = v
            setattr(s, name, arr)
    return s


def check_degenerate(layout: Layout, fit: RigidFit, data: RigidData) -> None:
    """Refuse (CurveReconError, one line) a fitted motion that does not determine the body."""
    if fit.state.axis is not None:
        tilt = _axis_tilt_deg(fit.state)
        if tilt < MIN_AXIS_TILT_DEG and not layout.pinhole:
            raise CurveReconError(
                f"motion {layout.motion}: the fitted axis is {tilt:.2f} degrees from the viewing "
                "direction (a turn about the line of sight shows no depth): not determined"
            )
        if layout.motion == "uniform-rotation":
            turn = abs(fit.state.rate) * float(np.ptp(data.times))
        else:
            turn = float(np.max(np.abs(fit.state.angles)))
        if np.degrees(turn) < MIN_TURN_DEG:
            raise CurveReconError(
                f"motion {layout.motion}: the fitted rotation turns {np.degrees(turn):.3f} "
                "degrees in all (a rate of zero, all frames alike): the depth is not determined"
            )
    if fit.covariance is None:
        cov, lev = information_inverse(layout, fit.state, data)
        if cov is None:
            raise CurveReconError(
                f"motion {layout.motion}: the Fisher information of the fit is singular "
                "(a degenerate motion for these points): the shape is not determined"
            )
        fit.covariance, fit.leverage = cov, lev


def fit_row(
    layout: Layout, data: RigidData, min_frames: int, o: OutlierOptions | None = None
) -> tuple[RigidFit, np.ndarray]:
    """(the fit on the inliers with its covariance, the (N,) inlier mask)."""
    o = o or OutlierOptions()
    threshold = float(chi2_dist.isf(o.false_alarm, frame_dof(layout)))
    fit, consensus = best_fit(layout, data, threshold)
    inliers, fit = outlier_frames(layout, data, fit, min_frames, o, consensus)
    if layout.free_rotations and not layout.pinhole and not np.all(inliers):
        # orthographic rows only: its rotations are re-aligned from the images' closed form
        inliers, fit = readmit(layout, data, fit, inliers, o)
    sub = data.subset(np.flatnonzero(inliers))
    check_degenerate(layout, fit, sub)
    return fit, inliers
