"""Nearest-point searches of the curve bundle (``curve.bundle``): numba loops, one core.

Each residual evaluation of the bundle searches, for every interior polyline point of every
frame, the nearest sample of that frame's densely sampled projected curve (the foot point's
start), and for every reverse-term curve sample the nearest vertex of its frame's polyline.
Both were k-d tree queries (``scipy.spatial.cKDTree``: a tree built per evaluation over every
frame's samples, the frames kept apart along a third axis); here they are exact linear scans
of the point's own frame, pruned by the bounding boxes of runs of consecutive samples (a run
whose box is farther than the best distance so far cannot hold the nearest sample).  The same
nearest points as the trees (to ties of equal distance: the scan keeps the first).

Compiled with ``cache=True`` (numba's on-disk cache: the first import of a new version compiles
once, about a second); no C compiler is needed at install time.
"""

from __future__ import annotations

import numba
import numpy as np

_JIT = {"cache": True, "nogil": True, "fastmath": False}

#: Samples per bounding box of the pruned scans (the dense curve has 24 per knot span).
RUN = 8


@numba.njit(**_JIT)
def _boxes(pts, lo, hi, run):
    """Bounding boxes (x0, x1, y0, y1) of runs of ``run`` consecutive points pts[lo:hi]."""
    nb = (hi - lo + run - 1) // run
    box = np.empty((nb, 4))
    for k in range(nb):
        a = lo + k * run
        b = min(a + run, hi)
        x0 = pts[a, 0]
        x1 = x0
        y0 = pts[a, 1]
        y1 = y0
        for j in range(a + 1, b):
            x = pts[j, 0]
            y = pts[j, 1]
            if x < x0:
                x0 = x
            if x > x1:
                x1 = x
            if y < y0:
                y0 = y
            if y > y1:
                y1 = y
        box[k, 0] = x0
        box[k, 1] = x1
        box[k, 2] = y0
        box[k, 3] = y1
    return box


@numba.njit(**_JIT)
def _scan(pts, lo, hi, box, run, qx, qy, start):
    """Index in pts[lo:hi] (global) of the point nearest to (qx, qy): the run holding
    ``start`` first (a good guess makes the pruning tight), then every run whose box can hold
    a nearer point.  Ties: the lowest index."""
    best = np.inf
    bj = lo
    nb = box.shape[0]
    k0 = (start - lo) // run
    if k0 < 0 or k0 >= nb:
        k0 = 0
    for t in range(nb + 1):
        if t == 0:
            k = k0
        else:
            k = t - 1
            if k == k0:
                continue
            dx = 0.0
            if qx < box[k, 0]:
                dx = box[k, 0] - qx
            elif qx > box[k, 1]:
                dx = qx - box[k, 1]
            dy = 0.0
            if qy < box[k, 2]:
                dy = box[k, 2] - qy
            elif qy > box[k, 3]:
                dy = qy - box[k, 3]
            if dx * dx + dy * dy > best:
                continue
        a = lo + k * run
        b = min(a + run, hi)
        for j in range(a, b):
            ex = pts[j, 0] - qx
            ey = pts[j, 1] - qy
            d = ex * ex + ey * ey
            if d < best or (d == best and j < bj):
                best = d
                bj = j
    return bj


@numba.njit(**_JIT)
def nearest_in_frames(pts, lo, hi, q, qlo, qhi):
    """For every frame f, the nearest of pts[lo[f]:hi[f]] to each of q[qlo[f]:qhi[f]]:
    (len(q),) global indices into pts.  Frames with an empty range of pts give lo[f]."""
    out = np.empty(q.shape[0], np.int64)
    for f in range(lo.shape[0]):
        a, b = lo[f], hi[f]
        if b <= a:
            for p in range(qlo[f], qhi[f]):
                out[p] = a
            continue
        box = _boxes(pts, a, b, RUN)
        guess = a
        for p in range(qlo[f], qhi[f]):
            guess = _scan(pts, a, b, box, RUN, q[p, 0], q[p, 1], guess)
            out[p] = guess
    return out


@numba.njit(**_JIT)
def foot_parameters(proj, u_grid, ps, q, q_lo, q_cnt):
    """Curve parameter u of the foot point of each polyline point on its frame's projected
    curve (``residuals.Problem._all_foot_points``): the nearest dense sample (proj (N, G, 2) at
    ``u_grid``), the nearer of its two dense segments, then two Newton steps on |p(u) - q|^2
    (each at most one grid step) on the exact curve, whose spans' power-series coefficients
    are ps (N, spans, 4, 2).  Frame f's points are q[q_lo[f] : q_lo[f] + q_cnt[f]]."""
    n, g = proj.shape[0], proj.shape[1]
    spans = ps.shape[1]
    du = u_grid[1] - u_grid[0]
    out = np.empty(q.shape[0])
    for f in range(n):
        pts = proj[f]
        box = _boxes(pts, 0, g, RUN)
        guess = 0
        for p in range(q_lo[f], q_lo[f] + q_cnt[f]):
            qx, qy = q[p, 0], q[p, 1]
            j = _scan(pts, 0, g, box, RUN, qx, qy, guess)
            guess = j
            best_d = np.inf
            u = 0.0
            for side in range(2):
                js = max(j - 1, 0) if side == 0 else min(j, g - 2)
                s0x, s0y = pts[js, 0], pts[js, 1]
                sx, sy = pts[js + 1, 0] - s0x, pts[js + 1, 1] - s0y
                len2 = max(sx * sx + sy * sy, 1e-300)
                t = ((qx - s0x) * sx + (qy - s0y) * sy) / len2
                t = min(max(t, 0.0), 1.0)
                ex = s0x + t * sx - qx
                ey = s0y + t * sy - qy
                d = ex * ex + ey * ey
                if d < best_d:
                    best_d = d
                    u = u_grid[js] + t * du
            for _ in range(2):  # Newton
                tt = min(max(u, 0.0), 1.0) * spans
                k = min(int(tt), spans - 1)
                x = tt - k
                c = ps[f, k]
                ex = ((c[3, 0] * x + c[2, 0]) * x + c[1, 0]) * x + c[0, 0] - qx
                ey = ((c[3, 1] * x + c[2, 1]) * x + c[1, 1]) * x + c[0, 1] - qy
                d1x = ((3.0 * c[3, 0] * x + 2.0 * c[2, 0]) * x + c[1, 0]) * spans
                d1y = ((3.0 * c[3, 1] * x + 2.0 * c[2, 1]) * x + c[1, 1]) * spans
                ddx = (6.0 * c[3, 0] * x + 2.0 * c[2, 0]) * spans * spans
                ddy = (6.0 * c[3, 1] * x + 2.0 * c[2, 1]) * spans * spans
                g1 = d1x * ex + d1y * ey
                g2 = d1x * d1x + d1y * d1y + ddx * ex + ddy * ey
                step = -g1 / g2 if g2 > 0 else 0.0
                u = min(max(u + min(max(step, -du), du), 0.0), 1.0)
            out[p] = u
    return out


@numba.njit(**_JIT)
def forward_rows(ps, u, q, q_lo, q_cnt):
    """The forward term's rows (``residuals.Problem.evaluate``) at the foot parameters u: per
    polyline point the offset direction (the projected curve's unit normal at the foot point;
    the offset's own direction at the curve's ends), the signed distance along it and the
    squared distance.  ps (N, spans, 4, 2) as in :func:`foot_parameters`."""
    n, spans = ps.shape[0], ps.shape[1]
    nq = q.shape[0]
    direc = np.empty((nq, 2))
    r = np.empty(nq)
    dist2 = np.empty(nq)
    for f in range(n):
        for p in range(q_lo[f], q_lo[f] + q_cnt[f]):
            uu = u[p]
            tt = min(max(uu, 0.0), 1.0) * spans
            k = min(int(tt), spans - 1)
            x = tt - k
            c = ps[f, k]
            ex = ((c[3, 0] * x + c[2, 0]) * x + c[1, 0]) * x + c[0, 0] - q[p, 0]
            ey = ((c[3, 1] * x + c[2, 1]) * x + c[1, 1]) * x + c[0, 1] - q[p, 1]
            tx = ((3.0 * c[3, 0] * x + 2.0 * c[2, 0]) * x + c[1, 0]) * spans
            ty = ((3.0 * c[3, 1] * x + 2.0 * c[2, 1]) * x + c[1, 1]) * spans
            tn = np.sqrt(tx * tx + ty * ty)
            d2 = ex * ex + ey * ey
            if uu > 0.0 and uu < 1.0 and tn > 0:
                s = max(tn, 1e-300)
                dx, dy = -ty / s, tx / s
            else:
                s = max(np.sqrt(d2), 1e-300)
                dx, dy = ex / s, ey / s
            direc[p, 0] = dx
            direc[p, 1] = dy
            r[p] = dx * ex + dy * ey
            dist2[p] = d2
    return direc, r, dist2


@numba.njit(**_JIT)
def segment_offsets(verts, v_lo, v_hi, pts, q_lo, q_hi):
    """Direction and signed distance of points from their frame's polyline
    (``residuals._segment_offsets`` after the nearest vertex, :func:`nearest_in_frames`): the
    nearer of the two segments at the nearest vertex (the segment's normal; beyond the
    polyline's ends the offset direction).  Frame f's polyline is verts[v_lo[f] : v_hi[f] + 1],
    its points pts[q_lo[f] : q_hi[f]]."""
    j_all = nearest_in_frames(verts, v_lo, v_hi + 1, pts, q_lo, q_hi)
    npt = pts.shape[0]
    best_dir = np.zeros((npt, 2))
    best_r = np.zeros(npt)
    for f in range(v_lo.shape[0]):
        lo, hi = v_lo[f], v_hi[f]
        for p in range(q_lo[f], q_hi[f]):
            j = j_all[p]
            px, py = pts[p, 0], pts[p, 1]
            best_d = np.inf
            for side in range(2):
                js = max(j - 1, lo) if side == 0 else min(j, hi - 1)
                s0x, s0y = verts[js, 0], verts[js, 1]
                sx, sy = verts[js + 1, 0] - s0x, verts[js + 1, 1] - s0y
                len2 = max(sx * sx + sy * sy, 1e-300)
                t = ((px - s0x) * sx + (py - s0y) * sy) / len2
                inside = (t > 0 or js > lo) and (t < 1 or js < hi - 1)
                t = min(max(t, 0.0), 1.0)
                ex = px - (s0x + t * sx)
                ey = py - (s0y + t * sy)
                d = ex * ex + ey * ey
                if inside:
                    sl = np.sqrt(len2)
                    dx, dy = -sy / sl, sx / sl
                else:
                    sd = max(np.sqrt(d), 1e-300)
                    dx, dy = ex / sd, ey / sd
                if d < best_d:
                    best_d = d
                    best_dir[p, 0] = dx
                    best_dir[p, 1] = dy
                    best_r[p] = dx * ex + dy * ey
    return best_dir, best_r


@numba.njit(**_JIT)
def polyline_normal_blocks(nus, dmw, jp, res, rows, cidx, u, gc, v, w, gp):
    """Add the polyline rows' terms to the bundle's normal equations in blocks
    (``residuals.Problem.normal_equations``) without the dense Jacobian: row i's curve Jacobian
    is ``nus[i, k] * dmw[i, c]`` at column ``cidx[k, c]`` (a cubic B-spline point depends on
    at most 4 control points: the zero basis values are skipped), its pose Jacobian jp[i]
    (frame rows[i]; frame 0's pose is the gauge, no block).  Accumulates U = Jc^T Jc and
    gc = Jc^T r (u, gc) and per frame V = Jp^T Jp, W = Jc^T Jp, gp = Jp^T r in place; u and v
    must start at zero (their upper triangles are summed, then mirrored)."""
    kk = nus.shape[1]
    cols = np.empty(3 * kk, np.int64)
    vals = np.empty(3 * kk)
    for i in range(nus.shape[0]):
        m = 0
        for k in range(kk):
            nk = nus[i, k]
            if nk == 0.0:
                continue
            for c in range(3):
                col = cidx[k, c]
                if col >= 0:
                    cols[m] = col
                    vals[m] = nk * dmw[i, c]
                    m += 1
        ri = res[i]
        for a in range(m):
            ca, va = cols[a], vals[a]
            gc[ca] += va * ri
            for b2 in range(a, m):  # the upper triangle (cols increase along a row)
                u[ca, cols[b2]] += va * vals[b2]
        f = rows[i]
        if f < 1:
            continue
        for p in range(5):
            jpp = jp[i, p]
            gp[f, p] += jpp * ri
            for q2 in range(p, 5):
                v[f, p, q2] += jpp * jp[i, q2]
        for a in range(m):
            ca, va = cols[a], vals[a]
            for p in range(5):
                w[f, ca, p] += va * jp[i, p]
    # the lower triangles: the same products (x y = y x), the same sums
    nc = u.shape[0]
    for a in range(nc):
        for b2 in range(a):
            u[a, b2] = u[b2, a]
    for f in range(v.shape[0]):
        for p in range(5):
            for q2 in range(p):
                v[f, p, q2] = v[f, q2, p]


@numba.njit(**_JIT)
def nearest_distances(pts, q):
    """Distance of each point q[i] from the nearest of pts (the pose sweep of
    ``pose_search._resect_starts``: a polyline resampled, every sweep pose's projected curve
    samples): the pruned scan, each query starting from the previous one's nearest point
    (consecutive queries are neighbouring curve samples).  The same distances as a k-d tree's
    query."""
    g = pts.shape[0]
    box = _boxes(pts, 0, g, RUN)
    out = np.empty(q.shape[0])
    guess = 0
    for i in range(q.shape[0]):
        j = _scan(pts, 0, g, box, RUN, q[i, 0], q[i, 1], guess)
        guess = j
        ex = pts[j, 0] - q[i, 0]
        ey = pts[j, 1] - q[i, 1]
        out[i] = np.sqrt(ex * ex + ey * ey)
    return out


@numba.njit(**_JIT)
def sweep_distances(pts, q, per, bound):
    """:func:`nearest_distances` of q, ``per`` consecutive points per sweep pose (pose-major),
    each pose's points measured only until their sum of squared distances exceeds ``bound``:
    returns (distances, inf where not measured; (poses,) bool, True for a pose stopped so).
    The distances measured are :func:`nearest_distances`' (the scan is exact whatever its
    start)."""
    g = pts.shape[0]
    box = _boxes(pts, 0, g, RUN)
    n_pose = q.shape[0] // per
    out = np.full(q.shape[0], np.inf)
    over = np.zeros(n_pose, np.bool_)
    guess = 0
    for p in range(n_pose):
        acc = 0.0
        for s in range(per):
            i = p * per + s
            j = _scan(pts, 0, g, box, RUN, q[i, 0], q[i, 1], guess)
            guess = j
            ex = pts[j, 0] - q[i, 0]
            ey = pts[j, 1] - q[i, 1]
            d = np.sqrt(ex * ex + ey * ey)
            out[i] = d
            acc += d * d
            if acc > bound:
                over[p] = True
                break
    return out, over


@numba.njit(**_JIT)
def basis_rows(coef, u, rev_basis, n):
    """The spline's basis values (``spline.Basis.values``, the same arithmetic) at the foot
    parameters u, then ``n`` copies of the reverse samples' rows ``rev_basis``: the polyline
    rows' nus of ``residuals.Problem.evaluate`` (len(u) + n * len(rev_basis), K).  coef: the
    basis's per-span power-series coefficients (spans, 4, K)."""
    nq = u.shape[0]
    spans, kk = coef.shape[0], coef.shape[2]
    n_rev = rev_basis.shape[0]
    nus = np.empty((nq + n * n_rev, kk))
    for i in range(nq):
        tt = min(max(u[i], 0.0), 1.0) * spans
        js = min(int(tt), spans - 1)
        x = tt - js
        for k in range(kk):
            nus[i, k] = ((coef[js, 3, k] * x + coef[js, 2, k]) * x + coef[js, 1, k]) * x + coef[
                js, 0, k
            ]
    for f in range(n):
        for t in range(n_rev):
            for k in range(kk):
                nus[nq + f * n_rev + t, k] = rev_basis[t, k]
    return nus


@numba.njit(**_JIT)
def polyline_rows(r_fw, rev_r, rows, fwd_w, rev_w, pw, fw, s, hk, jac, dm, dirs, yy):
    """The polyline rows of ``residuals.Problem.evaluate`` (forward rows, then every frame's
    reverse rows, frame-major; ``rows``: each row's frame) from their signed distances: Huber
    (threshold ``hk``, units of sigma ``s``; forward rows weighted by their frame's ``fwd_w``,
    reverse rows by its ``rev_w``),
    the polyline weights ``pw`` and the square roots of the frame weights ``fw`` applied, in
    the order the NumPy code applied them (the same values bit for bit).  With ``jac``: the
    curve Jacobian's factor dmw (the offset direction through the pose, ``dm``, scaled) and the
    pose Jacobian jp (d y / d w = -[Y]x, then b) from the offset directions ``dirs`` and the
    rows' points ``yy`` in their frame's camera."""
    nq = r_fw.shape[0]
    nr = rows.shape[0]
    res = np.empty(nr)
    nj = nr if jac else 0
    dmw = np.empty((nj, 3))
    jp = np.empty((nj, 5))
    for i in range(nr):
        f = rows[i]
        if i < nq:
            r = r_fw[i]
            wt = fwd_w[f]
        else:
            r = rev_r[i - nq]
            wt = rev_w[f]
        a = abs(r) / s
        if a > hk:
            fa = np.sqrt(max(2.0 * hk * a - hk * hk, 0.0))
            w = fa / max(a, 1e-300)
            wj = hk / max(fa, 1e-300)
        else:
            w = 1.0
            wj = 1.0
        w = w * wt
        wj = wj * wt
        pf = pw[f]
        ff = fw[f]
        res[i] = w * r / s * pf * ff
        if not jac:
            continue
        sc = wj / s
        for c in range(3):
            dmw[i, c] = dm[i, c] * sc * pf * ff
        d0 = dirs[i, 0]
        d1 = dirs[i, 1]
        jp[i, 0] = -d1 * yy[i, 2] * sc * pf * ff
        jp[i, 1] = d0 * yy[i, 2] * sc * pf * ff
        jp[i, 2] = (-d0 * yy[i, 1] + d1 * yy[i, 0]) * sc * pf * ff
        jp[i, 3] = d0 * sc * pf * ff
        jp[i, 4] = d1 * sc * pf * ff
    return res, dmw, jp


@numba.njit(**_JIT)
def end_rows(ctrl, m, b, pts, scale, cidx, n_curve, jac):
    """``residuals.Problem._end_rows``: the 2-D offsets of every frame's projected A, B
    (ctrl[0], ctrl[-1]; poses m (N, 3, 3), b (N, 3)) from pts (N, 2, 2) in units of ``scale``:
    rows (N, 4) [A x, A y, B x, B y] and with ``jac`` their Jacobians (N, 4, n_curve) at the free
    columns ``cidx`` (K, 3; -1: none), (N, 4, 5).  The same arithmetic as the NumPy code (its
    einsum over 3 terms adds the first and third product, then the second)."""
    n = m.shape[0]
    kk = ctrl.shape[0]
    r = np.empty((n, 4))
    nj = n if jac else 0
    jc = np.zeros((nj, 4, n_curve))
    jp = np.zeros((nj, 4, 5))
    for f in range(n):
        for e in range(2):
            w = 0 if e == 0 else kk - 1
            c0, c1, c2 = ctrl[w, 0], ctrl[w, 1], ctrl[w, 2]
            y0 = (m[f, 0, 0] * c0 + m[f, 0, 2] * c2) + m[f, 0, 1] * c1
            y1 = (m[f, 1, 0] * c0 + m[f, 1, 2] * c2) + m[f, 1, 1] * c1
            y2 = (m[f, 2, 0] * c0 + m[f, 2, 2] * c2) + m[f, 2, 1] * c1
            r[f, 2 * e] = ((y0 + b[f, 0]) - pts[f, e, 0]) / scale
            r[f, 2 * e + 1] = ((y1 + b[f, 1]) - pts[f, e, 1]) / scale
            if not jac:
                continue
            for c in range(3):
                col = cidx[w, c]
                if col >= 0:
                    jc[f, 2 * e, col] = m[f, 0, c] / scale
                    jc[f, 2 * e + 1, col] = m[f, 1, c] / scale
            jp[f, 2 * e, 1] = y2 / scale
            jp[f, 2 * e, 2] = -y1 / scale
            jp[f, 2 * e, 3] = 1.0 / scale
            jp[f, 2 * e + 1, 0] = -y2 / scale
            jp[f, 2 * e + 1, 2] = y0 / scale
            jp[f, 2 * e + 1, 4] = 1.0 / scale
    return r, jc, jp


@numba.njit(**_JIT)
def tangent_rows(v3, ang, ok, m, ts, cidx, n_curve, jac):
    """``residuals.Problem.evaluate``'s rows of the given tangent directions from the projected
    end tangents v3 (N, 2, 3: frame i's m (ctrl[1] - ctrl[0]) at A, m (ctrl[-2] - ctrl[-1]) at
    B) and their angles from the given directions ``ang`` (N, 2; NumPy's arctan2), ``ok``
    where given: the angle folded into [-pi/2, pi/2) (lines, any sign) in units of ``ts``
    (0 where not given), rows (N, 2), and with ``jac`` their Jacobians (N, 2, n_curve),
    (N, 2, 5).  The same arithmetic as the NumPy code."""
    n = m.shape[0]
    kk = cidx.shape[0]
    out = np.zeros((n, 2))
    nj = n if jac else 0
    jt = np.zeros((nj, 2, n_curve))
    jtp = np.zeros((nj, 2, 5))
    half = np.pi / 2
    for f in range(n):
        for row in range(2):
            lo = 0 if row == 0 else kk - 1
            hi = 1 if row == 0 else kk - 2
            v0, v1, v2 = v3[f, row, 0], v3[f, row, 1], v3[f, row, 2]
            if ok[f, row]:
                out[f, row] = ((ang[f, row] + half) % np.pi - half) / ts
            if not jac:
                continue
            vv = max(v0 * v0 + v1 * v1, 1e-300)
            g0 = 0.0
            g1 = 0.0
            if ok[f, row]:
                g0 = -v1 / vv / ts
                g1 = v0 / vv / ts
            for c in range(3):
                gm = g0 * m[f, 0, c] + g1 * m[f, 1, c]
                if cidx[hi, c] >= 0:
                    jt[f, row, cidx[hi, c]] += gm
                if cidx[lo, c] >= 0:
                    jt[f, row, cidx[lo, c]] -= gm
            jtp[f, row, 0] = -g1 * v2
            jtp[f, row, 1] = g0 * v2
            jtp[f, row, 2] = -g0 * v1 + g1 * v0
    return out, jt, jtp


@numba.njit(**_JIT)
def longest_nondecreasing(x):
    """Mask of one longest non-decreasing subsequence of ``x`` (patience sorting:
    ``residuals.nondecreasing_mask``'s loop with its ``bisect.bisect_right``, the same
    subsequence)."""
    n = x.shape[0]
    tails = np.empty(n)  # least last value of a run of each length
    tail_idx = np.empty(n, np.int64)
    prev = np.full(n, -1, np.int64)
    size = 0
    for i in range(n):
        v = x[i]
        lo, hi = 0, size  # bisect_right: the first run whose last value exceeds v
        while lo < hi:
            mid = (lo + hi) // 2
            if v < tails[mid]:
                hi = mid
            else:
                lo = mid + 1
        tails[lo] = v
        tail_idx[lo] = i
        if lo == size:
            size += 1
        prev[i] = tail_idx[lo - 1] if lo > 0 else -1
    keep = np.zeros(n, np.bool_)
    i = tail_idx[size - 1] if size > 0 else -1
    while i >= 0:
        keep[i] = True
        i = prev[i]
    return keep
