"""Which end is A: the same physical end of the curve in every frame.

Each traced polyline runs from one end to the other in an order the tracer chose.

1. Continuity.  Each frame is compared, in its two orders, with the shape predicted from the
   previous two traced frames: polylines resampled at equal arc length and centred on their
   centroids (a drift across the image does not count), the last shape moved on by
   ``PREDICTION_GAIN`` times its change per frame times the frames elapsed (a frame left out
   doubles the motion).  The cost is the mean distance between corresponding points plus
   ``DIRECTION_WEIGHT`` times the mean change of the end steps (the vectors from each end to
   the fifth sample: the ends' directions and the spacing near them).  The cheaper order wins.
   A link is ambiguous when the other order costs less than ``ambiguity_ratio`` times as much,
   or when it spans more than ``MAX_GAP`` frames.
2. The reconstruction, where continuity is ambiguous.  The frames between ambiguous links form
   blocks that may each be reversed as a whole.  The continuity order and, link by link, the
   order with the block after that link reversed (at most ``MAX_AMBIGUOUS_LINKS`` links) are
   reconstructed with their polylines (``curverecon.reconstruct``: the curve bundle fits one
   3-D curve to every frame's polyline); a reversal is kept when its curve reprojects closer to
   the polylines (mean over frames of the RMS distance; clearly closer, ``REVERSAL_GAIN``): a wrong
   order cannot be fitted by one rigid curve.  Frame 0 keeps the tracer's order.  Each order
   is reconstructed as ``curverecon trace`` writes it (the tracer's end tangents,
   ``frame_tangents``, marked ``"tangents_from_curve": true``), so the reconstruction fits it
   twice, with those tangents as measurements and with the polylines alone (the adaptive fit
   as a start only), and scores its better fit: poor tangents (a hooked or end-on end) can
   leave the bundle in a wrong minimum for the right order (bench seed 20: the right order
   scored 1.56 px with the adaptive tangents alone, the wrong one 1.07; with both, 0.50
   against 1.07).  Scored with both kinds of tangents as measurements (as before), held-out
   seed 1006 (a helix, whose two ends look alike) was reversed: the right order 2.5 px (the
   end-point answer from hooked-end tangents, which the bundle must not leave), the wrong
   one 0.07; with the polylines alone the right order fits as well.

3. Whether the order is established at all (:func:`ends_identified`): with more ambiguous links
   than ``MAX_AMBIGUOUS_LINKS``, or a shape that changes more from frame to frame than
   ``SMOOTH_CHANGE``, or links whose two orders differ in cost by a median factor below
   ``MIN_CONTRAST`` (no smooth motion between frames: images taken apart in time, in
   independent orientations) continuity says nothing, and ``curverecon trace`` writes
   ``"ends_identified": false``: the reconstruction then decides each frame's labelling
   (``curverecon.robust.labels``).  ``--ordered`` and ``--unordered`` say it instead.

(Per-frame checks at a shape from the end points and tangents alone were tried and dropped:
the end tangents of traced polylines misfit that shape by 5-30 degrees in many frames, as much
as a reversed frame does.)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from curverecon.curve.polyline import end_tangents, resample

N_SAMPLES = 48
"""Points per polyline in the shape comparison."""

MAX_AMBIGUOUS_LINKS = 2
"""At most 3 orders (each a reconstruction that fits twice, about 10-60 s for 16 frames)
decide the ambiguous links; with more, the continuity answer stands (and the command warns)."""

MAX_GAP = 2
"""A link across more than one left-out frame is ambiguous whatever its costs (the motion since
the last traced frame is too large for continuity; a rendered sequence with three frames left
out of four was ordered wrong with confidence)."""

PREDICTION_GAIN = 0.5
"""Share of the last change per frame carried into the prediction.  On 40 rendered sequences
(true polylines, 25 degrees a frame) links across one left-out frame were ordered wrong 9 times
in 520 without prediction, 3 with gain 1 and 2 with gain 0.5; across two left-out frames 53, 16
and 16 in 480; at 40 degrees a frame 11, 2 and 2 in 560."""

REVERSAL_GAIN = 0.8
"""A reversal is kept only when its curve fits below this fraction of the continuity order's
(mean frame RMS): where both orders fit (a helix's two ends look alike, and a rigid curve
turned end over end explains either order), continuity decides.  Held-out seed 1006: the
right order 0.069 px, the wrong one 0.068 (ratio 0.98); seed 20: a reversal that was right
fitted 0.50 px against 1.07 (0.47)."""

DIRECTION_WEIGHT = 2.0
"""Weight of the end steps' change in the continuity cost.  On 600 links of 40 rendered
sequences (25 degrees a frame) the centred distance alone ordered 2 links wrong, with this term
none; at 40 degrees a frame 14 against 11."""


@dataclass
class EndAssignment:
    """``flip[k]``: reverse frame k's polyline; ``ambiguous``: links (k-1, k) continuity found
    ambiguous; ``decided_by_reconstruction``: whether the reconstruction chose among them;
    ``change``: see below."""

    flip: np.ndarray
    ambiguous: list[int]
    decided_by_reconstruction: bool
    change: float = 0.0
    """Median over links of the cheaper order's continuity cost over the median polyline
    length (:func:`shape_change`): how far the projected shape moves from frame to frame."""
    contrast: float = float("inf")
    """Median over links of the dearer order's continuity cost over the cheaper's (the
    prediction's, as :func:`by_continuity` compares them): how clearly continuity tells the
    two orders apart, link by link (:data:`MIN_CONTRAST`)."""


def _centred(curve: np.ndarray) -> np.ndarray:
    p, _ = resample(curve, N_SAMPLES)
    return p - p.mean(axis=0)


def link_costs(prev: np.ndarray, cur: np.ndarray, centred: bool = False) -> tuple[float, float]:
    """Continuity cost (px) of ``cur`` after ``prev`` in the same order and reversed
    (``centred``: ``prev`` is already resampled and centred, e.g. a prediction)."""
    p = prev if centred else _centred(prev)
    q = _centred(cur)
    costs = []
    for r in (q, q[::-1]):
        shape = float(np.hypot(*(p - r).T).mean())
        steps_p = np.array([p[4] - p[0], p[-5] - p[-1]]) / 4.0
        steps_r = np.array([r[4] - r[0], r[-5] - r[-1]]) / 4.0
        costs.append(shape + DIRECTION_WEIGHT * float(np.hypot(*(steps_p - steps_r).T).mean()))
    return costs[0], costs[1]


def by_continuity(
    curves: list[np.ndarray], ratio: float, index: list[int] | None = None
) -> tuple[np.ndarray, list[int]]:
    """Flips from frame-to-frame continuity and the ambiguous links (position of the later
    frame in ``curves``); ``index``: the frames' numbers in the input (gaps: frames left out)."""
    flip, ambiguous, _ = _continuity(curves, ratio, index)
    return flip, ambiguous


def _continuity(
    curves: list[np.ndarray], ratio: float, index: list[int] | None = None
) -> tuple[np.ndarray, list[int], float]:
    """:func:`by_continuity`'s flips and ambiguous links, and the median over links of the
    dearer order's cost over the cheaper's (``EndAssignment.contrast``; inf for one frame)."""
    index = list(range(len(curves))) if index is None else list(index)
    flip = np.zeros(len(curves), bool)
    ambiguous = []
    ratios = []
    shapes: list[np.ndarray] = []
    for k in range(len(curves)):
        if k == 0:
            shapes.append(_centred(curves[0]))
            continue
        pred = shapes[-1]
        if k >= 2:
            per_frame = (shapes[-1] - shapes[-2]) / max(index[k - 1] - index[k - 2], 1)
            pred = pred + PREDICTION_GAIN * (index[k] - index[k - 1]) * per_frame
        same, swap = link_costs(pred, curves[k], centred=True)
        flip[k] = swap < same
        ratios.append(max(same, swap) / max(min(same, swap), 1e-12))
        shapes.append(_centred(curves[k][::-1] if flip[k] else curves[k]))
        if max(same, swap) < ratio * min(same, swap) or index[k] - index[k - 1] > MAX_GAP:
            ambiguous.append(k)
    return flip, ambiguous, float(np.median(ratios)) if ratios else float("inf")


def frame_tangents(curve: np.ndarray, fit_length: float) -> tuple[np.ndarray, np.ndarray]:
    """The end tangents ``curverecon trace`` writes for a polyline from A to B: a quadratic
    over ``fit_length`` px from each end, the located end point itself left out (see
    ``TraceOptions.tangent_fit_length``)."""
    return end_tangents(curve[1:-1] if len(curve) > 8 else curve, fit_length=fit_length)


def frame_record(curve: np.ndarray, fit_length: float) -> dict:
    """One frame of ``curverecon.observations/1`` from a traced polyline oriented A to B: A and B
    its ends, the tangents :func:`frame_tangents`, ``curve`` the polyline (lists of floats)."""
    ta, tb = frame_tangents(curve, fit_length)
    return {
        "A": curve[0].tolist(),
        "B": curve[-1].tolist(),
        "tangent_A": ta.tolist(),
        "tangent_B": tb.tolist(),
        "curve": curve.tolist(),
    }


def _score(curves: list[np.ndarray], flip: np.ndarray, fit_length: float | None = None) -> float:
    """Mean over frames of the reprojection RMS (px) of the curve reconstructed from the
    polylines so ordered; with ``fit_length``, as ``curverecon trace`` writes them
    (:func:`frame_record`: the tracer's tangents, marked as fitted to the polylines: the
    reconstruction keeps the better of its fits with them and with the polylines alone);
    without, the adaptive fit's tangents as measurements."""
    from curverecon.errors import CurveReconError
    from curverecon.io import OBSERVATIONS_FORMAT, observations_from_dict
    from curverecon.pipeline import reconstruct

    frames = []
    for c, f in zip(curves, flip, strict=True):
        c = c[::-1] if f else c
        if fit_length is not None:
            frames.append(frame_record(c, fit_length))
            continue
        ta, tb = end_tangents(c)
        frames.append(
            {
                "A": c[0].tolist(),
                "B": c[-1].tolist(),
                "tangent_A": ta.tolist(),
                "tangent_B": tb.tolist(),
                "curve": c.tolist(),
            }
        )
    try:
        doc = {"format": OBSERVATIONS_FORMAT, "frames": frames}
        if fit_length is not None:
            doc["tangents_from_curve"] = True
        rec = reconstruct(observations_from_dict(doc))
    except (CurveReconError, ArithmeticError, ValueError, np.linalg.LinAlgError):
        return np.inf  # an order the reconstruction cannot use does not fit
    if not rec.curve_bundle or "frame_rms_px" not in rec.curve_bundle:
        return np.inf
    return float(np.mean(rec.curve_bundle["frame_rms_px"]))


def assign_ends(
    curves: list[np.ndarray],
    ratio: float,
    index: list[int] | None = None,
    use_reconstruction: bool = True,
    fit_length: float | None = None,
) -> EndAssignment:
    """The end order of every frame (see the module docstring); ``fit_length``: the tracer's
    tangent fit length (``TraceOptions.tangent_fit_length``; None: the adaptive fit alone)."""
    flip, ambiguous, contrast = _continuity(curves, ratio, index)
    decided = False
    if use_reconstruction and ambiguous and len(ambiguous) <= MAX_AMBIGUOUS_LINKS:
        if len(curves) >= 4:
            best = _score(curves, flip, fit_length)
            for k in ambiguous:  # each ambiguous link toggled in turn, kept when it fits better
                f = flip.copy()
                f[k:] = ~f[k:]
                score = _score(curves, f, fit_length)
                if score < REVERSAL_GAIN * best:
                    flip, best = f, score
            decided = True
    return EndAssignment(flip, ambiguous, decided, shape_change(curves), contrast)


def shape_change(curves: list[np.ndarray]) -> float:
    """Median over consecutive frames of the cheaper order's continuity cost
    (:func:`link_costs`) over the median polyline length."""
    if len(curves) < 2:
        return 0.0
    costs = [min(link_costs(curves[k - 1], curves[k])) for k in range(1, len(curves))]
    length = float(np.median([np.sum(np.hypot(*np.diff(c, axis=0).T)) for c in curves]))
    return float(np.median(costs)) / max(length, 1e-12)


SMOOTH_CHANGE = 0.2
"""Largest frame-to-frame shape change (``EndAssignment.change``) of a sequence whose ends
continuity identifies.  On the true polylines of 40 rendered sequences of 16 frames (25 and 40
degrees a frame) it ran 0.05-0.195, on 40 with independent random orientations 0.17-0.30;
with this bound and at most ``MAX_AMBIGUOUS_LINKS`` ambiguous links 39 of the 40 smooth ones
count as identified and 2 of the 40 random ones (ambiguous links alone: 39 and 3)."""

MIN_CONTRAST = 3.0
"""Smallest ``EndAssignment.contrast`` (median over links of the dearer order's continuity cost
over the cheaper's) of a sequence whose ends continuity identifies.  Traced rendered sequences
(bench/trace.py's seeds 0-20 and 1000-1008, 25 degrees a frame) ran 4.7-17.4, the six in
independent random orientations (seeds 2000-2005) 1.3-2.2, among them seed 2004 (2.2), which
passes the other two tests (two ambiguous links, change 0.199) and whose continuity labels,
8 of 16 frames wrong, put its curve 20.6 % off; on true polylines 40 sequences at 25 degrees a
frame 4.9-17.0, 40 at 40 degrees 3.2-7.9, 40 random ones 1.3-2.4."""

ENDS_MODES = ("auto", "ordered", "unordered")
"""What ``curverecon trace`` is told about the frames: ``auto`` (continuity decides whether the
ends are identified), ``ordered`` (they are: smooth motion, ``--ordered``), ``unordered`` (they
are not: ``--unordered``)."""


def ends_identified(assignment: EndAssignment, mode: str = "auto") -> bool:
    """Whether the labels of ``assignment`` name the same physical end in every frame: ``mode``
    ``ordered`` or ``unordered`` says so; ``auto``: unless continuity left more links ambiguous
    than ``MAX_AMBIGUOUS_LINKS``, the shape changed more than ``SMOOTH_CHANGE`` or continuity's
    contrast is below ``MIN_CONTRAST`` (module docstring, step 3)."""
    if mode not in ENDS_MODES:
        raise ValueError(f"unknown ends mode {mode!r} (choose {', '.join(ENDS_MODES)})")
    if mode != "auto":
        return mode == "ordered"
    return (
        len(assignment.ambiguous) <= MAX_AMBIGUOUS_LINKS
        and assignment.change <= SMOOTH_CHANGE
        and assignment.contrast >= MIN_CONTRAST
    )
