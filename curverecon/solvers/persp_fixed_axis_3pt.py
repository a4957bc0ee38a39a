"""Perspective, rotation about a fixed direction, A, B and C, three frames: parameter homotopy.

The derivation (``derivations/section2_perspective.py``, docs/derivation.md): each edge of the
triangle ABC lies in the plane through the camera centre and its image line, so per frame
(m_P x m_Q) . (X_Q - X_P) = 0 for PQ = AB, AC, BC (m the rays); the three together say the
triangle is inscribed in the three rays.  With X_f - A_f = R_f (X_0 - A_0),
R_f = cayley(mu_f n) about one axis n, and frame 0's differences b0 m_B0 - m_A0,
c0 m_C0 - m_A0 (A's depth in frame 0 is 1), two later frames give six equations in
(b0, c0, n1, n2, mu1, mu2): three frames, as the seed's table says.  msolve counts 88 complex
solutions (random and noise-free instances; four frames leave the truth alone); 84 of them are
reached by monodromy from constructed scenes, the other four lie on a component no real
scene's truth is on.  No closed form was found, so the 84 are tracked to the frames' rays
(:mod:`curverecon.solvers.homotopy`, on the straight-line kernels of
``generated/persp_fixed_axis_kernel.py``) and the real ones kept, in one solve, in a chart in
which no real motion is at infinity (``generated/persp_fixed_axis_system.py``): the Cayley
parameter as mu_f = m_f / (1 + zeta_f m_f) with a non-real zeta_f (a half turn is a finite
m_f), the rays turned by a complex rotation (``COMPLEX_CHART``: the axis chart
n = (n1, n2, 1) then misses one real direction only), from the start nearest the scene among
start parameters near real scenes (``_starts``: short paths).  Before, three solves in the real
Cayley chart were merged (each frame the reference once, for the half turns): 0.12 s of CPU a
solve against 0.007 s now (docs/accuracy.md; F, F_x and F_t are generated in Horner form and the
linear solve without the Jacobian's structural zeros, ``sparse_solve``).
"""

from __future__ import annotations

import sys
from dataclasses import replace
from functools import cache

import numba
import numpy as np

from curverecon import jit_cache
from curverecon.generated import persp_fixed_axis_kernel as kernel_module
from curverecon.generated import persp_fixed_axis_system as system_module
from curverecon.solvers import homotopy
from curverecon.solvers.camera import Camera
from curverecon.solvers.persp_common import (
    REAL_TOLERANCE,
    cayley,
    homotopy_parameters,
    rays_of,
)
from curverecon.solvers.persp_common import solutions as make_solutions
from curverecon.solvers.rigid_solutions import RigidSolutions

FRAMES = 3
POINTS: tuple[str, ...] = ("A", "B", "C")
ROW = "persp_fixed_axis_3pt"


N_W = kernel_module.N_COEFFICIENTS
_this = sys.modules[__name__]
"""This module: its kernels are passed to compiled code as module attributes (cached; see
``homotopy._this``)."""


def _vandermonde_inverse(degree: int) -> np.ndarray:
    """Inverse of the Vandermonde matrix of the nodes t_j = j / degree: the monomial
    coefficients of the polynomial through values at the nodes are ``inverse @ values``."""
    nodes = np.arange(degree + 1) / degree
    return np.linalg.inv(np.vander(nodes, increasing=True))


VANDERMONDE_2 = _vandermonde_inverse(2)
VANDERMONDE_4 = _vandermonde_inverse(4)


@numba.njit(cache=True, nogil=True)
def _w_polynomial(q0, q1, d, degree, w, wt):  # type: ignore[no-untyped-def]
    """W(q(t)) along q(t) = q0 + t (q1 - q0) + t (1 - t) d as a polynomial in t: W is
    quadratic in the moving parameters (a frame-0 ray times a plane normal; zeta fixed), so of
    degree 2 in t on a straight path, 4 on a detour; interpolated at ``degree`` + 1 nodes.
    Its coefficients W_0 .. W_degree go after W's entries, in ``w`` and ``wt`` alike."""
    inverse = VANDERMONDE_2 if degree == 2 else VANDERMONDE_4
    values = np.empty(N_W, np.complex128)
    q = np.empty_like(q0)
    w[:] = 0.0
    for j in range(degree + 1):
        t = j / degree
        for i in range(q0.shape[0]):
            q[i] = q0[i] + t * (q1[i] - q0[i]) + t * (1.0 - t) * d[i]
        kernel_module.coefficients(q, values)
        for b in range(degree + 1):
            c = inverse[b, j]
            for i in range(N_W):
                w[N_W * (b + 1) + i] += c * values[i]
    wt[:] = w


@numba.njit(cache=True, nogil=True, fastmath=True)
def _poly_coefficients(q, w):  # type: ignore[no-untyped-def]
    """W at t = q[0] from its polynomial (``_w_polynomial``; Horner).  t is real (the detour
    is inside the polynomial), so each step is two real multiplications, not a complex one."""
    tau = q[0].real
    top = w.shape[0] // N_W - 1
    if top == 3:  # a straight path: W = W_0 + t W_1 + t^2 W_2, unrolled
        for i in range(N_W):
            w[i] = (w[3 * N_W + i] * tau + w[2 * N_W + i]) * tau + w[N_W + i]
        return
    for i in range(N_W):
        c = w[N_W * top + i]
        re, im = c.real, c.imag
        for b in range(top - 1, 0, -1):
            c = w[N_W * b + i]
            re = re * tau + c.real
            im = im * tau + c.imag
        w[i] = complex(re, im)


@numba.njit(cache=True, nogil=True, fastmath=True)
def _poly_rates(q, dq, wt):  # type: ignore[no-untyped-def]
    """dW/dt at t = q[0] (dq[0] = dt/dt = 1) from the polynomial in ``wt`` (real t, as
    ``_poly_coefficients``)."""
    tau = q[0].real
    top = wt.shape[0] // N_W - 1
    if top == 3:  # a straight path: dW/dt = W_1 + 2 t W_2
        scale = dq[0]
        for i in range(N_W):
            wt[i] = (2.0 * tau * wt[3 * N_W + i] + wt[2 * N_W + i]) * scale
        return
    for i in range(N_W):
        c = wt[N_W * top + i]
        re, im = (top - 1) * c.real, (top - 1) * c.imag
        for b in range(top - 1, 1, -1):
            c = wt[N_W * b + i]
            re = re * tau + (b - 1) * c.real
            im = im * tau + (b - 1) * c.imag
        wt[i] = complex(re, im) * dq[0]


@numba.njit(cache=True, nogil=True)
def _poly_coefficients_t(q, dq, w, wt):  # type: ignore[no-untyped-def]
    """W and dW/dt at t = q[0]."""
    _this._poly_coefficients(q, w)
    _this._poly_rates(q, dq, wt)


@numba.njit(cache=True, nogil=True)
def _track_kernels(q0, q1, d, x_start, opts, plan, x_end, status, steps, t_end):  # type: ignore[no-untyped-def]
    """The homotopy tracker on the generated straight-line kernels
    (``generated/persp_fixed_axis_kernel.py``) with W(q(t)) as a polynomial in t
    (``_w_polynomial``): the tracker's parameter is t itself, W and dW/dt at a new t cost a
    Horner sum (the generated dW/dt along dq took 0.77 us, a fifth of a step)."""
    k = kernel_module
    degree = 2 if np.all(d == 0) else 4
    w = np.empty(N_W * (degree + 2), np.complex128)
    wt = np.empty_like(w)
    _w_polynomial(q0, q1, d, degree, w, wt)
    homotopy.track_workspace(
        _this._poly_coefficients, _this._poly_coefficients_t, _this._poly_rates,
        k.residual_jacobian, k.residual_jacobian_t, k.solve_pair, w, wt,
        np.zeros(1, np.complex128), np.ones(1, np.complex128), np.zeros(1, np.complex128),
        x_start, opts, plan, x_end, status, steps, t_end,
    )  # fmt: skip


@numba.njit(cache=True, nogil=True)
def _newton_kernels(xs, q, plan, iterations):  # type: ignore[no-untyped-def]
    """Newton's method on the generated kernels (``homotopy.newton_generated``)."""
    k = kernel_module
    homotopy.newton_generated(
        k.coefficients, k.residual_jacobian, k.N_COEFFICIENTS, xs, q, plan, iterations
    )


# numba caches the two above on this file's source alone (curverecon.jit_cache)
jit_cache.drop_stale(
    (_track_kernels, _newton_kernels, _w_polynomial, _poly_coefficients, _poly_rates,
     _poly_coefficients_t),
    (homotopy, kernel_module),
)  # fmt: skip


@cache
def _system() -> homotopy.PolynomialSystem:
    """The tracked system: the generated tables, tracked on the generated kernels when these
    were written for the same system and elimination plan."""
    tables = homotopy.PolynomialSystem.from_module(system_module)
    k = kernel_module
    same = (k.UNKNOWNS, k.PARAMETERS) == (system_module.UNKNOWNS, system_module.PARAMETERS)
    if not same or not np.array_equal(getattr(k, "ELIMINATION", ()), tables.elimination):
        return tables
    return replace(tables, tracker=_track_kernels, newton=_newton_kernels)


CHART_K = np.array([0.3 + 0.15j, -0.4 + 0.1j, 0.2 - 0.12j])
"""The rays are solved as G m with G = cayley(CHART_K), a complex rotation (G G^T = I; condition
number 2.2): a real axis a is at the chart's infinity ((G a)_3 = 0) only along one direction,
+-(-0.58, -0.18, 0.79), instead of on a great circle of axes as with a real G."""
COMPLEX_CHART = cayley(CHART_K)
ZETAS = np.asarray(system_module.START_PARAMETERS[-(FRAMES - 1) :], dtype=np.complex128)
"""The angle chart zeta_f (mu_f = m_f / (1 + zeta_f m_f)), held at its start values."""


def _real_rows(v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For each row of ``v`` (k, n): (u, scale, imaginary part) with v = scale * u and u real up
    to that largest |imaginary part| (u = the row / its largest component, so |u| <= 1)."""
    j = np.argmax(np.abs(v), axis=1)
    scale = v[np.arange(v.shape[0]), j]
    u = v / scale[:, None]
    return u.real, scale, np.max(np.abs(u.imag), axis=1)


def _motions(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(real?, unit axes (k, 3) in the camera's frame, angles (k, F) in radians, 0 first) of
    endpoints (b0, c0, n1, n2, m1, m2) (k, 6); real means real up to REAL_TOLERANCE.
    k_f = mu_f n with n = G^T (n1, n2, 1) = lam a (a real unit) and mu_f = s_f / c_f,
    (s_f, c_f) = (m_f, 1 + zeta_f m_f): tan(theta_f / 2) = s_f lam / c_f, read from the pair
    (s_f lam, c_f), which is real up to a complex factor (a half turn: c_f = 0)."""
    chart = np.column_stack([rows[:, 2], rows[:, 3], np.ones(len(rows))])
    u, scale, imag = _real_rows(chart @ COMPLEX_CHART)  # rows of (G^T n)^T
    norm = np.linalg.norm(u, axis=1)
    lam = scale * norm  # n = lam * (u / norm)
    angles = np.zeros((len(rows), FRAMES))
    for f in range(1, FRAMES):
        m = rows[:, 3 + f]
        pair, _, pair_imag = _real_rows(np.column_stack([m * lam, 1.0 + ZETAS[f - 1] * m]))
        imag = np.maximum(imag, pair_imag)
        angles[:, f] = 2.0 * np.arctan2(pair[:, 0], pair[:, 1])
    return imag <= REAL_TOLERANCE, u / norm[:, None], angles


def _unit_normals(q: np.ndarray, start: np.ndarray | None) -> np.ndarray:
    """The parameters with every plane normal (after frame 0's three rays) scaled to unit
    length and its sign turned towards the start parameters' normal (Re(N . conj(N_start))
    >= 0): each equation is homogeneous in its normal, so the solutions stay, and the straight
    path from the start does not pass near a zero normal (``start`` None: signs as they come).
    Bench scenes (seed 3, 20): 40 steps a path (median) against 51 with the signs as they
    come."""
    out = q.copy()
    normals = out[9:].reshape(-1, 3)
    normals = normals / np.linalg.norm(normals, axis=1, keepdims=True)
    if start is not None:
        flip = np.sum(normals * np.conj(start[9 : q.size].reshape(-1, 3)), axis=1).real < 0
        normals[flip] *= -1
    out[9:] = normals.reshape(-1)
    return out


def _rotations(axes: np.ndarray, angles: np.ndarray) -> np.ndarray:
    """Rot(axis, angle) (Rodrigues) for unit ``axes`` (k, 3) and ``angles`` (k, F): (k, F, 3,
    3)."""
    k = np.zeros((len(axes), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -axes[:, 2], axes[:, 1], -axes[:, 0]
    k = k - k.transpose(0, 2, 1)
    sin, cos = np.sin(angles)[..., None, None], np.cos(angles)[..., None, None]
    return np.eye(3) + sin * k[:, None] + (1 - cos) * (k @ k)[:, None]


NEAR_STARTS = 7
"""Start systems added at first use (``_starts``): each solve starts from the one whose
parameters are nearest its own.  Bench scenes (seed 3, 20): 33 steps a path (median) with 8
starts, 34 with 32, against 38-40 with the generated start alone."""
NEAR_STARTS_SEED = 20261128


def _near_parameters(rng: np.random.Generator) -> np.ndarray:
    """Parameters near a real scene (three points of a body a fifth of its distance across,
    one axis, any two angles, turned by the chart, unit normals) plus complex noise of half
    their mean modulus: a generic start near the scenes solved."""
    body = rng.normal(size=(3, 3)) * 0.15
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angles = np.concatenate([[0.0], rng.uniform(-np.pi, np.pi, FRAMES - 1)])
    x3 = np.array([body @ _rotations(axis[None], a[None, None])[0, 0].T for a in angles])
    x3 += np.array([0.0, 0.0, 1.0]) + rng.normal(size=(FRAMES, 1, 3)) * 0.1
    pairs = ((0, 1), (0, 2), (1, 2))
    q = _unit_normals(homotopy_parameters(x3 / x3[..., 2:], pairs, COMPLEX_CHART), None)
    noise = rng.normal(size=q.size) + 1j * rng.normal(size=q.size)
    return np.concatenate([q + 0.5 * np.abs(q).mean() * noise / np.sqrt(2), ZETAS])


@cache
def _starts() -> tuple[tuple[np.ndarray, np.ndarray], ...]:
    """(parameters, the 84 solutions there) of the generated start and of ``NEAR_STARTS``
    more near seeded real scenes, tracked from it with small steps (a start that loses a
    path is left out)."""
    system = _system()
    out = [(system.start_parameters, system.start_solutions)]
    rng = np.random.default_rng(NEAR_STARTS_SEED)
    careful = homotopy.HomotopyOptions(max_step=0.05, predictor_tolerance=1e-3)
    for _ in range(NEAR_STARTS):
        q = _near_parameters(rng)
        tracked = homotopy.track(system, q, careful)
        if tracked.n_failed == 0:
            out.append((q, np.ascontiguousarray(tracked.solutions)))
    return tuple(out)


def _nearest_start(q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(start parameters, start solutions, target) for the rays' parameters ``q`` (without
    the angle chart): the start nearest to q with its normals signed towards that start's
    (``_unit_normals``, for every start at once)."""
    starts = _starts()
    q0s = np.array([q0 for q0, _ in starts])  # (K, parameters)
    normals = q[9:].reshape(-1, 3)
    normals = normals / np.linalg.norm(normals, axis=1, keepdims=True)
    toward = q0s[:, 9 : q.size].reshape(len(starts), -1, 3)
    sign = np.where(np.einsum("nc,knc->kn", normals, np.conj(toward)).real < 0, -1.0, 1.0)
    signed = sign[..., None] * normals  # (K, normals, 3)
    dist = np.linalg.norm(signed - toward, axis=(1, 2)) ** 2
    dist += np.linalg.norm(q[:9] - q0s[:, :9], axis=1) ** 2  # the angle chart is the same
    best = int(np.argmin(dist))
    target = np.concatenate([q[:9], signed[best].reshape(-1), ZETAS])
    return starts[best][0], starts[best][1], target


def _place_all(m: np.ndarray, rotations: np.ndarray, depths: np.ndarray) -> np.ndarray:
    """``persp_common.place`` for k solutions at once: every point in every frame (k, F, 3, 3)
    from the rays ``m`` (F, 3, 3), the rotations (k, F, 3, 3) and frame 0's depths of B and C
    (k, 2); A's depth in frame f from the moved difference B - A (least squares of the three
    components, ``depths_from_difference``)."""
    diffs = depths[:, :, None] * m[0, 1:][None] - m[0, 0]  # (k, 2, 3): B_0 - A_0, C_0 - A_0
    out = np.empty((len(depths), FRAMES, 3, 3))
    out[:, 0, 0] = m[0, 0]
    out[:, 0, 1:] = m[0, 0] + diffs
    for f in range(1, FRAMES):
        moved = np.einsum("kij,kpj->kpi", rotations[:, f], diffs)
        ma, mb = m[f, 0], m[f, 1]
        aa, ab, bb = ma @ ma, ma @ mb, mb @ mb
        da, db = moved[:, 0] @ ma, moved[:, 0] @ mb
        lam_a = (ab * db - bb * da) / (aa * bb - ab * ab)
        out[:, f, 0] = lam_a[:, None] * ma
        out[:, f, 1:] = out[:, f, :1] + moved
    return out


def solve(points: np.ndarray, times: np.ndarray, camera: Camera) -> RigidSolutions:
    """Every real solution of three frames of A, B, C in pixels (``points`` (3, 3, 2),
    ``times`` (3,) increasing): ``points3`` in camera coordinates (A's depth in frame 0 = 1),
    ``rotations`` R_f = Rot(axis, angle_f), ``motion`` with ``axis`` (unit, frame 0's camera
    coordinates, its sign making frame 1's angle positive) and ``angle_deg`` per frame
    (degrees in [-180, 180)).  One homotopy solve of the 84 paths in the complex chart."""
    m, _ = rays_of(points, times, camera, FRAMES, POINTS, ROW)
    pairs = ((0, 1), (0, 2), (1, 2))
    q0, x0, target = _nearest_start(homotopy_parameters(m, pairs, COMPLEX_CHART))
    system = replace(_system(), start_parameters=q0, start_solutions=x0)
    tracked = homotopy.track(system, target)
    x = tracked.solutions
    finite = x[np.all(np.isfinite(x), axis=1)]
    depths_real = np.all(
        np.abs(finite[:, :2].imag) <= REAL_TOLERANCE * (1 + np.abs(finite[:, :2])), axis=1
    )
    candidates = system.polish(finite[depths_real], target, 4)
    real, axes, angles = _motions(candidates)
    rows, axes, angles = candidates[real], axes[real], angles[real]
    signs = np.where((np.degrees(angles[:, 1]) + 180) % 360 - 180 >= 0, 1.0, -1.0)
    rotations = _rotations(axes, angles)
    points3 = _place_all(m, rotations, rows[:, :2].real)
    wrapped = signs[:, None] * ((np.degrees(angles) + 180) % 360 - 180)
    motion = [{"axis": (sign * axis).tolist(), "angle_deg": theta.tolist()}
              for sign, axis, theta in zip(signs, axes, wrapped, strict=True)]  # fmt: skip
    n_paths = int(x.shape[0])
    n_complex = len(finite) - len(points3)
    return make_solutions(
        list(points3), list(rotations), motion, n_paths, n_complex, tracked.n_failed, (FRAMES, 3)
    )
