"""The joint fit of the curve bundle: every frame's pose and one 3-D B-spline fitted to every
polyline (:func:`bundle_adjust`), and the polylines-only refit of uneven frames
(:func:`resect_uneven_frames`).

Stages of :func:`bundle_adjust`, each a function here: a coarse curve (``K_COARSE`` control
points; with ``COARSE_POINTS`` set, on polylines thinned to about that many points that stand for
the full ones, ``Problem.stand_for``) with the start poses; every frame's pose searched again
against that curve (``pose_search``; a regauge when frame 0's own pose moves); the coarse fit
again (:func:`_coarse_rounds`); then the full curve; then a polish with robust ends (``END_POLISH``:
a traced end hooked back along the line of sight ends its polyline at the fold); a folded curve
refitted with its feet in the polylines' order (:func:`_full_stage`).  A flat start searches every
frame's pose against the flat curve before the first fit (``resect_first``): the end-point
answer's poses, made for another curve, bent the flat curve into a wrong minimum (trace bench
seed 0: every flat start from those poses lost, every one from the searched poses found the
noise level).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from curverecon.curve import lm
from curverecon.curve import polyline as pl
from curverecon.curve.fixed_poses import is_folded, unfolded_points
from curverecon.curve.lm import MAX_ITER
from curverecon.curve.pose_search import max_angle_deg, regauge, resect_all
from curverecon.curve.residuals import SIGMA_FLOOR, SMOOTH_WEIGHT, Problem, thinned
from curverecon.curve.section4 import noise_level
from curverecon.curve.spline import Basis, BundleResult, bundle_error, fit_spline, oriented_to

#: Control points of the curve's cubic B-spline (default; fewer for short polylines).
N_CONTROL = 12


#: After the full-curve fit, a polish in which the offsets of A', B' from the polyline's end
#: points are robust (Huber, ``HUBER_K``) while A', B' themselves must lie on the polyline
#: (quadratic): a traced end that hooks back along the line of sight ends the polyline at the
#: fold, not at A'.  Held as hard constraints such ends (2.5-25 px off) bent the whole curve
#: (trace bench seeds 6 and 7: 1.5 % and 4.8 % of the length, 0.4 % from the true curve's
#: start); robust from the start they let the curve wander (seed 0 from flat starts: every
#: start lost), so they are relaxed only once the fit has found its basin.
END_POLISH = True


#: Control points of the coarse stage (smoother cost landscape for the pose search).
K_COARSE = 6


#: Polyline points (about) of the coarse stage and its pose search (:func:`thinned`; 0: all,
#: the default).  Off, after measuring it on: a 6-point curve and the poses' basin need no 150
#: points per frame, and at 40 the stage's LM runs and pose searches took half the time (bench
#: time_20, seed 1400: coarse LM 0.52 s -> 0.25 s of the bundle's 1.27 s; time_20 ratio 2.89 ->
#: 2.52, held-out seeds 2000 and 2100 2.59 -> 2.23 and 2.48 -> 2.24; ``make bench`` 3.20 ->
#: 2.83), and curve_05 (12 frames, 0.5 px, seeds 1100-1107) kept every count.  But every start
#: lands in other basins, and where the data have several, that is a lottery the default must not
#: be moved by without a gain in accuracy: the trace bench's seed 20 (traced polylines, 0.08 px)
#: took the wrong end order (the right order's best fit 0.90 px RMS against 0.08 px with every
#: point; trace_end_identity_rate 21 of 21 -> 20 of 21); bench seed random 1203 (1 px) reached
#: a lower cost (2212.5 against 2233.1; the truth-start fit's 2255.3) with phi 4.5 std off
#: (std_coverage_3sigma 0.990 -> 0.984; held out 2100-2107 1.000 both, curve3d normal coverage
#: 0.987 -> 1.000); sharp-ends 6001 with the joint refits a basin of cost 3244 against 2652.
COARSE_POINTS = 0


#: Rounds of per-frame pose search against the coarse curve.
RESECT_ROUNDS = 2


#: ... in the coarse stages (they only need the basin).
COARSE_REL_TOL = 1e-4


#: Iteration cap of each coarse LM run.
COARSE_MAX_ITER = 30


#: A frame whose RMS distance from the fitted curve exceeds RMS_LIMIT_SIGMA * sigma +
#: RMS_LIMIT_PX does not fit (the coarse stage's reweighting limit; the flag and the warning of
#: :func:`refine_reconstruction` use ``CurveOptions.flag_rms_sigma``, ``flag_rms_px``).
RMS_LIMIT_SIGMA = 3.0


RMS_LIMIT_PX = 1.0


#: A frame whose RMS distance exceeds UNEVEN_RATIO times the median frame's (plus sigma / 4,
#: and at least sigma) fits clearly worse than the others: the coarse stage down-weights it
#: before the pose search, and :func:`refine_reconstruction` tries the second start.
UNEVEN_RATIO = 1.5


def _uneven_level(rms: np.ndarray, sigma: float) -> float:
    """RMS distance above which a frame fits clearly worse than the others (pixels)."""
    return max(UNEVEN_RATIO * float(np.median(rms)) + 0.25 * sigma, sigma)


def _uneven(rms: np.ndarray, sigma: float) -> bool:
    """Whether some frame fits clearly worse than the others (a pose on a wrong branch)."""
    return bool(np.max(rms) > _uneven_level(rms, sigma))


def calls_for_restart(rms: np.ndarray, sigma: float) -> bool:
    """Whether a fit calls for another start: some frame fits clearly worse than the others, or
    some frame does not fit at all (``RMS_LIMIT_*``: every frame can be equally far off)."""
    return _uneven(rms, sigma) or bool(np.max(rms) > RMS_LIMIT_SIGMA * sigma + RMS_LIMIT_PX)


def bundle_adjust(
    polylines: Sequence[np.ndarray],
    rotations: np.ndarray,
    translations: np.ndarray,
    curve0: np.ndarray,
    *,
    n_control: int | None = None,
    ends: np.ndarray | None = None,
    tangents: np.ndarray | None = None,
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    max_iter: int = MAX_ITER,
    polyline_mask: np.ndarray | None = None,
    resect_first: bool = False,
    smooth_weight: float = SMOOTH_WEIGHT,
    order_tol: float = 0.0,
    twin_m: np.ndarray | None = None,
    twin_deg: float = 0.0,
    twin_cost: float = np.inf,
    twin_cost_ratio: float = 1.0,
    twin_iter: int = 0,
) -> BundleResult:
    """Refine the poses and the 3-D curve jointly against every frame's polyline.

    polylines: N arrays (M_i, 2) from A' to B' (pixels).
    rotations, translations: (N, 3, 3), (N, 3) start poses, ``X_cam = R_i X_curve + t_i``.
    curve0: (K0, 3) start curve in frame 0's camera coordinates from A to B (e.g. ``curve3d``).
    n_control: control points of the spline (default ``N_CONTROL``, fewer for short polylines).
    ends: optional (N, 2, 2) given A', B' per frame; tangents: optional (N, 2, 2) given image
        tangent directions at A and B (any sign); with their sigmas (pixels, degrees).
    resect_first: search every frame's pose (but frame 0's) against the start curve before
        the first fit (a start curve that the start poses were not made for).
    polyline_mask: optional (N,) bool, False for frames whose polyline is left out of the fit
        (flagged as contradicting the given end points and tangents; needs ``ends``).
    smooth_weight: the difference penalty's weight (``CurveOptions.bundle_smooth_weight``).
    order_tol: above 0, a curve folded over itself (:func:`is_folded` with this tolerance, in
        sigma) is refitted from its points in a polyline's order with every foot in the
        polylines' order (``CurveOptions.bundle_order_tol``); 0 never.
    twin_m: another run's coarse-stage poses (``BundleResult.coarse_m``): when every frame's
        pose m at the end of this run's coarse stage is within ``twin_deg`` degrees of it,
        the run stops there (``stopped``, cost infinite): it would retrace the other run
        (``CurveOptions.frame0_branch_same_deg``).
    twin_iter: with ``twin_m``, above 0: the coarse LM runs before the first pose search stop
        after this many iterations, and the twin test is also made after each pose search
        (``CurveOptions.frame0_branch_first_iter``).
    twin_cost, twin_cost_ratio: the run also stops after its coarse stage (``stopped``) when
        its cost there exceeds ``twin_cost_ratio`` times ``twin_cost`` (another run's
        ``coarse_cost``; ``CurveOptions.restart_coarse_cost_ratio``).

    Stages: a coarse curve (``K_COARSE`` control points; with ``COARSE_POINTS`` set, on every
    polyline thinned to about that many points, weighted to stand for the full one) with the
    start poses; every
    frame's pose searched again against that curve (``resect_all``: the wrong-branch poses the
    end tangents leave are far from the right ones, beyond LM's reach) and the coarse fit
    repeated (``RESECT_ROUNDS``); then the full curve on the full polylines.

    Returns a :class:`BundleResult` (curve and poses in frame 0's camera coordinates).
    Raises ``CurveReconError`` for bad input.
    """
    setup, m, b, k, curve0 = _checked_setup(
        polylines,
        rotations,
        translations,
        curve0,
        n_control=n_control,
        ends=ends,
        tangents=tangents,
        point_sigma=point_sigma,
        tangent_sigma_deg=tangent_sigma_deg,
        polyline_mask=polyline_mask,
        smooth_weight=smooth_weight,
    )
    k_coarse = min(K_COARSE, k)
    prob = setup.problem(k_coarse, coarse=True)
    ctrl = fit_spline(curve0 - [0.0, 0.0, curve0[0, 2]], k_coarse)
    if resect_first:
        # the start poses were made for another curve: every frame's pose searched against the
        # start curve before it is bent to fit them
        found = resect_all(prob, ctrl, m, b, [i for i in range(1, len(m)) if setup.use_poly[i]])
        _take_better_poses(m, b, found, _frame_costs(prob, ctrl, m, b))
    cost_start = float(np.sum(prob.residuals(ctrl, m, b, jac=False)[0] ** 2))
    coarse = {"max_iter": min(max_iter, COARSE_MAX_ITER), "rel_tol": COARSE_REL_TOL}
    # a second start that may retrace another run (``twin_m``): its pose search comes early, and
    # it stops as soon as its poses are the other run's again
    early = twin_m is not None and twin_iter > 0
    first = {**coarse, "max_iter": min(coarse["max_iter"], int(twin_iter))} if early else coarse
    (ctrl, m, b), cost, total_it, _ = lm.lm_bundle(prob, (ctrl, m, b), **first)
    twin = twin_m if early else None
    ctrl, m, b, cost, it, retrace = _coarse_rounds(
        setup, prob, (ctrl, m, b), cost, first, coarse, twin, twin_deg
    )
    total_it += it
    coarse_cost = float(cost)
    if (
        retrace
        or (twin_m is not None and max_angle_deg(m, twin_m) < twin_deg)
        # far above the other run at the same stage: no rival of it
        # (CurveOptions.restart_coarse_cost_ratio)
        or coarse_cost > twin_cost_ratio * twin_cost
    ):
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        return BundleResult(
            ctrl, m, b, setup.sigma, rms, cost_start, np.inf, total_it, False, [], m.copy(), True,
            coarse_cost,
        )  # fmt: skip
    coarse_m = m.copy()
    prob, (ctrl, m, b), cost, it, converged = _full_stage(
        setup, prob, (ctrl, m, b), k, k_coarse, max_iter, order_tol
    )
    total_it += it
    rms = prob.residuals(ctrl, m, b, jac=False)[2]
    return BundleResult(
        ctrl,
        m,
        b,
        setup.sigma,
        rms,
        cost_start,
        cost,
        total_it,
        converged,
        coarse_m=coarse_m,
        coarse_cost=coarse_cost,
    )


@dataclass
class _Setup:
    """The checked data of one :func:`bundle_adjust` run, from which every stage makes its
    problem (:meth:`problem`)."""

    polys: list[np.ndarray]
    sigma: float
    ends: np.ndarray | None
    tangents: np.ndarray | None
    point_sigma: float
    tangent_sigma: float
    use_poly: np.ndarray
    smooth_weight: float

    def problem(self, kk: int, coarse: bool = False) -> Problem:
        """The problem with ``kk`` control points (``coarse``: on the polylines thinned to
        ``COARSE_POINTS``, when set)."""
        if coarse and COARSE_POINTS > 0:
            prob = Problem(
                [thinned(p, COARSE_POINTS) for p in self.polys],
                self.sigma,
                kk,
                self.ends,
                self.tangents,
                self.point_sigma,
                self.tangent_sigma,
            )
            prob.stand_for(self.polys)
        else:
            prob = Problem(
                self.polys,
                self.sigma,
                kk,
                self.ends,
                self.tangents,
                self.point_sigma,
                self.tangent_sigma,
            )
        prob.poly_w = self.use_poly.astype(float)
        prob.smooth_weight = float(self.smooth_weight)
        return prob


def _checked_setup(
    polylines: Sequence[np.ndarray],
    rotations: np.ndarray,
    translations: np.ndarray,
    curve0: np.ndarray,
    *,
    n_control: int | None,
    ends: np.ndarray | None,
    tangents: np.ndarray | None,
    point_sigma: float,
    tangent_sigma_deg: float,
    polyline_mask: np.ndarray | None,
    smooth_weight: float,
) -> tuple[_Setup, np.ndarray, np.ndarray, int, np.ndarray]:
    """:func:`bundle_adjust`'s input checked: (setup, start poses m, b (frame 0 camera ->
    frame i camera), control points K, start curve).  Raises ``CurveReconError``."""
    rot = np.asarray(rotations, float)
    tr = np.asarray(translations, float)
    n = len(polylines)
    if n < 2:
        raise bundle_error(f"the curve bundle needs at least 2 frames, got {n}")
    if rot.shape != (n, 3, 3) or tr.shape != (n, 3):
        raise bundle_error(f"rotations/translations must have shapes ({n}, 3, 3) and ({n}, 3)")
    if not (np.all(np.isfinite(rot)) and np.all(np.isfinite(tr))):
        raise bundle_error("rotations/translations contain NaN or infinite values")
    if np.abs(np.einsum("nij,nkj->nik", rot, rot) - np.eye(3)).max() > 1e-6:
        raise bundle_error("rotations are not orthonormal")
    polys = [pl.as_polyline(p, name=f"frame {i} curve") for i, p in enumerate(polylines)]
    curve0 = np.asarray(curve0, float)
    if curve0.ndim != 2 or curve0.shape[1] != 3 or len(curve0) < 4:
        raise bundle_error("the start curve must be at least 4 points [x, y, z]")
    if not np.all(np.isfinite(curve0)):
        raise bundle_error("the start curve contains NaN or infinite values")
    for name, arr in (("ends", ends), ("tangents", tangents)):
        # NaN tangents mean "not given" in that frame
        if arr is not None and (
            np.shape(arr) != (n, 2, 2)
            or np.any(np.isinf(np.asarray(arr, float)))
            or (name == "ends" and not np.all(np.isfinite(np.asarray(arr, float))))
        ):
            raise bundle_error(f"{name}: expected {n} pairs of finite 2-D vectors")
    # Polylines run from A to B; A's image is t_i[:2].
    for i, p in enumerate(polys):
        if np.hypot(*(p[-1] - tr[i, :2])) < np.hypot(*(p[0] - tr[i, :2])):
            polys[i] = p[::-1].copy()
    m_pts = min(len(p) for p in polys)
    k = int(n_control) if n_control is not None else int(np.clip(m_pts // 6, 5, N_CONTROL))
    if k < 4:
        raise bundle_error(f"n_control must be at least 4, got {k}")
    sigma = max(float(np.median([noise_level(p) for p in polys])), SIGMA_FLOOR)
    m = np.einsum("nij,kj->nik", rot, rot[0])  # R_i R_0^T: frame 0 camera -> frame i camera
    b = tr - np.einsum("nij,j->ni", m, tr[0])
    ends_arr = None if ends is None else np.asarray(ends, float)
    tans_arr = None if tangents is None else np.asarray(tangents, float)
    ts = float(np.radians(tangent_sigma_deg))

    use_poly = np.ones(n, bool) if polyline_mask is None else np.asarray(polyline_mask, bool)
    if use_poly.shape != (n,) or (ends_arr is None and not use_poly.all()):
        raise bundle_error(
            f"polyline_mask: expected {n} flags (and given end points to leave any out)"
        )
    setup = _Setup(
        polys, sigma, ends_arr, tans_arr, float(point_sigma), ts, use_poly, smooth_weight
    )
    return setup, m, b, k, curve0


def _frame_costs(prob: Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N,) each frame's cost in the current state."""
    r, _, _, rows, _ = prob.evaluate(ctrl, m, b, jac=False)
    return prob.frame_costs(r, rows)


def _take_better_poses(m: np.ndarray, b: np.ndarray, found: dict, cur: np.ndarray) -> bool:
    """Every frame whose searched pose (``found``, of ``pose_search.resect_all``) costs less
    than its current cost ``cur`` takes it (m, b changed in place).  Returns whether some
    frame's cost fell below 0.9 of its current one."""
    changed = False
    for i, (mi, bi, ci) in found.items():
        if ci < cur[i]:
            changed = changed or ci < 0.9 * cur[i]
            m[i], b[i] = mi, bi
    return changed


def _coarse_rounds(
    setup: _Setup,
    prob: Problem,
    state: tuple,
    cost: float,
    first: dict,
    coarse: dict,
    twin_m: np.ndarray | None,
    twin_deg: float,
):
    """The coarse stage's rounds (``RESECT_ROUNDS``): frames that fit clearly worse than the
    others down-weighted and the curve refitted, every frame's pose searched against the coarse
    curve, the coarse fit again; until no search lowers a frame's cost by a tenth.  ``twin_m``:
    stop after a pose search that leaves every pose within ``twin_deg`` of it.  Returns (ctrl,
    m, b, cost, iterations, stopped there)."""
    ctrl, m, b = state
    n, sigma = len(m), setup.sigma
    limit = RMS_LIMIT_SIGMA * sigma + RMS_LIMIT_PX
    total_it = 0
    for rnd in range(int(RESECT_ROUNDS)):
        # frames that do not fit (wrong pose branch) bend the coarse curve: refit it with them
        # down-weighted, then search their poses against the cleaner curve
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        if _uneven(rms, sigma):
            ref = min(limit, _uneven_level(rms, sigma))
            prob.frame_w = 1.0 / (1.0 + (rms / ref) ** 4)
            lm_opts = first if rnd == 0 else coarse
            (ctrl, m, b), _, it, _ = lm.lm_bundle(prob, (ctrl, m, b), **lm_opts)
            total_it += it
            prob.frame_w = np.ones(n)
        cur = _frame_costs(prob, ctrl, m, b)
        found = resect_all(prob, ctrl, m, b, [i for i in range(n) if setup.use_poly[i]])
        changed = _take_better_poses(m, b, found, cur)
        if not np.allclose(m[0], np.eye(3), atol=1e-12):
            ctrl, m, b = regauge(ctrl, m, b)
        if twin_m is not None and max_angle_deg(m, twin_m) < twin_deg:
            return ctrl, m, b, cost, total_it, True
        (ctrl, m, b), cost, it, _ = lm.lm_bundle(prob, (ctrl, m, b), **coarse)
        total_it += it
        if not changed:
            break
    return ctrl, m, b, cost, total_it, False


def _full_stage(
    setup: _Setup,
    prob: Problem,
    state: tuple,
    k: int,
    k_coarse: int,
    max_iter: int,
    order_tol: float,
):
    """After the coarse stage: the full curve (``k`` control points) on the full polylines,
    the polish with robust ends (``END_POLISH``), and a folded curve refitted with its feet in
    the polylines' order (``order_tol``).  Returns (problem, state, cost, iterations,
    converged)."""
    ctrl, m, b = state
    converged, total_it, cost = True, 0, np.inf
    if k > k_coarse or not END_POLISH:
        # the full curve on the full polylines (the coarse stage's were thinned)
        if k > k_coarse:
            ctrl = fit_spline(prob.basis.values(np.linspace(0.0, 1.0, 200)) @ ctrl, k)
        prob = setup.problem(k)
        (ctrl, m, b), cost, it, converged = lm.lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    if END_POLISH:
        prob = setup.problem(k)
        prob.robust_ends = True
        (ctrl, m, b), cost, it, converged = lm.lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    if order_tol > 0.0 and is_folded(prob, ctrl, m, b, order_tol):
        # the spline has folded over itself (forward, back, forward along one stretch): with
        # the nearest feet its strands share the polyline points and fit the noise, a cost no
        # single curve reaches; refitted with the feet in the polylines' order, kept whatever
        # its cost (``CurveOptions.bundle_order_tol``), from the curve's points at the feet in
        # a polyline's order (they run along the curve once)
        pts = unfolded_points(prob, ctrl, m, b, prob.poly_w > 0.0)
        if pts is not None:
            ctrl = fit_spline(pts, k)
        prob.ordered_feet = True
        (ctrl, m, b), cost, it, converged = lm.lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    return prob, (ctrl, m, b), cost, total_it, converged


def resect_uneven_frames(
    result: BundleResult,
    polylines: Sequence[np.ndarray],
    *,
    smooth_weight: float = SMOOTH_WEIGHT,
    max_iter: int = MAX_ITER,
) -> BundleResult:
    """A bundle whose frames fit unevenly (:func:`_uneven`: a few frames on a wrong pose
    branch, the others at the noise level) refitted with those frames left out, their poses
    searched against that curve (:func:`resect_all`, the full curve rather than the coarse
    stage's), then every frame together again; the result with the lower cost is returned.
    No given end points or tangents (polylines only).

    Polylines only, helix seed 1300 (bench, 0.5 px, 12 frames): the start from the end-point
    answer left frame 9 at 6.2 px RMS (the others 0.5 px) and phi 36 degrees off; seven flat
    starts from other frames' polylines fitted no better (2-7 px); the coarse stage's search
    (6 control points) missed the pose that the full curve finds."""
    sigma = result.sigma
    if not _uneven(result.rms, sigma):
        return result
    polys = oriented_to(polylines, result)
    n, k = len(polys), len(result.control)
    bad = result.rms > _uneven_level(result.rms, sigma)
    if bad.sum() > n // 3:
        return result
    prob = Problem(polys, sigma, k, None, None, 1.0, 1.0)
    prob.smooth_weight = float(smooth_weight)
    prob.robust_ends = END_POLISH
    prob.frame_w = np.where(bad, 1e-6, 1.0)
    state = (result.control.copy(), result.m.copy(), result.b.copy())
    (ctrl, m, b), _, it0, _ = lm.lm_bundle(prob, state, max_iter)
    r, _, _, rows, _ = prob.evaluate(ctrl, m, b, jac=False)
    cur = prob.frame_costs(r, rows) / prob.frame_w
    m, b = m.copy(), b.copy()
    for i, (mi, bi, ci) in resect_all(prob, ctrl, m, b, np.flatnonzero(bad)).items():
        if ci < cur[i]:
            m[i], b[i] = mi, bi
    if not np.allclose(m[0], np.eye(3), atol=1e-12):
        ctrl, m, b = regauge(ctrl, m, b)
    prob.frame_w = np.ones(n)
    (ctrl, m, b), cost, it, conv = lm.lm_bundle(prob, (ctrl, m, b), max_iter)
    if not cost < result.cost:
        return result
    rms = prob.residuals(ctrl, m, b, jac=False)[2]
    return BundleResult(
        ctrl,
        m,
        b,
        sigma,
        rms,
        result.cost_start,
        cost,
        result.iterations + it0 + it,
        conv,
        list(result.warnings),
    )


def _end_region_chi2(
    polys: list[np.ndarray],
    ctrl: np.ndarray,
    m: np.ndarray,
    b: np.ndarray,
    sigma: float,
    fraction: float,
) -> np.ndarray:
    """(2,) sums over the frames of the squared distances (units of sigma) of the polyline
    points in the first and the last ``fraction`` of each polyline's points from the projected
    curve (A's end, B's end)."""
    dense = Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 60 * len(ctrl))) @ ctrl
    out = np.zeros(2)
    for i, q in enumerate(polys):
        proj = (dense @ m[i].T + b[i])[:, :2]
        h = max(int(round(fraction * len(q))), 3)
        for e, part in enumerate((q[:h], q[-h:])):
            d, _ = pl.distance_to_polyline(part, proj)
            out[e] += float(np.sum(d * d)) / sigma**2
    return out
