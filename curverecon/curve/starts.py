"""The starts of the curve bundle: start curves and poses, and the further starts tried when a
fit leaves some frame clearly worse than the others.

:func:`run_starts` runs the bundle from the given start curve (or from frame 0's polyline at depth
0, :func:`flat_start`), from frame 0's other pose branch (``CurveOptions.frame0_branch_dchi2``),
again from frame 0's polyline when a frame still fits clearly worse than the others
(``joint.UNEVEN_RATIO``), then from other frames' polylines (:func:`bundle_from_frame`,
:func:`extra_start_frames`, ``CurveOptions.bundle_extra_starts``), and keeps the lowest cost.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from curverecon.curve import joint
from curverecon.curve import polyline as pl
from curverecon.curve.joint import calls_for_restart
from curverecon.curve.pose_search import regauge
from curverecon.curve.spline import BundleResult, bundle_error
from curverecon.model.pose import rotations as pose_rotations
from curverecon.model.pose import translations as pose_translations

if TYPE_CHECKING:
    from curverecon.curve.bundle import CurveRun


def flat_start(polyline: np.ndarray, n: int = 100) -> np.ndarray:
    """A start curve when no 3-D curve is available: frame 0's polyline at depth 0 (the pose
    search of :func:`bundle_adjust` then finds the other frames' poses against it)."""
    pts, _ = pl.resample(pl.as_polyline(polyline, name="frame 0 curve"), n)
    return np.column_stack([pts, np.zeros(len(pts))])


def bundle_from_frame(
    polylines: Sequence[np.ndarray],
    rotations: np.ndarray,
    translations: np.ndarray,
    ref: int,
    **kw,
) -> BundleResult:
    """:func:`bundle_adjust` started from frame ``ref``'s polyline at depth 0 (``ref`` the
    reference frame while fitting: its pose is the gauge and every other pose is searched
    against its flat curve), returned in frame 0's camera coordinates like any other result.
    ``kw``: further arguments of :func:`bundle_adjust` (per-frame arrays in frame order).

    The cost does not depend on the gauge, so results from different reference frames compare
    by ``cost``.  A flat start is a guess of the curve only as good as the frame is
    side-on; another frame's guess lands in another basin of the joint fit."""
    n = len(polylines)
    if not 0 <= ref < n:
        raise bundle_error(f"reference frame {ref} out of range (0..{n - 1})")
    perm = [ref] + [j for j in range(n) if j != ref]
    rot = np.asarray(rotations, float)[perm]
    tr = np.asarray(translations, float)[perm]
    for key in ("ends", "tangents", "polyline_mask"):
        if kw.get(key) is not None:
            kw[key] = np.asarray(kw[key])[perm]
    poly = pl.as_polyline(polylines[ref], name=f"frame {ref} curve")
    if np.hypot(*(poly[-1] - tr[0, :2])) < np.hypot(*(poly[0] - tr[0, :2])):
        poly = poly[::-1].copy()  # from A' (as bundle_adjust orients every polyline)
    br = joint.bundle_adjust(
        [polylines[j] for j in perm], rot, tr, flat_start(poly), resect_first=True, **kw
    )
    inv = np.argsort(perm)
    ctrl, m, b = regauge(br.control, br.m[inv], br.b[inv])
    return BundleResult(
        ctrl,
        m,
        b,
        br.sigma,
        br.rms[inv],
        br.cost_start,
        br.cost,
        br.iterations,
        br.converged,
        list(br.warnings),
    )


def extra_start_frames(n: int, count: int) -> list[int]:
    """``count`` reference frames for further flat starts, spread over a sequence of ``n``
    frames (the middle first, then the quarters, ...; frame 0 is the default start's)."""
    out: list[int] = []
    den = 2
    while len(out) < min(count, n - 1) and den <= 2 * n:
        for j in range(1, den, 2):
            f = int(round(n * j / den))
            if 0 < f < n and f not in out and len(out) < count:
                out.append(f)
        den *= 2
    for f in range(1, n):  # short sequences: every frame in turn
        if len(out) >= min(count, n - 1):
            break
        if f not in out:
            out.append(f)
    return out


def frame0_other_branch(run: CurveRun):
    """(rotations, translations, start curve) with frame 0 on its other pose branch, the
    start curve that of those poses (``run.start_for``; else the start curve turned with frame
    0, X_cam = R_0 X_curve + t_0), or None when that branch's end-point chi2 is more than
    ``CurveOptions.frame0_branch_dchi2`` above frame 0's own."""
    rec = run.rec
    if (
        rec.branch_alternatives is None
        or rec.branch_alternative_chi2 is None
        or rec.frame_chi2 is None
        or run.curve_start is None
    ):
        return None
    dchi2 = float(rec.branch_alternative_chi2[0]) - float(rec.frame_chi2[0])
    if not np.isfinite(dchi2) or dchi2 > run.o.frame0_branch_dchi2:
        return None
    poses = np.array(rec.poses, float)
    poses[0] = rec.branch_alternatives[0]
    rot, tra = pose_rotations(poses), pose_translations(poses)
    if "start" not in run.flipped_start:
        # the curve of the flipped poses themselves where it can be made: the start curve
        # turned with frame 0 keeps the other frames' view of it, and its bundle went back
        # to the first start's poses (sharp-ends seed 9105, 1 px, 12 frames: other branch
        # at chi2 + 7.8, stopped as a retrace, curve3d 7.1 % of its length off; from the
        # flipped poses' own section-4 curve cost 1882.9 against 1884.5, 0.2 % off)
        made = run.start_for(rot, tra) if run.start_for is not None else None
        if made is None:
            r0, t0 = rec.rotations()[0], rec.translations()[0]
            made = (np.asarray(run.curve_start, float) - t0) @ r0 @ rot[0].T + tra[0]
        run.flipped_start["start"] = np.asarray(made, float)
    return rot, tra, run.flipped_start["start"]


def _first_starts(run: CurveRun, mask: np.ndarray | None) -> BundleResult:
    """The bundle from the start curve and, where its end-point chi2 allows, from frame 0's
    other pose branch (the lower cost wins); from frame 0's polyline at depth 0 when there is
    no start curve."""
    rec, curves, kw, o, tried = run.rec, run.curves, run.kw, run.o, run.tried
    if run.flat:
        # no curve to start from: frame 0's polyline at depth 0, every pose searched
        return bundle_from_frame(
            curves, rec.rotations(), rec.translations(), 0, polyline_mask=mask, **kw
        )
    br = joint.bundle_adjust(
        curves, rec.rotations(), rec.translations(), run.curve_start, polyline_mask=mask, **kw
    )
    tried.append(br)
    flipped = frame0_other_branch(run)
    if flipped is not None:
        # frame 0's other branch (CurveOptions.frame0_branch_dchi2): the lower cost wins
        # it stops after its coarse stage when that is the first start's again
        # (CurveOptions.frame0_branch_same_deg)
        other = joint.bundle_adjust(
            curves,
            *flipped,
            polyline_mask=mask,
            twin_m=br.coarse_m,
            twin_deg=o.frame0_branch_same_deg,
            twin_iter=o.frame0_branch_first_iter,
            twin_cost=br.coarse_cost,
            twin_cost_ratio=o.restart_coarse_cost_ratio,
            **kw,
        )
        if not other.stopped:
            tried.append(other)
        if not other.stopped and other.cost < br.cost:
            br = other
    return br


def run_starts(run: CurveRun, mask: np.ndarray | None = None) -> BundleResult:
    """The bundle from every start the fit calls for, the lowest cost kept (``mask``: the
    frames whose polylines are fitted, None for all).  ``run.tried`` collects every completed
    start: the minima the answer's competes with (``CurveOptions.rival_minima_std``)."""
    rec, curves, kw, tried = run.rec, run.curves, run.kw, run.tried
    tried.clear()
    br = _first_starts(run, mask)
    if calls_for_restart(br.rms if mask is None else br.rms[mask], br.sigma) and not run.flat:
        # some frame does not fit: a second start from frame 0's polyline at depth 0 (every
        # pose searched again against it); the lower cost wins
        other = bundle_from_frame(
            curves, rec.rotations(), rec.translations(), 0, polyline_mask=mask, **kw
        )
        tried.append(other)
        if other.cost < br.cost:
            br = other
    # still uneven or off: flat starts from other frames (each reference frame's polyline
    # is another guess of the curve), the lowest cost kept, until every frame fits alike
    for ref in extra_start_frames(run.n, run.o.bundle_extra_starts):
        if not calls_for_restart(br.rms if mask is None else br.rms[mask], br.sigma):
            break
        if mask is not None and not mask[ref]:
            continue
        other = bundle_from_frame(
            curves, rec.rotations(), rec.translations(), ref, polyline_mask=mask, **kw
        )
        tried.append(other)
        if other.cost < br.cost:
            br = other
    return br
