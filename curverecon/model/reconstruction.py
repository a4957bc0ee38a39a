"""The answer of a reconstruction: shape, poses, uncertainty, alternatives, the curve.

Library units: lengths in input units, angles in radians; ``to_json_dict`` writes the
``curverecon.reconstruction/1`` document (degrees; docs/file-formats.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from curverecon.generated import measurement_model
from curverecon.model.configuration import PAPER_CONFIGURATION
from curverecon.model.observations import Observations, wrap_line_angle
from curverecon.model.pose import rotations, translations


@dataclass
class Alternative:
    """Another shape that fits the data about as well as the answer."""

    shape: np.ndarray
    poses: np.ndarray
    chi2: float
    std: np.ndarray | None = None
    ends_exchanged: np.ndarray | None = None
    """With ``"ends_identified": false``: per frame, this shape's labelling exchanges A and B."""


@dataclass
class Reconstruction:
    """The answer.

    Attributes:
        shape: (4,) c (input units), alpha, beta, phi (radians), normalised.
        poses: (N, 5) delta, tau, theta, tx, ty per frame (radians, input units).
        std: (4,) standard deviations of c, alpha, beta, phi from the covariance, or None.
        inliers: (N,) False for frames found not to fit (excluded from the shape estimate).
        alternatives: other shapes fitting equally well (best first).
        warnings: human-readable warnings (also printed by the command line).
        method: "auto" or "linear".
        chi2: sum of squared standardised residuals over the inlier frames (None for linear).
        frame_chi2: (N,) per-frame chi2 (None for linear).
        branch_alternatives: (N, 5) per frame the best pose on another branch of (10) (other
            sign of tau or another delta) for the same shape, or None.
        branch_alternative_chi2: (N,) its chi2 (inf if none).  Frames where it is within
            ``ambiguous_dchi2`` of ``frame_chi2`` are ambiguous from the end points and tangents
            alone (``ambiguous_frames``); a curve reconstruction may tell them apart.
        estimator: "marginal", "ml" or "curve-bundle", the estimate the shape is (None for
            linear); "ml" also where the marginal step does not apply (noise-free data, fewer
            than 5 frames).
        curve3d_std: (M,) standard deviation of each ``curve3d`` point (input units; root of
            the trace of its 3x3 covariance), from the curve bundle's covariance, or None.
            It includes the point's slide along the curve, which moves no point of the curve.
        curve3d_normal_std: (M,) the same across the curve (root of the trace of the
            covariance projected on the plane normal to the curve's tangent at the point): what
            a point's distance from the true curve is to be compared with.
        curve3d: (M, 3) the whole curve in frame 0's camera coordinates (A at z = 0), when the
            frames carry polylines; None otherwise.
        curve_bundle: the curve bundle's summary (the output's ``curve_bundle`` key), or None.
        ambiguous_dchi2: a frame whose other branch fits within this chi2 of its pose is
            ambiguous (``BranchOptions.ambiguous_dchi2``).
        ends_exchanged: (N,) with ``"ends_identified": false`` input: the frames whose labels
            A and B the answer exchanged (A and B are named as in frame 0); None otherwise.
        points3: per frame {name: [x, y, z]}, every traceable point in that frame's camera
            coordinates (A at z = 0), or None: then A and B from the shape and poses.
        configuration: the output's ``"configuration"`` (``Configuration.to_json_dict``), or
            None for the paper's own row.
        motion_parameters: the fitted motion (``"axis"``: unit vector in frame 0's camera
            coordinates, ``"rate_deg"``: degrees per unit of t, ``"angle_deg"``: per frame,
            ``"acceleration"``: whichever the model has), or None (free motion: ``{}``).
        motion_scores: with ``--motion auto``, every candidate model's score, or None.
        frame_poses: (N, 3, 4) per frame [R_f | T_f] with X_f = R_f X_0 + T_f: a point's
            coordinates in frame f's camera (camera 0's for stereo) from its coordinates in
            frame 0's (units of the answer's lengths), for the configurations whose answer
            places the camera in depth (perspective, stereo), else None.

    For the rows of the Section 2 table without tangents, ``shape``'s alpha, beta and phi and
    the per-frame poses may be NaN: they are written as null.
    """

    shape: np.ndarray
    poses: np.ndarray
    std: np.ndarray | None
    inliers: np.ndarray
    alternatives: list[Alternative] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    method: str = "auto"
    chi2: float | None = None
    frame_chi2: np.ndarray | None = None
    branch_alternatives: np.ndarray | None = None
    branch_alternative_chi2: np.ndarray | None = None
    estimator: str | None = None
    curve3d: np.ndarray | None = None
    curve3d_std: np.ndarray | None = None
    curve3d_normal_std: np.ndarray | None = None
    curve_bundle: dict | None = None
    ambiguous_dchi2: float = 4.0
    ends_exchanged: np.ndarray | None = None
    points3: list[dict[str, list[float]]] | None = None
    configuration: dict | None = None
    motion_parameters: dict | None = None
    motion_scores: dict | None = None
    frame_poses: np.ndarray | None = None

    @property
    def c(self) -> float:
        return float(self.shape[0])

    @property
    def alpha(self) -> float:
        return float(self.shape[1])

    @property
    def beta(self) -> float:
        return float(self.shape[2])

    @property
    def phi(self) -> float:
        return float(self.shape[3])

    def rotations(self) -> np.ndarray:
        """(N, 3, 3) curve-to-camera rotations R_z(theta) R_y(tau) R_x(delta)."""
        return rotations(self.poses)

    def translations(self) -> np.ndarray:
        """(N, 3) translations (tx, ty, 0): A at z = 0."""
        return translations(self.poses)

    def points_3d(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(A3, B3, tangent_A3, tangent_B3), each (N, 3), camera coordinates, A at z = 0."""
        out = measurement_model.points_3d(*self.shape, *self.poses.T)
        return tuple(np.asarray(v, float) for v in out)

    def ambiguous_frames(self) -> list[int]:
        """Frames whose pose another branch of (10) fits about as well (see the attributes)."""
        if self.branch_alternative_chi2 is None or self.frame_chi2 is None:
            return []
        amb = self.branch_alternative_chi2 - self.frame_chi2 < self.ambiguous_dchi2
        return [int(i) for i in np.flatnonzero(amb)]

    def outlier_frames(self) -> list[int]:
        return [int(i) for i in np.flatnonzero(~self.inliers)]

    def to_json_dict(self) -> dict:
        """The ``curverecon.reconstruction/1`` document (degrees; extra keys beyond the contract:
        per-frame theta_deg, tx, ty, inlier, chi2; top-level method, std, chi2, outlier_frames,
        alternatives, warnings; curve3d and curve_bundle when there are polylines).  Every
        configuration also writes per-frame ``points3`` and top-level ``configuration`` and
        ``motion_parameters`` (``{}`` for free motion), and ``motion_scores`` when fitted."""
        a3, b3, ta3, tb3 = self.points_3d()
        frames = []
        for i in range(len(self.poses)):
            d, t, th, tx, ty = self.poses[i]
            points3 = self._frame_points3(i, a3[i], b3[i])
            frame = {
                "delta_deg": math.degrees(d),
                "tau_deg": math.degrees(t),
                "A3": points3["A"],
                "B3": points3["B"],
                "tangent_A3": ta3[i].tolist(),
                "tangent_B3": tb3[i].tolist(),
                "theta_deg": math.degrees(th),
                "inlier": bool(self.inliers[i]),
                "points3": points3,
            }
            if self.frame_chi2 is not None:
                frame["chi2"] = float(self.frame_chi2[i])
            if self.frame_poses is not None:
                frame["R"] = np.asarray(self.frame_poses[i, :, :3], float).tolist()
                frame["T"] = np.asarray(self.frame_poses[i, :, 3], float).tolist()
            if self.ends_exchanged is not None:
                frame["ends_exchanged"] = bool(self.ends_exchanged[i])
            if self.branch_alternatives is not None:
                ad, at = self.branch_alternatives[i, :2]
                frame["branch_alternative"] = {
                    "delta_deg": math.degrees(ad),
                    "tau_deg": math.degrees(at),
                    "chi2": float(self.branch_alternative_chi2[i]),
                }
            frames.append(frame)
        out = {"format": "curverecon.reconstruction/1", **shape_dict(self.shape)}
        out["frames"] = frames
        out["method"] = self.method
        out["estimator"] = self.estimator
        out["std"] = None if self.std is None else shape_dict(self.std)
        out["chi2"] = self.chi2
        out["outlier_frames"] = self.outlier_frames()
        out["ambiguous_frames"] = self.ambiguous_frames()
        out["alternatives"] = [
            {
                **shape_dict(alt.shape),
                "chi2": alt.chi2,
                "std": None if alt.std is None else shape_dict(alt.std),
                **_exchanged_key(alt.ends_exchanged),
            }
            for alt in self.alternatives
        ]
        if self.ends_exchanged is not None:
            out["ends_identified"] = False
        out["configuration"] = dict(self.configuration or PAPER_CONFIGURATION.to_json_dict())
        out["motion_parameters"] = dict(self.motion_parameters or {})
        if self.motion_scores is not None:
            out["motion_scores"] = self.motion_scores
        out["warnings"] = list(self.warnings)
        if self.curve3d is not None:
            out["curve3d"] = np.asarray(self.curve3d, float).tolist()
        if self.curve3d is not None and self.curve3d_std is not None:
            out["curve3d_std"] = np.asarray(self.curve3d_std, float).tolist()
        if self.curve3d is not None and self.curve3d_normal_std is not None:
            out["curve3d_normal_std"] = np.asarray(self.curve3d_normal_std, float).tolist()
        if self.curve_bundle is not None:
            out["curve_bundle"] = self.curve_bundle
        return out

    def _frame_points3(self, i: int, a3: np.ndarray, b3: np.ndarray) -> dict[str, list[float]]:
        """Frame ``i``'s ``points3``: the given ones, else A and B from the shape and pose."""
        if self.points3 is None:
            return {"A": a3.tolist(), "B": b3.tolist()}
        return {k: [float(v) for v in xyz] for k, xyz in self.points3[i].items()}


def _exchanged_key(exchanged: np.ndarray | None) -> dict:
    """An alternative's ``ends_exchanged`` list (frames whose labels it exchanges), if any."""
    return {} if exchanged is None else {"ends_exchanged": [bool(v) for v in exchanged]}


def alternatives_warning(
    shape: np.ndarray, std: np.ndarray | None, alternatives: list[Alternative]
) -> str:
    """One line saying how many shapes fit about equally well and whether they really differ.

    Alternatives within two standard deviations (of the best fit's covariance) in every parameter
    are local optima of the same answer; farther ones mean the frames do not determine the shape.
    """
    n = len(alternatives) + 1
    if std is not None and all(
        np.all(np.abs(alt.shape - shape) <= 2.0 * std) for alt in alternatives
    ):
        return (
            f"{n} local optima fit the data about equally well but agree within two standard "
            "deviations; the best is returned, the others are listed in alternatives"
        )
    return (
        f"{n} distinct shapes fit the data about equally well (these frames do not determine the "
        "shape uniquely; more frames or more varied motion would); the best is returned, the "
        "others are listed in alternatives"
    )


def shape_dict(shape: np.ndarray) -> dict:
    c, a, b, p = (float(v) for v in shape)
    return {
        "c": c,
        "alpha_deg": math.degrees(a),
        "beta_deg": math.degrees(b),
        "phi_deg": math.degrees(p),
    }


def angle_residuals_deg(rec: Reconstruction, obs: Observations) -> np.ndarray:
    """(N, 2) tangent-angle residuals of a reconstruction (degrees), for diagnostics."""
    pred = measurement_model.predict(*rec.shape, *rec.poses.T)
    return np.degrees(wrap_line_angle(pred[:, 4:6] - obs.measurements()[:, 4:6]))
