"""One image to one traced polyline: ridge mask, chain, sub-pixel centre, located ends.

Conventions: images indexed [row, column], grey levels in [0, 1]; polylines (M, 2) of (x, y) =
(column, row) in pixels, the centre of the top-left pixel at (0, 0), from one end to the other
(which end comes first is decided across frames by ``curverecon.trace.ends``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from curverecon.trace.options import TraceOptions
from curverecon.trace.ridge import centre_points, ridge, scale_for_width, smoothed_profile
from curverecon.trace.topology import TraceFailure, trace_chain


@dataclass
class FrameTrace:
    """A traced frame: the polyline (end to end, both ends located) and its warnings."""

    curve: np.ndarray
    warnings: list[str] = field(default_factory=list)
    crossings: int = 0


def _forward_only(pts: np.ndarray, min_step: float = 0.3) -> np.ndarray:
    """Drop points that do not advance along the chain (a centre step can reorder neighbours)."""
    keep = [0]
    for i in range(1, len(pts)):
        j = keep[-1]
        ahead = pts[min(i + 2, len(pts) - 1)] - pts[j]
        n = float(np.hypot(*ahead))
        step = pts[i] - pts[j]
        if n > 0 and float(step @ ahead) / n >= min_step:
            keep.append(i)
    if keep[-1] != len(pts) - 1:
        keep[-1] = len(pts) - 1
    return pts[keep]


def _end_point(img: np.ndarray, pts: np.ndarray, options: TraceOptions) -> np.ndarray | None:
    """Where the line ends beyond ``pts[0]``: the 50 % point between the line's brightness and the
    background along the end's direction (the line is the curve convolved with the blur, so it
    is at half brightness where the curve ends).  None when no such point is found."""
    w = options.width
    k = min(len(pts) - 1, max(2, int(round(options.end_direction_widths * w))))
    d = pts[0] - pts[k]
    n = float(np.hypot(*d))
    if n == 0:
        return None
    d = d / n
    normal = np.array([-d[1], d[0]])
    s = scale_for_width(w)
    u = np.arange(-w, options.end_search_widths * w, 0.05)
    prof = smoothed_profile(img, pts[0] + u[:, None] * d, options)
    inner = pts[k : 4 * k + 1]
    side = 2.0 * w + 2.0 * s
    bg = float(
        np.median(
            smoothed_profile(
                img, np.vstack([inner + side * normal, inner - side * normal]), options
            )
        )
    )
    peak = float(np.median(smoothed_profile(img, inner, options)))
    if not peak > bg:
        return None
    half = 0.5 * (peak + bg)
    start = int(np.searchsorted(u, -w))
    below = np.flatnonzero(prof[start:] < half)
    if len(below) == 0:
        return None
    i = start + int(below[0])
    if i == 0:
        return None
    f = (prof[i - 1] - half) / (prof[i - 1] - prof[i])
    ue = u[i - 1] + f * (u[i] - u[i - 1])
    return pts[0] + ue * d


def _with_end(pts: np.ndarray, end: np.ndarray | None) -> np.ndarray:
    """Prepend the end point, dropping centre points that lie beyond it."""
    if end is None:
        return pts
    d = end - pts[min(3, len(pts) - 1)]
    beyond = (pts - end) @ d >= -0.3 * float(np.hypot(*d)) / max(float(np.hypot(*d)), 1e-12)
    first = int(np.argmax(~beyond)) if (~beyond).any() else len(pts)
    return np.vstack([end, pts[first:]])


def trace_image(img: np.ndarray, options: TraceOptions | None = None) -> FrameTrace:
    """Trace the line of one grey image (see the module docstring).

    Raises :class:`curverecon.trace.topology.TraceFailure` with the reason when the frame
    cannot be traced (no line, branching, closed, broken beyond repair, an end cut off by the
    border, too short).
    """
    o = options or TraceOptions()
    img = np.asarray(img, float)
    if o.dark_curve:
        img = 1.0 - img
    if not float(np.ptp(img)) > 0:
        raise TraceFailure("the image is constant")
    rid = ridge(img, o)
    chain = trace_chain(rid.mask, o)
    warnings = []
    h, w = img.shape
    m = o.border_margin
    near = (
        (chain.points[:, 0] < m)
        | (chain.points[:, 1] < m)
        | (chain.points[:, 0] > w - 1 - m)
        | (chain.points[:, 1] > h - 1 - m)
    )
    if near[0] or near[-1]:
        raise TraceFailure("an end of the line is at the image border (it may be cut off)")
    if near.any():
        warnings.append("the line touches the image border")
    pts, ok = centre_points(img, chain.points, o)
    pts = pts[ok]
    if len(pts) < 5:
        raise TraceFailure("no line centre found along the skeleton")
    pts = _forward_only(pts)
    if len(pts) < 5:
        raise TraceFailure("no line centre found along the skeleton")
    pts = _with_end(pts, _end_point(img, pts, o))
    pts = _with_end(pts[::-1], _end_point(img, pts[::-1], o))[::-1]
    length = float(np.hypot(*np.diff(pts, axis=0).T).sum())
    if length < o.min_length:
        raise TraceFailure(
            f"the traced line is only {length:.0f} px long (seen nearly end-on, or no line)"
        )
    if chain.crossings:
        warnings.append(
            f"the line crosses itself ({chain.crossings} crossing(s), traced through by "
            "continuity of direction)"
        )
    if chain.gaps:
        gaps = ", ".join(f"{g:.1f}" for g in chain.gaps)
        warnings.append(f"the line is broken (gaps of {gaps} px bridged)")
    if chain.untraced_length > o.spur_widths * o.width:
        warnings.append(
            f"{chain.untraced_length:.0f} px of line-like structure off the traced curve"
        )
    return FrameTrace(pts, warnings, chain.crossings)
