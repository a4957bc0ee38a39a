"""A perspective or stereo row's fit as the toolkit's answer.

Units (CONTRACT.md, "Configurations"): perspective lengths in units of A's depth in frame 0
(A3 z = 1 there; the force field's fit, gauged by its parabola, is rescaled to it) or, when the
document gives ``length_AB``, in its units (|AB| = length_AB); stereo lengths in the units of
the rig's t.  ``frame_poses`` (N, 3, 4) are [R_f | T_f] with X_f = R_f X_0 + T_f (frame 0's
camera coordinates to frame f's; camera 0's for stereo); ``points3`` are every point in every
frame's camera coordinates with its depth.  With polylines the curve stage runs on the fitted
poses: ``curve.pinhole.curve_on_pinhole_poses`` (perspective) or ``curve.stereo.stereo_curve3d``
(stereo), where this build has them.  Stereo with A and B alone leaves each frame's turn about
AB free: the curve stage fixes it and places every frame by the curve, and the answer's
``frame_poses`` and paper poses are those (one set of poses, the curve's); ``points3`` stay the
fit's A and B (under the curve's poses A and B move within their std:
tests/test_stereo_curve_place.py).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.model.configuration import RigidObservations
from curverecon.model.reconstruction import Alternative, Reconstruction, alternatives_warning
from curverecon.options import ReconstructOptions
from curverecon.rigid.answer import (
    chord_std,
    configuration_answer,
    curve_frame,
    decompose,
    inlier_frame_chi2,
    motion_parameters,
    paper_answer,
    rigid_dof,
)
from curverecon.rigid.curve import end_tangents
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import (
    Layout,
    frame_angles,
    frame_rotations,
    normalise,
    points3,
    tangent_vectors,
    with_frames,
)
from curverecon.rigid.pinhole_search import answer_valleys, widened_covariance
from curverecon.rigid.refinement import RigidFit

CURVE_MISSING = "curve stage under perspective not available"
CURVE_ANGLES = (
    "alpha, beta, phi come from the 3-D curve's end tangents (no tangents were given) and have no "
    "std: a curve triangulated from noisy polylines fixes its end tangents poorly (stereo, 0.5 px, "
    "simulated: alpha and beta 8-11 degrees off, phi 35-53; noise-free within 2)"
)
CURVE_HINT = "; a body moving freely: --motion free (A, B and polylines: the curve bundle)"


def answer_scale(obs: RigidObservations, p3: np.ndarray) -> float:
    """The factor from the fit's lengths to the answer's units (module docstring).  Raises
    CurveReconError when the fit puts A behind the camera in frame 0 (a pinhole sees X and -X
    alike; such a fit is a wrong minimum, and its units would turn c negative)."""
    cfg = obs.configuration
    if cfg.projection != "perspective":
        return 1.0
    if not p3[0, 0, 2] > 0:
        raise CurveReconError(
            f"motion {cfg.motion}: the best fit puts A behind the camera in frame 0 (no start "
            "reached a fit in front of it; the frames hardly determine this motion)"
        )
    if cfg.length_ab is not None:
        return float(cfg.length_ab) / float(np.linalg.norm(p3[0, 1] - p3[0, 0]))
    return 1.0 / float(p3[0, 0, 2])


def frame_poses(rot: np.ndarray, p3: np.ndarray) -> np.ndarray:
    """(N, 3, 4) [R_f | T_f], T_f = A_f - R_f A_0 (X_f = R_f X_0 + T_f)."""
    trans = p3[:, 0] - np.einsum("fij,j->fi", rot, p3[0, 0])
    return np.concatenate([rot, trans[..., None]], axis=2)


def curve_stage(obs: RigidObservations, poses, p3: np.ndarray, idx, sigma: float, turn_free=False):
    """(curve3d (M, 3) or None, its std (M,) or None, warnings) on the inlier frames ``idx``;
    ``turn_free`` (stereo, A and B alone): their ``poses`` refitted to the curve, in place."""
    if obs.curves is None:
        return None, None, []
    cfg = obs.configuration
    curves = [obs.curves[i] for i in idx]
    try:
        if cfg.projection == "stereo":
            from curverecon.curve.stereo import stereo_curve_and_poses

            other = [obs.view1.curves[i] for i in idx]
            chord = p3[0, :2] if turn_free else None
            curve, std, poses[idx] = stereo_curve_and_poses(
                cfg.rig, curves, other, poses[idx], sigma, chord
            )
            return curve, std, []
        from curverecon.curve.pinhole import curve_on_pinhole_poses

        return curve_on_pinhole_poses(cfg.camera, poses[idx], curves, p3[0], sigma)
    except ImportError:
        return None, None, [CURVE_MISSING]
    except CurveReconError as exc:  # the points' answer stands; the polylines do not fit it
        return None, None, [f"motion {cfg.motion}: no curve fits its poses ({exc}){CURVE_HINT}"]


def paper_pose_rows(poses: np.ndarray, a0: np.ndarray, b0: np.ndarray) -> np.ndarray:
    """(N, 5) the paper's poses (delta, tau, theta, x, y) of frame poses (N, 3, 4) [R_f | T_f]
    whose curve frame in frame 0 is A ``a0``, B ``b0`` and, with no tangents, the viewing axis
    (as ``answer.paper_answer``): R_f [e1 e2 e3] decomposed, and A's image R_f A_0 + T_f."""
    frame = curve_frame(np.asarray(b0, float) - a0, np.array([0.0, 0.0, 1.0]))
    angles = decompose(np.einsum("fij,jk->fik", poses[:, :, :3], frame))
    return np.column_stack([angles, (poses[:, :, :3] @ a0 + poses[:, :, 3])[:, :2]])


def _motion(layout: Layout, fit: RigidFit, data: RigidData, scale: float) -> dict:
    """``motion_parameters`` in the answer's units (the force field's 3-D parabola scaled)."""
    mp = motion_parameters(layout, fit, data)
    if layout.centred:
        g = np.asarray(fit.state.parabola, float) * scale
        mp["position"], mp["velocity"], mp["acceleration"] = (v.tolist() for v in g)
        if fit.covariance is not None:
            g0 = 3 * layout.n_body + (4 if layout.tangents else 0) + 6
            sd = np.sqrt(np.maximum(np.diag(fit.covariance)[g0 : g0 + 3], 0.0)) * scale
            mp.setdefault("std", {})["acceleration"] = sd.tolist()
    return mp


def valley(obs: RigidObservations, layout: Layout, fit: RigidFit, times) -> Alternative:
    """Another valley's fit (on the inlier frames) as an alternative in the answer's units."""
    state = normalise(layout, fit.state, times)
    scale = answer_scale(obs, points3(layout, state, times))
    shape, poses = paper_answer(layout, state, times, None)
    shape[0] *= scale
    poses[:, 3:5] *= scale
    std = np.array([chord_std(layout, state, fit.covariance) * scale, np.nan, np.nan, np.nan])
    return Alternative(shape=shape, poses=poses, chi2=float(fit.chi2), std=std)


def pinhole_answer(
    obs: RigidObservations,
    layout: Layout,
    fit: RigidFit,
    inliers: np.ndarray,
    data: RigidData,
    options: ReconstructOptions,
) -> Reconstruction:
    """The Reconstruction of a fitted pinhole row (every frame; outlier frames with their last
    parameters)."""
    idx = np.flatnonzero(inliers)
    fit, others = answer_valleys(layout, data, fit, idx)
    full = normalise(layout, fit.full_state or fit.state, data.times)
    state = with_frames(full, idx)
    p3 = points3(layout, full, data.times)
    scale = answer_scale(obs, p3)
    p3 = p3 * scale
    rot = frame_rotations(layout, full, data.times)[0]
    poses = frame_poses(rot, p3)
    warnings = list(obs.warnings)
    turns = layout.free_rotations and data.n_frames > 1  # frame 0's pose is the identity
    free = layout.projection == "stereo" and len(layout.points) == 2 and turns
    if free and obs.curves is None:
        warnings.append(
            "A and B alone: each frame's turn about the chord AB is not determined (the frame "
            "poses keep one; the points are determined)"
        )
    free = free and not layout.tangents
    curve3d, curve_std, more = curve_stage(obs, poses, p3, idx, options.point_sigma, free)
    warnings += more
    tangents3 = tangent_vectors(state)
    if tangents3 is None and curve3d is not None:  # the angles from the curve's end tangents
        tangents3 = end_tangents(np.asarray(curve3d, float))
        warnings.append(CURVE_ANGLES)
    shape, paper_poses = paper_answer(layout, full, data.times, tangents3)
    shape[0] *= scale
    paper_poses[:, 3:5] *= scale
    if free and curve3d is not None:  # the turns the curve was fused with, not the fit's
        paper_poses[idx] = paper_pose_rows(poses[idx], p3[0, 0], p3[0, 1])
    cov = widened_covariance(fit, others)  # reaches every valley that fits about as well
    std = np.array([chord_std(layout, state, cov) * scale, np.nan, np.nan, np.nan])
    alternatives = [valley(obs, layout, alt, data.times[idx]) for alt in others]
    if alternatives:
        warnings.append(alternatives_warning(shape, std, alternatives))
    mp = _motion(layout, replace(fit, state=state), data.subset(idx), scale)
    if "angle_deg" in mp:
        mp["angle_deg"] = np.degrees(frame_angles(layout, full, data.times)).tolist()
    stereo = layout.projection == "stereo"
    return configuration_answer(
        obs.configuration,
        layout.motion,
        shape=shape,
        poses=paper_poses,
        std=std,
        inliers=inliers,
        chi2=fit.chi2,
        frame_chi2=inlier_frame_chi2(fit, inliers),
        dof=rigid_dof(layout, len(idx)),
        estimator="ml",
        points3=p3,
        names=layout.points,
        motion_parameters=mp,
        warnings=warnings,
        frame_poses=poses,
        alternatives=alternatives,
        curve3d=curve3d,
        # the stereo curve's std is across the curve (a match slides along it freely)
        curve3d_std=None if stereo else curve_std,
        curve3d_normal_std=curve_std if stereo else None,
    )
