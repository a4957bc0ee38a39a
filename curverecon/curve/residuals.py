"""The residual model of the curve bundle (the problem the solvers of ``curve.lm`` minimise):
the spline basis on the problem's grids, every frame's residual rows and their Jacobians
(:meth:`Problem.evaluate`), the normal equations in blocks (:meth:`Problem.normal_equations`).

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
"""

from __future__ import annotations

import functools
from collections.abc import Sequence

import numpy as np

from curverecon.curve import polyline as pl
from curverecon.curve.bundle_kernel import (
    basis_rows,
    end_rows,
    foot_parameters,
    forward_rows,
    longest_nondecreasing,
    polyline_normal_blocks,
    polyline_rows,
    segment_offsets,
    tangent_rows,
)
from curverecon.curve.spline import Basis
from curverecon.options import CurveOptions

#: Weight of the difference penalty (order DIFF_ORDER) relative to one polyline point's residual:
#: the default of ``CurveOptions.bundle_smooth_weight`` (the reason for its value there).
SMOOTH_WEIGHT = CurveOptions.bundle_smooth_weight


#: Huber threshold of the polyline-point residuals, in units of sigma.
HUBER_K = 3.0


#: Floor of the pixel noise used as the residual unit (float rounding, sub-pixel tracing).
SIGMA_FLOOR = 0.05


#: Dense samples per knot span for the foot-point search.
SAMPLES_PER_SPAN = 24


#: Order of the differences of the control points the regulariser penalises.
DIFF_ORDER = 4


#: Curve samples per knot span of the reverse term (curve to polyline) ...
REVERSE_SAMPLES_PER_SPAN = 6


#: ... and its total weight relative to the forward term (polyline points to curve).
REVERSE_WEIGHT = 0.02


#: Newton steps of a foot searched again on its polyline neighbours' stretch of the curve
#: (:meth:`Problem._ordered_feet`).
ORDER_NEWTON = 8


_EMPTY2 = np.empty((0, 2))


_EMPTY3 = np.empty((0, 3))


@functools.lru_cache(maxsize=64)
def _problem_tables(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:class:`Problem`'s tables that depend on K alone, once per K (read-only, shared): the
    dense grid u and its basis values (foot-point search), the reverse samples' basis rows."""
    basis = Basis(k)
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


def expm_so3_batch(w: np.ndarray) -> np.ndarray:
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


def thinned(poly: np.ndarray, target: int) -> np.ndarray:
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


def nondecreasing_mask(x: np.ndarray) -> np.ndarray:
    """Mask of one longest non-decreasing subsequence of ``x`` (patience sorting,
    ``bundle_kernel.longest_nondecreasing``: the fold test runs it on every frame's feet)."""
    return longest_nondecreasing(np.ascontiguousarray(x, float))


class Problem:
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
        self.basis = Basis(k)
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
        kept: :func:`thinned`), stand for them: each forward row weighted by the square root
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
            keep = nondecreasing_mask(uf)
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

    def _polyline_part(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, jac: bool):
        """The polyline rows of :meth:`evaluate` (the forward term, then the reverse term), with
        Huber and the weights: (residuals, basis rows ``nus``, ``dmw``, pose Jacobian rows (None
        without ``jac``), per-frame RMS px)."""
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
            np.asarray(self.poly_w, float),
            np.sqrt(np.asarray(self.frame_w, float)),
            float(s),
            HUBER_K,
            bool(jac),
            dm,
            dirs,
            yy,
        )
        return res_p, nus, dmw, (jp_p if jac else None), rms

    def _robust_end_rows(self, ctrl, m, b, er, ejc, ejp, jac: bool):
        """The end rows with robust ends (``END_POLISH``): Huber on each 2-D offset of A', B'
        from the polyline's ends by its length (see :func:`_huber_points`), and A, B themselves
        on the polyline (quadratic)."""
        n, s = self.n, self.sigma
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
        return er, ejc, ejp

    def _tangent_part(self, ctrl: np.ndarray, m: np.ndarray, jac: bool):
        """The given tangent directions' rows (lines; per frame at A and B): (residuals (N, 2),
        their Jacobians (N, 2, n_curve), (N, 2, 5))."""
        n = self.n
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
        return tangent_rows(
            v3,
            ang,
            self._tangent_ok,
            m,
            float(self.tangent_sigma),
            self.cidx,
            self.n_curve,
            jac,
        )

    def _frame_blocks(self, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, jac: bool):
        """Every frame's fixed number of rows besides its polyline's: the polyline's ends as the
        images of A and B, the given A', B' and tangents.  Returns (residuals (N, rows per
        frame), their Jacobians (N, rows, n_curve), (N, rows, 5)); the Jacobians None without
        ``jac``."""
        s = self.sigma
        pw = np.asarray(self.poly_w, float)
        # the polyline's end points are the images of A and B
        er, ejc, ejp = end_rows(ctrl, m, b, self.end_img, float(s), self.cidx, self.n_curve, jac)
        if self.robust_ends:
            er, ejc, ejp = self._robust_end_rows(ctrl, m, b, er, ejc, ejp, jac)
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
            out, jt, jtp = self._tangent_part(ctrl, m, jac)
            blocks_r.append(out)
            blocks_c.append(jt)
            blocks_p.append(jtp)
        per = np.concatenate(blocks_r, axis=1)  # (N, rows per frame)
        if not jac:
            return per, None, None
        return per, np.concatenate(blocks_c, axis=1), np.concatenate(blocks_p, axis=1)

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
        n = self.n
        res_p, nus, dmw, jp_p, rms = self._polyline_part(ctrl, m, b, jac)
        per, per_c, per_p = self._frame_blocks(ctrl, m, b, jac)
        # the frame weights (the polyline rows have theirs from polyline_rows)
        fwe = np.sqrt(np.asarray(self.frame_w, float))[:, None]
        # difference regulariser on the control points (see the module docstring)
        wreg = self.smooth_weight / self.sigma
        reg = ((self.dreg @ ctrl) * wreg).reshape(-1)
        rr = np.concatenate([res_p, (per * fwe).reshape(-1), reg])
        rows = self._rows.get(per.shape[1])
        if rows is None:  # each row's frame (-1: the regulariser), by the rows per frame
            rows = np.concatenate(
                [self.rows_f, np.repeat(np.arange(n), per.shape[1]), np.full(len(reg), -1)]
            )
            rows.flags.writeable = False
            self._rows[per.shape[1]] = rows
        if not jac:
            return rr, None, None, rows, rms
        jc_other = (per_c * fwe[:, :, None]).reshape(-1, self.n_curve)
        jp = np.vstack([jp_p, (per_p * fwe[:, :, None]).reshape(-1, 5), np.zeros((len(reg), 5))])
        if not curve_jac:
            return rr, None, jp, rows, rms
        jreg = np.zeros((len(reg), self.n_curve))
        for cc in range(3):
            col = self.cidx[:, cc]
            ok = col >= 0
            jreg[cc::3][:, col[ok]] = self.dreg[:, ok] * wreg
        if compact:
            return rr, (nus, dmw, np.vstack([jc_other, jreg])), jp, rows, rms
        jc = np.vstack([self._jc_rows(nus, dmw), jc_other, jreg])
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

    def subset(self, frames: Sequence[int]) -> Problem:
        """The problem of the given frames alone (repeats allowed: one per pose to refine),
        with their weights; for the pose search (:func:`resect_all`)."""
        fr = np.asarray(frames, int)
        sub = Problem(
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
            m2[1:] = expm_so3_batch(dp[:, :3]) @ m[1:]
            b2[1:, :2] += dp[:, 3:5]
        return c2, m2, b2


def bic(prob: Problem, rms: np.ndarray, n_par: int, per_param: float | None = None) -> float:
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
