"""JSON files of the command line (formats in /work/shared/CONTRACT.md).

- ``curverecon.observations/1``: per frame A', B', tangent directions, optional polyline "curve".
- ``curverecon.reconstruction/1``: the shape (degrees) and per-frame delta, tau, 3-D A, B and
  tangent directions (camera coordinates, A at z = 0), optional "curve3d".
- ``curverecon.truth/1`` (written by ``curverecon simulate``): the simulator's truth.

Every problem with a file raises :class:`CurveReconError` with a one-line message.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from curverecon.curve.polyline import bin_average
from curverecon.errors import CurveReconError
from curverecon.model.configuration import (
    MOTIONS,
    PROJECTIONS,
    Configuration,
    RigidObservations,
    StereoView,
    camera_to_json,
    motion_determined,
    rig_to_json,
)
from curverecon.model.observations import Observations
from curverecon.solvers.camera import Camera, StereoRig

OBSERVATIONS_FORMAT = "curverecon.observations/1"
RECONSTRUCTION_FORMAT = "curverecon.reconstruction/1"
TRUTH_FORMAT = "curverecon.truth/1"


FORMAT_HINTS = {
    OBSERVATIONS_FORMAT: "observations: give them to `curverecon reconstruct`",
    RECONSTRUCTION_FORMAT: "the answer `curverecon reconstruct` writes, not its input",
    TRUTH_FORMAT: "the truth `simulate --truth` writes: give reconstruct the scene of `-o`",
    "curverecon.flat-views/1": "two views of a planar curve: give them to `curverecon match-flat`",
    "curverecon.matches/1": "the answer `curverecon match-flat` writes, not its input",
}
"""What each of the project's document kinds is, for the message refusing it elsewhere."""


def format_hint(fmt: Any) -> str:
    """``": <what the document is>"`` for a known format tag of the wrong kind, else ``""``."""
    hint = FORMAT_HINTS.get(fmt) if isinstance(fmt, str) else None
    return f": {hint}" if hint else ""


def _first_non_finite(x: Any, where: str = "") -> str | None:
    """The path (``frames[3].A[0]``) of the first NaN or infinite number in parsed JSON, or None."""
    if isinstance(x, float) and not math.isfinite(x):
        return where or "top level"
    items = x.items() if isinstance(x, dict) else enumerate(x) if isinstance(x, list) else ()
    for k, v in items:
        found = _first_non_finite(v, f"{where}.{k}" if isinstance(k, str) else f"{where}[{k}]")
        if found is not None:
            return found.lstrip(".")
    return None


def read_json(path: str | Path) -> Any:
    """Parse a JSON file; NaN / Infinity literals (named with their place, e.g.
    ``frames[3].A[0]``) and unreadable files are errors."""
    try:
        text = Path(path).read_text(encoding="utf-8-sig")  # a byte-order mark (Notepad) is fine
    except FileNotFoundError as exc:
        here = "" if Path(path).is_absolute() else f" (looked in {Path.cwd()})"
        raise CurveReconError(f"cannot read {path}: {exc.strerror or exc}{here}") from exc
    except OSError as exc:
        raise CurveReconError(f"cannot read {path}: {exc.strerror or exc}") from exc
    except UnicodeDecodeError as exc:
        raise CurveReconError(
            f"{path} is not UTF-8 text (an image or a video? `curverecon trace` reads those)"
        ) from exc
    seen: list[str] = []
    try:
        data = json.loads(text, parse_constant=lambda name: seen.append(name) or float(name))
    except RecursionError as exc:  # the decoder recurses once per nesting level
        raise CurveReconError(f"JSON in {path} is nested too deeply") from exc
    except json.JSONDecodeError as exc:
        before = exc.doc[: exc.pos].rstrip()
        hint = "; JSON allows no comma before ] or }" if before.endswith(",") else ""
        raise CurveReconError(
            f"malformed JSON in {path}: {exc.msg} (line {exc.lineno} column {exc.colno}){hint}"
        ) from exc
    if seen:  # only then walk the document: a large file is not walked twice
        try:
            where = _first_non_finite(data)
        except RecursionError:
            where = "a deeply nested value"
        where = where if len(where) <= 80 else where[:77] + "..."
        raise CurveReconError(f"non-finite number {seen[0]} in JSON at {where} ({path})")
    return data


def write_json(path: str | Path, data: Any) -> None:
    """Write JSON (parent directories created); non-finite floats are written as null."""
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(_finite(data), indent=1) + "\n", encoding="utf-8")
    except OSError as exc:
        raise CurveReconError(f"cannot write {path}: {exc.strerror or exc}") from exc


def _finite(x: Any) -> Any:
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_finite(v) for v in x]
    if isinstance(x, np.ndarray):
        return _finite(x.tolist())
    if isinstance(x, np.bool_):
        return bool(x)
    if isinstance(x, np.integer):
        return int(x)
    if isinstance(x, float | np.floating):
        return float(x) if math.isfinite(x) else None
    return x


def _xy(frame: dict, key: str, i: int) -> list[float]:
    value = frame[key]
    if key not in ("A", "B", "tangent_A", "tangent_B"):
        key = f'point "{key}"'
    if (
        not isinstance(value, list)
        or len(value) != 2
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
    ):
        raise CurveReconError(f"frame {i}: {key} must be [x, y] (two numbers)")
    if not all(math.isfinite(v) for v in value):
        raise CurveReconError(f"frame {i}: {key} is not finite (NaN or inf)")
    return [float(v) for v in value]


def _polyline(frame: dict, i: int) -> np.ndarray:
    pts = frame["curve"]
    if not isinstance(pts, list) or len(pts) < 2:
        raise CurveReconError(f"frame {i}: curve must be a list of at least 2 [x, y] points")
    try:
        arr = np.array(pts, dtype=float)
    except (TypeError, ValueError) as exc:
        raise CurveReconError(f"frame {i}: curve must be a list of [x, y] points") from exc
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise CurveReconError(f"frame {i}: curve must be a list of [x, y] points")
    if not np.all(np.isfinite(arr)):
        raise CurveReconError(f"frame {i}: curve has a non-finite point (NaN or inf)")
    return arr


MAX_POLYLINE_POINTS = 1000
"""A polyline with more points is averaged down to this many (``curve.polyline.bin_average``):
the curve bundle's time grows with the points (200,000 points in one frame: 73 s against 5 s),
while 1,000 points resolve a curve of a few hundred pixels to a fraction of a pixel."""


def observations_from_dict(data: Any) -> Observations | RigidObservations:
    """Observations from a parsed ``curverecon.observations/1`` document.

    The paper's own setting (no ``"motion"`` or ``"motion": "free"``, no further ``"points"``)
    reads as :class:`Observations`, exactly as before the other configurations existed: a
    frame carrying "curve" may omit the tangents (they come from
    ``curverecon.curve.polyline.end_tangents``) and A, B (the polyline's end points are used);
    curves are kept only when every frame carries one.  Every other configuration (a motion
    model, further points) reads as :class:`RigidObservations` (``_rigid_observations``).
    Per-frame ``"t"`` is checked in every document (finite, increasing; all frames or none).
    """
    if not isinstance(data, dict):
        raise CurveReconError("input must be a JSON object")
    fmt = data.get("format")
    if fmt is None:
        raise CurveReconError(f'missing key "format" (expected "{OBSERVATIONS_FORMAT}")')
    if fmt != OBSERVATIONS_FORMAT:
        raise CurveReconError(
            f'wrong format tag "{fmt}" (expected "{OBSERVATIONS_FORMAT}"){format_hint(fmt)}'
        )
    projection = data.get("projection", "orthographic")
    if not isinstance(projection, str) or projection not in PROJECTIONS:
        raise CurveReconError(
            f"unknown projection {json.dumps(projection)} (choose {', '.join(PROJECTIONS)})"
        )
    frames = data.get("frames")
    if frames is None:
        raise CurveReconError('missing key "frames"')
    if not isinstance(frames, list):
        raise CurveReconError('"frames" must be a list')
    for i, frame in enumerate(frames):
        if not isinstance(frame, dict):
            raise CurveReconError(f"frame {i} must be a JSON object")
    motion = data.get("motion", "free")
    if not isinstance(motion, str) or motion not in MOTIONS:
        raise CurveReconError(f"unknown motion {json.dumps(motion)} (choose {', '.join(MOTIONS)})")
    times = _times(frames)
    _require_projection_keys(data, projection)
    if projection == "stereo":
        return _stereo_observations(data, frames, motion, times)
    for i, frame in enumerate(frames):
        if "views" in frame:
            raise CurveReconError(
                f'frame {i}: "views" (two cameras) belong to projection "stereo" with "cameras"; '
                f'this document\'s projection is "{projection}"'
            )
    names = _further_points(frames)
    if projection == "orthographic" and motion == "free" and not names:
        if "motion" in data and frames and not _any_tangents_or_curve(frames):
            raise CurveReconError(motion_determined("free", 2, False) or "")
        return _require_image_scale(_paper_observations(data, frames))
    return _require_image_scale(_rigid_observations(data, frames, motion, times, names))


MAX_IMAGE_COORDINATE = 1e6
"""Image coordinates (points and polylines, input units) beyond this in magnitude are refused:
no image is a million pixels across, and the estimation is not scale-free in floating point
(examples/wire.json scaled by 1e4, coordinates to 3.7e6, with --point-sigma scaled alike gives
the same angles; scaled by 1e6 it warns, wrongly, that the shape is not determined; by 1e12 its
angles are off by 8 degrees)."""

MAX_FIELD_FOCAL_LENGTHS = 10.0
"""A pinhole image point farther than this many focal lengths from the principal point (a ray
84 degrees off the optical axis) is refused: an undistorted image reaches a few focal lengths at
most, so the camera and the points are in different units (e.g. a camera in normalised
coordinates, focal_px 1, with points in pixels)."""


def _require_image_scale(obs: Observations | RigidObservations) -> Observations | RigidObservations:
    """``obs`` itself, after refusing coordinates beyond ``MAX_IMAGE_COORDINATE`` and pinhole
    points beyond ``MAX_FIELD_FOCAL_LENGTHS`` from the principal point (one line naming the
    frame, the worst value and what to check)."""
    if isinstance(obs, Observations):
        views = [(np.stack([obs.a, obs.b], axis=1), obs.curves, None)]
    else:
        cfg = obs.configuration
        cams = [cfg.camera, None] if cfg.rig is None else [cfg.rig.camera0, cfg.rig.camera1]
        views = [(obs.points, obs.curves, cams[0])]
        if obs.view1 is not None:
            views.append((obs.view1.points, obs.view1.curves, cams[1]))
    for k, (points, curves, camera) in enumerate(views):
        where = f"camera {k}: " if len(views) > 1 else ""
        n = len(points)
        xy = np.asarray(points, float).reshape(n, -1, 2)
        frame = np.repeat(np.arange(n), xy.shape[1])
        xy = xy.reshape(-1, 2)
        if curves is not None and n:
            frame = np.concatenate([frame, np.repeat(np.arange(n), [len(c) for c in curves])])
            xy = np.vstack([xy, *curves])
        if not len(xy):
            continue
        size = np.abs(xy).max(axis=1)
        if size.max() > MAX_IMAGE_COORDINATE:
            i = _first_frame(frame, size > MAX_IMAGE_COORDINATE)
            raise CurveReconError(
                f"{where}frame {frame[i]}: an image coordinate of {size[i]:.3g}, beyond "
                f"{MAX_IMAGE_COORDINATE:.0e}: image points are expected in pixels (or units "
                "of that size); scale them down (the answer's lengths scale with them)"
            )
        if camera is None:
            continue
        off = np.hypot(*(xy - np.asarray(camera.principal_point)).T) / camera.focal_px
        if off.max() > MAX_FIELD_FOCAL_LENGTHS:
            i = _first_frame(frame, off > MAX_FIELD_FOCAL_LENGTHS)
            raise CurveReconError(
                f"{where}frame {frame[i]}: an image point {off[i]:.3g} focal lengths from the "
                f"principal point (more than {MAX_FIELD_FOCAL_LENGTHS:g}): the points and the "
                "camera are in different units? focal_px, principal_point and the points are "
                "all in pixels"
            )
    return obs


def _first_frame(frame: np.ndarray, bad: np.ndarray) -> int:
    """The index of the first of the ``bad`` entries in frame order (``frame``: each entry's)."""
    hits = np.flatnonzero(bad)
    return int(hits[np.argmin(frame[hits])])


def _require_projection_keys(data: dict, projection: str) -> None:
    """Refuse ``"camera"`` or ``"cameras"`` under another projection (the usual slip: no
    ``"projection"`` key, so the document reads as orthographic and the camera is unused)."""
    for key, own in (("camera", "perspective"), ("cameras", "stereo")):
        if key in data and projection != own:
            hint = f'; add "projection": "{own}"' if "projection" not in data else ""
            raise CurveReconError(f'"{key}" given with projection "{projection}"{hint}')


def _paper_observations(data: dict, frames: list) -> Observations:
    """The paper's own setting: A', B', tangents (or polylines) in every frame."""
    a, b, ta, tb, curves = [], [], [], [], []
    long: list[int] = []  # frames whose polylines were averaged down
    for i, frame in enumerate(frames):
        curve = _frame_polyline(frame, i, long)
        curves.append(curve)
        a.append(_end_point(frame, "A", curve, i))
        b.append(_end_point(frame, "B", curve, i))
        has_ta, has_tb = "tangent_A" in frame, "tangent_B" in frame
        if not (has_ta and has_tb):
            if curve is None:
                missing = "tangent_A" if not has_ta else "tangent_B"
                hint = "" if _any_tangents_or_curve(frames) else NO_TANGENTS_HINT
                raise CurveReconError(f'frame {i}: missing key "{missing}" (and no "curve"){hint}')
            est_a, est_b = _end_tangents(curve, i)
        ta.append(_xy(frame, "tangent_A", i) if has_ta else list(est_a))
        tb.append(_xy(frame, "tangent_B", i) if has_tb else list(est_b))
    if not frames:
        raise CurveReconError('"frames" is empty')
    keep = None if any(c is None for c in curves) else curves
    given = all(all(k in f for k in ("A", "B", "tangent_A", "tangent_B")) for f in frames)
    warnings = _long_warning(long)
    from_curve = data.get("tangents_from_curve", False)
    if not isinstance(from_curve, bool):
        raise CurveReconError('"tangents_from_curve" must be true or false')
    identified = data.get("ends_identified", True)
    if not isinstance(identified, bool):
        raise CurveReconError('"ends_identified" must be true or false')
    obs = Observations(
        np.array(a), np.array(b), np.array(ta), np.array(tb), keep, given, warnings, from_curve
    )
    obs.ends_identified = identified
    return obs


NO_TANGENTS_HINT = (
    '; with only A and B traced, give the motion ("motion": "fixed-axis", '
    '"uniform-rotation" or "force-field") or a third point ("points": {"C": [x, y]})'
)
"""Appended to the missing-tangent message when no frame has tangents or a polyline: the
document may be one of the other configurations without saying so."""


def _any_tangents_or_curve(frames: list) -> bool:
    return any(
        k in f for f in frames for k in ("tangent_A", "tangent_B", "curve") if isinstance(f, dict)
    )


def _frame_polyline(frame: dict, i: int, long: list[int]) -> np.ndarray | None:
    """Frame ``i``'s polyline or None; a long one averaged down (its index added to ``long``)."""
    curve = _polyline(frame, i) if "curve" in frame else None
    if curve is not None and len(curve) > MAX_POLYLINE_POINTS:
        curve = bin_average(curve, MAX_POLYLINE_POINTS)
        long.append(i)
    return curve


def _end_point(frame: dict, key: str, curve: np.ndarray | None, i: int) -> list[float]:
    """A or B of a frame: given, else the polyline's first or last point."""
    if key in frame:
        return _xy(frame, key, i)
    if curve is None:
        raise CurveReconError(f'frame {i}: missing key "{key}"')
    return list(curve[0] if key == "A" else curve[-1])


def _long_warning(long: list[int]) -> list[str]:
    if not long:
        return []
    return [
        f"frames {long}: polylines of more than {MAX_POLYLINE_POINTS} points averaged "
        f"down to {MAX_POLYLINE_POINTS} (equal arc-length bins)"
    ]


def _times(frames: list) -> np.ndarray | None:
    """Every frame's ``"t"`` (finite numbers, strictly increasing), or None if no frame has one."""
    given = ["t" in f for f in frames]
    if not any(given):
        return None
    if not all(given):
        i = given.index(False)
        raise CurveReconError(f'frame {i}: missing key "t" (other frames give their times)')
    times = []
    for i, frame in enumerate(frames):
        t = frame["t"]
        if not isinstance(t, int | float) or isinstance(t, bool):
            raise CurveReconError(f'frame {i}: "t" must be a number')
        if not math.isfinite(t):
            raise CurveReconError(f'frame {i}: "t" is not finite (NaN or inf)')
        if times and t <= times[-1]:
            raise CurveReconError(
                f"frame {i}: times are not increasing (t = {t:g} after {times[-1]:g})"
            )
        times.append(float(t))
    return np.array(times)


def _further_points(frames: list) -> list[str]:
    """The names in the frames' ``"points"`` (sorted); each must be in every frame."""
    seen: dict[str, int] = {}
    for i, frame in enumerate(frames):
        pts = frame.get("points", {})
        if not isinstance(pts, dict):
            raise CurveReconError(f'frame {i}: "points" must be an object {{"C": [x, y], ...}}')
        for name in pts:
            if name in ("A", "B"):
                raise CurveReconError(
                    f'frame {i}: "points" names "{name}" (A and B are given as "A", "B")'
                )
            if not name.strip():
                raise CurveReconError(f'frame {i}: "points" has an empty name')
            seen.setdefault(name, i)
    for i, frame in enumerate(frames):
        pts = frame.get("points", {})
        for name, first in seen.items():
            if name not in pts:
                raise CurveReconError(
                    f'frame {i}: point "{name}" missing (frame {first} gives it; a further '
                    "point must be traced in every frame)"
                )
    return sorted(seen)


def _rigid_observations(
    data: dict, frames: list, motion: str, times: np.ndarray | None, names: list[str]
) -> RigidObservations:
    """A configuration beyond the paper's own: points (A and B from the polylines where not
    given), optional tangents and polylines (each used only when every frame gives it)."""
    _require_frames_identified(data, frames)
    return _assemble(data, motion, times, names, _view_arrays(data, frames, names))


def _assemble(
    data: dict,
    motion: str,
    times: np.ndarray | None,
    names: list[str],
    first: _View,
    second: _View | None = None,
) -> RigidObservations:
    """The observations of camera 0's view ``first`` (and stereo camera 1's ``second``)."""
    cfg = _configuration(data, motion, ("A", "B", *names), first.tangents is not None)
    n = len(first.points)
    warnings = _camera_key_warnings(data) + list(first.warnings)
    view1 = None
    if second is not None:
        warnings += [f"camera 1: {w}" for w in second.warnings]
        view1 = StereoView(second.points, second.tangents, second.curves)
    return RigidObservations(
        cfg,
        np.arange(float(n)) if times is None else times,
        first.points,
        first.tangents,
        first.curves,
        np.arange(n),
        warnings,
        view1,
    )


def _require_frames_identified(data: dict, frames: list) -> None:
    if not frames:
        raise CurveReconError('"frames" is empty')
    if data.get("ends_identified", True) is not True:
        raise CurveReconError(
            '"ends_identified": false is supported in the paper\'s own setting only (free '
            "motion, A and B with tangents): this configuration needs A and B identified"
        )


def _stereo_observations(
    data: dict, frames: list, motion: str, times: np.ndarray | None
) -> RigidObservations:
    """A stereo document: every frame's ``"views"``, camera 0's then camera 1's, each with the
    keys of a frame (A, B, points, tangents, curve); ``"t"`` on the frame."""
    _require_frames_identified(data, frames)
    views: list[list[dict]] = [[], []]
    for i, frame in enumerate(frames):
        pair = frame.get("views")
        if (
            not isinstance(pair, list)
            or len(pair) != 2
            or not all(isinstance(v, dict) for v in pair)
        ):
            top = ' (a stereo frame has no "A" of its own)' if "A" in frame else ""
            raise CurveReconError(
                f'frame {i}: "views" must be a list of two objects (camera 0, camera 1){top}'
            )
        views[0].append(pair[0])
        views[1].append(pair[1])
    names = _further_points(views[0])
    if _further_points(views[1]) != names:
        raise CurveReconError("camera 1's views name other points than camera 0's")
    first = _camera_view_arrays(data, views, names, 0)
    second = _camera_view_arrays(data, views, names, 1)
    if (first.tangents is None) != (second.tangents is None):
        raise CurveReconError("tangents must be given in both cameras' views or in neither")
    if (first.curves is None) != (second.curves is None):
        raise CurveReconError("polylines must be given in both cameras' views or in neither")
    obs = _require_image_scale(_assemble(data, motion, times, names, first, second))
    _require_in_front(obs.configuration.rig, first.points, second.points, ("A", "B", *names))
    return obs


def _camera_view_arrays(data: dict, views: list[list[dict]], names: list[str], k: int) -> _View:
    """Camera ``k``'s views of every frame (``_view_arrays``); an error names the camera."""
    try:
        return _view_arrays(data, views[k], names)
    except CurveReconError as exc:
        raise CurveReconError(f"camera {k}: {exc}") from exc


def _require_in_front(rig: StereoRig, p0: np.ndarray, p1: np.ndarray, names: tuple) -> None:
    """Refuse a stereo document whose traceable points triangulate behind a camera in most
    frames (the usual cause: ``t`` or ``R`` of the other direction, camera 0's position instead
    of X1 = R X0 + t, or the views' order swapped).  ``p0``, ``p1``: (N, P, 2) pixels.

    Each point is the midpoint of the two rays' closest approach: depth d0 along camera 0's ray
    m0, d1 along camera 1's ray m1 (in camera 0's coordinates), from d0 m0 - d1 R^T m1 = -R^T t
    by least squares.  Rays within 1e-9 of parallel are left out (they show no depth)."""
    r = np.asarray(rig.R, dtype=float)
    t = np.asarray(rig.t, dtype=float)
    m0 = rig.camera0.rays(p0)
    m1 = np.einsum("ji,...j->...i", r, rig.camera1.rays(p1))  # R^T m1
    rhs = -(r.T @ t)
    a, b, c = (m0 * m0).sum(-1), -(m0 * m1).sum(-1), (m1 * m1).sum(-1)
    u, v = (m0 @ rhs), -(m1 @ rhs)
    det = a * c - b * b
    ok = det > 1e-9 * a * c
    d0 = np.where(ok, (c * u - b * v) / np.where(ok, det, 1.0), np.nan)
    d1 = np.where(ok, (a * v - b * u) / np.where(ok, det, 1.0), np.nan)
    behind = ok & ((d0 <= 0) | (d1 <= 0))
    if ok.any() and behind.sum() * 2 > ok.sum():
        f, k = np.argwhere(behind)[0]
        raise CurveReconError(
            f"stereo: the points triangulate behind the cameras ({int(behind.sum())} of "
            f"{int(ok.sum())}; frame {f}'s {names[k]} at depth {d0[f, k]:.4g} in camera 0, "
            f"{d1[f, k]:.4g} in camera 1): check that cameras[1] gives X1 = R X0 + t (camera 0's "
            "coordinates to camera 1's, not camera 1's position) and that each frame's views are "
            "[camera 0, camera 1]"
        )


def _configuration(data: dict, motion: str, names: tuple, tangents: bool) -> Configuration:
    """The document's projection and camera(s) (CONTRACT.md, "Configurations")."""
    projection = data.get("projection", "orthographic")
    camera = rig = length = None
    if projection == "perspective":
        camera = _camera(data.get("camera"), "camera")
    elif "camera" in data:
        raise CurveReconError(f'"camera" given with projection "{projection}"')
    if projection == "stereo":
        rig = _rig(data.get("cameras"))
    elif "cameras" in data:
        raise CurveReconError(f'"cameras" given with projection "{projection}"')
    if "length_AB" in data:
        length = data["length_AB"]
        if not isinstance(length, int | float) or isinstance(length, bool):
            raise CurveReconError('"length_AB" must be a positive number')
    return Configuration(projection, motion, names, tangents, camera, rig, length)


CAMERA_KEYS = ("focal_px", "principal_point")
"""A camera's keys (CONTRACT.md, "Configurations"); camera 1 of a stereo rig adds ``R``, ``t``."""


def _camera_key_warnings(data: dict) -> list[str]:
    """A warning naming keys of ``"camera"`` / ``"cameras"`` that are not read (fx, fy, K,
    distortion, ...): the model is one focal length, a principal point and no distortion."""
    cams = [("camera", data.get("camera"))]
    if isinstance(data.get("cameras"), list):
        cams = [(f"cameras[{i}]", c) for i, c in enumerate(data["cameras"])]
    out = []
    for where, cam in cams:
        known = CAMERA_KEYS + (("R", "t") if where == "cameras[1]" else ())
        extra = [k for k in cam if k not in known] if isinstance(cam, dict) else []
        if extra:
            out.append(
                f"{where}: keys {', '.join(extra)} ignored (a camera is focal_px and "
                "principal_point in pixels, square pixels, no lens distortion: undistort the "
                "image points first)"
            )
    return out


def _camera(value: Any, where: str) -> Camera:
    """A camera object ``{"focal_px": f, "principal_point": [cx, cy]}``."""
    if value is None:
        raise CurveReconError(
            f'projection "perspective" needs "{where}" (focal_px, principal_point)'
        )
    if not isinstance(value, dict):
        raise CurveReconError(f'"{where}" must be an object with focal_px and principal_point')
    for key in CAMERA_KEYS:
        if key not in value:
            raise CurveReconError(
                f'{where}: missing key "{key}" (a camera is {{"focal_px": f, '
                '"principal_point": [cx, cy]}, in pixels)'
            )
    f = value["focal_px"]
    if not isinstance(f, int | float) or isinstance(f, bool):
        raise CurveReconError(f"{where}: focal_px must be a number")
    pp = value["principal_point"]
    if (
        not isinstance(pp, list)
        or len(pp) != 2
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in pp)
    ):
        raise CurveReconError(f"{where}: principal_point must be [cx, cy] (two numbers)")
    try:
        return Camera(float(f), (float(pp[0]), float(pp[1])))
    except CurveReconError as exc:
        raise CurveReconError(str(exc).replace("camera:", f"{where}:", 1)) from exc


def _rig(value: Any) -> StereoRig:
    """The stereo document's ``"cameras"``: camera 0, then camera 1 with R and t."""
    if value is None:
        raise CurveReconError('missing key "cameras" (projection "stereo": two cameras)')
    if not isinstance(value, list) or len(value) != 2:
        raise CurveReconError('"cameras" must be a list of two camera objects')
    cam0 = _camera(value[0], "cameras[0]")
    cam1 = _camera(value[1], "cameras[1]")
    for key in ("R", "t"):
        if key not in value[1]:
            raise CurveReconError(f'cameras[1]: missing key "{key}" (X1 = R X0 + t)')
    try:
        r = np.array(value[1]["R"], dtype=float)
        t = np.array(value[1]["t"], dtype=float)
    except (TypeError, ValueError) as exc:
        raise CurveReconError("cameras[1]: R and t must be arrays of numbers") from exc
    return StereoRig(cam0, cam1, _nearest_rotation(r), t)


ROTATION_ROUNDING = 1e-3
"""Camera 1's ``R`` within this of a rotation (max |R R^T - I|) is taken as the nearest rotation:
a calibration printed to 4 decimals is off by up to 1e-4.  Farther off, StereoRig refuses it."""


def _nearest_rotation(r: np.ndarray) -> np.ndarray:
    """``r`` replaced by the nearest rotation (SVD) when it is one up to rounding, else as given."""
    if r.shape != (3, 3) or not np.all(np.isfinite(r)):
        return r
    if np.max(np.abs(r @ r.T - np.eye(3))) > ROTATION_ROUNDING or np.linalg.det(r) < 0:
        return r
    u, _, vt = np.linalg.svd(r)
    return u @ vt


@dataclass
class _View:
    """One camera's arrays of every frame, read as ``_view_arrays`` reads them."""

    points: np.ndarray
    tangents: np.ndarray | None
    curves: list[np.ndarray] | None
    warnings: list[str]


def _view_arrays(data: dict, frames: list, names: list[str]) -> _View:
    """Points (A and B from the polylines where not given), tangents and polylines of one
    camera's frames (tangents and polylines kept only when every frame gives them)."""
    pts, tangents, curves, long = [], [], [], []
    for i, frame in enumerate(frames):
        curve = _frame_polyline(frame, i, long)
        curves.append(curve)
        row = [_end_point(frame, "A", curve, i), _end_point(frame, "B", curve, i)]
        row += [_xy(frame["points"], k, i) for k in names]
        pts.append(row)
        if "tangent_A" in frame and "tangent_B" in frame:
            tangents.append([_xy(frame, "tangent_A", i), _xy(frame, "tangent_B", i)])
    warnings = _long_warning(long)
    if 0 < len(tangents) < len(frames):
        warnings.append(
            f"tangents ignored: given at both ends in {len(tangents)} of {len(frames)} frames "
            "(they are used only when every frame gives them)"
        )
    if any(c is not None for c in curves) and any(c is None for c in curves):
        warnings.append("polylines ignored: they are used only when every frame carries one")
    has_tangents = len(tangents) == len(frames)
    from_curve = data.get("tangents_from_curve", False)
    if not isinstance(from_curve, bool):
        raise CurveReconError('"tangents_from_curve" must be true or false')
    if has_tangents and from_curve and all(c is not None for c in curves):
        has_tangents = False  # fits to the polylines: not measurements beside them
        warnings.append("tangents fitted to the polylines are not used beside the polylines")
    return _View(
        np.array(pts),
        np.array(tangents) if has_tangents else None,
        None if any(c is None for c in curves) else curves,
        warnings,
    )


def _end_tangents(curve: np.ndarray, i: int) -> tuple[np.ndarray, np.ndarray]:
    try:
        from curverecon.curve.polyline import end_tangents
    except ImportError as exc:
        raise CurveReconError(
            f"frame {i}: no tangents given and curverecon.curve.polyline is not available"
        ) from exc
    try:
        ta, tb = end_tangents(curve)
    except CurveReconError:
        raise
    except ValueError as exc:
        raise CurveReconError(f"frame {i}: cannot estimate tangents from the curve: {exc}") from exc
    return np.asarray(ta, float), np.asarray(tb, float)


def load_observations(
    path: str | Path, motion: str | None = None
) -> Observations | RigidObservations:
    """Read and validate a ``curverecon.observations/1`` file (``observations_from_dict``);
    ``motion`` (the command's ``--motion``) replaces the document's ``"motion"``."""
    data = read_json(path)
    if motion is not None and isinstance(data, dict):
        data = {**data, "motion": motion}
    return observations_from_dict(data)


def observations_to_dict(obs: Observations | RigidObservations) -> dict:
    """The ``curverecon.observations/1`` document of observations (curves included if any)."""
    if isinstance(obs, RigidObservations):
        return _rigid_to_dict(obs)
    frames = []
    for i in range(obs.n_frames):
        frame = {
            "A": obs.a[i].tolist(),
            "B": obs.b[i].tolist(),
            "tangent_A": obs.tangent_a[i].tolist(),
            "tangent_B": obs.tangent_b[i].tolist(),
        }
        if obs.curves is not None:
            frame["curve"] = np.round(obs.curves[i], 6).tolist()
        frames.append(frame)
    doc = {"format": OBSERVATIONS_FORMAT, "projection": "orthographic", "frames": frames}
    if obs.tangents_from_curve:
        doc["tangents_from_curve"] = True
    if not obs.ends_identified:
        doc["ends_identified"] = False
    return doc


def _rigid_to_dict(obs: RigidObservations) -> dict:
    """The document of a configuration beyond the paper's own (it reads back the same)."""
    cfg = obs.configuration
    frames = []
    for i in range(obs.n_frames):
        view = _view_dict(cfg.points, obs.points[i], obs.tangents, obs.curves, i)
        if obs.view1 is None:
            frames.append({"t": float(obs.times[i]), **view})
            continue
        v1 = obs.view1
        second = _view_dict(cfg.points, v1.points[i], v1.tangents, v1.curves, i)
        frames.append({"t": float(obs.times[i]), "views": [view, second]})
    doc = {
        "format": OBSERVATIONS_FORMAT,
        "projection": cfg.projection,
        "motion": cfg.motion,
        "frames": frames,
    }
    if cfg.camera is not None:
        doc["camera"] = camera_to_json(cfg.camera)
    if cfg.rig is not None:
        doc["cameras"] = rig_to_json(cfg.rig)
    if cfg.length_ab is not None:
        doc["length_AB"] = cfg.length_ab
    return doc


def _view_dict(
    names: tuple[str, ...],
    points: np.ndarray,
    tangents: np.ndarray | None,
    curves: list[np.ndarray] | None,
    i: int,
) -> dict:
    """Frame ``i`` as one camera sees it: A, B, further points, tangents, polyline."""
    frame = {"A": points[0].tolist(), "B": points[1].tolist()}
    if len(names) > 2:
        frame["points"] = {k: points[j].tolist() for j, k in enumerate(names[2:], 2)}
    if tangents is not None:
        frame["tangent_A"] = tangents[i, 0].tolist()
        frame["tangent_B"] = tangents[i, 1].tolist()
    if curves is not None:
        frame["curve"] = np.round(curves[i], 6).tolist()
    return frame
