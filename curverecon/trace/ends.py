"""Which end is A: the same physical end of the curve in every frame.

Each traced polyline runs from one end to the other in an order the tracer chose.  Consecutive
frames are linked by continuity: both polylines are resampled at equal arc length and centred
on their centroids (so a drift across the image does not count), and the mean distance between
corresponding points is compared for the two orders of the new frame; the order closer to the
previous frame's shape (which also carries the end positions and end directions) wins.  A link
is ambiguous when the other order costs less than ``ambiguity_ratio`` times as much (a curve
that is nearly symmetric, or a large motion between the frames).  The frames between ambiguous
links form blocks that may each be reversed as a whole; the combination chosen is the one whose
reconstruction (end points and tangents, ``curverecon.reconstruct``) explains the frames best:
the least sum over frames of the standardised residual chi2, each frame's capped at
``FRAME_CHI2_CAP`` (a frame with the wrong end order is a gross outlier; the cap keeps one
such frame from deciding alone).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from curverecon.curve.polyline import resample

N_SAMPLES = 48
"""Points per polyline in the shape comparison."""

FRAME_CHI2_CAP = 100.0
"""Largest chi2 a frame adds to an assignment's score (see the module docstring)."""

MAX_AMBIGUOUS_LINKS = 4
"""At most 2**4 = 16 reconstructions decide between the ambiguous links' assignments; beyond
that the continuity answer stands (and the command warns)."""


@dataclass
class EndAssignment:
    """``flip[k]``: reverse frame k's polyline; ``ambiguous``: links (k-1, k) continuity could
    not decide; ``decided_by_reconstruction``: whether the reconstruction chose among them."""

    flip: np.ndarray
    ambiguous: list[int]
    decided_by_reconstruction: bool


def _centred(curve: np.ndarray) -> np.ndarray:
    pts, _ = resample(curve, N_SAMPLES)
    return pts - pts.mean(axis=0)


def link_costs(prev: np.ndarray, cur: np.ndarray) -> tuple[float, float]:
    """Mean distance (px) of ``cur`` to ``prev`` in the same order and reversed, both centred."""
    p, q = _centred(prev), _centred(cur)
    same = float(np.hypot(*(p - q).T).mean())
    swap = float(np.hypot(*(p - q[::-1]).T).mean())
    return same, swap


def by_continuity(curves: list[np.ndarray], ratio: float) -> tuple[np.ndarray, list[int]]:
    """Flips from frame-to-frame continuity and the ambiguous links (index of the later frame)."""
    flip = np.zeros(len(curves), bool)
    ambiguous = []
    for k in range(1, len(curves)):
        prev = curves[k - 1][::-1] if flip[k - 1] else curves[k - 1]
        same, swap = link_costs(prev, curves[k])
        flip[k] = swap < same
        lo, hi = min(same, swap), max(same, swap)
        if hi < ratio * lo:
            ambiguous.append(k)
    return flip, ambiguous


def _score(curves: list[np.ndarray], flip: np.ndarray) -> float:
    from curverecon.curve.polyline import end_tangents
    from curverecon.errors import CurveReconError
    from curverecon.model.observations import Observations
    from curverecon.pipeline import reconstruct

    oriented = [c[::-1] if f else c for c, f in zip(curves, flip, strict=True)]
    tangents = [end_tangents(c) for c in oriented]
    obs = Observations(
        np.array([c[0] for c in oriented]),
        np.array([c[-1] for c in oriented]),
        np.array([t[0] for t in tangents]),
        np.array([t[1] for t in tangents]),
    )
    try:
        rec = reconstruct(obs)
    except CurveReconError:
        return np.inf
    chi = rec.frame_chi2
    if chi is None:
        return float(rec.chi2) if rec.chi2 is not None else np.inf
    chi = np.where(np.isfinite(chi), chi, FRAME_CHI2_CAP)
    return float(np.minimum(chi, FRAME_CHI2_CAP).sum())


def assign_ends(curves: list[np.ndarray], ratio: float, use_reconstruction: bool = True):
    """The end order of every frame (see the module docstring); frame 0 keeps its order."""
    flip, ambiguous = by_continuity(curves, ratio)
    if not ambiguous or not use_reconstruction or len(ambiguous) > MAX_AMBIGUOUS_LINKS:
        return EndAssignment(flip, ambiguous, False)
    if len(curves) < 4:
        return EndAssignment(flip, ambiguous, False)
    best, best_score = flip, np.inf
    for choice in itertools.product((False, True), repeat=len(ambiguous)):
        f = flip.copy()
        for k, c in zip(ambiguous, choice, strict=True):
            if c:
                f[k:] = ~f[k:]
        s = _score(curves, f)
        if s < best_score:
            best, best_score = f, s
    return EndAssignment(best, ambiguous, True)
