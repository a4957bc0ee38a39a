"""The Section 2 rows beyond the paper's own: a rigid body under a motion model, estimated from
its frames (orthographic, perspective, stereo).

``reconstruct_rigid(obs, options)`` is the stage's entry (``pipeline.reconstruct`` dispatches
``RigidObservations`` to it).  Files (PoseLib / COLMAP layout):

- ``model.py``: the parametrisation (body, motion model, per-frame parameters, the mirror);
- ``measurements.py``: standardised residuals and Jacobians from ``generated/rigid_model.py``;
- ``refinement.py``: maximum likelihood (Levenberg-Marquardt, Schur complement), covariance,
  Fisher information (Cramer-Rao bound);
- ``starts.py``: start states from every frame (robust scores); ``parabola.py``: the force
  field's global search (the mass centre's parabola and the body's invariants);
  ``geometry.py``: a state from 3-D points and rotations (a minimal solver's or a simulator's);
- ``estimate.py``: one row's fit, outlier frames, degenerate fits refused;
- ``select.py``: ``--motion auto`` (nested likelihood-ratio tests, BIC between the rest);
- ``answer.py``: the answer in the toolkit's conventions; ``curve.py``: section 4 on the row's
  poses.

The perspective and stereo rows (``Layout.projection``) share the parametrisation with depth
(``model.py``) and the same estimation, with:

- ``pinhole.py``: residuals and Jacobians from ``generated/rigid_pinhole.py`` (one camera or
  both of a stereo pair);
- ``pinhole_starts.py``: starts from triangulation (stereo), the all-frame closed form
  (rotation-free), the fixed axis's minimal solver, and weak perspective (the orthographic row
  on normalised coordinates); every frame's depth reversal tried in the consensus fit;
- ``pinhole_search.py``: the free row with four points: a search over frame 0's depths, each
  frame posed by P3P;
- ``pinhole_ransac.py``: LO-RANSAC over the rotation-free row's two-frame samples;
- ``pinhole_answer.py``: frame poses, points with depth, the contract's units, the curve stage
  on the poses where this build has it.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.model.configuration import RigidObservations, min_frames
from curverecon.model.reconstruction import Reconstruction
from curverecon.options import ReconstructOptions
from curverecon.rigid.answer import (
    chord_std,
    configuration_answer,
    inlier_frame_chi2,
    motion_parameters,
    paper_answer,
    rigid_dof,
)
from curverecon.rigid.estimate import fit_row
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import (
    Layout,
    frame_angles,
    normalise,
    points3,
    tangent_vectors,
    with_frames,
)


def rigid_data(obs: RigidObservations, options: ReconstructOptions) -> RigidData:
    """The measurements of ``obs`` with the options' noise levels (input units, radians); the
    camera or the stereo pair with camera 1's view for the pinhole rows."""
    cfg = obs.configuration

    def angles(tangents):
        return None if tangents is None else np.arctan2(tangents[..., 1], tangents[..., 0])

    v1 = obs.view1
    return RigidData(
        np.asarray(obs.times, float),
        np.asarray(obs.points, float),
        angles(obs.tangents),
        float(options.point_sigma),
        float(np.radians(options.tangent_sigma_deg)),
        cfg.camera,
        cfg.rig,
        None if v1 is None else np.asarray(v1.points, float),
        None if v1 is None else angles(v1.tangents),
    )


def fit_motion(obs: RigidObservations, motion: str, options: ReconstructOptions):
    """(layout, fit, inliers) of one motion model on ``obs``."""
    cfg = obs.configuration
    layout = Layout(motion, tuple(cfg.points), bool(cfg.tangents), cfg.projection)
    data = rigid_data(obs, options)
    need = min_frames(motion, obs.n_points, cfg.projection, bool(cfg.tangents))
    fit, inliers = fit_row(layout, data, need, options.outliers)
    return layout, fit, inliers


def answer(
    obs: RigidObservations,
    layout: Layout,
    fit,
    inliers: np.ndarray,
    options: ReconstructOptions,
) -> Reconstruction:
    """The Reconstruction of a fitted row (every frame; outlier frames with their last pose)."""
    from curverecon.rigid.curve import curve_on_poses

    if layout.pinhole:
        from curverecon.rigid.pinhole_answer import pinhole_answer

        return pinhole_answer(obs, layout, fit, inliers, rigid_data(obs, options), options)

    data = rigid_data(obs, options)
    idx = np.flatnonzero(inliers)
    sub = data.subset(idx)
    full = normalise(layout, fit.full_state or fit.state, data.times)
    state = with_frames(full, idx)
    tangents3 = tangent_vectors(state)
    warnings = list(obs.warnings)
    curve3d = None
    if obs.curves is not None:
        curve3d, tangents3, more, full = curve_on_poses(
            layout, full, data, obs.curves, tangents3, options.point_sigma
        )
        warnings += more
    shape, poses = paper_answer(layout, full, data.times, tangents3)
    std = np.array([chord_std(layout, state, fit.covariance), np.nan, np.nan, np.nan])
    mp = motion_parameters(layout, replace(fit, state=state), sub)
    if "angle_deg" in mp:
        mp["angle_deg"] = np.degrees(frame_angles(layout, full, data.times)).tolist()
    return configuration_answer(
        obs.configuration,
        layout.motion,
        shape=shape,
        poses=poses,
        std=std,
        inliers=inliers,
        chi2=fit.chi2,
        frame_chi2=inlier_frame_chi2(fit, inliers),
        dof=rigid_dof(layout, len(idx)),
        estimator="ml",
        points3=points3(layout, full, data.times),
        names=layout.points,
        motion_parameters=mp,
        warnings=warnings,
        curve3d=curve3d,
    )


def reconstruct_rigid(
    obs: RigidObservations, options: ReconstructOptions | None = None
) -> Reconstruction:
    """The reconstruction of a configuration of the Section 2 table (orthographic, perspective
    and stereo rows).

    ``obs.configuration.motion`` "auto" fits every model the points allow and chooses one
    (``rigid.select``), filling ``motion_scores``.  Raises CurveReconError (one line) for input
    the model cannot determine (too few frames or points, a degenerate fitted motion).
    """
    options = options or ReconstructOptions()
    cfg = obs.configuration
    if cfg.motion == "auto":
        from curverecon.rigid.select import reconstruct_auto

        return reconstruct_auto(obs, options)
    obs.require_reconstructable(options.point_sigma, options.tangent_sigma_deg)
    ortho = cfg.projection == "orthographic"
    if ortho and cfg.motion == "free" and obs.n_points < 3 and not cfg.tangents:
        raise CurveReconError("free motion with A and B alone needs tangents or a third point")
    layout, fit, inliers = fit_motion(obs, cfg.motion, options)
    return answer(obs, layout, fit, inliers, options)


__all__ = ["reconstruct_rigid"]
