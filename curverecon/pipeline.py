"""The reconstruction pipeline: observations in, shape, poses and curve out.

It reads like the README's "How it works" (docs/architecture.md draws it):

1. hypotheses: the global search over the shape (``robust.search``), seeded by the paper's
   linearisation when it is determined (``solvers.linear``); with few frames, or a fit
   improbably close for the noise, and no exact fit, also the shapes of a four-frame sample of
   the minimal solver, refined on all frames
   (``robust.frame_samples.few_frame_hypotheses``); when the answer of steps 2-5 has
   outlier frames, also LO-RANSAC over four-frame samples of the minimal solver
   (``robust.frame_samples``), whose shape replaces the search's if it explains the frames
   better;
2. maximum likelihood on all frames (``refine.ml``) from the best hypothesis;
3. outlier frames (``robust.outliers``), then, with few frames, single frames tried on their
   other pose branch (``robust.branches``);
4. every other hypothesis that fits about as well (``robust.alternatives``); with exactly four
   frames, every shape that fits them exactly (``robust.four_frames``, from the complete
   minimal solver ``solvers.minimal``);
5. the final estimate: the marginal likelihood's optimum among those fits, or maximum
   likelihood (``refine.answer``), with standard deviations and warnings;
6. with polylines, the curve: branch choice by the curve, section 4 and the curve bundle
   (``curve.stage``).

``method="linear"``: the paper's linearisation alone (``solvers.linear``), poses from the
shape (``solvers.pose``), no refinement.  Every tuned number is an option
(:mod:`curverecon.options`).  Library units: lengths in input units, angles in radians.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from curverecon.curve.stage import better_fit_to_polylines, fit_curve
from curverecon.errors import CurveReconError
from curverecon.model.configuration import RigidObservations
from curverecon.model.observations import Observations
from curverecon.model.pose import normalise
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import ESTIMATORS, METHODS, ReconstructOptions, SearchOptions
from curverecon.progress import StageProgress
from curverecon.refine.answer import final_estimate
from curverecon.refine.bias import BIAS_CORRECTED_FRAMES
from curverecon.refine.ml import refine
from curverecon.robust.alternatives import equally_good_fits
from curverecon.robust.branches import flip_ambiguous_frames
from curverecon.robust.four_frames import add_minimal_solutions
from curverecon.robust.frame_samples import (
    few_frame_hypotheses,
    fixed_shape_fit,
    frame_sample_hypothesis,
    sample_score,
)
from curverecon.robust.labels import reconstruct_any_labels
from curverecon.robust.outliers import chi2_lower_tail, chi2_tail, find_outlier_frames
from curverecon.robust.search import Candidate, robust_start
from curverecon.solvers import minimal
from curverecon.solvers.linear import frame_matrix, min_frames, solve_linear
from curverecon.solvers.pose import poses_from_shape

STAGES = ("hypotheses", "maximum likelihood", "alternatives", "final estimate", "curve")
"""The pipeline's stages as the progress bar names them."""


def reconstruct(
    obs: Observations | RigidObservations,
    method: str | None = None,
    point_sigma: float | None = None,
    tangent_sigma_deg: float | None = None,
    estimator: str | None = None,
    *,
    options: ReconstructOptions | None = None,
) -> Reconstruction:
    """Recover c, alpha, beta, phi, every frame's pose and, with polylines, the whole curve.

    This is what ``curverecon reconstruct`` writes (``Reconstruction.to_json_dict``).
    A configuration beyond the paper's own (:class:`RigidObservations`: a motion model,
    further points) goes to ``curverecon.rigid.reconstruct_rigid`` after its input checks
    (``RigidObservations.require_reconstructable``).

    Args:
        obs: observations (at least 4 frames, not all related by in-plane similarity), or a
            configuration of the Section 2 table.
        method, point_sigma, tangent_sigma_deg, estimator: shorthands that override the
            fields of the same names of ``options`` (see :class:`ReconstructOptions`).
        options: every stage's options (defaults: :mod:`curverecon.options`).
    Raises:
        CurveReconError: bad input, too few frames, degenerate motion.
    """
    opts = options or ReconstructOptions()
    given = {
        "method": method,
        "point_sigma": point_sigma,
        "tangent_sigma_deg": tangent_sigma_deg,
        "estimator": estimator,
    }
    opts = replace(opts, **{k: v for k, v in given.items() if v is not None})
    if opts.method not in METHODS:
        raise CurveReconError(f'unknown method "{opts.method}" (choose {" or ".join(METHODS)})')
    if opts.estimator not in ESTIMATORS:
        raise CurveReconError(
            f'unknown estimator "{opts.estimator}" (choose {" or ".join(ESTIMATORS)})'
        )
    if not (opts.point_sigma > 0 and opts.tangent_sigma_deg > 0):
        raise CurveReconError("point and tangent standard deviations must be positive")
    if isinstance(obs, RigidObservations):
        return _reconstruct_configuration(obs, opts)
    obs.require_reconstructable()
    if not obs.ends_identified:  # each frame's labelling an unknown (robust/labels.py)
        return reconstruct_any_labels(obs, opts, lambda o, op: reconstruct(o, options=op))
    if opts.method == "auto" and obs.n_frames == minimal.FRAMES:
        minimal.check_four_frames(obs, opts.minimal)
    progress = StageProgress(STAGES, opts.progress)
    if opts.method == "linear":
        rec = _reconstruct_linear(obs)
    else:
        rec = reconstruct_end_points(obs, opts, progress)
    progress.step(STAGES[-1])
    rec = fit_curve(rec, obs, opts)
    if (
        obs.tangents_from_curve
        and obs.ends_given
        and obs.curves is not None
        and opts.method == "auto"
        and opts.curve.bundle
        and opts.curve.traced_tangents_retry
    ):
        rec = better_fit_to_polylines(rec, obs, opts, reconstruct_end_points)
    progress.close()
    if obs.warnings:
        rec = replace(rec, warnings=list(obs.warnings) + list(rec.warnings))
    return rec


def _reconstruct_configuration(obs: RigidObservations, opts: ReconstructOptions) -> Reconstruction:
    """A row of the Section 2 table: its input checks, then the rigid stage (imported here, so
    that the command's start and the paper's row do not load it)."""
    if opts.method == "linear":
        raise CurveReconError(
            "--method linear is the paper's linearisation (free motion, A and B with tangents); "
            f"motion {obs.configuration.motion} with points {', '.join(obs.configuration.points)} "
            "uses the default method"
        )
    cfg = obs.configuration
    if (cfg.projection, cfg.motion) == ("perspective", "free") and obs.n_points < 4 and obs.curves:
        # the ordinary camera beyond the table: A, B and polylines (curve/pinhole.py)
        from curverecon.curve.pinhole import reconstruct_perspective_curve

        return reconstruct_perspective_curve(obs, opts)
    obs.require_reconstructable(opts.point_sigma, opts.tangent_sigma_deg)
    try:
        from curverecon.rigid import reconstruct_rigid
    except ModuleNotFoundError as exc:
        if exc.name != "curverecon.rigid":
            raise
        raise CurveReconError(
            f"motion {obs.configuration.motion} with points "
            f"{', '.join(obs.configuration.points)}: this build has no estimation stage for "
            "configurations beyond the paper's own (curverecon.rigid)"
        ) from exc
    return reconstruct_rigid(obs, opts)


def reconstruct_end_points(
    obs: Observations, opts: ReconstructOptions, progress: StageProgress | None = None
) -> Reconstruction:
    """Steps 1-5 of the pipeline: the answer from A', B' and the tangents alone."""
    progress = progress or StageProgress(STAGES, False)
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    # 1. hypotheses
    progress.step("hypotheses")
    seeds = _linear_seed(obs, opts.search)
    cands = robust_start(obs, ps, ts, options=opts.search, extra_shapes=seeds)
    if _few_frame_samples_needed(cands, obs, opts):
        # few frames or near-exact data, no exact fit: a four-frame sample's shapes join in
        extra = few_frame_hypotheses(obs, ps, ts, opts.few_frame_samples, opts.minimal, opts.search)
        cands = sorted([*cands, *extra], key=lambda c: c.robust_cost)
    if not cands:
        raise CurveReconError("no shape fits the data (the search found no candidate)")
    rec = answer_from_hypotheses(obs, cands, opts, progress)
    if _outliers_suspected(rec, obs, opts):
        # 1'. outlier frames: hypotheses from four-frame samples (LO-RANSAC on the minimal
        # solver), kept if their shape explains the frames better than the answer's
        rec = _with_frame_samples(obs, cands, rec, opts)
    if obs.n_frames == minimal.FRAMES:
        # exactly four frames: every shape that fits them exactly, from the minimal solver
        rec = add_minimal_solutions(rec, obs, ps, ts, opts.minimal)
    return rec


def answer_from_hypotheses(
    obs: Observations,
    cands: list[Candidate],
    opts: ReconstructOptions,
    progress: StageProgress | None = None,
    start_inliers: np.ndarray | None = None,
) -> Reconstruction:
    """Steps 2-5 of the pipeline from the hypotheses (best first; ``cands[0].result`` refined
    on all frames, e.g. by ``refine.start.refine_hypothesis``): outlier frames, pose branches,
    the equally good fits and the final estimate.  Linear in the number of frames.
    ``start_inliers``: frames known to fit ``cands[0]`` (a consensus set), where the outlier
    test starts (``robust.outliers.find_outlier_frames``)."""
    progress = progress or StageProgress(STAGES, False)
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    w8 = np.array([1 / ps] * 4 + [1 / ts] * 2)
    # 2.-3. maximum likelihood, outlier frames, pose branches
    progress.step("maximum likelihood")
    inliers, fit = find_outlier_frames(
        obs, cands[0].result, ps, ts, opts.outliers, opts.search, start_inliers
    )
    final = refine(obs.subset(inliers), fit.shape, fit.poses, ps, ts, covariance=True)
    if inliers.sum() <= opts.branches.flip_max_frames:
        final = flip_ambiguous_frames(
            obs.subset(inliers), final, ps, ts, w8, opts.branches, opts.search
        )
    warnings: list[str] = []
    if not final.converged:
        warnings.append(
            "the maximum-likelihood refinement stopped at its iteration limit (slow creep along "
            "c; the answer is near, not exactly at, the optimum)"
        )
    # 4. equally good fits
    progress.step("alternatives")
    fits = equally_good_fits(obs, inliers, cands, final, ps, ts, opts.branches)
    # 5. the final estimate
    progress.step("final estimate")
    marginal = opts.estimator == "marginal"
    # from BIAS_CORRECTED_FRAMES inlier frames the default answer is the maximum-likelihood
    # fit minus its estimated bias (refine.bias): honest error bars at any number of frames
    corrected = marginal and int(inliers.sum()) >= BIAS_CORRECTED_FRAMES
    if corrected:
        marginal = False
    elif marginal and int(inliers.sum()) >= opts.marginal_max_frames:
        marginal = False
        warnings.append(
            f"with {int(inliers.sum())} frames the answer is the maximum-likelihood fit: the "
            "marginal likelihood is not resolved at the scale of its correction beyond "
            f"{opts.marginal_max_frames} frames (ReconstructOptions.marginal_max_frames)"
        )
    rec = final_estimate(
        obs,
        inliers,
        fits,
        ps,
        ts,
        marginal,
        warnings,
        opts.branches,
        opts.search,
        corrected,
    )
    return rec


def _few_frame_samples_needed(
    cands: list[Candidate], obs: Observations, opts: ReconstructOptions
) -> bool:
    """No exact fit among the search's candidates (``SearchOptions.exact_cost``: nothing could
    beat it), and either a frame count the few-frame samples run for or a best fit improbably
    close for the noise (``FewFrameSampleOptions``: near-exact data)."""
    o = opts.few_frame_samples
    if not (o.enabled and opts.method == "auto" and o.min_frames <= obs.n_frames):
        return False
    if not cands:
        return obs.n_frames <= o.max_frames
    best = cands[0].robust_cost
    if best <= opts.search.exact_cost:
        return False
    if obs.n_frames <= o.max_frames:
        return True
    precise = chi2_lower_tail(best, obs.n_frames) < o.precise_p_value
    return precise and best < o.precise_chi2_ratio * (obs.n_frames - 4)


def _outliers_suspected(rec: Reconstruction, obs: Observations, opts: ReconstructOptions) -> bool:
    """Frames flagged as outliers, or a chi2 improbable for the noise
    (``FrameSampleOptions.trigger_p_value``), with a frame count the four-frame samples are run
    for."""
    o = opts.frame_samples
    if not (o.enabled and opts.method == "auto" and o.min_frames <= obs.n_frames <= o.max_frames):
        return False
    if not rec.inliers.all():
        return True
    return rec.chi2 is not None and chi2_tail(rec.chi2, int(rec.inliers.sum())) < o.trigger_p_value


def _with_frame_samples(
    obs: Observations,
    cands: list[Candidate],
    rec: Reconstruction,
    opts: ReconstructOptions,
) -> Reconstruction:
    """``rec``, or the answer from the four-frame samples' shape when that shape's robust cost
    on all frames (shape held fixed, every frame at its best pose) is lower than ``rec``'s."""
    ps, ts = float(opts.point_sigma), math.radians(opts.tangent_sigma_deg)
    o = opts.frame_samples
    initial = [rec.shape] if o.search_answer_start else []
    cand, stats = frame_sample_hypothesis(obs, ps, ts, o, opts.minimal, opts.search, initial)
    if cand is None:
        return rec
    current = fixed_shape_fit(obs, rec.shape, ps, ts, opts.search)
    new_score = sample_score(obs, cand.result.shape, cand.result.frame_chi2, ps, o)
    if not new_score < sample_score(obs, rec.shape, current.frame_chi2, ps, o):
        return rec
    # steps 2-5 again from the samples' shape (no progress steps: the bar has passed them)
    start = cand.result.frame_chi2 < o.truncate if o.consensus_start else None
    new = answer_from_hypotheses(obs, [cand, *cands], opts, start_inliers=start)
    note = (
        f"outlier frames: the answer comes from LO-RANSAC over {stats.iterations} four-frame "
        "samples (the global search's best fit was pulled by them)"
    )
    return replace(new, warnings=[*new.warnings, note])


def _reconstruct_linear(obs: Observations) -> Reconstruction:
    """The paper's linearisation alone, poses from its shape, no refinement."""
    lin = solve_linear(obs)
    poses, _ = poses_from_shape(obs, lin.shape)
    shape, poses = normalise(lin.shape, poses)
    warnings = []
    if lin.fit_residual > 1e-6:
        warnings.append(
            f"the linearisation's null vector fits the shape only to {lin.fit_residual:.1e} "
            "(noisy data: the linear method is not reliable; use --method auto)"
        )
    return Reconstruction(
        shape=shape,
        poses=poses,
        std=None,
        inliers=np.ones(obs.n_frames, bool),
        warnings=warnings,
        method="linear",
    )


def _linear_seed(obs: Observations, o: SearchOptions) -> list[np.ndarray]:
    """The linearisation's shape as an extra start, when it is determined (enough frames)."""
    try:
        if obs.n_frames < max(min_frames(), 45):
            return []
        # only when the null space is clearly one-dimensional (near noise-free data): at
        # realistic noise the linearisation is unusable (NOTES item 5) and costs time
        m, _ = frame_matrix(obs)
        with np.errstate(all="ignore"):
            sv = np.linalg.svd(m / np.linalg.norm(m, axis=0), compute_uv=False)
        if not (np.all(np.isfinite(sv)) and sv[-1] < o.linear_seed_gap * sv[-2]):
            return []
        lin = solve_linear(obs)
    except (CurveReconError, ValueError, np.linalg.LinAlgError):
        return []
    return [lin.shape] if np.all(np.isfinite(lin.shape)) else []
