"""Calibrated pinhole cameras of the perspective and stereo rows (CONTRACT.md, "Configurations").

A camera has a focal length ``focal_px`` and a principal point ``(cx, cy)``, both in pixels, and
no lens distortion.  Camera coordinates: x right, y down (as the image's pixel axes), z along the
optical axis, in front of the camera z > 0.  A pixel (u, v) is the ray
m = ((u - cx) / f, (v - cy) / f, 1) (normalised image coordinates), and a point X = lambda m
with lambda its depth (camera z).  A stereo rig is camera 0 and camera 1 with camera 1's
coordinates X1 = R X0 + t (t in the units the reconstruction is to have).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.errors import CurveReconError


@dataclass(frozen=True)
class Camera:
    """A calibrated pinhole camera: focal length and principal point in pixels."""

    focal_px: float
    principal_point: tuple[float, float]

    def __post_init__(self) -> None:
        f = float(self.focal_px)
        pp = np.asarray(self.principal_point, dtype=float)
        if not (np.isfinite(f) and f > 0):
            raise CurveReconError(f"camera: focal_px must be a positive number, got {f}")
        if pp.shape != (2,) or not np.all(np.isfinite(pp)):
            raise CurveReconError(
                f"camera: principal_point must be two finite numbers [cx, cy], got {pp.tolist()}"
            )

    def rays(self, points_px: np.ndarray) -> np.ndarray:
        """(..., 3) rays (x, y, 1) of (..., 2) pixel positions (normalised coordinates)."""
        p = np.asarray(points_px, dtype=float)
        xy = (p - np.asarray(self.principal_point, dtype=float)) / float(self.focal_px)
        return np.concatenate([xy, np.ones(xy.shape[:-1] + (1,))], axis=-1)

    def project(self, points3: np.ndarray) -> np.ndarray:
        """(..., 2) pixel positions of (..., 3) points in camera coordinates (z != 0)."""
        x = np.asarray(points3, dtype=float)
        return x[..., :2] / x[..., 2:] * float(self.focal_px) + np.asarray(
            self.principal_point, dtype=float
        )


@dataclass(frozen=True)
class StereoRig:
    """Two calibrated cameras: camera 1's coordinates X1 = R X0 + t (R a rotation)."""

    camera0: Camera
    camera1: Camera
    R: np.ndarray
    t: np.ndarray

    def __post_init__(self) -> None:
        r = np.asarray(self.R, dtype=float)
        t = np.asarray(self.t, dtype=float)
        if r.shape != (3, 3) or not np.all(np.isfinite(r)):
            raise CurveReconError("stereo: camera 1's R must be a 3 x 3 matrix of finite numbers")
        if np.max(np.abs(r @ r.T - np.eye(3))) > 1e-6 or np.linalg.det(r) < 0:
            raise CurveReconError("stereo: camera 1's R is not a rotation (R R^T != I or det < 0)")
        if t.shape != (3,) or not np.all(np.isfinite(t)):
            raise CurveReconError("stereo: camera 1's t must be three finite numbers")
        if not np.linalg.norm(t) > 0:
            raise CurveReconError("stereo: the two cameras coincide (t = 0): no baseline")
