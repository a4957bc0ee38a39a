"""The curve bundle's uncertainty: the covariance of the curve's parameters with every pose
marginalised out (:func:`curve_covariance`), the shape's std (:func:`shape_std`), each output
curve point's std (:func:`curve_point_std`), and the widening by another minimum about as low
(:func:`rival_minima_std`) or by the other answer when the gate refuses the bundle
(:func:`refused_std`).
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve.lm import sum_products
from curverecon.curve.residuals import Problem
from curverecon.curve.spline import Basis, BundleResult, oriented_to, shape_and_poses

if TYPE_CHECKING:
    from curverecon.curve.bundle import CurveRun


def curve_covariance(prob: Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
    """Covariance of the curve's parameters with every pose marginalised out: the curve block
    of (J^T J)^+ through the Schur complement on the per-frame pose blocks (residuals in units
    of sigma).  None if it is not finite."""
    _, (u, _, v, w, _), _ = prob.normal_equations(ctrl, m, b)
    try:
        vinv_wt = np.linalg.solve(v[1:], np.transpose(w[1:], (0, 2, 1)))
        s = u - sum_products(w[1:], vinv_wt)
        cov = np.linalg.pinv(s)
    except np.linalg.LinAlgError:
        return None
    return cov if np.all(np.isfinite(cov)) else None


def shape_std(result: BundleResult, prob_k: int, cov: np.ndarray | None) -> np.ndarray | None:
    """Standard deviations of (c, alpha, beta, phi) from the bundle's covariance of the curve's
    parameters (:func:`curve_covariance`), propagated through the end geometry."""
    n_curve = 3 * prob_k - 1
    if cov is None:
        return None
    idx = np.full((prob_k, 3), -1, dtype=int)
    flat = [j for j in range(3 * prob_k) if j != 2]
    idx.reshape(-1)[flat] = np.arange(n_curve)

    def shape_of(ctrl: np.ndarray) -> np.ndarray:
        r = BundleResult(ctrl, result.m, result.b, result.sigma, result.rms, 0.0, 0.0, 0, True)
        return shape_and_poses(r)[0]

    base = shape_of(result.control)
    grad = np.zeros((4, n_curve))
    h = 1e-6 * max(float(np.abs(result.control).max()), 1.0)
    for row in (0, 1, prob_k - 2, prob_k - 1):
        for c in range(3):
            j = idx[row, c]
            if j < 0:
                continue
            ctrl = result.control.copy()
            ctrl[row, c] += h
            d = shape_of(ctrl) - base
            d[3] = (d[3] + np.pi) % (2 * np.pi) - np.pi
            grad[:, j] = d / h
    var = np.einsum("ij,jk,ik->i", grad, cov, grad)
    return np.sqrt(np.clip(var, 0.0, None)) if np.all(np.isfinite(var)) else None


def curve_point_std(
    prob: Problem,
    ctrl: np.ndarray,
    m: np.ndarray,
    b: np.ndarray,
    u: np.ndarray,
    d_red: np.ndarray | None = None,
    cov: np.ndarray | None = None,
    xy_var: float = 0.0,
) -> tuple[np.ndarray, np.ndarray] | None:
    """Standard deviations (pixels) of the fitted curve's points at parameters u, from the
    fit's covariance (residuals in units of sigma, so (J^T J)^-1; the poses marginalised out
    when they were fitted): (the root of the trace of each point's 3x3 covariance, the root of
    the trace of its part across the curve, i.e. projected on the plane normal to the curve's
    tangent there).  The first includes the point's slide along the curve (where on the curve
    parameter u lands), which moves no point of the curve; the second is what a distance from
    the curve is to be compared with.  ``d_red``: the pinned parametrisation of
    :func:`fit_curve_fixed_poses` (poses fixed: the std is then the curve's alone, given the
    end-point answer's poses).  ``cov``: the curve parameters' covariance if already known
    (:func:`curve_covariance`).  ``xy_var``: the variance (pixels^2) of a translation of the
    whole curve in x and y, added to every point's (A' as frame 0 measured it, for the pinned
    fit).  None if the covariance is not finite."""
    if d_red is not None:
        _, jac, _ = prob.residuals(ctrl, m, b, jac=True, poses=False)
        jac = jac @ d_red
        try:
            cov = np.linalg.pinv(jac.T @ jac)
        except np.linalg.LinAlgError:
            return None
    elif cov is None:
        cov = curve_covariance(prob, ctrl, m, b)
        if cov is None:
            return None
    basis = Basis(len(ctrl))
    nb = basis.values(u)
    g = []
    for c in range(3):
        gc = np.zeros((len(u), prob.n_curve))
        col = prob.cidx[:, c]
        ok = col >= 0
        gc[:, col[ok]] = nb[:, ok]
        g.append(gc @ d_red if d_red is not None else gc)
    cov3 = np.empty((len(u), 3, 3))
    for i in range(3):
        gi = g[i] @ cov
        for j in range(i, 3):
            cov3[:, i, j] = cov3[:, j, i] = np.einsum("ij,ij->i", gi, g[j])
    if not np.all(np.isfinite(cov3)):
        return None
    cov3[:, 0, 0] += xy_var
    cov3[:, 1, 1] += xy_var
    tangent = basis.d1(u) @ ctrl
    tangent /= np.maximum(np.linalg.norm(tangent, axis=1, keepdims=True), 1e-300)
    total = np.trace(cov3, axis1=1, axis2=2)
    along = np.einsum("pi,pij,pj->p", tangent, cov3, tangent)
    return np.sqrt(np.clip(total, 0.0, None)), np.sqrt(np.clip(total - along, 0.0, None))


def gap_to_curve(points: np.ndarray, other: BundleResult) -> np.ndarray:
    """Each point's distance (input units) from ``other``'s curve or its mirror image (depth
    negated: the same answer, an exact symmetry of orthographic views), whichever is nearer
    on average."""
    curve = other.curve_points(400)
    return min(
        (pl.distance_to_polyline(points, q)[0] for q in (curve, curve * [1.0, 1.0, -1.0])),
        key=lambda g: float(np.mean(g)),
    )


def accepted_std(run: CurveRun, br: BundleResult, mask: np.ndarray, u_out: np.ndarray):
    """The std of a kept bundle: (shape std (4,) or None, each curve point's std, its part
    across the curve; the two None when the covariance is not finite), from the covariance of
    the curve's parameters with every pose marginalised out."""
    k = br.control.shape[0]
    prob = Problem(
        oriented_to(run.curves, br),
        br.sigma,
        k,
        run.ends,
        run.tangents,
        run.point_sigma,
        float(np.radians(run.tangent_sigma_deg)),
    )
    prob.poly_w = mask.astype(float)
    prob.smooth_weight = run.o.bundle_smooth_weight
    # the covariance without the reverse term: it measures the same polyline points again (a
    # guard against hidden detours, no information of its own), and its distances to a noisy
    # polyline's jagged segments fake information along the curve.  With it, polylines only,
    # Bezier seed 1300 (0.5 px, 12 frames) at the true curve and poses: alpha, beta, phi std
    # 2.7, 4.5, 9.6 degrees on noisy polylines against 5.4, 7.9, 12.3 on noise-free ones (4
    # control points: 0.32, 0.88, 0.92 against 0.58, 1.17, 1.09, the spread over noise draws
    # about 0.85, 1.1, 0.95); without it 5.5, 8.0, 12.4 (0.59, 1.17, 1.10) on both
    prob.rev_weight = [0.0] * prob.n
    cov = curve_covariance(prob, br.control, br.m, br.b)
    std = shape_std(br, k, cov)
    stds = curve_point_std(prob, br.control, br.m, br.b, u_out, cov=cov)
    point_std, normal_std = (None, None) if stds is None else stds
    return std, point_std, normal_std


def rival_minima_std(
    run: CurveRun, br: BundleResult, pts: np.ndarray, shape_n: np.ndarray, stds: tuple
) -> tuple:
    """``stds`` (shape std, curve point std, its part across the curve) widened by another
    start's minimum about as low (``CurveOptions.rival_minima_std``): the data leave the two
    open, and the answer's RMS error includes the gap to the rival weighted by its probability
    p = 1 / (1 + exp(dcost / 2)).  ``pts``: the answer's curve points (frame 0 camera)."""
    from curverecon.model.pose import normalise

    std, point_std, normal_std = stds
    rival = min((r for r in run.tried if r is not br), key=lambda r: r.cost, default=None)
    if not (run.o.rival_minima_std and run.use_given and rival is not None):
        return stds
    p_rival = 1.0 / (1.0 + np.exp(min(0.5 * (rival.cost - br.cost), 700.0)))
    gap = gap_to_curve(pts, rival)
    r_shape = normalise(*shape_and_poses(rival)[:2])[0]
    diff = np.asarray(r_shape, float) - np.asarray(shape_n, float)
    diff[3] = (diff[3] + np.pi) % (2.0 * np.pi) - np.pi
    if std is not None:
        std = np.sqrt(std**2 + p_rival * diff**2)
    if normal_std is not None:
        normal_std = np.sqrt(normal_std**2 + p_rival * gap**2)
        point_std = np.sqrt(point_std**2 + p_rival * gap**2)
    if p_rival >= run.o.rival_warning_probability:
        run.warnings.append(
            f"another minimum of the curve bundle fits about as well (cost "
            f"{rival.cost - br.cost:+.1f}, probability {p_rival:.2f}; its curve up to "
            f"{float(np.max(gap)):.1f} px away): the std include the gap"
        )
    return std, point_std, normal_std


def refused_std(run: CurveRun, out, curve3d: np.ndarray, br: BundleResult, verdict):
    """The end-point answer ``out`` kept over the bundle ``br`` (the gate's ``verdict``), its
    std widened by their disagreement (``CurveOptions.refused_std_disagreement``)."""
    o = run.o
    if out.std is not None:
        # the two answers disagree beyond the end points' 99 % region: one of the models
        # (the end points' or the curve's) is off, and refusals come most often where the
        # end-point answer itself is (1 px, tuning seeds 5000-5014: |error| / std RMS 1.7
        # on refused scenes, up to 3.7).  Its std is scaled (a Birge ratio) by the least
        # factor that brings the bundle's shape inside its 99 % region.
        scale = float(np.sqrt(max(float(verdict.dchi2) / o.never_worse_dchi2, 1.0)))
        std_out = out.std * scale
        if o.refused_std_disagreement:
            # ... and, per parameter, the two answers' difference is added in quadrature:
            # which model is off is not known, so the answer kept is uncertain by at least
            # its distance from the other one
            diff = np.asarray(verdict.shape_n, float) - np.asarray(run.rec.shape, float)
            diff[3] = (diff[3] + np.pi) % (2.0 * np.pi) - np.pi
            std_out = np.sqrt(std_out**2 + diff**2)
        out = replace(out, std=std_out)
    if o.refused_std_disagreement and out.curve3d_normal_std is not None:
        # ... and likewise each curve3d point by its distance from the bundle's curve: the
        # fixed-pose curve's std is the curve's alone given the end-point answer's poses,
        # which the refusal says are off (clothoid seed 1201, 1 px, 12 frames, a refused
        # noise draw: the curve 1.7 % of its length off, its std across the curve 0.04 %)
        gap = gap_to_curve(curve3d, br)
        out = replace(
            out,
            curve3d_std=np.sqrt(out.curve3d_std**2 + gap**2),
            curve3d_normal_std=np.sqrt(out.curve3d_normal_std**2 + gap**2),
        )
    return out
