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
from pathlib import Path
from typing import Any

import numpy as np

from curverecon.curve.polyline import bin_average
from curverecon.errors import CurveReconError
from curverecon.model.observations import Observations

OBSERVATIONS_FORMAT = "curverecon.observations/1"
RECONSTRUCTION_FORMAT = "curverecon.reconstruction/1"
TRUTH_FORMAT = "curverecon.truth/1"


def _reject_constant(name: str) -> float:
    raise CurveReconError(f"non-finite number {name} in JSON")


def read_json(path: str | Path) -> Any:
    """Parse a JSON file; NaN / Infinity literals and unreadable files are errors."""
    try:
        text = Path(path).read_text(encoding="utf-8")
    except OSError as exc:
        raise CurveReconError(f"cannot read {path}: {exc.strerror or exc}") from exc
    except UnicodeDecodeError as exc:
        raise CurveReconError(f"{path} is not UTF-8 text") from exc
    try:
        return json.loads(text, parse_constant=_reject_constant)
    except RecursionError as exc:  # the decoder recurses once per nesting level
        raise CurveReconError(f"JSON in {path} is nested too deeply") from exc
    except json.JSONDecodeError as exc:
        raise CurveReconError(
            f"malformed JSON in {path}: {exc.msg} (line {exc.lineno} column {exc.colno})"
        ) from exc


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


def observations_from_dict(data: Any) -> Observations:
    """Observations from a parsed ``curverecon.observations/1`` document.

    A frame carrying "curve" may omit the tangents (they come from
    ``curverecon.curve.polyline.end_tangents``) and A, B (the polyline's end points are used).
    Curves are kept only when every frame carries one.
    """
    if not isinstance(data, dict):
        raise CurveReconError("input must be a JSON object")
    fmt = data.get("format")
    if fmt is None:
        raise CurveReconError(f'missing key "format" (expected "{OBSERVATIONS_FORMAT}")')
    if fmt != OBSERVATIONS_FORMAT:
        raise CurveReconError(f'wrong format tag "{fmt}" (expected "{OBSERVATIONS_FORMAT}")')
    projection = data.get("projection", "orthographic")
    if projection != "orthographic":
        raise CurveReconError(f'projection "{projection}" is not supported (only "orthographic")')
    frames = data.get("frames")
    if frames is None:
        raise CurveReconError('missing key "frames"')
    if not isinstance(frames, list):
        raise CurveReconError('"frames" must be a list')
    a, b, ta, tb, curves = [], [], [], [], []
    long: list[int] = []  # frames whose polylines were averaged down
    for i, frame in enumerate(frames):
        if not isinstance(frame, dict):
            raise CurveReconError(f"frame {i} must be a JSON object")
        curve = _polyline(frame, i) if "curve" in frame else None
        if curve is not None and len(curve) > MAX_POLYLINE_POINTS:
            curve = bin_average(curve, MAX_POLYLINE_POINTS)
            long.append(i)
        curves.append(curve)
        for key in ("A", "B"):
            if key not in frame and curve is None:
                raise CurveReconError(f'frame {i}: missing key "{key}"')
        a.append(_xy(frame, "A", i) if "A" in frame else list(curve[0]))
        b.append(_xy(frame, "B", i) if "B" in frame else list(curve[-1]))
        has_ta, has_tb = "tangent_A" in frame, "tangent_B" in frame
        if not (has_ta and has_tb):
            if curve is None:
                missing = "tangent_A" if not has_ta else "tangent_B"
                raise CurveReconError(f'frame {i}: missing key "{missing}" (and no "curve")')
            est_a, est_b = _end_tangents(curve, i)
        ta.append(_xy(frame, "tangent_A", i) if has_ta else list(est_a))
        tb.append(_xy(frame, "tangent_B", i) if has_tb else list(est_b))
    if not frames:
        raise CurveReconError('"frames" is empty')
    keep = None if any(c is None for c in curves) else curves
    given = all(all(k in f for k in ("A", "B", "tangent_A", "tangent_B")) for f in frames)
    warnings = []
    if long:
        warnings.append(
            f"frames {long}: polylines of more than {MAX_POLYLINE_POINTS} points averaged "
            f"down to {MAX_POLYLINE_POINTS} (equal arc-length bins)"
        )
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


def load_observations(path: str | Path) -> Observations:
    """Read and validate a ``curverecon.observations/1`` file."""
    return observations_from_dict(read_json(path))


def observations_to_dict(obs: Observations) -> dict:
    """The ``curverecon.observations/1`` document of observations (curves included if any)."""
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
