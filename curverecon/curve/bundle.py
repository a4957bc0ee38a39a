"""Curve-aware bundle adjustment: poses and the 3-D curve fitted jointly to every frame's polyline.

The pipeline's shape and poses come from A', B' and the end tangents alone; when the tangents are
estimated from noisy polylines (``polyline.end_tangents``) they are off by degrees at
foreshortened ends and so are the poses, and section 4 (``curve3d``) inherits the error.  Here
the whole polyline of every frame is used: starting from the pipeline's poses and curve, the
per-frame poses and a 3-D curve model are refined jointly so that each frame's projected curve
fits that frame's polyline (maximum likelihood for Gaussian pixel noise on the polyline points).

Model.  Body frame = frame 0's camera coordinates (the contract's ``curve3d`` frame), so frame 0's
pose is the identity (gauge) and frame i maps ``X_i = M_i X_0 + b_i`` (orthographic, unit scale:
keep x, y).  The curve is a clamped cubic B-spline ``X(u) = sum_k N_k(u) P_k``, u in [0, 1], with
``X(0) = P_0 = A`` and ``X(1) = P_{K-1} = B``; A's depth is fixed at 0 (the depth gauge).
Parameters: the control points (3K - 1) and per frame i >= 1 a rotation increment (3, applied as
``M_i <- exp([w]x) M_i`` after each step) and the image translation (2).

Residuals (in units of the pixel noise sigma, estimated from the polylines): for every interior
polyline point q, the signed distance to the projected curve along its normal at the foot point
(closest point, found on a dense sampling and polished by Newton steps; its derivative is the
normal component of the curve point's derivative - the foot point's own motion drops out at the
optimum); for the first and last polyline points the 2-D offsets from the projected ends A, B.
That forward term alone does not see a detour of the curve that no polyline point is near (seen:
a loop hidden along the lines of sight, 34 % of the length off with every frame fitting at the
noise level), so a light reverse term adds the distances of fixed curve samples from each
polyline (``REVERSE_WEIGHT`` of the forward term's weight: a detour many sigma away costs a lot,
while the small bias of distances to a noisy polyline stays negligible).  Given A', B' and
tangents (input with ``tangent_A``/``tangent_B``) add their residuals in units of
``point_sigma`` / ``tangent_sigma``.  Huber (k = 3 sigma) on the polyline terms keeps stray
points from dragging the fit.

Regulariser.  Sliding control points along the curve changes the curve's shape only to second
order, so the normal equations are nearly singular along those directions (the spline's
parametrisation is not determined by the images; without it LM crept for 60+ iterations).  A
penalty on the fourth differences of the control points P_2 .. P_{K-3} (those with uniform knot
triples: zero for every cubic polynomial curve; it favours an even parametrisation) removes that
freedom; its weight is ``SMOOTH_WEIGHT`` relative to one polyline point's residual
(``CurveOptions.bundle_smooth_weight``).  The curves fitted are not cubics: a heavy penalty pulls
the curve towards one, a bias of the end tangents (the shape) that the covariance, which counts
the penalty as information, does not show; so it is kept light, enough to fix the
parametrisation.  The two control points at each end are left out: including them bent the end
tangents (2 degrees on alpha, noise-free).

Levenberg-Marquardt (a few hundred residuals per frame and 3K + 5(N - 1) parameters): every
frame's rows are evaluated at once (:meth:`_Problem.evaluate`; the projected curve per knot span
as a cubic, so foot points cost a gather of 8 coefficients) and the normal equations are formed
in blocks, the 5 x 5 pose blocks (a frame's rows see only its own pose) eliminated by their
Schur complement (:func:`_schur_solve`): O(N) per step, no dense Jacobian of all the poses (the
same steps as the dense solve, to rounding; the covariance of the curve likewise,
:func:`_curve_covariance`).  Stages (:func:`bundle_adjust`): a coarse curve (``K_COARSE``
control points; with ``COARSE_POINTS`` set, on polylines thinned to about that many points that
stand for the full ones, :meth:`_Problem.stand_for`) with the start poses; every frame's pose
searched again against that curve (:func:`_resect_starts`: a sweep over the poses that put A, B
on the polyline's ends - the wrong-branch poses that degree-off end tangents leave are beyond
LM's reach - refined for every frame at once by :func:`_resect_all`, and a regauge when frame
0's own pose moves); the coarse fit again; then the full curve; then a polish with robust ends
(``END_POLISH``: a traced end hooked back along the line of sight ends its polyline at the
fold); then, where the polyline residuals cluster along the curve (:meth:`_Problem.span_misfit`:
a bend or wiggle the spline misses), every knot span halved while Akaike's criterion improves
(``CurveOptions.bundle_max_control_points``, ``bundle_misfit_z``). :func:`refine_reconstruction`
retries from frame 0's polyline at depth 0 when a frame still fits clearly worse than the others
(``UNEVEN_RATIO``), then from other frames' polylines (:func:`bundle_from_frame`,
``CurveOptions.bundle_extra_starts``), and keeps the lowest cost. A flat start searches every
frame's pose against the flat curve before the first fit (``resect_first``): the end-point
answer's poses, made for another curve, bent the flat curve into a wrong minimum (trace bench
seed 0: every flat start from those poses lost, every one from the searched poses found the
noise level).

Afterwards the shape (c, alpha, beta, phi) and the end tangents come from the fitted curve and
every frame's pose from its fitted rotation (``shape_and_poses``), in the conventions of
docs/CONVENTIONS.md.

Given end points and tangents (:func:`refine_reconstruction`, ``CurveOptions``): they enter the
fit as measurements with their sigmas; a frame whose polyline contradicts them is flagged and
left out; the bundle's shape is kept only inside the end points' 99 % confidence region (their
profile chi2, in units of their own variance factor), else, and always for exact (noise-free)
end points, the end-point answer stays and the curve alone is fitted with every pose fixed and
its ends and end tangent lines pinned (:func:`fit_curve_fixed_poses`: truncated-SVD
Gauss-Newton, knot spans halved while the information criterion improves; for exact end
points from ``CurveOptions.exact_start_control_points``, a folded fit refitted from its own points
in a polyline's order, :func:`_unfolded_points`, and the feet searched in the polylines' order,
:meth:`_Problem._ordered_feet`; a fit left above the noise-free target, some frame's RMS over
``CurveOptions.exact_restart_rms`` of its polyline's length, run again from
``exact_restart_control_points`` and the lower misfit kept).  Each output curve point gets a
std from the fit's covariance (:func:`curve_point_std`).
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import BSpline

from curverecon.curve import polyline as pl
from curverecon.curve.bundle_kernel import (
    basis_rows,
    end_rows,
    foot_parameters,
    forward_rows,
    longest_nondecreasing,
    nearest_distances,
    polyline_normal_blocks,
    polyline_rows,
    segment_offsets,
    sweep_distances,
    tangent_rows,
)
from curverecon.curve.section4 import noise_level
from curverecon.model.pose import rotations as pose_rotations
from curverecon.model.pose import translations as pose_translations
from curverecon.options import CurveOptions

#: Control points of the curve's cubic B-spline (default; fewer for short polylines).
N_CONTROL = 12
#: Weight of the difference penalty (order DIFF_ORDER) relative to one polyline point's residual:
#: the default of ``CurveOptions.bundle_smooth_weight`` (the reason for its value there).
SMOOTH_WEIGHT = CurveOptions.bundle_smooth_weight
#: Huber threshold of the polyline-point residuals, in units of sigma.
HUBER_K = 3.0
#: After the full-curve fit, a polish in which the offsets of A', B' from the polyline's end
#: points are robust (Huber, ``HUBER_K``) while A', B' themselves must lie on the polyline
#: (quadratic): a traced end that hooks back along the line of sight ends the polyline at the
#: fold, not at A'.  Held as hard constraints such ends (2.5-25 px off) bent the whole curve
#: (trace bench seeds 6 and 7: 1.5 % and 4.8 % of the length, 0.4 % from the true curve's
#: start); robust from the start they let the curve wander (seed 0 from flat starts: every
#: start lost), so they are relaxed only once the fit has found its basin.
END_POLISH = True
#: Floor of the pixel noise used as the residual unit (float rounding, sub-pixel tracing).
SIGMA_FLOOR = 0.05
#: Dense samples per knot span for the foot-point search.
SAMPLES_PER_SPAN = 24
#: Iteration cap of each Levenberg-Marquardt run (the full-curve stage).
MAX_ITER = 60
#: Order of the differences of the control points the regulariser penalises.
DIFF_ORDER = 4
#: Control points of the coarse stage (smoother cost landscape for the pose search).
K_COARSE = 6
#: Polyline points (about) of the coarse stage and its pose search (:func:`_thinned`; 0: all,
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
#: Relative decrease of the cost below which LM stops.
REL_TOL = 1e-6
#: ... in the coarse stages (they only need the basin).
COARSE_REL_TOL = 1e-4
#: Iteration cap of each coarse LM run.
COARSE_MAX_ITER = 30
#: LM (:func:`_lm_bundle`): a Gauss-Newton step (damping at most LM_GN_LAMBDA) that does not
#: lower the cost while the linearisation predicts less than LM_STOP_DCHI2 (chi2 units) ends the
#: run.  (Up to rounding, :func:`_gauss_newton_damping`: at first the damping reached from 1e-3 by
#: tenfold decreases, 1.0000000000000002e-06, was not "at most 1e-6", and a run whose first
#: Gauss-Newton trial came there went on to damp it up to 10 times for gains of 0.005-0.07 chi2;
#: bench seed 1400, 20 frames: 57 of the LM's 847 cost evaluations; held out 2000 and 2100: 37 of
#: 487, 16 of 437; of 191 scenes of curve_05 and never_worse, 41 moved within noise, the counts,
#: rates and coverages the same.)  Measured and left off: Nielsen's damping update (gain ratio;
#: 912 evaluations, more iterations); the stop on a rejected damped step's own predicted decrease
#: (a damped step predicts little far from the minimum too: the noise-free polylines-only fit of
#: tests/test_curve_polylines_only.py stopped at 0.79 chi2 for 0.07); damped retries left
#: unevaluated while the step moves by under a tenth (sharp-ends 6001 of tests/test_curve_std.py
#: took another basin); the full fit and the robust-ends polish as one robust run (final costs
#: 0.1-3.4 chi2 higher on 11 of 12 scenes: seeds 1400 and 2000, every family).  Before, such a
#: step started a tail of 3-10 steps at damping raised up to 1e9-fold, each lowering the cost
#: by 0.001-0.02 and moving the shape by under 0.004 of its std (bench seed 1400, 20 frames,
#: fourier: the GN prediction there 0.2-0.5, the cost rough at that scale); a fifth of the LM's
#: evaluations.
#: The final polish then starts elsewhere and can settle in another dip of the rough floor: on
#: 30 scenes (1 px, 20 frames, seeds 1400, 2000-2003, every family; with the matrix products'
#: rounding) the shapes moved by a median 0.002 and at most 0.12 of their std, the curve errors
#: of 14 both ways (-0.11 to +0.07 % of the length); seed 1400 fourier's curve 0.22 of its std
#: across the curve (median point) from the tight solve's.  Also in the final polish with robust
#: ends (``END_POLISH``; it was left out there at first): its runs spent 9-21 trial steps of
#: predicted decreases 0.00-0.1 on the floor (time_20 seeds 1400); on 84 scenes (1 px, 20
#: frames, seeds 1400-1407, 2000-2005, every family) 21 answers moved, the shapes by a median
#: 0.000 and at most 0.03 of their std, the curve errors by -0.004 to +0.12 % of the length
#: (the +0.12 on fourier 1403, 2.4 % off either way), 5 % of the curve bundle's time saved.
LM_GN_LAMBDA = 1e-6
LM_STOP_DCHI2 = 0.5
#: A swept pose is refined only if its grid score (mean squared distance) is below this multiple
#: of the current pose's (the grid is coarse: a pose near the right one can score several px^2).
RESECT_GAIN = 4.0
#: ... and not within this angle (degrees, the sweep's step) of the current pose: a start
#: there lies in the current pose's own basin, and its refinement returns there (1 px, 20
#: frames, seeds 1400, 1401, 2000, 2100, every family: of 480 such starts 99.2 % ended within
#: 2 degrees of the current pose and none elsewhere with a lower cost; 70 % of the refined
#: starts, so about half of the pose search's time).  The starts farther out (other branches,
#: other turns about AB) are refined as before.
RESECT_SAME_DEG = 10.0
#: Curve samples per knot span of the reverse term (curve to polyline) ...
REVERSE_SAMPLES_PER_SPAN = 6
#: ... and its total weight relative to the forward term (polyline points to curve).
REVERSE_WEIGHT = 0.02
#: A frame whose RMS distance from the fitted curve exceeds RMS_LIMIT_SIGMA * sigma +
#: RMS_LIMIT_PX does not fit (the coarse stage's reweighting limit; the flag and the warning of
#: :func:`refine_reconstruction` use ``CurveOptions.flag_rms_sigma``, ``flag_rms_px``).
RMS_LIMIT_SIGMA = 3.0
RMS_LIMIT_PX = 1.0
#: Newton steps of a foot searched again on its polyline neighbours' stretch of the curve
#: (:meth:`_Problem._ordered_feet`).
ORDER_NEWTON = 8
#: Parts of every knot span in which :meth:`_Problem.span_misfit` sums the residuals (a cubic
#: span that misses a wiggle leaves residuals of alternating sign within it).
MISFIT_BINS = 4
#: A frame whose RMS distance exceeds UNEVEN_RATIO times the median frame's (plus sigma / 4,
#: and at least sigma) fits clearly worse than the others: the coarse stage down-weights it
#: before the pose search, and :func:`refine_reconstruction` tries the second start.
UNEVEN_RATIO = 1.5

_EMPTY2 = np.empty((0, 2))
_EMPTY3 = np.empty((0, 3))


@dataclass
class BundleResult:
    """Outcome of :func:`bundle_adjust`.

    control: (K, 3) control points of the curve's clamped cubic B-spline (frame 0 camera).
    m, b: (N, 3, 3), (N, 3) frame 0 camera -> frame i camera (``X_i = m_i X_0 + b_i``).
    sigma: the pixel noise used as the residual unit.
    rms: (N,) RMS distance (pixels) of each frame's polyline points from the projected curve.
    cost_start, cost: sum of squared (weighted) residuals before and after (cost_start on the
        coarse stage's thinned polylines, which stand for the full ones: the same scale).
    iterations: LM iterations taken; converged: whether the relative-change test was met.
    """

    control: np.ndarray
    m: np.ndarray
    b: np.ndarray
    sigma: float
    rms: np.ndarray
    cost_start: float
    cost: float
    iterations: int
    converged: bool
    warnings: list[str] = field(default_factory=list)
    #: (N, 3, 3) the poses m at the end of the coarse stage (before the full curve);
    #: ``stopped``: the run ended there (``twin_m`` of :func:`bundle_adjust`), cost infinite.
    coarse_m: np.ndarray | None = None
    stopped: bool = False
    #: the cost at the end of the coarse stage (its thinned polylines; comparable between runs)
    coarse_cost: float = np.inf

    def curve_points(self, n: int = 200) -> np.ndarray:
        """(n, 3) points of the fitted curve in frame 0's camera coordinates, A first."""
        basis = _Basis(len(self.control))
        return basis.values(np.linspace(0.0, 1.0, n)) @ self.control

    def ends(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(A, B, unit tangent at A into the curve, unit tangent at B into the curve), frame 0."""
        p = self.control
        ta, tb = p[1] - p[0], p[-2] - p[-1]
        return p[0], p[-1], ta / np.linalg.norm(ta), tb / np.linalg.norm(tb)


def _error(message: str) -> Exception:
    from curverecon.errors import CurveReconError

    return CurveReconError(message)


class _Basis:
    """Clamped uniform cubic B-spline basis with K control points on u in [0, 1].

    Evaluated as piecewise cubics: per knot span the K basis functions' power-series
    coefficients in the span's local coordinate (from scipy's ``BSpline`` once), so that values
    and derivatives at many u cost one gather and a few multiplications.
    """

    def __init__(self, k: int) -> None:
        self.k = k
        self.spans = k - 3
        self.knots, self.coef = _span_coefficients(k)

    def _local(self, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.clip(np.asarray(u, float), 0.0, 1.0) * self.spans
        j = np.minimum(t.astype(int), self.spans - 1)
        return self.coef[j], t - j

    def values(self, u: np.ndarray) -> np.ndarray:
        c, x = self._local(u)
        return ((c[:, 3] * x[:, None] + c[:, 2]) * x[:, None] + c[:, 1]) * x[:, None] + c[:, 0]

    def d1(self, u: np.ndarray) -> np.ndarray:
        c, x = self._local(u)
        return ((3.0 * c[:, 3] * x[:, None] + 2.0 * c[:, 2]) * x[:, None] + c[:, 1]) * self.spans

    def d2(self, u: np.ndarray) -> np.ndarray:
        c, x = self._local(u)
        return (6.0 * c[:, 3] * x[:, None] + 2.0 * c[:, 2]) * self.spans**2


@functools.lru_cache(maxsize=64)
def _span_coefficients(k: int) -> tuple[np.ndarray, np.ndarray]:
    """(knots, per-span power-series coefficients (spans, 4, K)) of :class:`_Basis` with K
    control points: from scipy's ``BSpline`` once per K (read-only arrays, shared)."""
    spans = k - 3
    inner = np.linspace(0.0, 1.0, k - 2)
    knots = np.concatenate([[0.0] * 3, inner, [1.0] * 3])
    spl = BSpline(knots, np.eye(k), 3)
    x = np.array([0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0])
    v = np.vander(x, 4, increasing=True)
    coef = np.empty((spans, 4, k))
    for j in range(spans):
        vals = spl((j + x) / spans)  # (4, K)
        coef[j] = np.linalg.solve(v, vals)
    knots.flags.writeable = False
    coef.flags.writeable = False
    return knots, coef


@functools.lru_cache(maxsize=64)
def _problem_tables(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:class:`_Problem`'s tables that depend on K alone, once per K (read-only, shared): the
    dense grid u and its basis values (foot-point search), the reverse samples' basis rows."""
    basis = _Basis(k)
    u_grid = np.linspace(0.0, 1.0, SAMPLES_PER_SPAN * (k - 3) + 1)
    n_grid = basis.values(u_grid)
    n_rev = REVERSE_SAMPLES_PER_SPAN * (k - 3) + 1
    rev_basis = basis.values(np.linspace(0.0, 1.0, n_rev)[1:-1])
    for a in (u_grid, n_grid, rev_basis):
        a.flags.writeable = False
    return u_grid, n_grid, rev_basis


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _expm_so3(w: np.ndarray) -> np.ndarray:
    th = float(np.linalg.norm(w))
    k = _skew(w)
    if th < 1e-12:
        return np.eye(3) + k
    return np.eye(3) + np.sin(th) / th * k + (1 - np.cos(th)) / th**2 * (k @ k)


def fit_spline(points: np.ndarray, k: int) -> np.ndarray:
    """(k, 3) control points of the clamped cubic B-spline fitting ``points`` (chord-length u),
    interpolating the first and last point."""
    pts = np.asarray(points, float)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    u = s / s[-1]
    basis = _Basis(k)
    n = basis.values(u)
    # Ends fixed: solve for the interior control points.
    rhs = pts - np.outer(n[:, 0], pts[0]) - np.outer(n[:, -1], pts[-1])
    d3 = np.diff(np.eye(k), 3, axis=0)
    reg = 1e-3 * np.sqrt(len(pts) / k) * d3
    a = np.vstack([n[:, 1:-1], reg[:, 1:-1]])
    r = np.vstack([rhs, -np.outer(reg[:, 0], pts[0]) - np.outer(reg[:, -1], pts[-1])])
    inner, *_ = np.linalg.lstsq(a, r, rcond=None)
    return np.vstack([pts[0], inner, pts[-1]])


def _thinned(poly: np.ndarray, target: int) -> np.ndarray:
    """Every s-th point of the polyline and its last one, s = round((M - 1) / target) (at
    least 1): about ``target`` points, the same ends."""
    step = max(int(round((len(poly) - 1) / max(target, 1))), 1)
    if step == 1:
        return poly
    idx = np.arange(0, len(poly), step)
    if idx[-1] != len(poly) - 1:
        idx = np.append(idx, len(poly) - 1)
    return np.ascontiguousarray(poly[idx])


def _huber_points(r: np.ndarray, jc: np.ndarray, jp: np.ndarray, k: float = HUBER_K):
    """Huber (``HUBER_K``) on each 2-D point residual (rows 2j, 2j + 1, units of sigma) by its
    length: ``r -> f(a) r / a`` with ``f(a)^2 = 2 k a - k^2`` beyond k, the Jacobian through
    the exact derivative (``f'`` along r, ``f / a`` across it)."""
    r = r.copy()
    jc, jp = jc.copy(), jp.copy()
    for j in range(len(r) // 2):
        rows = slice(2 * j, 2 * j + 2)
        v = r[rows]
        a = float(np.hypot(*v))
        if not a > k:
            continue
        f = float(np.sqrt(2.0 * k * a - k**2))
        u = v / a
        g = (f / a) * (np.eye(2) - np.outer(u, u)) + (k / f) * np.outer(u, u)
        r[rows] = v * (f / a)
        jc[rows] = g @ jc[rows]
        jp[rows] = g @ jp[rows]
    return r, jc, jp


def _segment_offsets(
    poly: np.ndarray, pts: np.ndarray, j: np.ndarray, lo, hi
) -> tuple[np.ndarray, np.ndarray]:
    """Direction and signed distance of points from a polyline: the nearer of the two segments
    at each point's nearest vertex ``j`` (the segment's normal; beyond the polyline's ends the
    offset direction).  ``poly`` holds the vertices, each point's polyline its indices
    ``lo``..``hi`` (scalars for one polyline, or one per point for many stacked)."""
    best_d = np.full(len(pts), np.inf)
    best_dir = np.zeros((len(pts), 2))
    best_r = np.zeros(len(pts))
    for js in (np.maximum(j - 1, lo), np.minimum(j, hi - 1)):
        s0 = poly[js]
        seg = poly[js + 1] - s0
        len2 = np.maximum(np.einsum("ij,ij->i", seg, seg), 1e-300)
        t = np.einsum("ij,ij->i", pts - s0, seg) / len2
        inside = ((t > 0) | (js > lo)) & ((t < 1) | (js < hi - 1))
        t = np.clip(t, 0.0, 1.0)
        e = pts - (s0 + t[:, None] * seg)
        d = np.einsum("ij,ij->i", e, e)
        nrm = np.column_stack([-seg[:, 1], seg[:, 0]]) / np.sqrt(len2)[:, None]
        off = e / np.maximum(np.sqrt(d), 1e-300)[:, None]
        dirn = np.where(inside[:, None], nrm, off)
        take = d < best_d
        best_d = np.where(take, d, best_d)
        best_dir = np.where(take[:, None], dirn, best_dir)
        best_r = np.where(take, np.einsum("ij,ij->i", dirn, e), best_r)
    return best_dir, best_r


class _Problem:
    """Residuals and Jacobians of the bundle for one state (control points, m, b)."""

    def __init__(
        self,
        polys: list[np.ndarray],
        sigma: float,
        k: int,
        ends: np.ndarray | None,
        tangents: np.ndarray | None,
        point_sigma: float,
        tangent_sigma: float,
    ) -> None:
        self.polys = polys
        self.n = len(polys)
        self.sigma = sigma
        self.basis = _Basis(k)
        self.k = k
        self.ends = ends
        self.tangents = tangents
        self._tangent_angles: list[np.ndarray] | None = None  # of the given tangents (evaluate)
        self._tangent_ok: np.ndarray | None = None
        self.point_sigma = point_sigma
        self.tangent_sigma = tangent_sigma
        self.u_grid, self.n_grid, self.rev_basis = _problem_tables(k)
        # differences over the control points whose knot triples are uniform (P_2 .. P_{K-3}):
        # zero for every cubic polynomial curve, so no bias; the two control points at each end
        # (clamped knots) are left free, or the penalty would bend the end tangents
        self.dreg = np.zeros((max(k - 4 - DIFF_ORDER, 0), k))
        if len(self.dreg):
            self.dreg[:, 2 : k - 2] = np.diff(np.eye(k - 4), DIFF_ORDER, axis=0)
        # parameter layout: control points (3k, minus P0_z), then per frame i >= 1 (w 3, b 2)
        self.n_curve = 3 * k - 1
        self.n_par = self.n_curve + 5 * (self.n - 1)
        idx = np.full((k, 3), -1, dtype=int)
        flat = [j for j in range(3 * k) if j != 2]
        idx.reshape(-1)[flat] = np.arange(self.n_curve)
        self.cidx = idx
        self.free_cols = np.array(flat)
        # k-d trees of the polylines for the per-frame reference path (:meth:`_to_polyline`),
        # built on first use (the batched evaluation scans in ``bundle_kernel``)
        self._trees: list | None = None
        self._resampled: list[np.ndarray | None] = [None] * self.n
        self.frame_w = np.ones(self.n)  # frame weights (the coarse stage's robust reweighting)
        # weight of each frame's polyline rows (0: a polyline flagged as contradicting the given
        # end points and tangents is left out; the frame keeps its end-point measurements)
        self.poly_w = np.ones(self.n)
        self.smooth_weight = SMOOTH_WEIGHT
        self.robust_ends = False  # see END_POLISH
        # feet that leave their polyline neighbours' stretch of the curve searched again there
        # (:meth:`_ordered_feet`; the exact path of :func:`fit_curve_fixed_poses`)
        self.ordered_feet = False
        # the reverse term carries REVERSE_WEIGHT of the forward term's total weight per frame
        self.rev_weight = [
            np.sqrt(REVERSE_WEIGHT * max(len(p) - 2, 1) / len(self.rev_basis)) for p in polys
        ]
        # weight of each frame's forward rows (above 1: thinned polylines, :meth:`stand_for`)
        self.fwd_w = np.ones(self.n)
        # the polylines the pose sweep measures distances to (:meth:`resampled`)
        self._sweep_polys = polys
        self._setup_batch()

    def stand_for(self, full: Sequence[np.ndarray]) -> None:
        """Let this problem's polylines, thinned from ``full`` (the same ends, every few points
        kept: :func:`_thinned`), stand for them: each forward row weighted by the square root
        of the interior points it stands for and the reverse term's weight from the full count
        (the cost on the scale of the full polylines', the balance with the end-point and
        tangent rows and ``LM_STOP_DCHI2`` as there), the pose sweep on the full polylines."""
        full_cnt = np.array([max(len(p) - 2, 1) for p in full], float)
        self.fwd_w = np.sqrt(full_cnt / np.maximum(self.q_cnt, 1))
        self.rev_weight = [np.sqrt(REVERSE_WEIGHT * c / len(self.rev_basis)) for c in full_cnt]
        self._sweep_polys = list(full)

    def resampled(self, i: int) -> np.ndarray:
        """Frame i's polyline resampled to 200 points equally spaced in arc length (the pose
        sweep's distances, :func:`_resect_starts`), computed once per problem."""
        if self._resampled[i] is None:
            self._resampled[i] = np.ascontiguousarray(
                pl.resample(self._sweep_polys[i], 200)[0], float
            )
        return self._resampled[i]

    def _to_polyline(self, pts: np.ndarray, i: int) -> tuple[np.ndarray, np.ndarray]:
        """Direction and signed distance of image points from frame i's polyline (normal of the
        nearest segment; the offset direction beyond the polyline's ends)."""
        poly = self.polys[i]
        if self._trees is None:
            from scipy.spatial import cKDTree

            self._trees = [cKDTree(p) for p in self.polys]
        return _segment_offsets(poly, pts, self._trees[i].query(pts)[1], 0, len(poly) - 1)

    def foot_points(self, ctrl: np.ndarray, mi: np.ndarray, bi: np.ndarray, i: int) -> np.ndarray:
        """Curve parameter u of the foot point of each interior polyline point of frame i."""
        from scipy.spatial import cKDTree

        q = self.polys[i][1:-1]
        cp2 = ctrl @ mi[:2].T
        proj = self.n_grid @ cp2 + bi[:2]
        g = len(proj)
        j = cKDTree(proj).query(q)[1]
        # the foot lies on one of the two dense segments next to the nearest dense sample
        best_u = np.zeros(len(q))
        best_d = np.full(len(q), np.inf)
        du = self.u_grid[1] - self.u_grid[0]
        for js in (np.maximum(j - 1, 0), np.minimum(j, g - 2)):
            s0, s1 = proj[js], proj[js + 1]
            seg = s1 - s0
            len2 = np.maximum(np.einsum("ij,ij->i", seg, seg), 1e-300)
            t = np.clip(np.einsum("ij,ij->i", q - s0, seg) / len2, 0.0, 1.0)
            d = np.sum((s0 + t[:, None] * seg - q) ** 2, axis=1)
            take = d < best_d
            best_d = np.where(take, d, best_d)
            best_u = np.where(take, self.u_grid[js] + t * du, best_u)
        return self._newton_feet(best_u, cp2, bi[:2], q, du, 2)

    def _newton_feet(
        self, u: np.ndarray, cp2: np.ndarray, offset: np.ndarray, q: np.ndarray, du: float, n: int
    ) -> np.ndarray:
        """``n`` Newton steps on |p(u) - q|^2 for the foot parameters u of the image points q
        (p(u) = basis(u) cp2 + offset: the curve projected into a frame), each step at most
        ``du`` (one dense-grid spacing), u kept in [0, 1]."""
        for _ in range(n):
            e = self.basis.values(u) @ cp2 + offset - q
            d1 = self.basis.d1(u) @ cp2
            dd = self.basis.d2(u) @ cp2
            g1 = np.einsum("ij,ij->i", d1, e)
            g2 = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", dd, e)
            step = np.where(g2 > 0, -g1 / np.where(g2 > 0, g2, 1.0), 0.0)
            u = np.clip(u + np.clip(step, -du, du), 0.0, 1.0)
        return u

    def _point_rows(self, ctrl, mi, bi, pts, which, scale):
        """2-D residual rows of curve points ctrl[which] against image points ``pts``."""
        r, jc, jp = [], [], []
        for w, pt in zip(which, pts, strict=True):
            y = mi @ ctrl[w] + bi
            r.append((y[:2] - pt) / scale)
            c = np.zeros((2, self.n_curve))
            ok = self.cidx[w] >= 0
            c[:, self.cidx[w][ok]] = mi[:2][:, ok] / scale
            jc.append(c)
            yp = mi @ ctrl[w]
            jp.append(
                np.array([[0.0, yp[2], -yp[1], 1.0, 0.0], [-yp[2], 0.0, yp[0], 0.0, 1.0]]) / scale
            )
        return np.concatenate(r), np.vstack(jc), np.vstack(jp)

    def frame_rows(
        self,
        ctrl: np.ndarray,
        mi: np.ndarray,
        bi: np.ndarray,
        i: int,
        jac: bool = True,
        curve_jac: bool = True,
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None, float]:
        """Frame i's residuals, their Jacobians with respect to the curve parameters and to the
        frame's pose increment (w, b), and the RMS point distance (pixels).  ``curve_jac``
        False: the polyline rows of the curve Jacobian are left zero (the pose search needs
        only the pose Jacobian)."""
        poly = self.polys[i]
        basis, s = self.basis, self.sigma
        u = self.foot_points(ctrl, mi, bi, i)
        nu = basis.values(u)
        x = nu @ ctrl  # (Q, 3) frame 0
        e = (x @ mi[:2].T + bi[:2]) - poly[1:-1]
        tan = basis.d1(u) @ ctrl @ mi[:2].T
        tn = np.linalg.norm(tan, axis=1)
        nrm = np.column_stack([-tan[:, 1], tan[:, 0]]) / np.maximum(tn, 1e-300)[:, None]
        interior = (u > 0.0) & (u < 1.0) & (tn > 0)
        dist = np.linalg.norm(e, axis=1)
        direc = np.where(interior[:, None], nrm, e / np.maximum(dist, 1e-300)[:, None])
        r = np.einsum("ij,ij->i", direc, e)
        rms = float(np.sqrt(np.mean(dist**2)))
        # reverse term: fixed curve samples to the polyline (a detour of the curve that no
        # polyline point is near costs nothing in the forward term)
        xs = self.rev_basis @ ctrl
        ps = xs @ mi[:2].T + bi[:2]
        rev_dir, rev_r = self._to_polyline(ps, i)
        nus = np.vstack([nu, self.rev_basis])
        xx = np.vstack([x, xs])
        direc = np.vstack([direc, rev_dir])
        r = np.concatenate([r, rev_r])
        wt = np.concatenate([np.ones(len(u)), np.full(len(rev_r), self.rev_weight[i])])
        # Huber cost: residual f(a) with f(a)^2 = 2 k |a| - k^2 beyond k (a = r / sigma),
        # f'(a) = k / |f(a)| there; rows of the Jacobian scaled by f'(a)
        a = np.abs(r) / s
        big = a > HUBER_K
        fa = np.where(big, np.sqrt(np.maximum(2.0 * HUBER_K * a - HUBER_K**2, 0.0)), a)
        w = np.where(big, fa / np.maximum(a, 1e-300), 1.0) * wt
        wj = np.where(big, HUBER_K / np.maximum(fa, 1e-300), 1.0) * wt
        res = [w * r / s]
        jcs, jps = [], []
        if jac:
            q = len(r)
            jc = np.zeros((q, self.n_curve))
            dm = direc @ mi[:2]  # (Q, 3)
            for c in range(3 if curve_jac else 0):
                col = self.cidx[:, c]
                ok = col >= 0
                jc[:, col[ok]] += nus[:, ok] * dm[:, c : c + 1]
            yy = xx @ mi.T  # rotation increment: d y / d w = -[Y]x
            jp = np.empty((q, 5))
            jp[:, 0] = -direc[:, 1] * yy[:, 2]
            jp[:, 1] = direc[:, 0] * yy[:, 2]
            jp[:, 2] = -direc[:, 0] * yy[:, 1] + direc[:, 1] * yy[:, 0]
            jp[:, 3:5] = direc
            scale = (wj / s)[:, None]
            jcs.append(jc * scale)
            jps.append(jp * scale)
        # the polyline's end points are the images of A and B
        er, ejc, ejp = self._point_rows(ctrl, mi, bi, (poly[0], poly[-1]), (0, -1), s)
        if self.robust_ends:
            er, ejc, ejp = _huber_points(er, ejc, ejp)
            # ... A and B themselves on the polyline (quadratic): a curve running on beyond
            # the polyline's end still costs as a hard end did
            ye = ctrl[[0, -1]] @ mi.T + bi
            od, orr = self._to_polyline(ye[:, :2], i)
            oc = np.zeros((2, self.n_curve))
            for row, w in enumerate((0, self.k - 1)):
                ok = self.cidx[w] >= 0
                oc[row, self.cidx[w][ok]] = (od[row] @ mi[:2])[ok]
            yp = ctrl[[0, -1]] @ mi.T
            op = np.empty((2, 5))
            op[:, 0] = -od[:, 1] * yp[:, 2]
            op[:, 1] = od[:, 0] * yp[:, 2]
            op[:, 2] = -od[:, 0] * yp[:, 1] + od[:, 1] * yp[:, 0]
            op[:, 3:5] = od
            er = np.concatenate([er, orr / s])
            ejc = np.vstack([ejc, oc / s])
            ejp = np.vstack([ejp, op / s])
        res.append(er)
        jcs.append(ejc)
        jps.append(ejp)
        if self.poly_w[i] != 1.0:
            pw = self.poly_w[i]
            res[:2] = [v * pw for v in res[:2]]
            jcs[:2] = [v * pw for v in jcs[:2]]
            jps[:2] = [v * pw for v in jps[:2]]
        if self.ends is not None:  # given A', B'
            er, ejc, ejp = self._point_rows(ctrl, mi, bi, self.ends[i], (0, -1), self.point_sigma)
            res.append(er)
            jcs.append(ejc)
            jps.append(ejp)
        if self.tangents is not None:  # given tangent directions (lines)
            ts = self.tangent_sigma
            out = np.zeros(2)
            jt = np.zeros((2, self.n_curve))
            jtp = np.zeros((2, 5))
            for row, (lo, hi) in enumerate(((0, 1), (-1, -2))):
                v3 = mi @ (ctrl[hi] - ctrl[lo])  # into the curve
                v = v3[:2]
                ob = self.tangents[i, row]
                if not np.all(np.isfinite(ob)):  # not given (or left out) in this frame
                    continue
                ang = np.arctan2(v[1], v[0]) - np.arctan2(ob[1], ob[0])
                out[row] = ((ang + np.pi / 2) % np.pi - np.pi / 2) / ts
                g = np.array([-v[1], v[0]]) / max(float(v @ v), 1e-300) / ts
                gm = g @ mi[:2]
                for c in range(3):
                    if self.cidx[hi, c] >= 0:
                        jt[row, self.cidx[hi, c]] += gm[c]
                    if self.cidx[lo, c] >= 0:
                        jt[row, self.cidx[lo, c]] -= gm[c]
                jtp[row, :3] = g @ np.array([[0.0, v3[2], -v3[1]], [-v3[2], 0.0, v3[0]]])
            res.append(out)
            jcs.append(jt)
            jps.append(jtp)
        rr = np.concatenate(res)
        fw = np.sqrt(self.frame_w[i])
        if not jac:
            return rr * fw, None, None, rms
        return rr * fw, np.vstack(jcs) * fw, np.vstack(jps) * fw, rms

    # ---- all frames at once (the LM's residuals; frame_rows is the per-frame reference) ----

    def _setup_batch(self) -> None:
        polys, n = self.polys, self.n
        cnt = np.array([len(p) - 2 for p in polys])
        self.q_all = np.vstack([p[1:-1] for p in polys])
        self.q_fid = np.repeat(np.arange(n), cnt)
        self.q_cnt = cnt
        self.q_lo = np.concatenate([[0], np.cumsum(cnt)[:-1]]).astype(np.int64)
        self.end_img = np.stack([np.stack([p[0], p[-1]]) for p in polys])  # (N, 2, 2)
        vcnt = np.array([len(p) for p in polys])
        self.v_all = np.vstack(polys)
        self.v_fid = np.repeat(np.arange(n), vcnt)
        self.v_lo = np.concatenate([[0], np.cumsum(vcnt)[:-1]])
        self.v_hi = self.v_lo + vcnt - 1  # index of each polyline's last vertex
        self._last = None  # (state, foot points, reverse-term search) of the last evaluation
        self.n_rev = len(self.rev_basis)
        self.rev_fid = np.repeat(np.arange(n), self.n_rev)
        self.rows_f = np.concatenate([self.q_fid, self.rev_fid])  # frame of each polyline row
        self.rows_f.flags.writeable = False
        self._rows: dict[int, np.ndarray] = {}  # evaluate's row frames by end rows per frame
        # the reverse samples' runs per frame (_to_polylines: frame-major, fixed)
        frames = np.arange(n)
        self._rev_runs = (
            np.searchsorted(self.rev_fid, frames),
            np.searchsorted(self.rev_fid, frames, side="right"),
        )

    def _to_polylines(self, pts: np.ndarray, fid: np.ndarray, runs=None):
        """:meth:`_to_polyline` for points of many frames (``fid``: each point's frame): the
        nearest vertex of the point's own polyline by an exact scan, then
        :func:`_segment_offsets` (both in ``bundle_kernel.segment_offsets``).  ``runs``: the
        (first, end) index of each frame's points when fid is known sorted."""
        if not np.all(np.isfinite(pts)):
            pts = np.nan_to_num(pts, nan=0.0, posinf=0.0, neginf=0.0)
        order = None
        if runs is not None:
            qlo, qhi = runs
        else:
            fid = np.asarray(fid, np.int64)
            if np.any(np.diff(fid) < 0):  # the kernel takes each frame's points as one run
                order = np.argsort(fid, kind="stable")
                fid, pts = fid[order], pts[order]
            frames = np.arange(self.n)
            qlo = np.searchsorted(fid, frames)
            qhi = np.searchsorted(fid, frames, side="right")
        dirn, r = segment_offsets(
            self.v_all, self.v_lo, self.v_hi, np.ascontiguousarray(pts, float), qlo, qhi
        )
        if order is not None:
            dirn[order], r[order] = dirn.copy(), r.copy()
        return dirn, r

    def _all_foot_points(
        self,
        ctrl: np.ndarray,
        m: np.ndarray,
        b: np.ndarray,
        ps: np.ndarray | None = None,
        ordered: bool | None = None,
    ) -> np.ndarray:
        """:meth:`foot_points` of every frame's interior polyline points at once (the search
        and the Newton steps in ``bundle_kernel.foot_parameters``); ``ordered`` (default
        ``self.ordered_feet``): then :meth:`_ordered_feet`."""
        proj = (self.n_grid @ ctrl) @ np.transpose(m[:, :2], (0, 2, 1)) + b[:, None, :2]
        if not np.all(np.isfinite(proj)):
            proj = np.nan_to_num(proj, nan=0.0, posinf=0.0, neginf=0.0)
        # the projected curve per knot span as a cubic in the span's local coordinate: a point's
        # value and derivatives cost a gather of 4 x 2 coefficients, not of K basis functions
        if ps is None:
            ps = self._projected_spans(ctrl, m, b)
        u = foot_parameters(
            np.ascontiguousarray(proj), self.u_grid, ps, self.q_all, self.q_lo, self.q_cnt
        )
        if ordered is None:
            ordered = self.ordered_feet
        return self._ordered_feet(u, ctrl, m, b) if ordered else u

    def _ordered_feet(self, u: np.ndarray, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
        """Foot parameters u with every foot out of its polyline's order searched again on the
        stretch of the curve its neighbours' feet fix.

        A polyline point near a crossing of the projected curve with another stretch of it
        (or near that stretch) can be nearest to the other stretch: its residual then pulls the
        wrong part of the curve, a local minimum (noise-free random curve, seed 7007, 8 frames:
        the fit stuck at 5e-6 of the length).  Along a polyline (A' to B') the feet run from 0
        to 1: the feet of the longest non-decreasing run of the polyline's points (not
        necessarily consecutive) stay, every other foot is searched again by Newton steps from
        the parameter interpolated between its nearest kept neighbours (the nearest point of
        the projected curve on their stretch).  Frames whose feet are in order are unchanged."""
        du = self.u_grid[1] - self.u_grid[0]
        for f in range(self.n):
            lo, cnt = int(self.q_lo[f]), int(self.q_cnt[f])
            uf = u[lo : lo + cnt]
            if cnt < 3 or not np.any(np.diff(uf) < 0.0):
                continue
            keep = _longest_nondecreasing(uf)
            bad = np.flatnonzero(~keep)
            idx = np.flatnonzero(keep)
            q = self.q_all[lo + bad]
            cp2 = ctrl @ m[f, :2].T
            v = np.interp(bad, idx, uf[idx])
            u[lo + bad] = self._newton_feet(v, cp2, b[f, :2], q, du, ORDER_NEWTON)
        return u

    def _projected_spans(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray) -> np.ndarray:
        """(N, spans, 4, 2): every frame's projected curve, per knot span the power-series
        coefficients in the span's local coordinate."""
        sc = np.einsum("sdk,kc->sdc", self.basis.coef, ctrl)
        ps = sc.reshape(-1, 3) @ np.transpose(m[:, :2], (0, 2, 1))  # (N, spans 4, 2)
        ps = ps.reshape(len(m), *sc.shape[:2], 2)
        ps[:, :, 0] += b[:, None, :2]
        return ps

    def _span_local(self, ps: np.ndarray, fid: np.ndarray, u: np.ndarray):
        """Coefficients (Q, 4, 2) of each point's span (frame ``fid``) and the local coordinate
        (Q, 1) of u in it (:meth:`span_misfit`; the residuals themselves come from
        ``bundle_kernel.forward_rows``)."""
        t = np.clip(u, 0.0, 1.0) * self.basis.spans
        j = np.minimum(t.astype(int), self.basis.spans - 1)
        return ps[fid, j], (t - j)[:, None]

    def _jc_rows(self, nus: np.ndarray, dm: np.ndarray) -> np.ndarray:
        """Curve-parameter Jacobian rows ``sum_k nus[r, k] dm[r, c]`` at the free (k, c)."""
        # every (k, c) product at once, then the free columns (P0_z, the depth gauge, left out)
        full = (nus[:, :, None] * dm[:, None, :]).reshape(len(nus), 3 * self.k)
        return full[:, self.free_cols]

    @staticmethod
    def _jp_rows(direc: np.ndarray, yy: np.ndarray) -> np.ndarray:
        """Pose-increment Jacobian rows of ``direc . y`` (d y / d w = -[Y]x, then b)."""
        jp = np.empty((len(direc), 5))
        jp[:, 0] = -direc[:, 1] * yy[:, 2]
        jp[:, 1] = direc[:, 0] * yy[:, 2]
        jp[:, 2] = -direc[:, 0] * yy[:, 1] + direc[:, 1] * yy[:, 0]
        jp[:, 3:5] = direc
        return jp

    def _end_rows(self, ctrl, m, b, pts, scale, jac):
        """2-D offsets of the projected A, B of every frame from ``pts`` (N, 2, 2): residual
        rows (N, 4) [A x, A y, B x, B y] and their Jacobians (N, 4, n_curve), (N, 4, 5)."""
        n = self.n
        yp = np.einsum("nij,ej->nei", m, ctrl[[0, -1]])  # (N, 2, 3)
        r = ((yp[:, :, :2] + b[:, None, :2]) - pts).reshape(n, 4) / scale
        if not jac:
            return r, None, None
        jc = np.zeros((n, 2, 2, self.n_curve))
        for e, w in enumerate((0, self.k - 1)):
            ok = self.cidx[w] >= 0
            jc[:, e][:, :, self.cidx[w][ok]] = m[:, :2][:, :, ok] / scale
        jp = np.zeros((n, 2, 2, 5))
        jp[:, :, 0, 1] = yp[:, :, 2]
        jp[:, :, 0, 2] = -yp[:, :, 1]
        jp[:, :, 0, 3] = 1.0
        jp[:, :, 1, 0] = -yp[:, :, 2]
        jp[:, :, 1, 2] = yp[:, :, 0]
        jp[:, :, 1, 4] = 1.0
        return r, jc.reshape(n, 4, -1), jp.reshape(n, 4, 5) / scale

    def evaluate(
        self,
        ctrl: np.ndarray,
        m: np.ndarray,
        b: np.ndarray,
        jac: bool = True,
        curve_jac: bool = True,
        compact: bool = False,
    ):
        """Every frame's rows of :meth:`frame_rows` at once (the same residuals, in another
        order) and the regulariser's.  Returns (r, jc, jp, frame of each row (-1: the
        regulariser), per-frame RMS px); jc, jp None without ``jac``, jc None without
        ``curve_jac`` (the pose search).  ``compact``: the polyline rows (the first
        ``len(nus)``) of the curve Jacobian in factored form, jc = (nus, dmw, the other rows
        dense): row i is ``nus[i, k] * dmw[i, c]`` at column ``cidx[k, c]``
        (:meth:`normal_equations`)."""
        n, s, basis = self.n, self.sigma, self.basis
        fid = self.q_fid
        # LM evaluates each accepted state twice (the trial, then the Jacobian): the searches
        # (foot points, the reverse term's nearest polyline segments) are kept for the last state
        key = (ctrl.tobytes(), m.tobytes(), b.tobytes())
        cached = self._last if self._last is not None and self._last[0] == key else None
        ps_all = self._projected_spans(ctrl, m, b)
        u = cached[1] if cached else self._all_foot_points(ctrl, m, b, ps_all)
        # the offset direction (the normal at the foot point) and the signed distance
        direc, r_fw, dist2 = forward_rows(ps_all, u, self.q_all, self.q_lo, self.q_cnt)
        with np.errstate(invalid="ignore", divide="ignore"):
            rms = np.sqrt(np.bincount(fid, dist2, minlength=n) / self.q_cnt)
        # reverse term
        xs = self.rev_basis @ ctrl
        ps = (xs @ np.transpose(m[:, :2], (0, 2, 1)) + b[:, None, :2]).reshape(-1, 2)
        rfid = self.rev_fid
        rev_dir, rev_r = cached[2] if cached else self._to_polylines(ps, rfid, self._rev_runs)
        self._last = (key, u, (rev_dir, rev_r))
        rows_f = self.rows_f
        pw = np.asarray(self.poly_w, float)
        fw = np.sqrt(np.asarray(self.frame_w, float))
        nus = None
        dm = yy = _EMPTY3
        dirs = _EMPTY2
        if jac:
            # the Jacobian's products as before (NumPy's matrix products: the same rounding)
            nus = basis_rows(basis.coef, u, self.rev_basis, n)
            x = nus[: len(u)] @ ctrl
            xx = np.vstack([x, np.tile(xs, (n, 1))])
            dirs = np.vstack([direc, rev_dir])
            mr = m[rows_f]
            dm = (dirs[:, None, :] @ mr[:, :2])[:, 0]
            yy = (mr @ xx[:, :, None])[:, :, 0]
        # Huber, the weights and the Jacobian rows of every polyline row in one loop
        # (bundle_kernel.polyline_rows; the weights as the NumPy code applied them)
        res_p, dmw, jp_p = polyline_rows(
            r_fw,
            rev_r,
            rows_f,
            np.asarray(self.fwd_w, float),
            np.asarray(self.rev_weight, float),
            pw,
            fw,
            float(s),
            HUBER_K,
            bool(jac),
            dm,
            dirs,
            yy,
        )
        res = [res_p]
        frames = [rows_f]
        jcs, jps = [], []
        if jac:
            if compact:
                jcs.append((nus, dmw))
            else:
                jcs.append(self._jc_rows(nus, dmw) if curve_jac else None)
            jps.append(jp_p)
        # the polyline's end points are the images of A and B
        er, ejc, ejp = end_rows(ctrl, m, b, self.end_img, float(s), self.cidx, self.n_curve, jac)
        if self.robust_ends:
            # Huber on each 2-D offset by its length (see _huber_points)
            v = er.reshape(n, 2, 2)
            al = np.hypot(v[..., 0], v[..., 1])
            bigp = al > HUBER_K
            f = np.sqrt(np.maximum(2.0 * HUBER_K * al - HUBER_K**2, 1e-300))
            uu = v / np.maximum(al, 1e-300)[..., None]
            outer = uu[..., :, None] * uu[..., None, :]
            across = (f / np.maximum(al, 1e-300))[..., None, None]
            along = (HUBER_K / f)[..., None, None]
            g = across * (np.eye(2) - outer) + along * outer
            g = np.where(bigp[..., None, None], g, np.eye(2))
            er = (v * np.where(bigp, f / np.maximum(al, 1e-300), 1.0)[..., None]).reshape(n, 4)
            if jac:
                ejc = np.einsum("neij,nejc->neic", g, ejc.reshape(n, 2, 2, -1)).reshape(n, 4, -1)
                ejp = np.einsum("neij,nejc->neic", g, ejp.reshape(n, 2, 2, 5)).reshape(n, 4, 5)
            # ... A and B themselves on the polyline (quadratic)
            ye = np.einsum("nij,ej->nei", m, ctrl[[0, -1]]) + b[:, None, :]  # (N, 2, 3)
            efid = np.repeat(np.arange(n), 2)
            od, orr = self._to_polylines(ye[:, :, :2].reshape(-1, 2), efid)
            er = np.concatenate([er, orr.reshape(n, 2) / s], axis=1)
            if jac:
                yp = (ye - b[:, None, :]).reshape(-1, 3)
                odm = np.einsum("ij,ijc->ic", od, m[efid, :2]).reshape(n, 2, 3)
                oc = np.zeros((n, 2, self.n_curve))
                for row, w_ in enumerate((0, self.k - 1)):
                    ok = self.cidx[w_] >= 0
                    oc[:, row][:, self.cidx[w_][ok]] = odm[:, row][:, ok]
                op = self._jp_rows(od, yp).reshape(n, 2, 5)
                ejc = np.concatenate([ejc, oc / s], axis=1)
                ejp = np.concatenate([ejp, op / s], axis=1)
        if np.any(pw != 1.0):
            er = er * pw[:, None]
            if jac:
                ejc = ejc * pw[:, None, None]
                ejp = ejp * pw[:, None, None]
        blocks_r, blocks_c, blocks_p = [er], [ejc], [ejp]
        if self.ends is not None:  # given A', B'
            gr, gjc, gjp = end_rows(
                ctrl, m, b, self.ends, float(self.point_sigma), self.cidx, self.n_curve, jac
            )
            blocks_r.append(gr)
            blocks_c.append(gjc)
            blocks_p.append(gjp)
        if self.tangents is not None:  # given tangent directions (lines)
            if self._tangent_angles is None:
                ob = np.asarray(self.tangents, float)
                with np.errstate(invalid="ignore"):
                    self._tangent_angles = [np.arctan2(ob[:, r, 1], ob[:, r, 0]) for r in (0, 1)]
                self._tangent_ok = np.all(np.isfinite(ob), axis=2)
            v3 = np.empty((n, 2, 3))
            ang = np.empty((n, 2))
            for row, (lo, hi) in enumerate(((0, 1), (-1, -2))):
                vr = np.einsum("nij,j->ni", m, ctrl[hi] - ctrl[lo])
                v3[:, row] = vr
                with np.errstate(invalid="ignore"):
                    ang[:, row] = np.arctan2(vr[:, 1], vr[:, 0]) - self._tangent_angles[row]
            # the rest in one loop (bundle_kernel.tangent_rows: the same arithmetic)
            out, jt, jtp = tangent_rows(
                v3,
                ang,
                self._tangent_ok,
                m,
                float(self.tangent_sigma),
                self.cidx,
                self.n_curve,
                jac,
            )
            blocks_r.append(out)
            blocks_c.append(jt)
            blocks_p.append(jtp)
        per = np.concatenate(blocks_r, axis=1)  # (N, rows per frame)
        # the frame weights (the polyline rows have theirs from polyline_rows)
        fwe = fw[:, None]
        res.append((per * fwe).reshape(-1))
        if jac:
            jcs.append(
                (np.concatenate(blocks_c, axis=1) * fwe[:, :, None]).reshape(-1, self.n_curve)
            )
            jps.append((np.concatenate(blocks_p, axis=1) * fwe[:, :, None]).reshape(-1, 5))
        # difference regulariser on the control points (see the module docstring)
        wreg = self.smooth_weight / self.sigma
        reg = ((self.dreg @ ctrl) * wreg).reshape(-1)
        rr = np.concatenate([*res, reg])
        rows = self._rows.get(per.shape[1])
        if rows is None:  # each row's frame (-1: the regulariser), by the rows per frame
            rows = np.concatenate(
                [*frames, np.repeat(np.arange(n), per.shape[1]), np.full(len(reg), -1)]
            )
            rows.flags.writeable = False
            self._rows[per.shape[1]] = rows
        if not jac:
            return rr, None, None, rows, rms
        jp = np.vstack([*jps, np.zeros((len(reg), 5))])
        if not curve_jac:
            return rr, None, jp, rows, rms
        jreg = np.zeros((len(reg), self.n_curve))
        for cc in range(3):
            col = self.cidx[:, cc]
            ok = col >= 0
            jreg[cc::3][:, col[ok]] = self.dreg[:, ok] * wreg
        if compact:
            nus, dmw = jcs[0]
            return rr, (nus, dmw, np.vstack([jcs[1], jreg])), jp, rows, rms
        jc = np.vstack([*jcs, jreg])
        return rr, jc, jp, rows, rms

    def residuals(
        self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, jac: bool = True, poses: bool = True
    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
        """(weighted residuals, Jacobian or None, per-frame RMS point distance in pixels).

        poses: False for the Jacobian with respect to the curve's parameters alone (the poses
        held fixed; ``n_curve`` columns).  Dense: the LM itself uses :meth:`normal_equations`."""
        r, jc, jp, rows, rms = self.evaluate(ctrl, m, b, jac)
        if not jac:
            return r, None, rms
        if not poses:
            return r, jc, rms
        full = np.zeros((len(r), self.n_par))
        full[:, : self.n_curve] = jc
        sel = np.flatnonzero(rows > 0)
        off = self.n_curve + 5 * (rows[sel] - 1)
        full[sel[:, None], off[:, None] + np.arange(5)] = jp[sel]
        return r, full, rms

    def normal_equations(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
        """Residuals and the normal equations in blocks: (r, U = Jc^T Jc, gc = Jc^T r, per frame
        i >= 1 V_i = Jp_i^T Jp_i, W_i = Jc_i^T Jp_i, gp_i = Jp_i^T r_i, per-frame RMS).  The
        pose blocks are 5 x 5 and independent of each other (a frame's rows see only its own
        pose), so the LM solves through their Schur complement (:func:`_schur_solve`)."""
        r, (nus, dmw, jc), jp, rows, rms = self.evaluate(ctrl, m, b, True, compact=True)
        n, nc = self.n, self.n_curve
        n_poly = len(nus)
        # the polyline rows (a few thousand, each on at most 4 control points and one pose):
        # accumulated row by row (bundle_kernel), no dense Jacobian
        u = np.zeros((nc, nc))
        gc = np.zeros(nc)
        v = np.zeros((n, 5, 5))
        w = np.zeros((n, nc, 5))
        gp = np.zeros((n, 5))
        polyline_normal_blocks(
            nus, dmw, jp[:n_poly], r[:n_poly], rows[:n_poly], self.cidx, u, gc, v, w, gp
        )
        # the other rows: per frame a fixed number (frame-major), then the regulariser's
        r2, jp2 = r[n_poly:], jp[n_poly:]
        u += jc.T @ jc
        gc += jc.T @ r2
        per = int(np.count_nonzero(rows[n_poly:] >= 0)) // n
        jcf = jc[: n * per].reshape(n, per, nc)
        jpf = jp2[: n * per].reshape(n, per, 5)
        rf = r2[: n * per].reshape(n, per)
        v[1:] += np.transpose(jpf[1:], (0, 2, 1)) @ jpf[1:]
        w[1:] += np.transpose(jcf[1:], (0, 2, 1)) @ jpf[1:]
        gp[1:] += np.einsum("npi,np->ni", jpf[1:], rf[1:])
        return r, (u, gc, v, w, gp), rms

    def subset(self, frames: Sequence[int]) -> _Problem:
        """The problem of the given frames alone (repeats allowed: one per pose to refine),
        with their weights; for the pose search (:func:`_resect_all`)."""
        fr = np.asarray(frames, int)
        sub = _Problem(
            [self.polys[i] for i in fr],
            self.sigma,
            self.k,
            None if self.ends is None else np.asarray(self.ends)[fr],
            None if self.tangents is None else np.asarray(self.tangents)[fr],
            self.point_sigma,
            self.tangent_sigma,
        )
        sub.poly_w = np.asarray(self.poly_w, float)[fr]
        sub.frame_w = np.asarray(self.frame_w, float)[fr]
        sub.smooth_weight = self.smooth_weight
        sub.robust_ends = self.robust_ends
        sub.rev_weight = [self.rev_weight[i] for i in fr]
        sub.fwd_w = np.asarray(self.fwd_w, float)[fr]
        sub._sweep_polys = [self._sweep_polys[i] for i in fr]
        return sub

    def frame_costs(self, r: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """(N,) each frame's sum of squared residuals (the regulariser's rows left out)."""
        keep = rows >= 0
        return np.bincount(rows[keep], r[keep] ** 2, minlength=self.n)

    def span_misfit(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, bins: int) -> float:
        """How much the polyline residuals cluster along the curve: the signed normal residuals
        (units of sigma, clipped at ``HUBER_K``) of the frames in the fit summed in ``bins``
        equal parts of every knot span per frame; ``T = sum over (frame, part) of sum^2 / count``
        is chi2 with one degree of freedom per part when the residuals are the polylines' noise
        and grows when the spline misses a bend or wiggle there (the residuals of a span then
        share a sign in every frame).  Returns ``(T - dof) / sqrt(2 dof)`` (about N(0, 1) for
        noise; the frames left out of the fit and empty parts are not counted)."""
        fid, u = self.q_fid, self._all_foot_points(ctrl, m, b)
        c, xl = self._span_local(self._projected_spans(ctrl, m, b), fid, u)
        e = ((c[:, 3] * xl + c[:, 2]) * xl + c[:, 1]) * xl + c[:, 0] - self.q_all
        tan = (3.0 * c[:, 3] * xl + 2.0 * c[:, 2]) * xl + c[:, 1]
        nrm = np.column_stack([-tan[:, 1], tan[:, 0]])
        nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-300)[:, None]
        r = np.clip(np.einsum("ij,ij->i", nrm, e) / self.sigma, -HUBER_K, HUBER_K)
        keep = (u > 0.0) & (u < 1.0) & (np.asarray(self.poly_w, float)[fid] > 0)
        nb = self.basis.spans * int(bins)
        part = np.minimum((u[keep] * nb).astype(int), nb - 1) + nb * fid[keep]
        sums = np.bincount(part, r[keep], minlength=nb * self.n)
        cnt = np.bincount(part, minlength=nb * self.n)
        full = cnt > 0
        dof = int(full.sum())
        if dof == 0:
            return 0.0
        t = float(np.sum(sums[full] ** 2 / cnt[full]))
        return (t - dof) / np.sqrt(2.0 * dof)

    def pose_normal_equations(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
        """Per frame (every frame, the curve fixed): (cost (N,), V = Jp^T Jp (N, 5, 5),
        gp = Jp^T r (N, 5))."""
        r, _, jp, rows, _ = self.evaluate(ctrl, m, b, True, curve_jac=False)
        keep = rows >= 0
        r, jp, rows = r[keep], jp[keep], rows[keep]
        order = np.argsort(rows, kind="stable")
        starts = np.searchsorted(rows[order], np.arange(self.n))
        jps, res = jp[order], r[order]
        v = np.add.reduceat(np.einsum("ri,rj->rij", jps, jps), starts, axis=0)
        gp = np.add.reduceat(jps * res[:, None], starts, axis=0)
        return np.bincount(rows, r**2, minlength=self.n), v, gp

    def apply(self, ctrl, m, b, dx):
        c2 = ctrl.copy()
        ok = self.cidx >= 0
        c2[ok] += dx[self.cidx[ok]]
        m2, b2 = m.copy(), b.copy()
        if self.n > 1:  # every frame's increment at once (frame 0: the gauge)
            dp = dx[self.n_curve :].reshape(self.n - 1, 5)
            m2[1:] = _expm_so3_batch(dp[:, :3]) @ m[1:]
            b2[1:, :2] += dp[:, 3:5]
        return c2, m2, b2


def _sum_products(w: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``sum_n w[n] @ x[n]`` for w (N, C, P), x (N, P, K): one matrix product (C, N P) (N P, K)
    (an einsum of these shapes took several times longer)."""
    n, c, p = w.shape
    return np.transpose(w, (1, 0, 2)).reshape(c, n * p) @ x.reshape(n * p, -1)


def _schur_solve(blocks, lam: float) -> np.ndarray:
    """The LM step ``-(J^T J + lam D)^-1 J^T r`` (D: Marquardt's diagonal of J^T J, floored
    at 1e-12 of its largest entry) from the normal equations' blocks of
    :meth:`_Problem.normal_equations`: the per-frame 5 x 5 pose blocks eliminated (Schur
    complement on the curve's parameters), then back-substituted.  The same step as the
    dense solve (to rounding) at O(N) cost instead of O(N^3).  Raises LinAlgError if singular."""
    u, gc, v, w, gp = blocks
    du = np.diag(u)
    dv = np.einsum("nii->ni", v[1:])
    top = max(float(np.max(du)), float(np.max(dv)) if dv.size else 0.0, 1e-300)
    floor = 1e-12 * top
    a = u + lam * np.diag(np.maximum(du, floor))
    vd = v[1:] + lam * np.maximum(dv, floor)[:, :, None] * np.eye(5)
    # (V + lam D)^-1 [W^T | gp] for every frame at once
    rhs = np.concatenate([np.transpose(w[1:], (0, 2, 1)), gp[1:, :, None]], axis=2)
    sol = np.linalg.solve(vd, rhs)  # (N - 1, 5, n_curve + 1)
    s = a - _sum_products(w[1:], sol[:, :, :-1])
    rc = gc - np.einsum("ncp,np->c", w[1:], sol[:, :, -1])
    dc = -np.linalg.solve(s, rc)
    dp = -(sol[:, :, -1] + np.einsum("npk,k->np", sol[:, :, :-1], dc))
    return np.concatenate([dc, dp.reshape(-1)])


def _model_decrease(blocks, dx: np.ndarray) -> float:
    """The decrease of the cost ``|r|^2`` (chi2: residuals in units of sigma) that the
    linearisation predicts for the step dx, ``-(2 g^T dx + dx^T H dx)`` with H = J^T J and
    g = J^T r from the blocks of :meth:`_Problem.normal_equations` (frame 0's pose is the
    gauge: no parameters)."""
    u, gc, v, w, gp = blocks
    nc = len(gc)
    dc, dp = dx[:nc], dx[nc:].reshape(-1, 5)
    hc = u @ dc + np.einsum("ncp,np->c", w[1:], dp)
    hp = np.transpose(w[1:], (0, 2, 1)) @ dc + (v[1:] @ dp[:, :, None])[:, :, 0]
    g_dx = float(gc @ dc + np.sum(gp[1:] * dp))
    return -(2.0 * g_dx + float(dc @ hc + np.sum(dp * hp)))


def _gauss_newton_damping(lam: float) -> bool:
    """Whether the damping ``lam`` is at most ``LM_GN_LAMBDA`` (the Gauss-Newton step), up to
    the rounding of the tenfold steps that reach it (1e-3 / 10 / 10 / 10 is
    1.0000000000000002e-06)."""
    return lam <= LM_GN_LAMBDA * (1.0 + 1e-9)


def _lm_bundle(prob, state, max_iter: int, lam: float = 1e-3, rel_tol: float = REL_TOL):
    """Levenberg-Marquardt (Marquardt's diagonal scaling) on the bundle's joint problem (curve
    and every pose), the steps from the normal equations' blocks (:func:`_schur_solve`): no
    dense Jacobian of all the poses.  A step is taken when it lowers the cost (lambda times 10
    until it does, at most 10 times; then converged), lambda / 10 after it; stops when the cost
    falls by less than ``rel_tol`` of itself, or when a step at the least damping (``lambda <=
    LM_GN_LAMBDA``: the Gauss-Newton step) does not lower the cost although the linearisation
    predicts a decrease below ``LM_STOP_DCHI2``: the cost is then at its floor (the foot points,
    the reverse term's polyline segments and Huber make it rough at that scale).  Returns
    (state, cost, iterations, converged)."""
    r, blocks, _ = prob.normal_equations(*state)
    cost = float(r @ r)
    it, converged = 0, False
    while it < max_iter:
        it += 1
        improved = floor = False
        for attempt in range(10):
            try:
                dx = _schur_solve(blocks, lam)
            except np.linalg.LinAlgError:
                lam *= 10.0
                continue
            new = prob.apply(*state, dx)
            r2 = prob.evaluate(*new, jac=False)[0]
            cost2 = float(r2 @ r2)
            if np.isfinite(cost2) and cost2 < cost:
                improved = True
                break
            if (
                attempt == 0
                and _gauss_newton_damping(lam)
                and _model_decrease(blocks, dx) < LM_STOP_DCHI2
            ):
                floor = True
                break
            lam *= 10.0
        if floor:
            converged = True
            break
        if not improved:
            converged = True
            break
        rel = (cost - cost2) / max(cost, 1e-300)
        state = new
        lam = max(lam / 10.0, 1e-9)
        if rel < rel_tol or it >= max_iter:
            # the last step: its cost is the trial's (the same residuals), no linearisation
            converged = rel < rel_tol
            cost = cost2
            break
        r, blocks, _ = prob.normal_equations(*state)
        cost = float(r @ r)
    return state, cost, it, converged


def _gauss_newton_tsvd(residual, p, max_iter: int, rcond: float, abs_tol: float):
    """Gauss-Newton with truncated-SVD steps on ``residual(p, jac) -> (r, J, ...)``.

    The curve's parametrisation is nearly free (sliding control points along the curve changes
    it only to second order): full steps along those near-null directions are huge and leave
    the linearisation (the cost rose tenfold per step, seen).  Singular directions below
    ``rcond`` times the largest are dropped from each step (they change the cost by nothing
    that matters), so the steps stay in the determined part and converge in a few iterations.
    Step halving (by 4) when a step does not lower the cost; stops when the cost falls by less
    than ``abs_tol`` per residual (or a relative ``REL_TOL``).  Returns (p, cost)."""
    r, jac, *_ = residual(p)
    cost = float(r @ r)
    for _ in range(max_iter):
        dx = -np.linalg.lstsq(jac, r, rcond=rcond)[0]
        step, new = 1.0, None
        for _ in range(8):
            r2 = residual(p + step * dx, jac=False)[0]
            cost2 = float(r2 @ r2)
            if np.isfinite(cost2) and cost2 < cost:
                new = p + step * dx
                break
            step /= 4.0
        if new is None:
            break
        drop = cost - cost2
        p = new
        r, jac, *_ = residual(p)
        cost = float(r @ r)
        if drop < abs_tol * len(r) or drop < REL_TOL * cost:
            break
    return p, cost


def _rot_zyx(theta: float, tau: np.ndarray, delta: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotations ``Rz(theta) Ry(tau) Rx(delta)`` for n pairs (tau, delta)."""
    ct, st, cd, sd = np.cos(tau), np.sin(tau), np.cos(delta), np.sin(delta)
    ch, sh = np.cos(theta), np.sin(theta)
    n = len(tau)
    rz = np.array([[ch, -sh, 0.0], [sh, ch, 0.0], [0.0, 0.0, 1.0]])
    ry = np.zeros((n, 3, 3))
    ry[:, 0, 0], ry[:, 0, 2], ry[:, 1, 1], ry[:, 2, 0], ry[:, 2, 2] = ct, st, 1.0, -st, ct
    rx = np.zeros((n, 3, 3))
    rx[:, 0, 0], rx[:, 1, 1], rx[:, 1, 2], rx[:, 2, 1], rx[:, 2, 2] = 1.0, cd, -sd, sd, cd
    return rz @ ry @ rx


def _resect_starts(prob: _Problem, ctrl: np.ndarray, mi: np.ndarray, bi: np.ndarray, i: int):
    """Best pose of frame i for the fixed curve: a sweep over the poses that put A, B on the
    polyline's ends (both signs of tau, rotation about AB in 10-degree steps), scored by the
    mean squared distance of the projected curve from the polyline.  The best two are refined
    by LM if they score below ``RESECT_GAIN`` times the current pose (a frame on the right
    branch scores near the noise level, far below any grid pose) and lie at least
    ``RESECT_SAME_DEG`` from it.  Returns the (m_i, b_i) to refine (:func:`_resect_all`), none
    when no sweep pose beats the current one."""
    poly = prob.polys[i]
    a3 = ctrl[0]
    ab = ctrl[-1] - a3
    c = float(np.linalg.norm(ab))
    chord = poly[-1] - poly[0]
    cp = float(np.hypot(*chord))
    e1 = ab / c
    e2 = _cross3(e1, np.array([1.0, 0.0, 0.0] if abs(e1[0]) < 0.9 else [0.0, 1.0, 0.0]))
    e2 /= np.linalg.norm(e2)
    cmat = np.column_stack([e1, e2, _cross3(e1, e2)])
    tau_abs = float(np.arccos(min(cp / c, 1.0)))
    theta = float(np.arctan2(chord[1], chord[0]))
    pts = _sweep_basis(prob.k) @ ctrl - a3
    dense = prob.resampled(i)
    deltas = _SWEEP_DELTAS
    taus = np.array(sorted({tau_abs, -tau_abs}))
    mms = _rot_zyx(theta, np.repeat(taus, len(deltas)), np.tile(deltas, len(taus))) @ cmat.T
    current = float(np.mean(nearest_distances(dense, (pts + a3) @ mi[:2].T + bi[:2]) ** 2))
    # every sweep pose's projected curve in one query (the same distances as one by one); a
    # pose is measured only until its sum exceeds the refinement's limit (RESECT_GAIN times
    # the current score, with a margin for the order of the sums): such a pose is not refined
    # whatever its score, and the others keep theirs (the same starts as measuring them all)
    proj = pts @ np.transpose(mms[:, :2], (0, 2, 1)) + poly[0]
    bound = RESECT_GAIN * current * len(pts) * (1.0 + 1e-9)
    dist, over = sweep_distances(dense, proj.reshape(-1, 2), len(pts), bound)
    dist = dist.reshape(len(mms), len(pts))
    scores = np.mean(dist**2, axis=1)  # row by row: the same sums as one pose at a time
    scores[over] = np.inf
    best = np.argsort(scores, kind="stable")[:2]  # ties: the first pose (by score, index)
    # only sweep poses that beat the current one even on the coarse grid are refined
    # ... and only outside the current pose's own basin (RESECT_SAME_DEG)
    starts = [
        (mms[j], np.append(poly[0] - (mms[j] @ a3)[:2], 0.0))
        for j in best
        if float(scores[j]) < RESECT_GAIN * current
        and _max_angle_deg(mms[j][None], mi[None]) > RESECT_SAME_DEG
    ]
    return starts


#: The pose sweep's rotations about AB (:func:`_resect_starts`), 10 degrees apart.
_SWEEP_DELTAS = np.radians(np.arange(0.0, 360.0, 10.0))
_SWEEP_DELTAS.flags.writeable = False


@functools.cache
def _sweep_basis(k: int) -> np.ndarray:
    """The basis values (40, k) of the pose sweep's curve samples (:func:`_resect_starts`)."""
    out = _Basis(k).values(np.linspace(0.0, 1.0, 40))
    out.flags.writeable = False
    return out


def _cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross`` of two 3-vectors (its products and differences, without its dispatch)."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def _expm_so3_batch(w: np.ndarray) -> np.ndarray:
    """:func:`_expm_so3` of every row of w (n, 3)."""
    th = np.linalg.norm(w, axis=1)
    k = np.zeros((len(w), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
    k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
    small = th < 1e-12
    ts = np.where(small, 1.0, th)
    a = np.where(small, 1.0, np.sin(ts) / ts)
    c = np.where(small, 0.0, (1 - np.cos(ts)) / ts**2)
    return np.eye(3) + a[:, None, None] * k + c[:, None, None] * (k @ k)


def _lm_poses(prob: _Problem, ctrl, m, b, max_iter: int, rel_tol: float, lam0: float = 1e-3):
    """Levenberg-Marquardt (as :func:`_lm_bundle`) on each frame's pose alone (the curve
    fixed), every frame of ``prob`` at once: the frames are independent, so each keeps its own
    damping, iteration count and
    stopping test, exactly as separate runs would (the frames still running are evaluated,
    in a smaller problem once half have stopped).  Returns (m, b, cost per frame)."""
    n = prob.n
    m, b = m.copy(), b.copy()
    lam = np.full(n, lam0)
    it = np.zeros(n, int)
    active = np.ones(n, bool)
    sub, sel = prob, np.arange(n)

    def normal(mm, bb):
        c_s, v_s, g_s = sub.pose_normal_equations(ctrl, mm[sel], bb[sel])
        c, v, g = np.full(n, np.inf), np.zeros((n, 5, 5)), np.zeros((n, 5))
        c[sel], v[sel], g[sel] = c_s, v_s, g_s
        return c, v, g

    cost, v, gp = normal(m, b)
    eye5 = np.eye(5)
    while active.any():
        if active.sum() <= len(sel) // 2:
            sel = np.flatnonzero(active)
            sub = prob.subset(sel)
        it[active] += 1
        dv = np.einsum("nii->ni", v)
        diag = np.maximum(dv, 1e-12 * np.maximum(dv.max(axis=1), 1e-300)[:, None])
        inner = active.copy()
        improved = np.zeros(n, bool)
        tries = np.zeros(n, int)
        m_new, b_new, cost2 = m.copy(), b.copy(), cost.copy()
        while inner.any():
            idx = np.flatnonzero(inner)
            a = v[idx] + lam[idx, None, None] * diag[idx][:, :, None] * eye5
            dx = np.full((len(idx), 5), np.nan)
            try:
                dx = -np.linalg.solve(a, gp[idx][:, :, None])[:, :, 0]
            except np.linalg.LinAlgError:
                for j, ii in enumerate(idx):
                    try:
                        dx[j] = -np.linalg.solve(a[j], gp[ii])
                    except np.linalg.LinAlgError:
                        pass
            solved = np.all(np.isfinite(dx), axis=1)
            mt, bt = m.copy(), b.copy()
            ok_idx = idx[solved]
            mt[ok_idx] = _expm_so3_batch(dx[solved, :3]) @ m[ok_idx]
            bt[ok_idx, :2] += dx[solved, 3:5]
            r2, _, _, rows, _ = sub.evaluate(ctrl, mt[sel], bt[sel], jac=False)
            c2 = np.full(n, np.inf)
            c2[sel] = sub.frame_costs(r2, rows)
            good = np.zeros(n, bool)
            good[ok_idx] = np.isfinite(c2[ok_idx]) & (c2[ok_idx] < cost[ok_idx])
            m_new[good], b_new[good], cost2[good] = mt[good], bt[good], c2[good]
            improved |= good
            bad = inner & ~good
            lam[bad] *= 10.0
            tries[bad] += 1
            inner &= ~good & (tries < 10)
        active &= improved  # a frame no step improves has converged
        rel = (cost - cost2) / np.maximum(cost, 1e-300)
        m[active], b[active] = m_new[active], b_new[active]
        lam[active] = np.maximum(lam[active] / 10.0, 1e-9)
        cost_all, v_all, gp_all = normal(m, b)
        cost[active], v[active], gp[active] = cost_all[active], v_all[active], gp_all[active]
        active &= ~(rel < rel_tol) & (it < max_iter)
    return m, b, cost


def _resect_all(prob: _Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, frames):
    """:func:`_resect_starts` of the given frames, the starts refined by LM on their poses
    (at most 15 iterations), all at once.  Returns {frame: (m_i, b_i, cost) of its best
    refined pose} for the frames with a start."""
    owner, ms, bs = [], [], []
    for i in frames:
        for mm, bb in _resect_starts(prob, ctrl, m[i], b[i], i):
            owner.append(i)
            ms.append(mm)
            bs.append(bb)
    if not owner:
        return {}
    sub = prob.subset(owner)
    m2, b2, cost = _lm_poses(sub, ctrl, np.array(ms), np.array(bs), 15, 1e-4)
    best: dict = {}
    for j, i in enumerate(owner):
        if i not in best or cost[j] < best[i][2]:
            best[i] = (m2[j], b2[j], float(cost[j]))
    return best


def _uneven_level(rms: np.ndarray, sigma: float) -> float:
    """RMS distance above which a frame fits clearly worse than the others (pixels)."""
    return max(UNEVEN_RATIO * float(np.median(rms)) + 0.25 * sigma, sigma)


def _uneven(rms: np.ndarray, sigma: float) -> bool:
    """Whether some frame fits clearly worse than the others (a pose on a wrong branch)."""
    return bool(np.max(rms) > _uneven_level(rms, sigma))


def _restart(rms: np.ndarray, sigma: float) -> bool:
    """Whether a fit calls for another start: some frame fits clearly worse than the others, or
    some frame does not fit at all (``RMS_LIMIT_*``: every frame can be equally far off)."""
    return _uneven(rms, sigma) or bool(np.max(rms) > RMS_LIMIT_SIGMA * sigma + RMS_LIMIT_PX)


def _regauge(ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
    """Re-express the state in frame 0's (new) camera coordinates with A at depth 0."""
    m0, b0 = m[0].copy(), b[0].copy()
    ctrl = ctrl @ m0.T + b0
    m = np.einsum("nij,kj->nik", m, m0)  # m_i m_0^T
    b = b - np.einsum("nij,j->ni", m, b0)
    dz = ctrl[0, 2]
    ctrl = ctrl - [0.0, 0.0, dz]
    b = b + dz * m[:, :, 2]
    m[0], b[0] = np.eye(3), np.zeros(3)
    return ctrl, m, b


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
    k_max: int = 0,
    resect_first: bool = False,
    smooth_weight: float = SMOOTH_WEIGHT,
    misfit_z: float = CurveOptions.bundle_misfit_z,
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
    k_max: the control points grow (knot spans halved) up to this many while the residuals
        cluster along the curve (:meth:`_Problem.span_misfit` above ``misfit_z``) and Akaike's
        criterion (:func:`_bic` with 2 per parameter) improves (0: no growth).
    resect_first: search every frame's pose (but frame 0's) against the start curve before
        the first fit (a start curve that the start poses were not made for).
    polyline_mask: optional (N,) bool, False for frames whose polyline is left out of the fit
        (flagged as contradicting the given end points and tangents; needs ``ends``).
    smooth_weight: the difference penalty's weight (``CurveOptions.bundle_smooth_weight``).
    order_tol: above 0, a curve folded over itself (:func:`_folded` with this tolerance, in
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
    frame's pose searched again against that curve (``_resect_all``: the wrong-branch poses the
    end tangents leave are far from the right ones, beyond LM's reach) and the coarse fit
    repeated (``RESECT_ROUNDS``); then the full curve on the full polylines.

    Returns a :class:`BundleResult` (curve and poses in frame 0's camera coordinates).
    Raises ``CurveReconError`` for bad input.
    """
    rot = np.asarray(rotations, float)
    tr = np.asarray(translations, float)
    n = len(polylines)
    if n < 2:
        raise _error(f"the curve bundle needs at least 2 frames, got {n}")
    if rot.shape != (n, 3, 3) or tr.shape != (n, 3):
        raise _error(f"rotations/translations must have shapes ({n}, 3, 3) and ({n}, 3)")
    if not (np.all(np.isfinite(rot)) and np.all(np.isfinite(tr))):
        raise _error("rotations/translations contain NaN or infinite values")
    if np.abs(np.einsum("nij,nkj->nik", rot, rot) - np.eye(3)).max() > 1e-6:
        raise _error("rotations are not orthonormal")
    polys = [pl.as_polyline(p, name=f"frame {i} curve") for i, p in enumerate(polylines)]
    curve0 = np.asarray(curve0, float)
    if curve0.ndim != 2 or curve0.shape[1] != 3 or len(curve0) < 4:
        raise _error("the start curve must be at least 4 points [x, y, z]")
    if not np.all(np.isfinite(curve0)):
        raise _error("the start curve contains NaN or infinite values")
    for name, arr in (("ends", ends), ("tangents", tangents)):
        # NaN tangents mean "not given" in that frame
        if arr is not None and (
            np.shape(arr) != (n, 2, 2)
            or np.any(np.isinf(np.asarray(arr, float)))
            or (name == "ends" and not np.all(np.isfinite(np.asarray(arr, float))))
        ):
            raise _error(f"{name}: expected {n} pairs of finite 2-D vectors")
    # Polylines run from A to B; A's image is t_i[:2].
    for i, p in enumerate(polys):
        if np.hypot(*(p[-1] - tr[i, :2])) < np.hypot(*(p[0] - tr[i, :2])):
            polys[i] = p[::-1].copy()
    m_pts = min(len(p) for p in polys)
    k = int(n_control) if n_control is not None else int(np.clip(m_pts // 6, 5, N_CONTROL))
    if k < 4:
        raise _error(f"n_control must be at least 4, got {k}")
    sigma = max(float(np.median([noise_level(p) for p in polys])), SIGMA_FLOOR)
    m = np.einsum("nij,kj->nik", rot, rot[0])  # R_i R_0^T: frame 0 camera -> frame i camera
    b = tr - np.einsum("nij,j->ni", m, tr[0])
    ends_arr = None if ends is None else np.asarray(ends, float)
    tans_arr = None if tangents is None else np.asarray(tangents, float)
    ts = float(np.radians(tangent_sigma_deg))

    use_poly = np.ones(n, bool) if polyline_mask is None else np.asarray(polyline_mask, bool)
    if use_poly.shape != (n,) or (ends_arr is None and not use_poly.all()):
        raise _error(f"polyline_mask: expected {n} flags (and given end points to leave any out)")

    def problem(kk: int, coarse: bool = False) -> _Problem:
        if coarse and COARSE_POINTS > 0:
            prob = _Problem(
                [_thinned(p, COARSE_POINTS) for p in polys],
                sigma,
                kk,
                ends_arr,
                tans_arr,
                float(point_sigma),
                ts,
            )
            prob.stand_for(polys)
        else:
            prob = _Problem(polys, sigma, kk, ends_arr, tans_arr, float(point_sigma), ts)
        prob.poly_w = use_poly.astype(float)
        prob.smooth_weight = float(smooth_weight)
        return prob

    k_coarse = min(K_COARSE, k)
    prob = problem(k_coarse, coarse=True)
    ctrl = fit_spline(curve0 - [0.0, 0.0, curve0[0, 2]], k_coarse)
    if resect_first:
        # the start poses were made for another curve: every frame's pose searched against the
        # start curve before it is bent to fit them
        found = _resect_all(prob, ctrl, m, b, [i for i in range(1, n) if use_poly[i]])
        r, _, _, rows, _ = prob.evaluate(ctrl, m, b, jac=False)
        cur = prob.frame_costs(r, rows)
        for i, (mi, bi, ci) in found.items():
            if ci < cur[i]:
                m[i], b[i] = mi, bi
    cost_start = float(np.sum(prob.residuals(ctrl, m, b, jac=False)[0] ** 2))
    coarse = {"max_iter": min(max_iter, COARSE_MAX_ITER), "rel_tol": COARSE_REL_TOL}
    # a second start that may retrace another run (``twin_m``): its pose search comes early, and
    # it stops as soon as its poses are the other run's again
    early = twin_m is not None and twin_iter > 0
    first = {**coarse, "max_iter": min(coarse["max_iter"], int(twin_iter))} if early else coarse
    (ctrl, m, b), cost, total_it, _ = _lm_bundle(prob, (ctrl, m, b), **first)
    limit = RMS_LIMIT_SIGMA * sigma + RMS_LIMIT_PX

    def twin_stop(ctrl, m, b, at: float) -> BundleResult:
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        return BundleResult(
            ctrl, m, b, sigma, rms, cost_start, np.inf, total_it, False, [], m.copy(), True, at
        )

    for rnd in range(int(RESECT_ROUNDS)):
        changed = False
        # frames that do not fit (wrong pose branch) bend the coarse curve: refit it with them
        # down-weighted, then search their poses against the cleaner curve
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        if _uneven(rms, sigma):
            ref = min(limit, _uneven_level(rms, sigma))
            prob.frame_w = 1.0 / (1.0 + (rms / ref) ** 4)
            lm_opts = first if rnd == 0 else coarse
            (ctrl, m, b), _, it, _ = _lm_bundle(prob, (ctrl, m, b), **lm_opts)
            total_it += it
            prob.frame_w = np.ones(n)
        r, _, _, rows, _ = prob.evaluate(ctrl, m, b, jac=False)
        cur = prob.frame_costs(r, rows)
        found = _resect_all(prob, ctrl, m, b, [i for i in range(n) if use_poly[i]])
        for i, (mi, bi, ci) in found.items():
            if ci < cur[i]:
                changed = changed or ci < 0.9 * cur[i]
                m[i], b[i] = mi, bi
        if not np.allclose(m[0], np.eye(3), atol=1e-12):
            ctrl, m, b = _regauge(ctrl, m, b)
        if early and _max_angle_deg(m, twin_m) < twin_deg:
            return twin_stop(ctrl, m, b, float(cost))
        (ctrl, m, b), cost, it, _ = _lm_bundle(prob, (ctrl, m, b), **coarse)
        total_it += it
        if not changed:
            break
    coarse_m = m.copy()
    coarse_cost = float(cost)
    if twin_m is not None and _max_angle_deg(m, twin_m) < twin_deg:
        return twin_stop(ctrl, m, b, coarse_cost)
    if coarse_cost > twin_cost_ratio * twin_cost:
        # far above the other run at the same stage: no rival of it
        # (CurveOptions.restart_coarse_cost_ratio)
        return twin_stop(ctrl, m, b, coarse_cost)
    converged = True
    if k > k_coarse or not END_POLISH:
        # the full curve on the full polylines (the coarse stage's were thinned)
        if k > k_coarse:
            ctrl = fit_spline(prob.basis.values(np.linspace(0.0, 1.0, 200)) @ ctrl, k)
        prob = problem(k)
        (ctrl, m, b), cost, it, converged = _lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    if END_POLISH:
        prob = problem(k)
        prob.robust_ends = True
        (ctrl, m, b), cost, it, converged = _lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    if order_tol > 0.0 and _folded(prob, ctrl, m, b, order_tol):
        # the spline has folded over itself (forward, back, forward along one stretch): with
        # the nearest feet its strands share the polyline points and fit the noise, a cost no
        # single curve reaches; refitted with the feet in the polylines' order, kept whatever
        # its cost (``CurveOptions.bundle_order_tol``), from the curve's points at the feet in
        # a polyline's order (they run along the curve once)
        pts = _unfolded_points(prob, ctrl, m, b, prob.poly_w > 0.0)
        if pts is not None:
            ctrl = fit_spline(pts, k)
        prob.ordered_feet = True
        (ctrl, m, b), cost, it, converged = _lm_bundle(prob, (ctrl, m, b), max_iter)
        total_it += it
    rms = prob.residuals(ctrl, m, b, jac=False)[2]
    crit = _bic(prob, rms, prob.n_par, 2.0)
    while 2 * k - 3 <= int(k_max):
        # every knot span halved (the old curve exactly, so the fit starts at the old optimum);
        # tried only where the residuals cluster along the curve (``misfit_z``: a bend or wiggle
        # the spline misses; the trial costs a fit) and kept while the information criterion
        # improves
        # not while some frame fits clearly worse than the others (``_uneven``): a polyline
        # that contradicts the others (to be flagged) or a wrong pose is no bend of the curve,
        # and a freer curve would hide it
        if _uneven(rms[use_poly], sigma) or prob.span_misfit(ctrl, m, b, MISFIT_BINS) <= misfit_z:
            break
        k2 = 2 * k - 3
        u = np.linspace(0.0, 1.0, 20 * k2)
        ctrl2 = np.linalg.lstsq(_Basis(k2).values(u), prob.basis.values(u) @ ctrl, rcond=None)[0]
        prob2 = problem(k2)
        prob2.robust_ends = END_POLISH
        (c2, m2, b2), cost2, it, conv2 = _lm_bundle(prob2, (ctrl2, m, b), max_iter)
        total_it += it
        rms2 = prob2.residuals(c2, m2, b2, jac=False)[2]
        crit2 = _bic(prob2, rms2, prob2.n_par, 2.0)
        if not crit2 < crit:
            break
        k, prob, ctrl, m, b, cost, converged, rms, crit = (
            k2,
            prob2,
            c2,
            m2,
            b2,
            cost2,
            conv2,
            rms2,
            crit2,
        )
    return BundleResult(
        ctrl,
        m,
        b,
        sigma,
        rms,
        cost_start,
        cost,
        total_it,
        converged,
        coarse_m=coarse_m,
        coarse_cost=coarse_cost,
    )


def _max_angle_deg(m1: np.ndarray, m2: np.ndarray) -> float:
    """The largest rotation angle (degrees) between the frames' rotations m1[i] and m2[i]."""
    c = (np.einsum("nij,nij->n", m1, m2) - 1.0) / 2.0  # (trace(m1 m2^T) - 1) / 2
    return float(np.degrees(np.arccos(np.clip(c, -1.0, 1.0))).max())


def select_control_points(
    result: BundleResult,
    polylines: Sequence[np.ndarray],
    candidates: Sequence[int],
    *,
    smooth_weight: float = SMOOTH_WEIGHT,
    max_iter: int = MAX_ITER,
    end_fraction: float = 0.15,
    end_dchi2: float = 1.0,
) -> tuple[BundleResult, dict[int, float]]:
    """The bundle refitted with each number of control points of ``candidates`` (fewer or more
    than ``result``'s), every pose free, no given end points or tangents; the fit with the
    least Bayesian information criterion (:func:`_bic`, ln n per parameter) is returned, with
    every candidate's criterion.  Each refit starts from ``result``'s curve (least squares on
    the new basis) and poses.

    Polylines only, the end tangents (alpha, beta, phi) are the curve's at its ends: the more
    control points, the shorter the end spans that fix them and the larger their variance, while
    a curve with too few bends away from the polylines (the criterion sees it in the residuals).
    """
    ctrl0 = np.asarray(result.control, float)
    k0 = len(ctrl0)
    polys = _oriented_to(polylines, result)

    def problem(kk: int) -> _Problem:
        prob = _Problem(polys, result.sigma, kk, None, None, 1.0, 1.0)
        prob.smooth_weight = float(smooth_weight)
        prob.robust_ends = END_POLISH
        return prob

    prob0 = problem(k0)
    rms0 = prob0.residuals(ctrl0, result.m, result.b, jac=False)[2]
    crits = {k0: _bic(prob0, rms0, prob0.n_par)}
    best = (crits[k0], result)
    end0 = _end_region_chi2(polys, ctrl0, result.m, result.b, result.sigma, end_fraction)
    u = np.linspace(0.0, 1.0, 400)
    dense = _Basis(k0).values(u) @ ctrl0
    for kk in sorted({int(k) for k in candidates} - {k0}):
        if kk < 4:
            continue
        prob = problem(kk)
        ctrl = np.linalg.lstsq(_Basis(kk).values(u), dense, rcond=None)[0]
        ctrl -= [0.0, 0.0, ctrl[0, 2]]  # A's depth: the gauge
        state = (ctrl, result.m.copy(), result.b.copy())
        (ctrl, m, b), cost, it, conv = _lm_bundle(prob, state, max_iter)
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        crits[kk] = _bic(prob, rms, prob.n_par)
        end = _end_region_chi2(polys, ctrl, m, b, result.sigma, end_fraction)
        # the ends must fit as well as with the reference curve: a curve too stiff for a bend
        # near an end bends its end tangent, which the whole polyline's criterion hardly sees
        limit = end_dchi2 * max(3 * (k0 - kk), 1)
        if np.any(end - end0 > limit):
            crits[kk] = np.inf
        if crits[kk] < best[0]:
            res = BundleResult(
                ctrl,
                m,
                b,
                result.sigma,
                rms,
                result.cost_start,
                cost,
                result.iterations + it,
                conv,
                list(result.warnings),
            )
            best = (crits[kk], res)
    return best[1], crits


def resect_uneven_frames(
    result: BundleResult,
    polylines: Sequence[np.ndarray],
    *,
    smooth_weight: float = SMOOTH_WEIGHT,
    max_iter: int = MAX_ITER,
) -> BundleResult:
    """A bundle whose frames fit unevenly (:func:`_uneven`: a few frames on a wrong pose
    branch, the others at the noise level) refitted with those frames left out, their poses
    searched against that curve (:func:`_resect_all`, the full curve rather than the coarse
    stage's), then every frame together again; the result with the lower cost is returned.
    No given end points or tangents (polylines only).

    Polylines only, helix seed 1300 (bench, 0.5 px, 12 frames): the start from the end-point
    answer left frame 9 at 6.2 px RMS (the others 0.5 px) and phi 36 degrees off; seven flat
    starts from other frames' polylines fitted no better (2-7 px); the coarse stage's search
    (6 control points) missed the pose that the full curve finds."""
    sigma = result.sigma
    if not _uneven(result.rms, sigma):
        return result
    polys = _oriented_to(polylines, result)
    n, k = len(polys), len(result.control)
    bad = result.rms > _uneven_level(result.rms, sigma)
    if bad.sum() > n // 3:
        return result
    prob = _Problem(polys, sigma, k, None, None, 1.0, 1.0)
    prob.smooth_weight = float(smooth_weight)
    prob.robust_ends = END_POLISH
    prob.frame_w = np.where(bad, 1e-6, 1.0)
    state = (result.control.copy(), result.m.copy(), result.b.copy())
    (ctrl, m, b), _, it0, _ = _lm_bundle(prob, state, max_iter)
    r, _, _, rows, _ = prob.evaluate(ctrl, m, b, jac=False)
    cur = prob.frame_costs(r, rows) / prob.frame_w
    m, b = m.copy(), b.copy()
    for i, (mi, bi, ci) in _resect_all(prob, ctrl, m, b, np.flatnonzero(bad)).items():
        if ci < cur[i]:
            m[i], b[i] = mi, bi
    if not np.allclose(m[0], np.eye(3), atol=1e-12):
        ctrl, m, b = _regauge(ctrl, m, b)
    prob.frame_w = np.ones(n)
    (ctrl, m, b), cost, it, conv = _lm_bundle(prob, (ctrl, m, b), max_iter)
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
    dense = _Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 60 * len(ctrl))) @ ctrl
    out = np.zeros(2)
    for i, q in enumerate(polys):
        proj = (dense @ m[i].T + b[i])[:, :2]
        h = max(int(round(fraction * len(q))), 3)
        for e, part in enumerate((q[:h], q[-h:])):
            d, _ = pl.distance_to_polyline(part, proj)
            out[e] += float(np.sum(d * d)) / sigma**2
    return out


def _oriented_to(polylines: Sequence[np.ndarray], result: BundleResult) -> list[np.ndarray]:
    """Every polyline from A' to B' of a bundle result (the end nearer its projected A first)."""
    out = []
    for i, p in enumerate(polylines):
        q = pl.as_polyline(p, name=f"frame {i} curve")
        a_img = (result.m[i] @ result.control[0] + result.b[i])[:2]
        if np.hypot(*(q[-1] - a_img)) < np.hypot(*(q[0] - a_img)):
            q = q[::-1].copy()
        out.append(q)
    return out


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
    nb = _Basis(k).values(u)  # (M, K)
    # x(u) = nb @ (base + (D p).reshape(K, 3)) = points
    a_mat = np.einsum("mk,kcp->mcp", nb, d.reshape(k, 3, -1)).reshape(-1, d.shape[1])
    rhs = (pts - nb @ base).reshape(-1)
    p, *_ = np.linalg.lstsq(a_mat, rhs, rcond=None)
    p[:2] = np.maximum(p[:2], 1e-3 * float(np.linalg.norm(base[-1] - base[0])))
    return p


def _bic(prob: _Problem, rms: np.ndarray, n_par: int, per_param: float | None = None) -> float:
    """Bayesian information criterion of a fit with ``n_par`` free parameters from each frame's
    RMS point distance ``rms`` (pixels): ``n ln(RSS / n) + n_par ln n`` over the polyline
    points (n) of the frames in the fit, the noise level estimated from the fit itself
    (scale-free), so noise-free data keep asking for knots until float rounding while noisy
    data stop at the noise.  The reverse term and the regulariser are left out (their floors,
    e.g. the pull towards the polyline's chords, are not the data's)."""
    use = prob.poly_w > 0
    counts = np.array([max(len(p) - 2, 1) for p in prob.polys], float)[use]
    n_obs = max(float(counts.sum()), n_par + 1.0)
    rss = float(np.sum(counts * rms[use] ** 2))
    pen = np.log(n_obs) if per_param is None else per_param
    return float(n_obs * np.log(max(rss, 1e-300) / n_obs) + n_par * pen)


def _folded(prob: _Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, tol: float) -> bool:
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
            keep = _longest_nondecreasing(uf)
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


def _longest_nondecreasing(x: np.ndarray) -> np.ndarray:
    """Mask of one longest non-decreasing subsequence of ``x`` (patience sorting,
    ``bundle_kernel.longest_nondecreasing``: the fold test runs it on every frame's feet)."""
    return longest_nondecreasing(np.ascontiguousarray(x, float))


def _unfolded_points(
    prob: _Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, mask: np.ndarray
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
    (:func:`_bic`) improves and some frame's RMS distance exceeds ``resolution`` times its
    polyline's length.  ``unfold``: at each number of control points, up to this many refits
    from the fitted curve's points in a polyline's order (:func:`_unfolded_points`) when the
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
        prob = _Problem(polys, sigma, k, None, None, 1.0, 1.0)
        prob.poly_w = mask.astype(float)
        prob.smooth_weight = smooth_weight
        prob.rev_weight = [w * reverse_factor for w in prob.rev_weight]
        # from the second number of control points on, the fit starts at the last optimum:
        # every foot searched on its polyline neighbours' stretch (_Problem._ordered_feet)
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
            p0 = _pinned_start(_Basis(len(best[0])).values(u) @ best[0], k, base, d, u)

        def ctrl_of(p: np.ndarray, base=base, d=d, k=k) -> np.ndarray:
            return base + (d @ p).reshape(k, 3)

        def residual(p, jac=True, prob=prob, ctrl_of=ctrl_of, d_red=d_red):
            r, j, rms = prob.residuals(ctrl_of(p), m, b, jac=jac, poses=False)
            return r, (j @ d_red if jac else None), rms

        p, cost = _gauss_newton_tsvd(residual, p0, max_iter, rcond, abs_tol)
        for _ in range(unfold):
            # a fold (the spline running forward, back and forward again over one stretch of
            # the curve: invisible in every image) is a local minimum the steps do not leave;
            # refitted to the curve's own points in the order of a polyline, the fold is gone
            pts = _unfolded_points(prob, ctrl_of(p), m, b, mask)
            if pts is None:
                break
            p2, cost2 = _gauss_newton_tsvd(
                residual, _pinned_start(pts, k, base, d), max_iter, rcond, abs_tol
            )
            if not cost2 < cost:
                break
            p, cost = p2, cost2
        if unfold and not prob.ordered_feet:
            # then polished with every foot on its polyline neighbours' stretch of the curve
            # (a crossing in some image otherwise holds the fit near it, _Problem._ordered_feet)
            prob.ordered_feet, prob._last = True, None
            p, cost = _gauss_newton_tsvd(residual, p, max_iter, rcond, abs_tol)
        ctrl = ctrl_of(p)
        rms = prob.residuals(ctrl, m, b, jac=False)[2]
        crit = _bic(prob, rms, d.shape[1])
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


def shape_and_poses(
    result: BundleResult, theta_ref: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Shape (c, alpha, beta, phi), poses (N, 5) and the curve-frame rotation of a bundle.

    The curve frame of docs/CONVENTIONS.md: A at the origin, B on +x, the tangent line at B in
    the x-y plane with direction (-cos alpha, sin alpha, 0), alpha in [0, pi/2]; phi in (-pi, pi]
    is then the angle of the tangent at A about +x (the caller's ``pose.normalise`` folds the
    mirror image).  Returns ``(shape, poses, C)`` with ``X_cam0 = A + C X_curve``.
    """
    a, bpt, ta, tb = result.ends()
    ab = bpt - a
    c = float(np.linalg.norm(ab))
    if not c > 0:
        raise _error("the fitted curve has A = B")
    e1 = ab / c
    if tb @ e1 > 0:
        tb = -tb  # a tangent is a line: the direction making an acute angle with BA
    if ta @ e1 < 0:
        ta = -ta
    perp = tb - (tb @ e1) * e1
    if np.linalg.norm(perp) < 1e-12:  # tangent at B along AB: any normal
        perp = np.cross(e1, [0.0, 0.0, 1.0] if abs(e1[2]) < 0.9 else [1.0, 0.0, 0.0])
    e2 = perp / np.linalg.norm(perp)
    e3 = np.cross(e1, e2)
    cmat = np.column_stack([e1, e2, e3])
    alpha = float(np.arctan2(np.linalg.norm(perp), -(tb @ e1)))
    beta = float(np.arctan2(np.hypot(ta @ e2, ta @ e3), ta @ e1))
    phi = float(np.arctan2(ta @ e3, ta @ e2))
    rot = np.einsum("nij,jk->nik", result.m, cmat)
    t = np.einsum("nij,j->ni", result.m, a) + result.b
    tau = np.arcsin(np.clip(-rot[:, 2, 0], -1.0, 1.0))
    theta = np.arctan2(rot[:, 1, 0], rot[:, 0, 0])
    delta = np.arctan2(rot[:, 2, 1], rot[:, 2, 2])
    poses = np.column_stack([delta, tau, theta, t[:, 0], t[:, 1]])
    return np.array([c, alpha, beta, phi]), poses, cmat


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
        raise _error(f"reference frame {ref} out of range (0..{n - 1})")
    perm = [ref] + [j for j in range(n) if j != ref]
    rot = np.asarray(rotations, float)[perm]
    tr = np.asarray(translations, float)[perm]
    for key in ("ends", "tangents", "polyline_mask"):
        if kw.get(key) is not None:
            kw[key] = np.asarray(kw[key])[perm]
    poly = pl.as_polyline(polylines[ref], name=f"frame {ref} curve")
    if np.hypot(*(poly[-1] - tr[0, :2])) < np.hypot(*(poly[0] - tr[0, :2])):
        poly = poly[::-1].copy()  # from A' (as bundle_adjust orients every polyline)
    br = bundle_adjust(
        [polylines[j] for j in perm], rot, tr, flat_start(poly), resect_first=True, **kw
    )
    inv = np.argsort(perm)
    ctrl, m, b = _regauge(br.control, br.m[inv], br.b[inv])
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


def _curve_covariance(prob: _Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
    """Covariance of the curve's parameters with every pose marginalised out: the curve block
    of (J^T J)^+ through the Schur complement on the per-frame pose blocks (residuals in units
    of sigma).  None if it is not finite."""
    _, (u, _, v, w, _), _ = prob.normal_equations(ctrl, m, b)
    try:
        vinv_wt = np.linalg.solve(v[1:], np.transpose(w[1:], (0, 2, 1)))
        s = u - _sum_products(w[1:], vinv_wt)
        cov = np.linalg.pinv(s)
    except np.linalg.LinAlgError:
        return None
    return cov if np.all(np.isfinite(cov)) else None


def _shape_std(result: BundleResult, prob_k: int, cov: np.ndarray | None) -> np.ndarray | None:
    """Standard deviations of (c, alpha, beta, phi) from the bundle's covariance of the curve's
    parameters (:func:`_curve_covariance`), propagated through the end geometry."""
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


def _arc_parameters(ctrl: np.ndarray, n_out: int) -> np.ndarray:
    """Spline parameters u of ``n_out`` points equally spaced in 3-D arc length."""
    u = np.linspace(0.0, 1.0, 4000)
    dense = _Basis(len(ctrl)).values(u) @ ctrl
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))])
    return np.interp(np.linspace(0.0, s[-1], n_out), s, u)


def curve_point_std(
    prob: _Problem,
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
    (:func:`_curve_covariance`).  ``xy_var``: the variance (pixels^2) of a translation of the
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
        cov = _curve_covariance(prob, ctrl, m, b)
        if cov is None:
            return None
    basis = _Basis(len(ctrl))
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


def end_point_chi2(shape: np.ndarray, poses: np.ndarray, obs, inliers, w8) -> np.ndarray:
    """(N,) per-frame chi2 of a shape and poses against the end points and tangents."""
    from curverecon.refine.ml import standardised_residuals

    resid = standardised_residuals(shape, poses, obs.measurements(), w8)
    return np.sum(resid * resid, axis=1)


def gate_reference_chi2(chi2_answer: float, alternatives, options=None) -> float:
    """The end-point chi2 the never-worse gate measures the bundle's shape from.

    ``chi2_answer``: the end-point answer's chi2 on its inlier frames; ``alternatives``: its
    equally good ``Reconstruction.alternatives`` (each refitted on the same inlier frames with
    the same sigmas, so their chi2 compare).  With ``CurveOptions.never_worse_alternatives``
    the least of these chi2, else the answer's.  The end points' likelihood-ratio confidence
    region is then the set of shapes within :func:`never_worse_limit` (in units of the variance
    factor) of the best fit: the union of the regions about every hypothesis that fits about
    as well, which takes a bundle that chose one of them by the curve and refuses a shape
    outside all of them."""
    o = options if options is not None else CurveOptions()
    chi2 = float(chi2_answer)
    if o.never_worse_alternatives:
        for alt in alternatives or []:
            if np.isfinite(alt.chi2):
                chi2 = min(chi2, float(alt.chi2))
    return chi2


def never_worse_limit(dof: int, options=None) -> float:
    """The upper end of the never-worse gate's band (``CurveOptions.never_worse_f_test``): the
    limit on ``end_point_dchi2`` (the bundle shape's end-point chi2 above the reference, in
    units of the variance factor s2 = chi2 / ``dof`` of the end-point fit, ``dof`` = inlier
    frames - 4) when s2 is estimated from the fit itself, 4 F(4, dof) at the probability of
    ``CurveOptions.never_worse_dchi2`` under chi2 with 4 degrees of freedom (the known-variance
    limit, 99 %), which it tends to as dof grows: 28.0 at 12 frames, 19.1 at 20."""
    o = options if options is not None else CurveOptions()
    limit = float(o.never_worse_dchi2)
    if dof < 1 or not np.isfinite(limit) or limit <= 0.0:
        return limit
    from scipy.stats import chi2, f

    return float(4.0 * f.ppf(chi2.cdf(limit, 4), 4, int(dof)))


def polylines_reject_fixed_poses(
    counts: np.ndarray,
    rms_fixed: np.ndarray,
    rms_bundle: np.ndarray,
    k: int,
    level: float,
) -> tuple[bool, float]:
    """Whether the polylines reject the end-point answer's poses: the nested-model F test of
    the curve fitted with every pose fixed and its ends pinned (:func:`fit_curve_fixed_poses`,
    per-frame RMS ``rms_fixed`` px) against the bundle (``rms_bundle``; both on the frames
    whose polylines the fits use).  ``counts``: polyline points of those frames (each less 2,
    as :func:`_bic` counts them); ``k``: the bundle's control points.  The bundle has 5 N + 4
    more parameters than the pinned fixed-pose curve (3 K - 1 + 5 (N - 1) against
    2 + 3 (K - 4)), the noise level is the bundle's own RSS over its residual degrees of
    freedom (scale-free, like :func:`_bic`).  Returns (rejected at ``level``, the upper-tail
    probability)."""
    from scipy.stats import f

    counts = np.asarray(counts, float)
    n_fr = len(counts)
    n_obs = float(counts.sum())
    p = 5 * n_fr + 4
    dof2 = n_obs - (3 * k - 1 + 5 * (n_fr - 1))
    rss_f = float(np.sum(counts * np.asarray(rms_fixed, float) ** 2))
    rss_b = float(np.sum(counts * np.asarray(rms_bundle, float) ** 2))
    if dof2 < 1 or not (np.isfinite(rss_f) and np.isfinite(rss_b)) or rss_b <= 0.0:
        return False, 1.0
    stat = ((rss_f - rss_b) / p) / (rss_b / dof2)
    tail = float(f.sf(stat, p, dof2))
    return tail < 1.0 - level, tail


def _gap_to_curve(points: np.ndarray, other: BundleResult) -> np.ndarray:
    """Each point's distance (input units) from ``other``'s curve or its mirror image (depth
    negated: the same answer, an exact symmetry of orthographic views), whichever is nearer
    on average."""
    curve = other.curve_points(400)
    return min(
        (pl.distance_to_polyline(points, q)[0] for q in (curve, curve * [1.0, 1.0, -1.0])),
        key=lambda g: float(np.mean(g)),
    )


def refine_reconstruction(
    rec,
    obs,
    curve_start: np.ndarray | None,
    *,
    use_given: bool = False,
    point_sigma: float = 1.0,
    tangent_sigma_deg: float = 1.0,
    n_out: int | None = None,
    options=None,
    curve_frames: np.ndarray | None = None,
    fixed_start: Callable[[], np.ndarray | None] | None = None,
    start_for: Callable[[np.ndarray, np.ndarray], np.ndarray | None] | None = None,
):
    """Run the curve bundle on a reconstruction and return the updated answer.

    rec: a ``reconstruct.Reconstruction`` (its poses are the start); obs: the observations
    (with curves); curve_start: the start curve in frame 0's camera coordinates (``curve3d``),
    or None for :func:`flat_start`.  use_given: the input gave A', B' and the tangents (they
    join the fit as measurements with ``point_sigma``, ``tangent_sigma_deg``; tangents of
    frames the end-point fit marked as outliers are left out).  options: ``CurveOptions``.

    With given end points and tangents, two more steps (``CurveOptions``):

    - a frame whose polyline stays far from the fitted curve (``flag_rms_*``) while its end
      points fit is flagged: its polyline contradicts the end points (another curve, a tracking
      error) and is left out of a second fit, not averaged in (``curve_bundle.flagged_frames``);
    - never worse: the bundle's shape and poses are kept only if their end-point chi2 exceeds
      the end-point answer's by at most :func:`never_worse_limit` (``never_worse_dchi2``, or
      with ``never_worse_f_test`` its F-distribution counterpart for a variance estimated from
      the fit) in units of the end-point fit's own variance factor (chi2 / dof, the noise
      level the end points show).  Beyond that the
      polylines (or the curve model) pull the answer outside the end points' confidence region,
      so the end-point answer stays and the curve alone is fitted to the polylines with every
      pose fixed and the ends and end tangent lines pinned (:func:`fit_curve_fixed_poses`).
      Noise-free end points have a variance factor of float rounding: any curve-model error
      moves the bundle out of that region, and the exact answer stays exact.

    Returns ``(reconstruction, curve3d (n_out, 3), info)``: the shape and every pose from the
    fitted curve (normalised as in ``pose.normalise``), ``std`` from the bundle's covariance,
    ``chi2`` / per-frame ``chi2`` recomputed for the end points and tangents, the branch
    alternatives recomputed for the new shape; ``curve3d`` in frame 0's camera coordinates
    with A at z = 0 (the mirror image consistent with the frames' ``A3``, ``B3``, tangents);
    ``info`` the ``curve_bundle`` key of the output (see docs/file-formats.md).

    ``curve_frames`` (long sequences with given end points, ``CurveOptions.bundle_max_frames``):
    no joint fit; the end-point answer stays and the curve alone is fitted with every pose
    fixed (as when the never-worse test refuses the bundle) to the polylines of these frames;
    ``frame_rms_px`` is then measured on every frame.

    ``fixed_start``: the start curve of the fits with every pose fixed (exact end points, long
    sequences, a refused bundle), made only when one of them runs (None, or a None result:
    ``curve_start``).  That fit has local minima, so its start must be good, while the bundle
    itself starts well from a coarser curve (``curve.stage``: section 4's 60-sample curve of
    the branch search for the bundle, its full reconstruction made here only when needed).

    ``start_for(rotations, translations)``: a start curve (frame 0's camera coordinates) for
    other poses, for the bundle from frame 0's other pose branch
    (``CurveOptions.frame0_branch_dchi2``); None, or a None result: ``curve_start`` turned with
    frame 0.
    """
    from dataclasses import replace

    from curverecon.model.pose import normalise
    from curverecon.options import CurveOptions
    from curverecon.robust.search import branch_alternatives

    o = options if options is not None else CurveOptions()
    curves = obs.curves
    if curves is None:
        raise _error("the curve bundle needs a polyline in every frame")
    n = len(curves)
    flat = curve_start is None
    if flat:
        curve_start = flat_start(curves[0])
    ends = tangents = None
    if use_given:
        ends = np.stack([obs.a, obs.b], axis=1)
        tangents = np.stack([obs.tangent_a, obs.tangent_b], axis=1)
        tangents[~np.asarray(rec.inliers, bool)] = np.nan  # gross tangent errors: left out
    kw = {
        "ends": ends,
        "tangents": tangents,
        "point_sigma": point_sigma,
        "tangent_sigma_deg": tangent_sigma_deg,
        "k_max": o.bundle_max_control_points,
        "smooth_weight": o.bundle_smooth_weight,
        "misfit_z": o.bundle_misfit_z,
        "order_tol": o.bundle_order_tol,
    }

    def fixed_curve_start() -> np.ndarray:
        """The start of the fits with every pose fixed (``fixed_start``, else ``curve_start``)."""
        made = fixed_start() if fixed_start is not None else None
        return np.asarray(curve_start if made is None else made, float)

    flipped_start: dict = {}

    def frame0_other_branch():
        """(rotations, translations, start curve) with frame 0 on its other pose branch, the
        start curve that of those poses (``start_for``; else the start curve turned with frame
        0, X_cam = R_0 X_curve + t_0), or None when that branch's end-point chi2 is more than
        ``o.frame0_branch_dchi2`` above frame 0's own."""
        if (
            rec.branch_alternatives is None
            or rec.branch_alternative_chi2 is None
            or rec.frame_chi2 is None
            or curve_start is None
        ):
            return None
        dchi2 = float(rec.branch_alternative_chi2[0]) - float(rec.frame_chi2[0])
        if not np.isfinite(dchi2) or dchi2 > o.frame0_branch_dchi2:
            return None
        poses = np.array(rec.poses, float)
        poses[0] = rec.branch_alternatives[0]
        rot, tra = pose_rotations(poses), pose_translations(poses)
        if "start" not in flipped_start:
            # the curve of the flipped poses themselves where it can be made: the start curve
            # turned with frame 0 keeps the other frames' view of it, and its bundle went back
            # to the first start's poses (sharp-ends seed 9105, 1 px, 12 frames: other branch
            # at chi2 + 7.8, stopped as a retrace, curve3d 7.1 % of its length off; from the
            # flipped poses' own section-4 curve cost 1882.9 against 1884.5, 0.2 % off)
            made = start_for(rot, tra) if start_for is not None else None
            if made is None:
                r0, t0 = rec.rotations()[0], rec.translations()[0]
                made = (np.asarray(curve_start, float) - t0) @ r0 @ rot[0].T + tra[0]
            flipped_start["start"] = np.asarray(made, float)
        return rot, tra, flipped_start["start"]

    # every completed start of the last run: the minima the answer's competes with
    # (CurveOptions.rival_minima_std)
    tried: list[BundleResult] = []

    def run(mask=None):
        tried.clear()
        if flat:
            # no curve to start from: frame 0's polyline at depth 0, every pose searched
            br = bundle_from_frame(
                curves, rec.rotations(), rec.translations(), 0, polyline_mask=mask, **kw
            )
        else:
            br = bundle_adjust(
                curves, rec.rotations(), rec.translations(), curve_start, polyline_mask=mask, **kw
            )
            tried.append(br)
            flipped = frame0_other_branch()
            if flipped is not None:
                # frame 0's other branch (CurveOptions.frame0_branch_dchi2): the lower cost wins
                # it stops after its coarse stage when that is the first start's again
                # (CurveOptions.frame0_branch_same_deg)
                other = bundle_adjust(
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
        if _restart(br.rms if mask is None else br.rms[mask], br.sigma) and not flat:
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
        for ref in extra_start_frames(n, o.bundle_extra_starts):
            if not _restart(br.rms if mask is None else br.rms[mask], br.sigma):
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

    w8 = np.array([1.0 / point_sigma] * 4 + [1.0 / np.radians(tangent_sigma_deg)] * 2)
    inl = np.asarray(rec.inliers, bool)
    s2 = chi2_ep = None
    # the end-point fit's degrees of freedom: one per inlier frame (6 measurements, 5 pose
    # parameters) less the 4 of the shape
    dof = max(int(inl.sum()) - 4, 1)
    if use_given and rec.poses is not None:
        # the end-point fit's variance factor: the noise level its end points show
        chi2_ep = float(np.sum(end_point_chi2(rec.shape, rec.poses, obs, inl, w8)[inl]))
        s2 = max(chi2_ep / dof, o.variance_floor)
    # the polylines' noise level from the frames the curve is fitted to (long sequences: the
    # ``curve_frames`` subset; all 1,000 frames' estimates took a fifth of the curve stage)
    measured = curves if curve_frames is None else [curves[i] for i in curve_frames]
    sigma = max(float(np.median([noise_level(pl.as_polyline(p)) for p in measured])), SIGMA_FLOOR)
    limit = o.flag_rms_sigma * sigma + o.flag_rms_px
    warnings = list(rec.warnings)

    def flag_warning(flagged: list[int], rms: np.ndarray) -> None:
        warnings.append(
            f"frames {flagged}: the polyline contradicts the end points and tangents (RMS "
            f"{', '.join(f'{rms[i]:.1f}' for i in flagged)} px from the curve they fix, limit "
            f"{limit:.1f} px): left out of the curve fit"
        )

    def fixed_answer(
        start: np.ndarray, k_start: int, mask: np.ndarray, extra: dict, exact: bool = False
    ):
        """The end-point answer with the curve fitted to the polylines, every pose fixed
        (exact end points: the knots grow as the data ask, the model's own floors lowered;
        otherwise the bundle's curve model with the poses held)."""
        m_all, bb_all = _fixed_pose_frames(rec)
        a3, b3, ta3, tb3 = rec.points_3d()
        polys_all = _oriented(curves, rec)
        # the frames whose polylines the curve is fitted to (frame 0 first: its pose is the
        # curve's coordinates)
        sel = np.arange(n) if curve_frames is None else np.asarray(curve_frames, int)
        polys = [polys_all[i] for i in sel]
        m, bb, mask = m_all[sel], bb_all[sel], np.asarray(mask, bool)[sel]

        def fit(mask: np.ndarray, start: np.ndarray, k0: int):
            return fit_curve_fixed_poses(
                polys,
                m,
                bb,
                (a3[0], b3[0], ta3[0], tb3[0]),
                start - start[0] + a3[0],
                sigma=sigma,
                k_start=k0,
                k_max=o.max_control_points if exact else k0,
                polyline_mask=mask,
                smooth_weight=o.fixed_pose_smooth_weight
                * (o.fixed_pose_smooth_factor if exact else 1.0),
                reverse_factor=o.fixed_pose_reverse_factor if exact else 1.0,
                abs_tol=o.fixed_pose_abs_tol,
                resolution=o.fixed_pose_resolution,
                unfold=o.exact_unfold if exact else 0,
            )

        def fit_exact(mask: np.ndarray, start: np.ndarray, k0: int):
            """:func:`fit`, and for exact end points, when the fit stays stuck above the
            noise-free target (``CurveOptions.exact_restart_rms`` of a polyline's length), again
            from ``exact_restart_control_points``: the lower polyline misfit kept."""
            out = fit(mask, start, k0)
            k1 = o.exact_restart_control_points
            if not exact or not k1 or k1 == k0:
                return out
            stuck = (out[2] > o.exact_restart_rms * lengths) & mask
            if not stuck.any():
                return out
            out2 = fit(mask, start, k1)
            if np.sum(out2[2][mask] ** 2) < np.sum(out[2][mask] ** 2):
                return out2
            return out

        lengths = np.array([pl.arc_length(p)[-1] for p in polys])  # px, the fitted frames
        ctrl, _, rms = fit_exact(mask, start, k_start)
        flagged = list(extra.get("flagged_frames", []))
        if not flagged and use_given:
            bad = rms > limit
            if bad.any() and bad.sum() <= o.max_flagged_fraction * len(sel):
                flagged = [int(i) for i in sel[np.flatnonzero(bad)]]
                flag_warning(flagged, np.bincount(sel, rms, minlength=n))
                mask = ~bad
                dense = _Basis(len(ctrl)).values(np.linspace(0.0, 1.0, 400)) @ ctrl
                ctrl, _, rms = fit_exact(mask, dense, k_start)
        k = ctrl.shape[0]
        rms_all = rms
        if curve_frames is not None:  # every frame's distance from the curve (one evaluation)
            rms_all = _Problem(polys_all, sigma, k, None, None, 1.0, 1.0).residuals(
                ctrl, m_all, bb_all, jac=False
            )[2]
        u = _arc_parameters(ctrl, n_out or 200)
        curve3d = _Basis(k).values(u) @ ctrl
        prob = _Problem(polys, sigma, k, None, None, 1.0, 1.0)
        prob.poly_w = mask.astype(float)
        prob.smooth_weight = o.fixed_pose_smooth_weight
        base, d = _pinned_map(k, a3[0], b3[0], ta3[0], tb3[0])
        # the pinned fit holds A where frame 0 measured it, A' with point_sigma in x and y:
        # that translation of the whole curve adds point_sigma^2 diag(1, 1, 0) to each point's
        # covariance
        stds = curve_point_std(
            prob,
            ctrl,
            m,
            bb,
            u,
            d[[j for j in range(3 * k) if j != 2]],
            xy_var=point_sigma**2,
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
        return (
            replace(rec, warnings=warnings, curve3d_std=std, curve3d_normal_std=normal_std),
            curve3d,
            info,
        )

    if s2 is not None and s2 < o.exact_variance_factor:
        # exact end points (noise-free): the bundle could only move the answer out of their
        # confidence region, which has shrunk to float rounding
        start = fixed_curve_start()
        return fixed_answer(start, o.exact_start_control_points, np.ones(n, bool), {}, exact=True)
    if curve_frames is not None and not flat:
        return fixed_answer(fixed_curve_start(), N_CONTROL, np.ones(n, bool), {})
    br = run()
    flagged: list[int] = []
    mask = np.ones(n, bool)
    if use_given:
        bad = br.rms > limit
        if bad.any() and bad.sum() <= o.max_flagged_fraction * n:
            flagged = [int(i) for i in np.flatnonzero(bad)]
            flag_warning(flagged, br.rms)
            mask = ~bad
            br = run(mask)
    if not use_given:
        # polylines only: a few frames left on a wrong pose branch searched again against the
        # curve the others fit (the end tangents are the curve's own: one such frame bends them)
        br = resect_uneven_frames(br, curves, smooth_weight=o.bundle_smooth_weight)
    if not use_given and o.polylines_only_control_points:
        # polylines only: the end tangents are the curve's own; its number of control points
        # from the data (the information criterion), not the fixed default
        br, _ = select_control_points(
            br, curves, o.polylines_only_control_points, smooth_weight=o.bundle_smooth_weight
        )
    shape, poses, _ = shape_and_poses(br)
    shape_n, poses_n = normalise(shape, poses)
    frame_chi2 = end_point_chi2(shape_n, poses_n, obs, inl, w8)
    accepted, dchi2, band = True, None, False
    if s2 is not None:
        # the end points' profile chi2 of the bundle's shape (every pose at its best for that
        # shape): the shape's own distance from the end-point answer, in 4 dimensions
        from curverecon.refine.ml import optimise_poses

        _, resid = optimise_poses(shape_n, poses_n, obs.measurements(), w8, 10)
        profile = float(np.sum((resid * resid).sum(axis=1)[inl]))
        dchi2 = (
            min(profile, float(np.sum(frame_chi2[inl])))
            - gate_reference_chi2(chi2_ep, rec.alternatives, o)
        ) / s2
        # the gate guards a determined end-point answer; where the end points leave the shape
        # undetermined (singular information; with ``o.never_worse_alternatives`` off also
        # other shapes fitting as well) the curve decides
        undetermined = rec.std is None or (
            bool(rec.alternatives) and not o.never_worse_alternatives
        )
        accepted = undetermined or dchi2 <= o.never_worse_dchi2
        # between the known-variance limit and the estimated-variance one the end points leave
        # it open whether the shape is inside their 99 % region: the polylines decide below
        band = not accepted and o.never_worse_f_test and dchi2 <= never_worse_limit(dof, o)
    k = br.control.shape[0]
    if not accepted:
        # the end-point answer stays; the curve alone is fitted with its poses and ends
        a3, _, ta3, _ = rec.points_3d()
        start = np.asarray(curve_start, float) if flat else fixed_curve_start()
        if flat:
            start = br.curve_points(200)
            d0 = start[min(5, len(start) - 1)] - start[0]
            if d0 @ ta3[0] < (d0 * [1.0, 1.0, -1.0]) @ ta3[0]:
                start = start * [1.0, 1.0, -1.0]
        extra = {
            "iterations": int(br.iterations),
            "converged": bool(br.converged),
            "end_point_dchi2": float(dchi2),
            "flagged_frames": flagged,
        }
        n_warnings = len(warnings)
        out, curve3d, info = fixed_answer(start, k, mask, extra)
        if band:
            # the band (CurveOptions.never_worse_f_test): the bundle's shape is kept when the
            # polylines reject the end-point answer's poses (the curve fitted on them stays
            # beyond the noise from the polylines the bundle fits)
            counts = np.array([max(len(c) - 2, 1) for c in curves], float)[mask]
            rms_fixed = np.asarray(info["frame_rms_px"], float)[mask]
            accepted, tail = polylines_reject_fixed_poses(
                counts, rms_fixed, br.rms[mask], k, o.never_worse_polyline_level
            )
            if accepted:
                del warnings[n_warnings:]  # the fixed-pose fit's own flags: not the answer's
                warnings.append(
                    f"the curve bundle's shape is {float(dchi2):.1f} (variance factors) above the "
                    "end points' best fit, beyond the 99 % limit for a known noise level "
                    f"({o.never_worse_dchi2:g}) but within it for the level the end points show "
                    f"({dof} degrees of freedom); the polylines reject the "
                    f"end-point answer's poses (probability {tail:.1e}): the bundle's answer kept"
                )
    if not accepted:
        if out.std is not None:
            # the two answers disagree beyond the end points' 99 % region: one of the models
            # (the end points' or the curve's) is off, and refusals come most often where the
            # end-point answer itself is (1 px, tuning seeds 5000-5014: |error| / std RMS 1.7
            # on refused scenes, up to 3.7).  Its std is scaled (a Birge ratio) by the least
            # factor that brings the bundle's shape inside its 99 % region.
            scale = float(np.sqrt(max(float(dchi2) / o.never_worse_dchi2, 1.0)))
            std_out = out.std * scale
            if o.refused_std_disagreement:
                # ... and, per parameter, the two answers' difference is added in quadrature:
                # which model is off is not known, so the answer kept is uncertain by at least
                # its distance from the other one
                diff = np.asarray(shape_n, float) - np.asarray(rec.shape, float)
                diff[3] = (diff[3] + np.pi) % (2.0 * np.pi) - np.pi
                std_out = np.sqrt(std_out**2 + diff**2)
            out = replace(out, std=std_out)
        if o.refused_std_disagreement and out.curve3d_normal_std is not None:
            # ... and likewise each curve3d point by its distance from the bundle's curve: the
            # fixed-pose curve's std is the curve's alone given the end-point answer's poses,
            # which the refusal says are off (clothoid seed 1201, 1 px, 12 frames, a refused
            # noise draw: the curve 1.7 % of its length off, its std across the curve 0.04 %)
            gap = _gap_to_curve(curve3d, br)
            out = replace(
                out,
                curve3d_std=np.sqrt(out.curve3d_std**2 + gap**2),
                curve3d_normal_std=np.sqrt(out.curve3d_normal_std**2 + gap**2),
            )
        return out, curve3d, info
    # curve samples equally spaced in 3-D arc length, in the curve frame
    u_out = _arc_parameters(br.control, int(n_out) if n_out is not None else 200)
    pts = _Basis(len(br.control)).values(u_out) @ br.control
    # normalise changes the curve frame by rotations (no change in camera coordinates) and,
    # for phi < 0, by the mirror image z -> -z (camera depth negated; A stays at z = 0)
    curve3d = pts * [1.0, 1.0, -1.0] if shape[3] < 0 else pts
    alt_poses, alt_chi2 = branch_alternatives(obs, shape_n, poses_n, w8)
    prob = _Problem(
        _oriented_to(curves, br),
        br.sigma,
        k,
        ends,
        tangents,
        point_sigma,
        float(np.radians(tangent_sigma_deg)),
    )
    prob.poly_w = mask.astype(float)
    prob.smooth_weight = o.bundle_smooth_weight
    # the covariance without the reverse term: it measures the same polyline points again (a
    # guard against hidden detours, no information of its own), and its distances to a noisy
    # polyline's jagged segments fake information along the curve.  With it, polylines only,
    # Bezier seed 1300 (0.5 px, 12 frames) at the true curve and poses: alpha, beta, phi std
    # 2.7, 4.5, 9.6 degrees on noisy polylines against 5.4, 7.9, 12.3 on noise-free ones (4
    # control points: 0.32, 0.88, 0.92 against 0.58, 1.17, 1.09, the spread over noise draws
    # about 0.85, 1.1, 0.95); without it 5.5, 8.0, 12.4 (0.59, 1.17, 1.10) on both
    prob.rev_weight = [0.0] * prob.n
    cov = _curve_covariance(prob, br.control, br.m, br.b)
    std = _shape_std(br, k, cov)
    stds = curve_point_std(prob, br.control, br.m, br.b, u_out, cov=cov)
    point_std, normal_std = (None, None) if stds is None else stds
    rival = min((r for r in tried if r is not br), key=lambda r: r.cost, default=None)
    if o.rival_minima_std and use_given and rival is not None:
        # another start ended in another minimum about as low (CurveOptions.rival_minima_std):
        # the data leave the two open, and the answer's RMS error includes the gap to the
        # rival weighted by its probability p = 1 / (1 + exp(dcost / 2))
        p_rival = 1.0 / (1.0 + np.exp(min(0.5 * (rival.cost - br.cost), 700.0)))
        gap = _gap_to_curve(pts, rival)
        r_shape = normalise(*shape_and_poses(rival)[:2])[0]
        diff = np.asarray(r_shape, float) - np.asarray(shape_n, float)
        diff[3] = (diff[3] + np.pi) % (2.0 * np.pi) - np.pi
        if std is not None:
            std = np.sqrt(std**2 + p_rival * diff**2)
        if normal_std is not None:
            normal_std = np.sqrt(normal_std**2 + p_rival * gap**2)
            point_std = np.sqrt(point_std**2 + p_rival * gap**2)
        if p_rival >= o.rival_warning_probability:
            warnings.append(
                f"another minimum of the curve bundle fits about as well (cost "
                f"{rival.cost - br.cost:+.1f}, probability {p_rival:.2f}; its curve up to "
                f"{float(np.max(gap)):.1f} px away): the std include the gap"
            )
    limit = o.flag_rms_sigma * br.sigma + o.flag_rms_px
    bad = [int(i) for i in np.flatnonzero((br.rms > limit) & mask)]
    if bad:
        warnings.append(
            f"frames {bad}: the fitted curve stays up to {float(br.rms[bad].max()):.1f} px (RMS) "
            f"from their polylines (limit {limit:.1f} px)"
        )
    if not use_given:
        warnings.append(
            "alpha, beta, phi come from the fitted curve's end tangents (no tangents were given): "
            "ends of noisy polylines fix them less well than their std says"
        )
    new = replace(
        rec,
        estimator="curve-bundle",
        shape=shape_n,
        poses=poses_n,
        std=std if std is not None else rec.std,
        warnings=warnings,
        chi2=float(np.sum(frame_chi2[inl])),
        frame_chi2=frame_chi2,
        branch_alternatives=alt_poses,
        branch_alternative_chi2=alt_chi2,
        curve3d_std=point_std,
        curve3d_normal_std=normal_std,
    )
    info = {
        "control_points": int(k),
        "sigma_px": float(br.sigma),
        "frame_rms_px": [float(v) for v in br.rms],
        "iterations": int(br.iterations),
        "converged": bool(br.converged),
        "accepted": True,
        "end_point_dchi2": None if dchi2 is None else float(dchi2),
        "flagged_frames": flagged,
    }
    return new, curve3d, info
