"""The curve bundle's numerical core: the analytic Jacobian and the normal equations in blocks
(``curve.residuals.Problem``) against finite differences of the residual function, and the numba
kernels (``curve.bundle_kernel``) against brute-force NumPy and k-d tree constructions.

Scenes from ``simulate.make_scene(..., with_curve=True)`` (3-D curves moved and projected
without project code), the state at the true poses and curve, 1 px noise on the polylines.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from bench.curve_end_to_end import curve_error
from curverecon.curve import bundle as bd
from curverecon.curve import bundle_kernel as bk
from curverecon.curve import lm, residuals
from curverecon.curve import pose_search as ps
from curverecon.simulate import make_scene


def _truth_problem(seed: int, frames: int, family: str, robust_ends: bool, noise: float = 1.0):
    """A bundle problem of a scene with ``noise`` px (end points and tangents given) at the
    true state."""
    scene = make_scene(
        np.random.default_rng(seed), frames, noise, noise, with_curve=True, curve_family=family
    )
    obs = scene.observations
    rot, tr = scene.truth.rotations, scene.truth.A3
    polys = []
    for i, p in enumerate(obs.curves):
        p = np.asarray(p, float)
        if np.hypot(*(p[-1] - tr[i, :2])) < np.hypot(*(p[0] - tr[i, :2])):
            p = p[::-1].copy()
        polys.append(p)
    m = np.einsum("nij,kj->nik", rot, rot[0])
    b = tr - np.einsum("nij,j->ni", m, tr[0])
    curve = scene.curve_3d - [0.0, 0.0, scene.curve_3d[0, 2]]
    ctrl = bd.fit_spline(curve, 12)
    prob = residuals.Problem(
        polys,
        1.0,
        12,
        np.stack([obs.a, obs.b], axis=1),
        np.stack([obs.tangent_a, obs.tangent_b], axis=1),
        1.0,
        np.radians(1.0),
    )
    prob.robust_ends = robust_ends
    # uneven frame weights and one polyline left out: every multiplier of the rows in play
    prob.frame_w = np.linspace(0.5, 1.0, frames)
    prob.poly_w[frames - 1] = 0.0
    return prob, (ctrl, m, b), scene


def _fd_jacobian(prob, state, h: float = 1e-5) -> np.ndarray:
    """Central differences of the residuals over the parameter increments (``apply``)."""
    cols = []
    for j in range(prob.n_par):
        dx = np.zeros(prob.n_par)
        dx[j] = h
        rp = prob.evaluate(*prob.apply(*state, dx), jac=False)[0]
        rm = prob.evaluate(*prob.apply(*state, -dx), jac=False)[0]
        cols.append((rp - rm) / (2.0 * h))
    return np.column_stack(cols)


@pytest.mark.parametrize("robust_ends", [False, True])
def test_analytic_jacobian_matches_finite_differences(robust_ends):
    prob, state, _ = _truth_problem(3, 6, "helix", robust_ends)
    r, jac, _ = prob.residuals(*state)
    jfd = _fd_jacobian(prob, state)
    assert jac.shape == jfd.shape
    # the residuals are piecewise smooth (Huber's threshold, the reverse term's nearest segment):
    # a row may straddle a kink, so the whole matrix and most rows are compared
    assert np.linalg.norm(jac - jfd) < 1e-5 * np.linalg.norm(jfd)
    row_err = np.linalg.norm(jac - jfd, axis=1) / np.maximum(np.linalg.norm(jfd, axis=1), 1e-12)
    assert np.mean(row_err < 1e-5) > 0.99
    # the normal equations in blocks (numba accumulation of the polyline rows) and the Schur
    # step against the dense normal equations of the finite-difference Jacobian
    r2, (u, gc, v, w, gp), _ = prob.normal_equations(*state)
    assert np.allclose(r2, r, rtol=0, atol=1e-12 * np.abs(r).max())
    nc = prob.n_curve
    jtj, jtr = jfd.T @ jfd, jfd.T @ r
    scale = np.abs(jtj).max()
    assert np.abs(u - jtj[:nc, :nc]).max() < 1e-5 * scale
    assert np.abs(gc - jtr[:nc]).max() < 1e-5 * np.abs(jtr).max()
    for i in range(1, prob.n):
        sl = slice(nc + 5 * (i - 1), nc + 5 * i)
        assert np.abs(v[i] - jtj[sl, sl]).max() < 1e-5 * scale
        assert np.abs(w[i] - jtj[:nc, sl]).max() < 1e-5 * scale
        assert np.abs(gp[i] - jtr[sl]).max() < 1e-5 * np.abs(jtr).max()
    lam = 1e-3
    d = np.maximum(np.diag(jtj), 1e-12 * np.diag(jtj).max())
    dense = -np.linalg.solve(jtj + lam * np.diag(d), jtr)
    step = lm._schur_solve((u, gc, v, w, gp), lam)
    assert np.linalg.norm(step - dense) < 1e-4 * np.linalg.norm(dense)


def test_nearest_in_frames_is_the_brute_force_nearest():
    rng = np.random.default_rng(0)
    # three frames' curves (ordered samples, as the kernel's boxes assume nothing but order)
    t = np.linspace(0.0, 6.0, 300)
    pts = np.vstack(
        [np.column_stack([40 * np.cos(t + k), 25 * np.sin(2 * t) + 10 * k]) for k in range(3)]
    )
    lo = np.array([0, 300, 600])
    hi = lo + 300
    q = rng.uniform(-60, 60, size=(450, 2))
    qlo = np.array([0, 100, 250])
    qhi = np.array([100, 250, 450])
    got = bk.nearest_in_frames(pts, lo, hi, q, qlo, qhi)
    for f in range(3):
        own = pts[lo[f] : hi[f]]
        d_got = np.linalg.norm(pts[got[qlo[f] : qhi[f]]] - q[qlo[f] : qhi[f]], axis=1)
        d_true = cKDTree(own).query(q[qlo[f] : qhi[f]])[0]
        assert np.all(got[qlo[f] : qhi[f]] >= lo[f]) and np.all(got[qlo[f] : qhi[f]] < hi[f])
        assert np.allclose(d_got, d_true, rtol=0, atol=1e-12)


def test_foot_points_are_the_nearest_curve_points():
    """Foot parameters against a brute-force minimum over 200,000 samples of each frame's
    projected spline (the distance agrees to the sampling's resolution)."""
    prob, (ctrl, m, b), _ = _truth_problem(4, 5, "random", False)
    u = prob._all_foot_points(ctrl, m, b)
    dense_u = np.linspace(0.0, 1.0, 200_001)
    x = prob.basis.values(dense_u) @ ctrl
    for i in range(prob.n):
        proj = x @ m[i, :2].T + b[i, :2]
        sel = prob.q_fid == i
        q = prob.q_all[sel]
        d_true = cKDTree(proj).query(q)[0]
        foot = prob.basis.values(u[sel]) @ ctrl @ m[i, :2].T + b[i, :2]
        d_got = np.linalg.norm(foot - q, axis=1)
        step = np.linalg.norm(np.diff(proj, axis=0), axis=1).max()
        assert np.all(d_got <= d_true + 1e-9)  # never farther than the dense minimum
        assert np.all(d_got >= d_true - step)


def test_bundle_on_a_seeded_scene_reaches_the_truth():
    """A 1 px, 12-frame scene started at the true poses and curve: the fit stays within 0.5 %
    of the curve's length of the true curve and every frame fits at the noise level."""
    prob, (ctrl, m, b), scene = _truth_problem(7, 12, "clothoid", False)
    rot, tr = scene.truth.rotations, scene.truth.A3
    res = bd.bundle_adjust(scene.observations.curves, rot, tr, scene.curve_3d)
    assert curve_error(res.curve_points(), scene.curve_3d) < 0.005
    assert np.max(res.rms) < 2.0


@pytest.mark.parametrize("family", ["helix", "random"])
def test_pose_sweep_distances_equal_the_k_d_tree(family):
    """``bundle_kernel.nearest_distances`` (the pose sweep of ``pose_search._resect_starts``):
    a frame's resampled polyline against the projected curve samples of every sweep pose and
    scattered points, the same distances as a k-d tree's query (to the last bit: the same
    squared differences, the same nearest point up to ties)."""
    prob, *_ = _truth_problem(3, 6, family, False)
    rng = np.random.default_rng(4)
    for i in range(prob.n):
        dense = prob.resampled(i)
        q = np.vstack(
            [
                dense + rng.normal(scale=3.0, size=dense.shape),
                dense.mean(axis=0) + rng.normal(scale=80.0, size=(500, 2)),
            ]
        )
        expected = cKDTree(dense).query(q)[0]
        got = bk.nearest_distances(dense, q)
        assert np.array_equal(got, expected)


def test_end_and_tangent_rows_equal_the_numpy_construction():
    """``bundle_kernel.end_rows`` / ``tangent_rows`` (the bundle's rows of the polylines' end
    points and of the given end tangents) against NumPy: the reference ``Problem._end_rows``,
    and the tangent angles and their derivatives written out (angle of m (P1 - P0) against
    the given direction folded to a line, d angle / d v = (-v_y, v_x) / |v|^2), on a
    simulated scene's true state, every pose, with one tangent not given."""
    prob, (ctrl, m, b), _ = _truth_problem(5, 8, "clothoid", False)
    prob.tangents = np.array(prob.tangents, float)
    prob.tangents[2, 1] = np.nan
    r, jc, jp = bk.end_rows(ctrl, m, b, prob.end_img, 0.7, prob.cidx, prob.n_curve, True)
    r0, jc0, jp0 = prob._end_rows(ctrl, m, b, prob.end_img, 0.7, True)
    assert np.allclose(r, r0, rtol=1e-13, atol=1e-12)
    assert np.allclose(jc, jc0, rtol=1e-13, atol=1e-12)
    assert np.allclose(jp, jp0, rtol=1e-13, atol=1e-12)
    ts = np.radians(1.0)
    v3 = np.stack([m @ (ctrl[1] - ctrl[0]), m @ (ctrl[-2] - ctrl[-1])], axis=1)
    ob = prob.tangents
    ok = np.all(np.isfinite(ob), axis=2)
    with np.errstate(invalid="ignore"):
        ang = np.arctan2(v3[..., 1], v3[..., 0]) - np.arctan2(ob[..., 1], ob[..., 0])
    out, jt, jtp = bk.tangent_rows(v3, ang, ok, m, ts, prob.cidx, prob.n_curve, True)
    # the residual: the smallest angle between the two lines, in units of ts
    d = np.where(ok, np.remainder(ang + np.pi / 2, np.pi) - np.pi / 2, 0.0) / ts
    assert np.allclose(out, d, rtol=0, atol=1e-9) and not out[2, 1] and np.all(np.abs(d) <= 90)
    assert not jt[2, 1].any() and not jtp[2, 1].any()
    for f in range(len(m)):
        for row, (hi, lo) in enumerate(((1, 0), (len(ctrl) - 2, len(ctrl) - 1))):
            if not ok[f, row]:
                continue
            v = v3[f, row]
            g = np.array([-v[1], v[0]]) / (v[:2] @ v[:2]) / ts  # d out / d v[:2]
            want = np.zeros(prob.n_curve)
            for c in range(3):
                if prob.cidx[hi, c] >= 0:
                    want[prob.cidx[hi, c]] += g @ m[f, :2, c]
                if prob.cidx[lo, c] >= 0:
                    want[prob.cidx[lo, c]] -= g @ m[f, :2, c]
            assert np.allclose(jt[f, row], want, rtol=1e-12, atol=1e-12 * np.abs(want).max())
            # rotation increment: d v / d w = -[v]x
            dvdw = -np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
            assert np.allclose(jtp[f, row, :3], g @ dvdw[:2], rtol=1e-12, atol=1e-9)
            assert not jtp[f, row, 3:].any()


def test_sweep_distances_stop_each_pose_beyond_the_bound():
    """``bundle_kernel.sweep_distances`` (the pose sweep with each pose's scan stopped once
    its sum of squared distances exceeds the bound): the distances it measures are the k-d
    tree's; a pose is stopped exactly when the k-d tree's full sum exceeds the bound (up to
    the sums' rounding), and then its first points' partial sum does."""
    prob, *_ = _truth_problem(3, 6, "helix", False)
    rng = np.random.default_rng(5)
    dense = prob.resampled(2)
    per = 40
    # 30 "poses": the polyline's samples shifted by offsets of 0.5 - 20 px
    base = dense[:: len(dense) // per][:per]
    q = np.vstack([base + rng.normal(scale=s, size=base.shape) for s in np.linspace(0.5, 20, 30)])
    expected = cKDTree(dense).query(q)[0].reshape(30, per)
    full = np.sum(expected**2, axis=1)
    bound = float(np.median(full))
    got, over = bk.sweep_distances(dense, q, per, bound)
    got = got.reshape(30, per)
    assert 0 < over.sum() < 30
    measured = np.isfinite(got)
    assert np.array_equal(got[measured], expected[measured])
    assert np.all(measured[~over])
    assert np.array_equal(over, full > bound)
    for p in np.flatnonzero(over):
        k = int(measured[p].sum())
        assert np.sum(expected[p, :k] ** 2) > bound >= np.sum(expected[p, : k - 1] ** 2)


def test_thinned_problem_stands_for_the_full_polylines():
    """The coarse stage's thinned polylines (``residuals.thinned``, ``Problem.stand_for``):
    the same ends and every s-th point of each polyline; the cost on the scale of the full
    polylines' (the forward rows weighted by the points they stand for): at the true state of
    a noisy scene (within the noise of the sums) with per-frame RMS distances alike, and, on
    the noise-free scene, the rise of one frame's cost when its pose is turned 3 degrees (what
    the pose search compares)."""

    def problems(noise: float):
        prob, state, _ = _truth_problem(11, 12, "helix", False, noise)
        prob.frame_w = np.ones(prob.n)
        prob.poly_w = np.ones(prob.n)
        thin_polys = [residuals.thinned(p, 40) for p in prob.polys]
        thin = residuals.Problem(
            thin_polys, 1.0, 12, prob.ends, prob.tangents, prob.point_sigma, prob.tangent_sigma
        )
        thin.stand_for(prob.polys)
        return prob, thin, state

    prob, thin, (ctrl, m, b) = problems(1.0)
    for p, t in zip(prob.polys, thin.polys, strict=True):
        step = round((len(p) - 1) / 40)
        assert step > 1
        assert np.array_equal(t[0], p[0]) and np.array_equal(t[-1], p[-1])
        assert np.array_equal(t[: len(p[::step])], p[::step])
        assert 30 <= len(t) <= 50
    r, _, _, rows, rms = prob.evaluate(ctrl, m, b, jac=False)
    r_t, _, _, rows_t, rms_t = thin.evaluate(ctrl, m, b, jac=False)
    # chi2 of ~150 points per frame against ~40 weighted ones: within the noise of the sums
    assert 0.75 < np.sum(r_t**2) / np.sum(r**2) < 1.33
    assert np.allclose(rms_t, rms, rtol=0.25)
    prob, thin, (ctrl, m, b) = problems(0.0)
    turned = m.copy()
    turned[4] = residuals._expm_so3(np.radians(3.0) * np.array([0.6, 0.8, 0.0])) @ m[4]
    rise = []
    for pr in (prob, thin):
        r, _, _, rows, _ = pr.evaluate(ctrl, m, b, jac=False)
        r2, _, _, rows2, _ = pr.evaluate(ctrl, turned, b, jac=False)
        rise.append(pr.frame_costs(r2, rows2)[4] - pr.frame_costs(r, rows)[4])
    assert rise[0] > 20.0
    assert 0.9 < rise[1] / rise[0] < 1.1


def _longest_nondecreasing_reference(x: np.ndarray) -> np.ndarray:
    """The patience sorting with ``bisect.bisect_right`` (the NumPy-era implementation)."""
    import bisect

    tails: list[float] = []
    tail_idx: list[int] = []
    prev = np.full(len(x), -1)
    for i, v in enumerate(x):
        j = bisect.bisect_right(tails, v)
        if j == len(tails):
            tails.append(v)
            tail_idx.append(i)
        else:
            tails[j], tail_idx[j] = v, i
        prev[i] = tail_idx[j - 1] if j else -1
    keep = np.zeros(len(x), bool)
    i = tail_idx[-1] if tail_idx else -1
    while i >= 0:
        keep[i] = True
        i = prev[i]
    return keep


def test_longest_nondecreasing_run_is_a_longest_one():
    """``residuals.nondecreasing_mask`` (numba): a non-decreasing subsequence as long as the
    longest (O(M^2) dynamic programme), and the same one as the bisect implementation, on
    noisy increasing sequences (the feet of noisy polylines), with ties and empty input."""
    rng = np.random.default_rng(3)
    for t in range(400):
        n = int(rng.integers(0, 40))
        x = np.sort(rng.uniform(size=n)) + rng.normal(size=n) * [0.0, 0.02, 0.3][t % 3]
        if t % 4 == 0:
            x = np.round(x, 1)  # ties
        keep = residuals.nondecreasing_mask(x)
        best = np.ones(n, int)  # longest non-decreasing run ending at each point
        for i in range(n):
            for j in range(i):
                if x[j] <= x[i]:
                    best[i] = max(best[i], best[j] + 1)
        assert keep.sum() == (best.max() if n else 0)
        assert np.all(np.diff(x[keep]) >= 0)
        assert np.array_equal(keep, _longest_nondecreasing_reference(x))


def _turn_deg(r1: np.ndarray, r2: np.ndarray) -> float:
    """The rotation angle between two rotations (degrees; ``pose_search.max_angle_deg``)."""
    return ps.max_angle_deg(r1[None], r2[None])


def test_pose_search_leaves_the_current_basin_and_finds_a_far_pose(monkeypatch):
    """``pose_search._resect_starts`` / ``resect_all`` on a Bezier scene (1 px, 8 frames) with the
    true curve and poses: every frame at its true pose gets no start within
    ``RESECT_SAME_DEG`` of it (the sweep itself finds such poses: with the filter off some
    frames get one), and a frame turned 180 degrees about AB (A, B and their images stay put,
    the rest of the curve's image moves: built from the 3-D geometry) is brought back to
    within 2 degrees of its true pose at a lower cost."""
    prob, (ctrl, m, b), _ = _truth_problem(1, 8, "bezier", False)
    prob.frame_w = np.ones(8)
    prob.poly_w[:] = 1.0
    near = 0
    for i in range(1, 8):
        for mm, _ in ps._resect_starts(prob, ctrl, m[i], b[i], i):
            assert _turn_deg(mm, m[i]) >= ps.RESECT_SAME_DEG
    monkeypatch.setattr(ps, "RESECT_SAME_DEG", 0.0)
    for i in range(1, 8):
        near += sum(
            _turn_deg(mm, m[i]) < 10.0 for mm, _ in ps._resect_starts(prob, ctrl, m[i], b[i], i)
        )
    assert near >= 3
    monkeypatch.undo()
    # frame 4 turned by 180 degrees about AB through A: X_i = m_i (A + T (X - A)) + b_i
    i = 4
    a3 = ctrl[0]
    axis = (ctrl[-1] - a3) / np.linalg.norm(ctrl[-1] - a3)
    turn = 2.0 * np.outer(axis, axis) - np.eye(3)  # the half turn about the axis
    m_wrong, b_wrong = m.copy(), b.copy()
    m_wrong[i] = m[i] @ turn
    b_wrong[i] = b[i] + m[i] @ (a3 - turn @ a3)
    r, _, _, rows, _ = prob.evaluate(ctrl, m_wrong, b_wrong, jac=False)
    cost_wrong = prob.frame_costs(r, rows)[i]
    found = ps.resect_all(prob, ctrl, m_wrong, b_wrong, [i])
    m_i, _, cost = found[i]
    assert _turn_deg(m_i, m[i]) < 2.0
    assert cost < 0.1 * cost_wrong
