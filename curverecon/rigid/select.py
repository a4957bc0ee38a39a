"""``--motion auto``: every motion model the points allow, chosen by BIC with a robust chi2.

Candidates: two points without tangents: uniform-rotation, fixed-axis, force-field; two points
with tangents: those and free motion through the paper's pipeline; three points or more: all
four.  Each is fitted (``rigid.estimate``) and scored by

    BIC = sum_f min(chi2_f, T) + k ln(n),

chi2_f each frame's chi2 at the candidate's fit (T the outlier test's threshold for a frame of
that model, so an outlier frame costs the same under every model: the robust form of GRIC's
rho), k the number of parameters (global plus every frame's own), n the number of
measurements.  The lowest score wins; every candidate's score goes to ``motion_scores`` (a model
that cannot be fitted gets null and the reason).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.errors import CurveReconError
from curverecon.model.configuration import RigidObservations, min_frames
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import ReconstructOptions


def candidates(n_points: int, tangents: bool, projection: str = "orthographic") -> list[str]:
    """The motion models ``auto`` fits for these points (see the module docstring); under a
    pinhole or a stereo pair also rotation-free, and only the models the points determine."""
    if projection != "orthographic":
        from curverecon.model.configuration import motion_determined

        models = ["rotation-free", "uniform-rotation", "fixed-axis", "force-field", "free"]
        return [m for m in models if motion_determined(m, n_points, tangents, projection) is None]
    out = ["uniform-rotation", "fixed-axis", "force-field"]
    if n_points >= 3 or tangents:
        out.append("free")
    return out


def robust_bic(frame_chi2: np.ndarray, threshold: float, k: int, n_meas: int) -> float:
    """sum min(chi2_f, threshold) + k ln(n_meas)."""
    return float(np.sum(np.minimum(frame_chi2, threshold)) + k * math.log(n_meas))


def _score_rigid(obs: RigidObservations, motion: str, options: ReconstructOptions):
    from curverecon.rigid import answer, fit_motion
    from curverecon.rigid.estimate import frame_dof
    from curverecon.rigid.refinement import refine

    layout, fit, inliers = fit_motion(obs, motion, options)
    from curverecon.rigid import rigid_data

    data = rigid_data(obs, options)
    full = refine(layout, fit.full_state or fit.state, data, max_iter=0, covariance=False)
    thr = float(chi2_dist.isf(options.outliers.false_alarm, frame_dof(layout)))
    n = data.n_frames
    k = layout.n_global + n * layout.n_local - np.count_nonzero(_fixed(layout, n))
    score = robust_bic(full.frame_chi2, thr, k, n * layout.n_measurements)
    return score, lambda: answer(obs, layout, fit, inliers, options)


def _fixed(layout, n):
    from curverecon.rigid.measurements import fixed_locals

    return fixed_locals(layout, n)


def _score_paper(obs: RigidObservations, options: ReconstructOptions):
    """Free motion of A and B with tangents: the paper's pipeline, scored alike (4 shape
    parameters, 5 per frame, one degree of freedom per frame)."""
    from curverecon.model.observations import Observations
    from curverecon.pipeline import reconstruct

    paper = Observations(obs.points[:, 0], obs.points[:, 1], obs.tangents[:, 0], obs.tangents[:, 1])
    rec = reconstruct(paper, options=options)
    n = obs.n_frames
    thr = float(chi2_dist.isf(options.outliers.false_alarm, 1))
    fc = np.where(rec.inliers, rec.frame_chi2, thr)
    score = robust_bic(fc, thr, 4 + 5 * n, 6 * n)
    return score, lambda: rec


def reconstruct_auto(obs: RigidObservations, options: ReconstructOptions) -> Reconstruction:
    """The best-scoring model's reconstruction with every candidate's score."""
    cfg = obs.configuration
    scores: dict = {}
    best = None
    for motion in candidates(obs.n_points, cfg.tangents, cfg.projection):
        try:
            need = min_frames(motion, obs.n_points, cfg.projection, cfg.tangents)
            if obs.n_frames < need:
                raise CurveReconError(f"needs at least {need} frames")
            cand = obs.with_motion(motion)
            cand.require_reconstructable(options.point_sigma, options.tangent_sigma_deg)
            if motion == "free" and obs.n_points == 2 and cfg.projection == "orthographic":
                score, make = _score_paper(cand, options)
            else:
                score, make = _score_rigid(cand, motion, options)
        except CurveReconError as exc:
            scores[motion] = {"bic": None, "reason": str(exc)}
            continue
        scores[motion] = {"bic": score}
        if best is None or score < best[0]:
            best = (score, motion, make)
    if best is None:
        reasons = "; ".join(f"{m}: {s['reason']}" for m, s in scores.items())
        raise CurveReconError(f"motion auto: no model could be fitted ({reasons})")
    rec = best[2]()
    rec.motion_scores = {"criterion": "BIC", "chosen": best[1], "scores": scores}
    rec.configuration = {**cfg.to_json_dict(), "motion": best[1]}
    return rec
