"""``curverecon trace``: inputs to a ``curverecon.observations/1`` document, frame by frame.

Reads the frames (``images``), traces each (``frame``), skips those that cannot be traced with
their reason, makes the same end A in every frame (``ends``), and writes A, B, the end tangents
(``curverecon.curve.polyline.end_tangents``, pointing into the curve) and the polyline from A to
B.  Pixel convention: x = column, y = row, the centre of the top-left pixel at (0, 0).
"""

from __future__ import annotations

import sys
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.io import OBSERVATIONS_FORMAT
from curverecon.trace.ends import assign_ends, ends_identified, frame_record
from curverecon.trace.frame import trace_image
from curverecon.trace.images import count_frames, iter_frames
from curverecon.trace.options import TraceOptions
from curverecon.trace.topology import TraceFailure

MIN_TRACED_FRAMES = 4
"""Fewest traced frames the reconstruction can use (the minimal problem has four frames)."""

FORESHORTENED = 0.3
"""A frame whose chord A'B' is below this fraction of the longest is warned about (seen nearly
end-on: its end tangents are poorly defined)."""


@dataclass
class TraceResult:
    """The document to write, the warnings for stderr, and the frames for ``--plot``."""

    document: dict
    warnings: list[str] = field(default_factory=list)
    frames: list[dict] = field(default_factory=list)


def trace_inputs(
    inputs: Sequence[str],
    options: TraceOptions | None = None,
    progress: bool = False,
    keep_images: bool = False,
    ends: str = "auto",
) -> TraceResult:
    """Trace every frame of ``inputs`` (image files, one folder, or one video).

    ``ends``: what is known of the frames' order (``trace.ends.ENDS_MODES``; ``--ordered``,
    ``--unordered``): the document says ``"ends_identified": false`` where the labels may
    name different ends in different frames (``trace.ends.ends_identified``).

    Raises :class:`CurveReconError` for an input that cannot be read or fewer than
    ``MIN_TRACED_FRAMES`` traced frames (the message names the reasons).
    """
    from tqdm import tqdm

    o = options or TraceOptions()
    total = count_frames(inputs)
    traced: list[dict] = []
    skipped: list[dict] = []
    warnings: list[str] = []
    bar = tqdm(total=total, desc="trace", file=sys.stderr, disable=not progress, leave=False)
    try:
        for index, frame in enumerate(iter_frames(inputs)):
            try:
                tr = trace_image(frame.image, o)
            except TraceFailure as exc:
                skipped.append({"index": index, "file": frame.source, "reason": str(exc)})
                warnings.append(f"frame {index} ({frame.source}) left out: {exc}")
            else:
                traced.append(
                    {
                        "index": index,
                        "file": frame.source,
                        "curve": tr.curve,
                        "image": frame.image if keep_images else None,
                    }
                )
                warnings += [f"frame {index} ({frame.source}): {w}" for w in tr.warnings]
            bar.update(1)
    finally:
        bar.close()
    n = len(traced) + len(skipped)
    if len(traced) < MIN_TRACED_FRAMES:
        reasons = "; ".join(f"frame {s['index']}: {s['reason']}" for s in skipped[:3])
        more = f" (first reasons: {reasons})" if reasons else ""
        raise CurveReconError(
            f"only {len(traced)} of {n} frames could be traced, at least "
            f"{MIN_TRACED_FRAMES} are needed{more}"
        )
    curves = [t["curve"] for t in traced]
    assignment = assign_ends(
        curves,
        o.ambiguity_ratio,
        [t["index"] for t in traced],
        use_reconstruction=ends != "unordered",
        fit_length=o.tangent_fit_length,
    )
    identified = ends_identified(assignment, ends)
    if assignment.ambiguous and identified:
        which = ", ".join(str(traced[k]["index"]) for k in assignment.ambiguous[:10])
        how = (
            "the reconstruction from the polylines decided"
            if assignment.decided_by_reconstruction
            else "continuity of shape decided"
        )
        warnings.append(f"which end is A was ambiguous by continuity before frames {which} ({how})")
    elif not identified and ends == "auto":
        warnings.append(
            f"which end is A: continuity was ambiguous at {len(assignment.ambiguous)} of "
            f"{len(traced) - 1} links, the two orders' costs a median factor "
            f"{assignment.contrast:.1f} apart (no smooth motion between frames); written as "
            '"ends_identified": false, the reconstruction decides each frame (--ordered if '
            "the frames are in order)"
        )
    frames = []
    for t, f in zip(traced, assignment.flip, strict=True):
        curve = np.round(t["curve"][::-1] if f else t["curve"], 4)  # 1e-4 px: far below the noise
        t["curve"] = curve
        frames.append(
            {**frame_record(curve, o.tangent_fit_length), "index": t["index"], "file": t["file"]}
        )
    chords = np.array([np.hypot(*(np.array(f["B"]) - f["A"])) for f in frames])
    for f, c in zip(frames, chords, strict=True):
        if c < FORESHORTENED * chords.max():
            warnings.append(
                f"frame {f['index']} ({f['file']}): A'B' is {c:.0f} px against "
                f"{chords.max():.0f} px at most (seen nearly end-on)"
            )
    doc = {
        "format": OBSERVATIONS_FORMAT,
        "projection": "orthographic",
        "frames": frames,
        "frames_skipped": skipped,
        # the tangents are fits to the polylines, not measurements of their own
        "tangents_from_curve": True,
        **({} if identified else {"ends_identified": False}),
        "pixel_convention": "x = column, y = row, centre of the top-left pixel at (0, 0)",
    }
    return TraceResult(doc, warnings, traced)
