"""The curve alone with every pose fixed: the end-point answer kept, its curve fitted to the
polylines (:func:`fit_curve_fixed_poses`, and the answer built on it, :func:`fixed_pose_answer`).

The curve's ends and end tangent lines are pinned (:func:`_pinned_map`): truncated-SVD
Gauss-Newton, knot spans halved while the information criterion improves; for exact end points
from ``CurveOptions.exact_start_control_points``, a folded fit refitted from its own points in a
polyline's order (:func:`unfolded_points`), and the feet searched in the polylines' order
(``Problem._ordered_feet``); a fit left above the noise-free target, some frame's RMS over
``CurveOptions.exact_restart_rms`` of its polyline's length, run again from
``exact_restart_control_points`` and the lower misfit kept.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve.lm import MAX_ITER, gauss_newton_tsvd
from curverecon.curve.residuals import SMOOTH_WEIGHT, Problem, bic, nondecreasing_mask
from curverecon.curve.spline import Basis, arc_parameters
from curverecon.curve.uncertainty import curve_point_std

if TYPE_CHECKING:
    from curverecon.curve.bundle import CurveRun


def _pinned_map(k: int, a: np.ndarray, bpt: np.ndarray, ta: np.ndarray, tb: np.ndarray):
    """Control points with A, B and the end tangent lines pinned: ``ctrl = base + D p``.

    P_0 = A, P_{K-1} = B, P_1 = A + p_0 ta, P_{K-2} = B + p_1 tb (ta, tb unit, into the curve)
    and the interior control points free.  Returns (base (K, 3), D (3K, 2 + 3(K - 4)))."""
    base = np.zeros((k, 3))
    base[0], base[1], base[-2], base[-1] = a, a, bpt, bpt
    d = np.zeros((3 * k, 2 + 3 * (k - 4)))
    d[3:6, 0] = ta
    d[3 * (k - 2) : 3 * (k - 1), 1] = tb
    d[6 : 3 * (k - 2), 2:] = np.eye(3 * (k - 4))
    return base, d


def _pinned_start(
    points: np.ndarray, k: int, base: np.ndarray, d: np.ndarray, u: np.ndarray | None = None
) -> np.ndarray:
    """Parameters p of the pinned spline nearest (least squares) to ``points`` at the curve
    parameters ``u`` (default: chord length)."""
    pts = np.asarray(points, float)
    if u is None:
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
        u = s / s[-1]
    nb = Basis(k).values(u)  # (M, K)
    # x(u) = nb @ (base + (D p).reshape(K, 3)) = points
    a_mat = np.einsum("mk,kcp->mcp", nb, d.reshape(k, 3, -1)).reshape(-1, d.shape[1])
    rhs = (pts - nb @ base).reshape(-1)
    p, *_ = np.linalg.lstsq(a_mat, rhs, rcond=None)
    p[:2] = np.maximum(p[:2], 1e-3 * float(np.linalg.norm(base[-1] - base[0])))
    return p


def is_folded(prob: Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, tol: float) -> bool:
    """Whether the fitted curve has folded over itself: in more than half of the frames whose
    polylines are fitted some polyline point's nearest foot steps back along the curve (against
    the polyline's order) by more than ``tol`` sigma of the projected curve's arc length from
    where its in-order neighbours' feet put it, or the feet leave a stretch of the projected
    curve that long (beyond twice the points' spacing) without any foot.  The noise moves feet
    by about a sigma; a fold's strands lie on the polyline in every frame, a crossing of the
    projected curve with itself only in a few."""
    u = prob._all_foot_points(ctrl, m, b, ordered=False)
    used = np.flatnonzero(np.asarray(prob.poly_w) > 0.0)
    dense = prob.n_grid @ ctrl
    count = 0
    for f in used:
        lo, cnt = int(prob.q_lo[f]), int(prob.q_cnt[f])
        if cnt < 3:
            continue
        uf = u[lo : lo + cnt]
        q = prob.q_all[lo : lo + cnt]
        length = float(np.sum(np.linalg.norm(np.diff(q, axis=0), axis=1)))
        limit = tol * prob.sigma
        # the feet as arc length along the projected curve
        proj = dense @ m[f, :2].T
        arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(proj, axis=0), axis=1))])
        sf = np.interp(uf, prob.u_grid, arc)
        if np.any(np.diff(uf) < 0.0):
            keep = nondecreasing_mask(uf)
            bad, idx = np.flatnonzero(~keep), np.flatnonzero(keep)
            v = np.interp(bad, idx, sf[idx])
            if np.any(np.abs(sf[bad] - v) > limit):
                count += 1
                continue
        # ... or a stretch of the projected curve that no point's foot lands on (the strands
        # of a fold that the nearest feet all leave for one of them), longer than the limit
        # beyond the polyline's point spacing
        gaps = np.diff(np.concatenate([[0.0], np.sort(sf), [arc[-1]]]))
        count += bool(gaps.max() > limit + 2.0 * length / (cnt - 1))
    return count > len(used) // 2


def unfolded_points(
    prob: Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, mask: np.ndarray
) -> np.ndarray | None:
    """The fitted curve's points in the order of one frame's polyline, or None if the curve
    has not folded.

    A fold shows in every frame: the foot parameters u of a polyline's points (A' to B') step
    back.  The curve's points at those feet, in the polyline's order, run along the curve once
    (the folded stretches coincide in every image, so in 3-D); the frame used is the one whose
    points step most evenly (least largest step over the median step: a frame whose projected
    curve crosses itself sends some points to the other branch).  Returns (M + 2, 3) with A and
    B at the ends (ctrl's first and last control points), frame 0 camera coordinates.
    """
    u = prob._all_foot_points(ctrl, m, b, ordered=False)  # the nearest points: folds show
    best, best_score, folded = None, np.inf, 0
    for i in np.flatnonzero(mask):
        ui = u[prob.q_lo[i] : prob.q_lo[i] + prob.q_cnt[i]]
        if len(ui) < 2:
            continue
        folded += bool(np.any(np.diff(ui) < 0.0))
        pts = np.vstack([ctrl[:1], prob.basis.values(ui) @ ctrl, ctrl[-1:]])
        step = np.linalg.norm(np.diff(pts, axis=0), axis=1)
        score = step.max() / max(float(np.median(step)), 1e-300)
        if score < best_score:
            best, best_score = pts, score
    # a fold steps back in (nearly) every frame; one frame's crossing only in that frame
    if best is None or folded <= np.count_nonzero(mask) // 2:
        return None
    return best


def fit_curve_fixed_poses(
    polylines: Sequence[np.ndarray],
    m: np.ndarray,
    b: np.ndarray,
    ends3d: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    start: np.ndarray,
    *,
    sigma: float,
    k_start: int,
    k_max: int,
    polyline_mask: np.ndarray | None = None,
    max_iter: int = MAX_ITER,
    smooth_weight: float = SMOOTH_WEIGHT,
    reverse_factor: float = 1.0,
    abs_tol: float = 0.0,
    resolution: float = 0.0,
    rcond: float = 1e-4,
    unfold: int = 0,
) -> tuple[np.ndarray, float, np.ndarray]:
    """The 3-D curve alone, every frame's pose fixed, its ends and end tangent lines pinned.

    polylines: N (M_i, 2) from A' to B'; m, b: (N, 3, 3), (N, 3) frame 0 camera -> frame i
    camera; ends3d: (A, B, unit tangent at A into the curve, unit tangent at B into the curve)
    in frame 0's camera coordinates (the end-point answer's: the shape stays exactly that
    answer's); start: (M, 3) a curve near the answer.  The number of control points grows from
    ``k_start`` by halving every knot span (K -> 2 K - 3, at most ``k_max``) while the
    information criterion
    (:func:`bic`) improves and some frame's RMS distance exceeds ``resolution`` times its
    polyline's length.  ``unfold``: at each number of control points, up to this many refits
    from the fitted curve's points in a polyline's order (:func:`unfolded_points`) when the
    fit has folded, each kept if it lowers the cost.  Returns (control points (K, 3),
    weighted cost, per-frame RMS px).
    """
    a, bpt, ta, tb = (np.asarray(v, float) for v in ends3d)
    polys = [pl.as_polyline(p, name=f"frame {i} curve") for i, p in enumerate(polylines)]
    n = len(polys)
    mask = np.ones(n, bool) if polyline_mask is None else np.asarray(polyline_mask, bool)
    lengths = np.array([np.linalg.norm(np.diff(p, axis=0), axis=1).sum() for p in polys])
    best = None
    k = max(int(k_start), 4)
    while True:
        prob = Problem(polys, sigma, k, None, None, 1.0, 1.0)
        prob.poly_w = mask.astype(float)
        prob.smooth_weight = smooth_weight
        prob.rev_weight = [w * reverse_factor for w in prob.rev_weight]
        # from the second number of control points on, the fit starts at the last optimum:
        # every foot searched on its polyline neighbours' stretch (Problem._ordered_feet)
        prob.ordered_feet = bool(unfold) and best is not None
        base, d = _pinned_map(k, a, bpt, ta, tb)
        flat = [j for j in range(3 * k) if j != 2]
        d_red = d[flat]
        if best is None:
            p0 = _pinned_start(start, k, base, d)
        else:
            # the knots of k = 2 k_old - 3 contain the old ones: the old curve exactly, so the
            # refined fit starts at the old optimum and can only improve on it
            u = np.linspace(0.0, 1.0, 20 * k)
            p0 = _pinned_start(Basis(len(best[0])).values(u) @ best[0], k, base, d, u)

        def ctrl_of(p: np.ndarray, base=base, d=d, k=k) -> np.ndarray:
            return base + (d @ p).reshape(k, 3)

        def residual(p, jac=True, prob=prob, ctrl_of=ctrl_of, d_red=d_red):
            r, j, rms = prob.residuals(ctrl_of(p), m, b, jac=jac, poses=False)
            return r, (j @ d_red if jac else None), rms

        p, cost = gauss_newton_tsvd(residual, p0, max_iter, rcond, abs_tol)
        for _ in range(unfold):
            # a fold (the spline running forward, back and forward again over one stretch of
            # the curve: invisible in every image) is a local minimum the steps do not leave;
            # refitted to the curve's own points in the order of a polyline, the fold is gone
            pts = unfolded_points(prob, ctrl_of(p), m, b, mask)
            if pts is None:
                break
            p2, cost2 = gauss_newton_tsvd(
                residual, _pinned_start(pts, k, base, d), max_iter, rcond, abs_tol
            )
            if not cost2 < cost:
                break
            p, cost = p2, cost2
        if unfold and not prob.ordered_feet:
            # then polished with every foot on its polyline neighbours' stretch of the curve
            # (a crossing in some image otherwise holds the fit near it, Problem._ordered_feet)
            prob.ordered_feet, prob._last = True, None
            p, cost = gauss_newton_tsvd(residual, p, max_iter, rcond, abs_tol)
        ctrl = ctrl_of(p)
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        crit = bic(prob, rms, d.shape[1])
        if best is not None and crit >= best[1]:
            break
        best = (ctrl, crit, cost, rms)
        if np.all((rms <= resolution * lengths) | ~mask):
            break
        k_next = 2 * k - 3  # every knot span halved
        if k_next > k_max:
            break
        k = k_next
    return best[0], best[2], best[3]


def _fixed_pose_frames(rec) -> tuple[np.ndarray, np.ndarray]:
    """(m, b) of a reconstruction's poses: frame 0 camera -> frame i camera."""
    rot, tr = rec.rotations(), rec.translations()
    m = np.einsum("nij,kj->nik", rot, rot[0])
    return m, tr - np.einsum("nij,j->ni", m, tr[0])


def _oriented(curves, rec) -> list[np.ndarray]:
    """Every polyline as an array from A' to B' (the end nearer the answer's A' first)."""
    tr = rec.translations()
    out = []
    for i, p in enumerate(curves):
        q = pl.as_polyline(p, name=f"frame {i} curve")
        if np.hypot(*(q[-1] - tr[i, :2])) < np.hypot(*(q[0] - tr[i, :2])):
            q = q[::-1].copy()
        out.append(q)
    return out


@dataclass
class _FixedFrames:
    """The frames a fixed-pose fit uses (frame 0 first: its pose is the curve's coordinates):
    their polylines from A' to B', poses (frame 0 camera -> frame i camera), the end-point
    answer's A, B and end tangents (frame 0 camera), the polylines' lengths (px)."""

    sel: np.ndarray
    polys: list[np.ndarray]
    m: np.ndarray
    bb: np.ndarray
    ends3d: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]
    lengths: np.ndarray
    #: every frame's polyline and pose (``frame_rms_px`` of long sequences)
    polys_all: list[np.ndarray]
    m_all: np.ndarray
    bb_all: np.ndarray


def _fit_fixed(run: CurveRun, ff: _FixedFrames, mask: np.ndarray, start, k0: int, exact: bool):
    """:func:`fit_curve_fixed_poses` on the frames ``ff`` with the options of ``run`` (exact
    end points: the knots grow as the data ask, the model's own floors lowered)."""
    o = run.o
    a3, b3, ta3, tb3 = ff.ends3d
    return fit_curve_fixed_poses(
        ff.polys,
        ff.m,
        ff.bb,
        (a3[0], b3[0], ta3[0], tb3[0]),
        start - start[0] + a3[0],
        sigma=run.sigma,
        k_start=k0,
        k_max=o.max_control_points if exact else k0,
        polyline_mask=mask,
        smooth_weight=o.fixed_pose_smooth_weight * (o.fixed_pose_smooth_factor if exact else 1.0),
        reverse_factor=o.fixed_pose_reverse_factor if exact else 1.0,
        abs_tol=o.fixed_pose_abs_tol,
        resolution=o.fixed_pose_resolution,
        unfold=o.exact_unfold if exact else 0,
    )


def _fit_fixed_restarted(
    run: CurveRun, ff: _FixedFrames, mask: np.ndarray, start, k0: int, exact: bool
):
    """:func:`_fit_fixed`, and for exact end points, when the fit stays stuck above the
    noise-free target (``CurveOptions.exact_restart_rms`` of a polyline's length), again from
    ``exact_restart_control_points``: the lower polyline misfit kept."""
    o = run.o
    out = _fit_fixed(run, ff, mask, start, k0, exact)
    k1 = o.exact_restart_control_points
    if not exact or not k1 or k1 == k0:
        return out
    stuck = (out[2] > o.exact_restart_rms * ff.lengths) & mask
    if not stuck.any():
        return out
    out2 = _fit_fixed(run, ff, mask, start, k1, exact)
    if np.sum(out2[2][mask] ** 2) < np.sum(out[2][mask] ** 2):
        return out2
    return out


def _fixed_frames(run: CurveRun) -> _FixedFrames:
    """The frames of the fixed-pose fit: every frame, or ``run.curve_frames``."""
    rec = run.rec
    m_all, bb_all = _fixed_pose_frames(rec)
    polys_all = _oriented(run.curves, rec)
    sel = np.arange(run.n) if run.curve_frames is None else np.asarray(run.curve_frames, int)
    polys = [polys_all[i] for i in sel]
    lengths = np.array([pl.arc_length(p)[-1] for p in polys])  # px, the fitted frames
    return _FixedFrames(
        sel, polys, m_all[sel], bb_all[sel], rec.points_3d(), lengths, polys_all, m_all, bb_all
    )


def fixed_pose_answer(
    run: CurveRun,
    start: np.ndarray,
    k_start: int,
    mask: np.ndarray,
    extra: dict,
    exact: bool = False,
):
    """The end-point answer with the curve fitted to the polylines, every pose fixed
    (exact end points: the knots grow as the data ask, the model's own floors lowered;
    otherwise the bundle's curve model with the poses held).  A frame whose polyline stays
    beyond ``run.limit`` from that curve is flagged (with given end points) and the curve
    fitted again without it.  Returns (reconstruction, curve3d, ``curve_bundle`` info)."""
    rec, o, n, sigma = run.rec, run.o, run.n, run.sigma
    ff = _fixed_frames(run)
    sel = ff.sel
    mask = np.asarray(mask, bool)[sel]
    ctrl, _, rms = _fit_fixed_restarted(run, ff, mask, start, k_start, exact)
    flagged = list(extra.get("flagged_frames", []))
    if not flagged and run.use_given:
        bad = rms > run.limit
        if bad.any() and bad.sum() <= o.max_flagged_fraction * len(sel):
            flagged = [int(i) for i in sel[np.flatnonzero(bad)]]
            run.flag_warning(flagged, np.bincount(sel, rms, minlength=n))
            mask = ~bad
            dense = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 400)) @ ctrl
            ctrl, _, rms = _fit_fixed_restarted(run, ff, mask, dense, k_start, exact)
    k = ctrl.shape[0]
    rms_all = rms
    if run.curve_frames is not None:  # every frame's distance from the curve (one evaluation)
        rms_all = Problem(ff.polys_all, sigma, k, None, None, 1.0, 1.0).residuals(
            ctrl, ff.m_all, ff.bb_all, jac=False
        )[2]
    u = arc_parameters(ctrl, run.n_out or 200)
    curve3d = Basis(k).values(u) @ ctrl
    prob = Problem(ff.polys, sigma, k, None, None, 1.0, 1.0)
    prob.poly_w = mask.astype(float)
    prob.smooth_weight = o.fixed_pose_smooth_weight
    a3, b3, ta3, tb3 = ff.ends3d
    base, d = _pinned_map(k, a3[0], b3[0], ta3[0], tb3[0])
    # the pinned fit holds A where frame 0 measured it, A' with point_sigma in x and y:
    # that translation of the whole curve adds point_sigma^2 diag(1, 1, 0) to each point's
    # covariance
    stds = curve_point_std(
        prob,
        ctrl,
        ff.m,
        ff.bb,
        u,
        d[[j for j in range(3 * k) if j != 2]],
        xy_var=run.point_sigma**2,
    )
    std, normal_std = (None, None) if stds is None else stds
    info = {
        "control_points": int(k),
        "sigma_px": float(sigma),
        "frame_rms_px": [float(v) for v in rms_all],
        "iterations": 0,
        "converged": True,
        "accepted": False,
        "end_point_dchi2": None,
        **extra,
        "flagged_frames": flagged,
    }
    out = replace(rec, warnings=run.warnings, curve3d_std=std, curve3d_normal_std=normal_std)
    return out, curve3d, info
