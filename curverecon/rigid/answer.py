"""A row's fit as the toolkit's answer: shape, the paper's poses, points3, motion parameters.

:func:`configuration_answer` builds the answer of every configuration beyond the paper's own
(the orthographic and pinhole rows, the ordinary camera's curve bundle) from its named parts and
adds the fit's warnings (:func:`fit_warnings`) in that one place.

The paper's pose convention (``model/pose.py``: X_cam = R_z(theta) R_y(tau) R_x(delta) X + t,
the curve frame with A at the origin, B on +x and the tangent at B in the xy plane) is reached
from a row's rotations R_f by the curve frame's axes in frame 0: e1 along AB, e2 the part of the
tangent at B (or, without tangents, of C - A, or of the viewing axis) normal to AB, e3 = e1 x e2;
the curve-to-camera rotation of frame f is R_f [e1 e2 e3].  alpha, beta, phi follow from the
tangent directions (given, or the curve's end tangents) by the contract's definitions
(t_B = (-cos alpha, sin alpha, 0), t_A = (cos beta, sin beta cos phi, sin beta sin phi)), NaN
where neither tangents nor curves are given.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from scipy.stats import chi2 as chi2_dist

from curverecon.model.configuration import Configuration
from curverecon.model.pose import normalise as normalise_pose
from curverecon.model.reconstruction import Alternative, Reconstruction
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import (
    Layout,
    RigidState,
    axis_vector,
    body_vectors,
    frame_angles,
    frame_rotations,
    points3,
)
from curverecon.rigid.refinement import RigidFit


def curve_frame(chord: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """(3, 3) columns e1 (along ``chord``), e2 (``reference``'s part normal to it), e3."""
    e1 = chord / np.linalg.norm(chord)
    r = reference - (reference @ e1) * e1
    if np.linalg.norm(r) < 1e-9 * max(np.linalg.norm(reference), 1.0):
        r = np.array([0.0, 0.0, 1.0]) - e1[2] * e1
    e2 = r / np.linalg.norm(r)
    return np.column_stack([e1, e2, np.cross(e1, e2)])


def decompose(m: np.ndarray) -> np.ndarray:
    """(N, 3) delta, tau, theta of rotations m = R_z(theta) R_y(tau) R_x(delta) (radians)."""
    theta = np.arctan2(m[:, 1, 0], m[:, 0, 0])
    tau = np.arctan2(-m[:, 2, 0], np.hypot(m[:, 0, 0], m[:, 1, 0]))
    delta = np.arctan2(m[:, 2, 1], m[:, 2, 2])
    return np.column_stack([delta, tau, theta])


def shape_angles(frame: np.ndarray, t_a: np.ndarray, t_b: np.ndarray) -> tuple[float, ...]:
    """(alpha, beta, phi) of unit tangents into the curve at A and B in the curve frame."""
    a, b = frame.T @ t_a, frame.T @ t_b
    alpha = math.atan2(b[1], -b[0])
    beta = math.atan2(math.hypot(a[1], a[2]), a[0])
    phi = math.atan2(a[2], a[1])
    return alpha, beta, phi


def paper_answer(
    layout: Layout,
    state: RigidState,
    times: np.ndarray,
    tangents3: np.ndarray | None,
) -> tuple[np.ndarray, np.ndarray]:
    """(shape (4,), poses (N, 5)) in the paper's convention (see the module docstring)."""
    q = body_vectors(layout, state)
    chord = q[1] - q[0]
    if tangents3 is not None:
        ref = tangents3[1]
    elif len(q) > 2:
        ref = q[2] - q[0]
    else:
        ref = np.array([0.0, 0.0, 1.0])
    frame = curve_frame(chord, ref)
    rot, _ = frame_rotations(layout, state, times)
    p3 = points3(layout, state, times)
    angles = decompose(np.einsum("fij,jk->fik", rot, frame))
    poses = np.column_stack([angles, p3[:, 0, :2]])
    c = float(np.linalg.norm(chord))
    if tangents3 is None:
        return np.array([c, np.nan, np.nan, np.nan]), poses
    alpha, beta, phi = shape_angles(frame, tangents3[0], tangents3[1])
    return normalise_pose(np.array([c, alpha, beta, phi]), poses)


def chord_std(layout: Layout, state: RigidState, cov: np.ndarray | None) -> float:
    """Standard deviation of c = |B - A| from the globals' covariance (delta method)."""
    if cov is None:
        return math.nan
    q = body_vectors(layout, state)
    d = q[1] - q[0]
    grad = np.zeros(cov.shape[0])
    if layout.centred:
        grad[0:3], grad[3:6] = -d / np.linalg.norm(d), d / np.linalg.norm(d)
    else:
        grad[0:3] = d / np.linalg.norm(d)
    return float(np.sqrt(max(grad @ cov @ grad, 0.0)))


def motion_parameters(layout: Layout, fit: RigidFit, data: RigidData) -> dict:
    """The contract's ``motion_parameters`` of a fit, with ``std`` where the covariance gives it
    (degrees, input units per unit of t squared)."""
    s, cov = fit.state, fit.covariance
    out: dict = {}
    g0 = 3 * layout.n_body + (4 if layout.tangents else 0)
    sd = None if cov is None else np.sqrt(np.maximum(np.diag(cov), 0.0))
    std: dict = {}
    if s.axis is not None:
        out["axis"] = axis_vector(s.axis).tolist()
        out["angle_deg"] = np.degrees(frame_angles(layout, s, data.times)).tolist()
        if sd is not None:
            std["axis_deg"] = float(
                np.degrees(math.hypot(sd[g0], math.sin(s.axis[0]) * sd[g0 + 1]))
            )
    if layout.motion == "uniform-rotation":
        out["rate_deg"] = math.degrees(s.rate)
        if sd is not None:
            std["rate_deg"] = math.degrees(sd[g0 + 2])
    if layout.centred:
        out["acceleration"] = np.asarray(s.parabola[2], float).tolist()
        out["velocity"] = np.asarray(s.parabola[1], float).tolist()
        out["position"] = np.asarray(s.parabola[0], float).tolist()
        if sd is not None:
            std["acceleration"] = sd[g0 + 4 : g0 + 6].tolist()
    if std:
        out["std"] = std
    return out


UNDETERMINED_FRACTION = 0.5
"""An answer whose std of c exceeds this fraction of c (or is not finite) carries a warning that
the frames hardly determine the body.  The bench's rows (1 px, 20 frames) have c's own bound at
0.4-6 % of c, the perspective force field with A and B alone at 10 times c (docs/accuracy.md,
"Perspective and stereo rows")."""


def undetermined_warning(c: float, c_std: float) -> list[str]:
    """A one-line warning when the std of c (input units) says the frames hardly determine the
    body's size, else nothing."""
    if np.isfinite(c_std) and c_std <= UNDETERMINED_FRACTION * abs(c):
        return []
    return [
        f"c = {c:.4g} with std {c_std:.3g}: these frames hardly determine the body (std above "
        f"{UNDETERMINED_FRACTION:.0%} of c): more frames, a further point or tangents would help"
    ]


MISFIT_FALSE_ALARM = 1e-6
"""A fit whose chi2 on its inlier frames is this improbable under the stated point noise carries a
warning (one false alarm in a million right answers)."""


def rigid_dof(layout: Layout, n_frames: int) -> int:
    """Degrees of freedom of a row's fit on ``n_frames`` frames: its measurements less every
    parameter it determines."""
    # with two points and no tangents a free rotation's turn about the chord AB is not observed:
    # that local costs no degree of freedom
    unseen = 1 if layout.free_rotations and len(layout.points) == 2 and not layout.tangents else 0
    return n_frames * (layout.n_measurements - layout.n_local + unseen) - layout.n_global


def misfit_warning(chi2: float, dof: int) -> list[str]:
    """A one-line warning when the inlier frames' chi2 (in units of the stated noise) is far above
    what the noise explains on ``dof`` degrees of freedom: the points are noisier than
    ``point_sigma`` says (the std are then too small by about sqrt(chi2 / dof)), or the model does
    not match the images (a wrong camera, rig, time stamps or motion).  Nothing otherwise, or when
    the fit has no degrees of freedom."""
    if dof < 1 or not np.isfinite(chi2) or chi2_dist.sf(chi2, dof) >= MISFIT_FALSE_ALARM:
        return []
    return [
        f"chi2 {chi2:.4g} on {dof} degrees of freedom: the images disagree with the model by "
        f"{math.sqrt(chi2 / dof):.2g} times the stated point noise (noisier points than "
        "--point-sigma says, or a wrong camera, rig, time stamps or motion); the std are too small"
    ]


OUTLIER_SHARE = 0.25
"""More than this share of the frames left out as outliers carries a warning (the bench's outlier
scenes draw a fifth)."""


def outlier_share_warning(inliers: np.ndarray) -> list[str]:
    """A one-line warning when more than ``OUTLIER_SHARE`` of the frames were left out as
    outliers: either that many images are bad, or the points are noisier than ``point_sigma``
    says (the outlier test is in its units), else nothing."""
    n, out = len(inliers), int(np.sum(~np.asarray(inliers, dtype=bool)))
    if out < 2 or out <= OUTLIER_SHARE * n:
        return []
    return [
        f"{out} of {n} frames do not fit the model and were left out: if that many images are "
        "not bad, the points are noisier than --point-sigma says (raise it)"
    ]


def fit_warnings(dof: int, chi2: float, inliers: np.ndarray, c: float, c_std: float) -> list[str]:
    """Every warning an answer's fit carries, whatever its camera: c hardly determined, a chi2 the
    stated noise cannot explain on ``dof`` degrees of freedom, too many frames left out (the three
    functions above)."""
    return (
        undetermined_warning(c, c_std) + misfit_warning(chi2, dof) + outlier_share_warning(inliers)
    )


def configuration_answer(
    configuration: Configuration,
    motion: str,
    *,
    shape: np.ndarray,
    poses: np.ndarray,
    std: np.ndarray | None,
    inliers: np.ndarray,
    chi2: float,
    frame_chi2: np.ndarray,
    dof: int,
    estimator: str,
    points3: np.ndarray,
    names: Sequence[str],
    motion_parameters: dict,
    warnings: list[str],
    frame_poses: np.ndarray | None = None,
    alternatives: list[Alternative] | None = None,
    curve3d: np.ndarray | None = None,
    curve3d_std: np.ndarray | None = None,
    curve3d_normal_std: np.ndarray | None = None,
    curve_bundle: dict | None = None,
) -> Reconstruction:
    """The answer of a configuration beyond the paper's own, whatever its camera (the
    orthographic and pinhole rows, the ordinary camera's curve bundle), from its named parts.

    Args:
        configuration, motion: what the frames show; ``motion`` the fitted model (``--motion
            auto`` chooses one), written as the output's ``configuration.motion``.
        shape, poses: (4,) c, alpha, beta, phi and (N, 5) the paper's poses (radians, the
            answer's length unit).
        std: (4,) their standard deviations (NaN where not estimated), or None.
        inliers: (N,) False for frames left out; chi2: over the inlier frames (units of the
            stated noise); frame_chi2: (N,) per frame (NaN for frames left out); dof: the fit's
            degrees of freedom on its inlier frames (the misfit warning's).
        estimator: "ml" or "curve-bundle".
        points3: (N, P, 3) the points ``names`` in every frame's camera coordinates.
        motion_parameters: the contract's (``{}`` for free motion).
        warnings: the route's own, in order; the fit's (:func:`fit_warnings`) are appended.
        frame_poses: (N, 3, 4) [R_f | T_f] where the camera places the answer in depth.
        alternatives: other fits as good (the route adds its warning about them).
        curve3d, curve3d_std, curve3d_normal_std, curve_bundle: the curve where there are
            polylines (Reconstruction's attributes: the std across the curve alone where a
            point's slide along it is not determined, stereo).
    """
    cfg = configuration.to_json_dict()
    cfg["motion"] = motion
    c_std = math.nan if std is None else float(std[0])
    p3 = np.asarray(points3, float)
    return Reconstruction(
        shape=shape,
        poses=poses,
        std=std,
        inliers=inliers,
        alternatives=list(alternatives or []),
        warnings=list(warnings) + fit_warnings(dof, chi2, inliers, float(shape[0]), c_std),
        method="auto",
        chi2=float(chi2),
        frame_chi2=frame_chi2,
        estimator=estimator,
        curve3d=curve3d,
        curve3d_std=curve3d_std,
        curve3d_normal_std=curve3d_normal_std,
        curve_bundle=curve_bundle,
        points3=[{n: p3[f, k].tolist() for k, n in enumerate(names)} for f in range(len(p3))],
        configuration=cfg,
        motion_parameters=motion_parameters,
        frame_poses=frame_poses,
    )


def inlier_frame_chi2(fit: RigidFit, inliers: np.ndarray) -> np.ndarray:
    """(N,) every frame's chi2 from a fit on the inlier frames, NaN for the frames left out."""
    out = np.full(len(inliers), np.nan)
    out[np.flatnonzero(inliers)] = fit.frame_chi2
    return out
