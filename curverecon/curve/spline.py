"""The curve model of the curve bundle: a clamped uniform cubic B-spline in frame 0's camera
coordinates, its fit to points, and a fitted bundle's result (:class:`BundleResult`) with the shape
and poses it gives (:func:`shape_and_poses`).

The curve is ``X(u) = sum_k N_k(u) P_k``, u in [0, 1], with ``X(0) = P_0 = A`` and
``X(1) = P_{K-1} = B``.  Afterwards the shape (c, alpha, beta, phi) and the end tangents come from
the fitted curve and every frame's pose from its fitted rotation, in the conventions of
docs/CONVENTIONS.md.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import BSpline

from curverecon.curve import polyline as pl


def bundle_error(message: str) -> Exception:
    from curverecon.errors import CurveReconError

    return CurveReconError(message)


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
        basis = Basis(len(self.control))
        return basis.values(np.linspace(0.0, 1.0, n)) @ self.control

    def ends(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(A, B, unit tangent at A into the curve, unit tangent at B into the curve), frame 0."""
        p = self.control
        ta, tb = p[1] - p[0], p[-2] - p[-1]
        return p[0], p[-1], ta / np.linalg.norm(ta), tb / np.linalg.norm(tb)


class Basis:
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
    """(knots, per-span power-series coefficients (spans, 4, K)) of :class:`Basis` with K
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


def fit_spline(points: np.ndarray, k: int) -> np.ndarray:
    """(k, 3) control points of the clamped cubic B-spline fitting ``points`` (chord-length u),
    interpolating the first and last point."""
    pts = np.asarray(points, float)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    u = s / s[-1]
    basis = Basis(k)
    n = basis.values(u)
    # Ends fixed: solve for the interior control points.
    rhs = pts - np.outer(n[:, 0], pts[0]) - np.outer(n[:, -1], pts[-1])
    d3 = np.diff(np.eye(k), 3, axis=0)
    reg = 1e-3 * np.sqrt(len(pts) / k) * d3
    a = np.vstack([n[:, 1:-1], reg[:, 1:-1]])
    r = np.vstack([rhs, -np.outer(reg[:, 0], pts[0]) - np.outer(reg[:, -1], pts[-1])])
    inner, *_ = np.linalg.lstsq(a, r, rcond=None)
    return np.vstack([pts[0], inner, pts[-1]])


def arc_parameters(ctrl: np.ndarray, n_out: int) -> np.ndarray:
    """Spline parameters u of ``n_out`` points equally spaced in 3-D arc length."""
    u = np.linspace(0.0, 1.0, 4000)
    dense = Basis(len(ctrl)).values(u) @ ctrl
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(dense, axis=0), axis=1))])
    return np.interp(np.linspace(0.0, s[-1], n_out), s, u)


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
        raise bundle_error("the fitted curve has A = B")
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


def oriented_to(polylines: Sequence[np.ndarray], result: BundleResult) -> list[np.ndarray]:
    """Every polyline from A' to B' of a bundle result (the end nearer its projected A first)."""
    out = []
    for i, p in enumerate(polylines):
        q = pl.as_polyline(p, name=f"frame {i} curve")
        a_img = (result.m[i] @ result.control[0] + result.b[i])[:2]
        if np.hypot(*(q[-1] - a_img)) < np.hypot(*(q[0] - a_img)):
            q = q[::-1].copy()
        out.append(q)
    return out
