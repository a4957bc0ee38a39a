"""Configurations beyond the paper's own row: the seed's Section 2 table.

A :class:`Configuration` says what a sequence of frames shows (projection, motion model, the
traceable points, whether tangents are given); :class:`RigidObservations` holds the frames of
one.  The paper's own row (orthographic, free motion, A and B with tangents, no further points)
is read as :class:`curverecon.model.observations.Observations` instead and runs the paper's
pipeline unchanged.

Conventions (/work/shared/CONTRACT.md, "Configurations beyond the paper's own"): image
coordinates x, y in input units (pixels); times t in the input's units (any unit; rates are per
unit of t); point names are the document's ("A", "B", then the further points in sorted order),
each the same body point in every frame; a tangent is a line (any length, either sign).

Checks: construction validates the structure (shapes, finite numbers, increasing times, A' != B',
tangents not zero) and raises :class:`CurveReconError` with a one-line message;
:meth:`RigidObservations.require_reconstructable` checks what the motion model needs (frames,
points, a motion that shows depth) and is called before any estimation.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field, replace

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.model.observations import wrap_line_angle
from curverecon.solvers.camera import Camera, StereoRig

PROJECTIONS = ("orthographic", "perspective", "stereo")
"""Projections the contract names."""

MOTIONS = ("free", "uniform-rotation", "fixed-axis", "force-field", "rotation-free", "auto")
"""Motion models of the contract (``"motion"``; default "free")."""

FITTED_MOTIONS = ("free", "uniform-rotation", "fixed-axis", "force-field")
"""The models the rigid stage fits (``--motion auto`` chooses among those the points allow)."""

SOLVER_MODULES = {
    ("free", 3): "curverecon.solvers.ortho_free_3pt",
    ("uniform-rotation", 2): "curverecon.solvers.ortho_uniform_rotation",
    ("fixed-axis", 2): "curverecon.solvers.ortho_fixed_axis",
    ("force-field", 2): "curverecon.solvers.ortho_force_field",
}
"""(motion, number of points) -> the minimal solver whose ``FRAMES`` is the least frame count."""

MIN_FRAMES = {
    "free": 3,
    "uniform-rotation": 3,
    "fixed-axis": 4,
    "force-field": 9,
}
"""Least frame counts of the rows (docs/derivation.md), used where a row's solver module is
absent: a solver module's ``FRAMES`` decides (``min_frames``).  Free motion needs three points;
with more points than a row's two the same counts apply (a conservative bound)."""


DEGENERACY_QUANTILE = 0.999
"""A frame sequence is refused as showing no rotation out of the image plane when every image
distance between its points (and, with tangents, every tangent angle relative to A'B') varies no
more than noise would at this quantile (chi-square test of constancy with the given point and
tangent noise).  Measured at 1 px over 1,000 scenes each: rotation about the viewing direction
(4 or 20 frames, 2 or 3 points) refused in 994 to 999; default ``simulate_configuration``
scenes of every row (4 and 20 frames) refused in none
(tests/test_configuration_cli.py repeats it on 200 and 50 scenes)."""


PINHOLE_SOLVER_MODULES = {
    ("perspective", "rotation-free", 2): "curverecon.solvers.persp_rotation_free",
    ("perspective", "uniform-rotation", 2): "curverecon.solvers.persp_uniform_rotation",
    ("perspective", "fixed-axis", 3): "curverecon.solvers.persp_fixed_axis_3pt",
    ("perspective", "free", 4): "curverecon.solvers.persp_free_4pt",
    ("perspective", "force-field", 2): "curverecon.solvers.persp_force_field",
    ("stereo", "free", 2): "curverecon.solvers.stereo_free",
}
"""(projection, motion, points) -> the perspective / stereo row whose solver module's ``FRAMES``
is the least frame count (docs/derivation.md)."""

STEREO_TWO_POINT_AXIS_FRAMES = 3
"""Stereo, A and B alone, a rotation about one axis: the chord's direction in three frames lies on
one cone about the axis (axis and half-angle, three unknowns): three frames, not the two a
parameter count gives (the turn about the chord itself is never seen)."""


def pinhole_count(
    projection: str, motion: str, n_points: int, tangents: bool
) -> tuple[int, int, int, int]:
    """(measurements per frame, own parameters per frame, globals, parameters of frame 0 fixed
    by the gauge) of a pinhole row (the parametrisation of ``curverecon.rigid.model``; a
    two-point body's turn about its chord, unseen under free rotations, not counted)."""
    views = 2 if projection == "stereo" else 1
    meas = views * (2 * n_points + (2 if tangents else 0))
    centred = motion == "force-field"
    free_rot = motion in ("free", "force-field")
    local = (0 if centred else 3) + (3 if free_rot else 0) + (1 if motion == "fixed-axis" else 0)
    if free_rot and n_points == 2 and not tangents:
        local -= 1
    body = 3 * (n_points if centred else n_points - 1) + (4 if tangents else 0)
    motion_g = {"uniform-rotation": 3, "fixed-axis": 2, "force-field": 9}.get(motion, 0)
    fixed0 = (3 if free_rot else 0) + (1 if motion == "fixed-axis" else 0)
    if free_rot and n_points == 2 and not tangents:
        fixed0 -= 1
    scale = 1 if projection == "perspective" else 0
    return meas, local, body + motion_g - scale, fixed0


def pinhole_min_frames(projection: str, motion: str, n_points: int, tangents: bool) -> int | None:
    """The least frame count of a pinhole row (its solver module's ``FRAMES`` where there is
    one for these points, else the parameter count), None when no count of frames determines
    it (each frame adds as many unknowns as measurements)."""
    meas, local, glob, fixed0 = pinhole_count(projection, motion, n_points, tangents)
    if meas <= local:
        return None
    module = PINHOLE_SOLVER_MODULES.get((projection, motion, n_points))
    if module is not None and not tangents:
        frames = getattr(importlib.import_module(module), "FRAMES", None)
        if isinstance(frames, int):
            return frames
    if projection == "stereo" and n_points == 2 and motion in ("uniform-rotation", "fixed-axis"):
        return STEREO_TWO_POINT_AXIS_FRAMES
    # n meas >= glob + n local - fixed0
    return max(1, -(-(glob - fixed0) // (meas - local)))


def min_frames(
    motion: str, n_points: int, projection: str = "orthographic", tangents: bool = False
) -> int:
    """The least number of frames for which ``motion`` with ``n_points`` points is determined:
    the minimal solver's ``FRAMES`` where the module exists, else :data:`MIN_FRAMES`
    (orthographic), or :func:`pinhole_min_frames`."""
    if projection != "orthographic":
        if motion == "auto":
            got = [
                pinhole_min_frames(projection, m, n_points, tangents)
                for m in (*FITTED_MOTIONS, "rotation-free")
            ]
            return min(g for g in got if g is not None) if any(got) else 1
        return pinhole_min_frames(projection, motion, n_points, tangents) or 10**9
    if motion == "auto":
        allowed = [m for m in FITTED_MOTIONS if motion_determined(m, n_points, False) is None]
        return min(min_frames(m, n_points) for m in allowed)
    module = SOLVER_MODULES.get((motion, min(n_points, 3 if motion == "free" else 2)))
    if module is not None:
        try:
            frames = getattr(importlib.import_module(module), "FRAMES", None)
        except ImportError:
            frames = None
        if isinstance(frames, int):
            return frames
    return MIN_FRAMES[motion]


def motion_determined(
    motion: str, n_points: int, tangents: bool, projection: str = "orthographic"
) -> str | None:
    """None when ``motion`` with these points can be determined under ``projection``, else the
    reason it cannot (one line, for the error message)."""
    if projection != "orthographic":
        if motion == "auto" or pinhole_min_frames(projection, motion, n_points, tangents):
            return None
        need = {
            "free": 'four points (A, B, C, D), or a polyline ("curve") in every frame',
            "fixed-axis": "a third point (C)",
        }.get(motion, "more points")
        return (
            f"motion {motion} under {projection} projection with {n_points} points"
            f"{' and tangents' if tangents else ''} is not determined (every frame adds as many "
            f"unknowns as it measures): it needs {need}"
        )
    if motion == "rotation-free":
        return (
            'motion "rotation-free" under orthographic projection shows no depth (every frame '
            "is the same view shifted): the shape is not determined"
        )
    if motion == "free" and n_points < 3 and not tangents:
        return (
            "free motion with only A and B and no tangents is not determined under orthographic "
            'projection: give a third point ("points": {"C": [x, y]}), tangents, or a '
            "restricted motion (uniform-rotation, fixed-axis, force-field)"
        )
    return None


@dataclass(frozen=True)
class Configuration:
    """What the frames show.

    Attributes:
        projection: one of :data:`PROJECTIONS`.
        motion: one of :data:`MOTIONS`.
        points: the traceable point names, "A" and "B" first, then the further points.
        tangents: every frame gives the tangent directions at A and B.
        camera: the calibrated camera of every frame ("perspective" only).
        rig: the calibrated stereo pair ("stereo" only): frame f's camera-0 view is
            ``RigidObservations.points``, its camera-1 view ``RigidObservations.view1``.
        length_ab: the document's ``"length_AB"`` (perspective: the unit of the answer's
            lengths, else A's depth in frame 0 is the unit), or None.
    """

    projection: str = "orthographic"
    motion: str = "free"
    points: tuple[str, ...] = ("A", "B")
    tangents: bool = True
    camera: Camera | None = None
    rig: StereoRig | None = None
    length_ab: float | None = None

    def __post_init__(self) -> None:
        if self.projection not in PROJECTIONS:
            raise CurveReconError(
                f'unknown projection "{self.projection}" (choose {", ".join(PROJECTIONS)})'
            )
        self._check_cameras()
        if self.motion not in MOTIONS:
            raise CurveReconError(f'unknown motion "{self.motion}" (choose {", ".join(MOTIONS)})')
        pts = tuple(self.points)
        if pts[:2] != ("A", "B"):
            raise CurveReconError('the points must start with "A", "B"')
        if len(set(pts)) != len(pts) or not all(isinstance(p, str) and p for p in pts):
            raise CurveReconError("point names must be distinct non-empty strings")
        object.__setattr__(self, "points", pts)
        if not isinstance(self.tangents, bool | np.bool_):
            raise CurveReconError("tangents must be true or false")
        object.__setattr__(self, "tangents", bool(self.tangents))
        if self.length_ab is not None:
            length = float(self.length_ab)
            if not (np.isfinite(length) and length > 0):
                raise CurveReconError(f"length_AB must be a positive number, got {length:g}")
            object.__setattr__(self, "length_ab", length)

    def _check_cameras(self) -> None:
        """A camera exactly for "perspective", a rig exactly for "stereo"."""
        want_camera = self.projection == "perspective"
        want_rig = self.projection == "stereo"
        if want_camera and not isinstance(self.camera, Camera):
            raise CurveReconError(
                'projection "perspective" needs "camera" (focal_px, principal_point)'
            )
        if want_rig and not isinstance(self.rig, StereoRig):
            raise CurveReconError('projection "stereo" needs "cameras" (two calibrated cameras)')
        if self.camera is not None and not want_camera:
            raise CurveReconError(f'"camera" given with projection "{self.projection}"')
        if self.rig is not None and not want_rig:
            raise CurveReconError(f'"cameras" given with projection "{self.projection}"')
        if self.length_ab is not None and self.projection != "perspective":
            raise CurveReconError(
                '"length_AB" applies to projection "perspective" only (its unknown scale)'
            )

    @property
    def is_paper_row(self) -> bool:
        """The paper's own setting: orthographic, free motion, A and B with tangents."""
        return (
            self.projection == "orthographic"
            and self.motion == "free"
            and self.points == ("A", "B")
            and self.tangents
        )

    def to_json_dict(self) -> dict:
        """The output's ``"configuration"`` object (with the camera(s) where there are any,
        as the input document gives them)."""
        out = {
            "projection": self.projection,
            "motion": self.motion,
            "points": list(self.points),
            "tangents": self.tangents,
        }
        if self.camera is not None:
            out["camera"] = camera_to_json(self.camera)
        if self.rig is not None:
            out["cameras"] = rig_to_json(self.rig)
        if self.length_ab is not None:
            out["length_AB"] = self.length_ab
        return out


def camera_to_json(camera: Camera) -> dict:
    """``{"focal_px": f, "principal_point": [cx, cy]}`` (CONTRACT.md, "Configurations")."""
    return {
        "focal_px": float(camera.focal_px),
        "principal_point": [float(v) for v in camera.principal_point],
    }


def rig_to_json(rig: StereoRig) -> list[dict]:
    """The document's ``"cameras"``: camera 0, then camera 1 with ``R`` and ``t``."""
    second = camera_to_json(rig.camera1)
    second["R"] = np.asarray(rig.R, float).tolist()
    second["t"] = np.asarray(rig.t, float).tolist()
    return [camera_to_json(rig.camera0), second]


@dataclass
class StereoView:
    """What camera 1 of a stereo rig sees in every frame (camera 0's view is the
    :class:`RigidObservations` itself).

    Attributes:
        points: (N, P, 2) image positions (pixels of camera 1) in the configuration's order.
        tangents: (N, 2, 2) image directions of the tangents at A and B, or None.
        curves: N polylines (K_i, 2) ordered from A' to B', or None.
    """

    points: np.ndarray
    tangents: np.ndarray | None = None
    curves: list[np.ndarray] | None = None

    def subset(self, idx: np.ndarray) -> StereoView:
        return StereoView(
            self.points[idx],
            None if self.tangents is None else self.tangents[idx],
            None if self.curves is None else [self.curves[i] for i in idx],
        )


PAPER_CONFIGURATION = Configuration()
"""The paper's own row."""


@dataclass
class RigidObservations:
    """Frames of a configuration of the Section 2 table.

    Attributes:
        configuration: the :class:`Configuration`.
        times: (N,) the frames' times t, strictly increasing (default: the frame index).
        points: (N, P, 2) image positions in ``configuration.points`` order (A first, then B).
        tangents: (N, 2, 2) image directions of the tangents at A and B, or None.
        curves: N polylines (K_i, 2) ordered from A' to B', or None.
        frame_ids: (N,) the frames' indices in the input document.
        warnings: what the loader changed or noticed; the reconstruction repeats them.
        view1: stereo only: camera 1's view of every frame (points, tangents and curves as
            above, in camera 1's pixels); the fields above are camera 0's.
    """

    configuration: Configuration
    times: np.ndarray
    points: np.ndarray
    tangents: np.ndarray | None = None
    curves: list[np.ndarray] | None = None
    frame_ids: np.ndarray | None = None
    warnings: list[str] = field(default_factory=list)
    view1: StereoView | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.configuration, Configuration):
            raise CurveReconError("configuration must be a Configuration")
        cfg = self.configuration
        self.points = _array("points", self.points, (None, len(cfg.points), 2))
        n = self.points.shape[0]
        if n == 0:
            raise CurveReconError("no frames")
        self.times = _array("times", self.times, (n,))
        steps = np.diff(self.times)
        if np.any(steps <= 0):
            i = int(np.argmax(steps <= 0)) + 1
            raise CurveReconError(
                f"frame {i}: times are not increasing (t = {self.times[i]:g} after "
                f"{self.times[i - 1]:g})"
            )
        _check_chords(self.points)
        if (self.tangents is None) == cfg.tangents:
            raise CurveReconError("tangents must be given exactly when configuration.tangents")
        if self.tangents is not None:
            self.tangents = _array("tangents", self.tangents, (n, 2, 2))
            norm = np.hypot(self.tangents[..., 0], self.tangents[..., 1])
            if np.any(norm == 0):
                i, k = np.argwhere(norm == 0)[0]
                raise CurveReconError(f"frame {i}: tangent_{'AB'[k]} is the zero vector")
        if self.frame_ids is None:
            self.frame_ids = np.arange(n)
        self.frame_ids = np.asarray(self.frame_ids, dtype=int)
        if self.frame_ids.shape != (n,):
            raise CurveReconError(f"frame_ids must have {n} entries")
        if self.curves is not None:
            self.curves = _curves(self.curves, n)
        self._check_view1()

    def _check_view1(self) -> None:
        """Camera 1's view exactly for stereo, with the same frames, points and keys."""
        cfg, n = self.configuration, self.n_frames
        if (self.view1 is not None) != (cfg.projection == "stereo"):
            raise CurveReconError('a second view is given exactly for projection "stereo"')
        if self.view1 is None:
            return
        v = self.view1
        v.points = _array("camera 1: points", v.points, (n, len(cfg.points), 2))
        _check_chords(v.points)
        if (v.tangents is None) != (self.tangents is None):
            raise CurveReconError("camera 1: tangents must be given exactly when camera 0 has them")
        if v.tangents is not None:
            v.tangents = _array("camera 1: tangents", v.tangents, (n, 2, 2))
        if (v.curves is None) != (self.curves is None):
            raise CurveReconError("camera 1: curves must be given exactly when camera 0 has them")
        if v.curves is not None:
            v.curves = _curves(v.curves, n)

    @property
    def n_frames(self) -> int:
        return int(self.points.shape[0])

    @property
    def n_points(self) -> int:
        return int(self.points.shape[1])

    def point(self, name: str) -> np.ndarray:
        """(N, 2) image positions of the point ``name``."""
        try:
            k = self.configuration.points.index(name)
        except ValueError as exc:
            raise CurveReconError(f'no point "{name}" in this configuration') from exc
        return self.points[:, k]

    def with_motion(self, motion: str) -> RigidObservations:
        """The same frames under another motion model (``--motion`` overriding the document)."""
        new = replace(self.configuration, motion=motion)
        return RigidObservations(
            new, self.times, self.points, self.tangents, self.curves, self.frame_ids,
            list(self.warnings), self.view1,
        )  # fmt: skip

    def subset(self, index: np.ndarray) -> RigidObservations:
        """The frames selected by an index or boolean mask (times stay as they were)."""
        idx = np.arange(self.n_frames)[index]
        return RigidObservations(
            self.configuration,
            self.times[idx],
            self.points[idx],
            None if self.tangents is None else self.tangents[idx],
            None if self.curves is None else [self.curves[i] for i in idx],
            self.frame_ids[idx],
            list(self.warnings),
            None if self.view1 is None else self.view1.subset(idx),
        )

    def require_reconstructable(self, point_sigma: float = 1.0, tangent_sigma_deg: float = 1.0):
        """Raise CurveReconError (one line) if the motion model cannot determine the shape from
        these frames: too few frames or points for it, or a motion that shows no depth (every
        frame alike, or no rotation out of the image plane within the noise ``point_sigma``,
        input units, and ``tangent_sigma_deg``, degrees; :data:`DEGENERACY_QUANTILE`)."""
        cfg = self.configuration
        reason = motion_determined(cfg.motion, self.n_points, cfg.tangents, cfg.projection)
        if reason is not None:
            raise CurveReconError(reason)
        need = min_frames(cfg.motion, self.n_points, cfg.projection, cfg.tangents)
        if self.n_frames < need:
            where = "" if cfg.projection == "orthographic" else f" under {cfg.projection}"
            raise CurveReconError(
                f"{self.n_frames} frame(s) given; motion {cfg.motion} with points "
                f"{', '.join(cfg.points)}{where} needs at least {need}"
            )
        if cfg.projection != "orthographic":
            return  # depth is seen through the pinhole: the fit's information decides
        degenerate = in_plane_motion(
            self.points, self.tangents, point_sigma, np.radians(tangent_sigma_deg)
        )
        if degenerate is not None:
            raise CurveReconError(degenerate)


def in_plane_motion(
    points: np.ndarray, tangents: np.ndarray | None, point_sigma: float, tangent_sigma: float
) -> str | None:
    """None when the frames show a rotation out of the image plane, else why they do not.

    Under orthographic projection a rotation about the viewing direction (with any translation)
    leaves every image distance between the points unchanged and shows nothing of depth.  Each
    distance's spread over the frames is tested against the noise (chi-square with N - 1
    degrees of freedom at :data:`DEGENERACY_QUANTILE`; a distance between two points each with
    ``point_sigma`` per coordinate has std ``sqrt(2) point_sigma``), and with tangents also each
    tangent's angle relative to A'B' (``tangent_sigma``, radians, plus the chord direction's
    noise).  ``points``: (N, P, 2); ``tangents``: (N, 2, 2) or None.
    """
    from scipy.stats import chi2

    n, p = points.shape[:2]
    if n < 2:
        return None
    limit = chi2.ppf(DEGENERACY_QUANTILE, n - 1)
    sig = max(float(point_sigma), 1e-12 * max(1.0, float(np.max(np.abs(points)))))
    varies = []
    for i in range(p):
        for j in range(i + 1, p):
            d = np.linalg.norm(points[:, j] - points[:, i], axis=1)
            varies.append(np.sum((d - d.mean()) ** 2) / (2 * sig**2) > limit)
    if tangents is not None:
        chord = points[:, 1] - points[:, 0]
        theta = np.arctan2(chord[:, 1], chord[:, 0])
        var = max(float(tangent_sigma), 1e-12) ** 2 + 2 * sig**2 / np.sum(chord**2, axis=1)
        for k in range(2):
            rel = wrap_line_angle(np.arctan2(tangents[:, k, 1], tangents[:, k, 0]) - theta)
            dev = wrap_line_angle(rel - rel[0])
            dev = wrap_line_angle(dev - np.average(dev, weights=1 / var))
            varies.append(np.sum(dev**2 / var) > limit)
    if any(varies):
        return None
    rel = points - points[:, :1]
    moved = np.sum((rel - rel.mean(axis=0)) ** 2) / (2 * sig**2)
    if moved <= chi2.ppf(DEGENERACY_QUANTILE, (n - 1) * 2 * max(p - 1, 1)):
        return "all frames alike (no motion within the noise): the shape is not determined"
    return (
        "no rotation out of the image plane (every distance between the points constant within "
        f"the noise assumed, {point_sigma:g} per coordinate, --point-sigma): the depth is not "
        "determined"
    )


def _array(
    name: str, value: object, shape: tuple[int | None, ...], per_frame: bool = True
) -> np.ndarray:
    """A finite float array of the given shape (None: any length) or a one-line error
    (``per_frame``: the first axis is the frame, named in the message)."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise CurveReconError(f"{name} must be an array of numbers") from exc
    if arr.ndim != len(shape) or any(
        s is not None and s != a for s, a in zip(shape, arr.shape, strict=False)
    ):
        want = ", ".join("N" if s is None else str(s) for s in shape)
        raise CurveReconError(f"{name} must have shape ({want}), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        if not per_frame:
            raise CurveReconError(f"{name} has a non-finite number (NaN or inf)")
        bad = np.argwhere(~np.isfinite(arr))[0]
        raise CurveReconError(f"frame {int(bad[0])}: {name} is not finite (NaN or inf)")
    return arr


def _check_chords(points: np.ndarray) -> None:
    """A' != B' in every frame (the chord sets the image scale and direction)."""
    chord = np.linalg.norm(points[:, 1] - points[:, 0], axis=1)
    scale = max(float(np.max(np.abs(points))), 1.0)
    bad = chord <= 1e-12 * scale
    if bad.any():
        raise CurveReconError(f"frame {int(np.argmax(bad))}: A' and B' coincide")


def _curves(curves: list, n: int) -> list[np.ndarray]:
    if len(curves) != n:
        raise CurveReconError(f"{len(curves)} curves for {n} frames")
    out = []
    for i, c in enumerate(curves):
        arr = _array(f"frame {i}: curve", c, (None, 2), per_frame=False)
        if arr.shape[0] < 2:
            raise CurveReconError(f"frame {i}: curve needs at least 2 finite points")
        out.append(arr)
    return out
