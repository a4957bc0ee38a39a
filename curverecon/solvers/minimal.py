"""The complete minimal solver: four frames, every shape that fits them exactly.

Four frames give four lean equations (``generated/lean_polynomial.py``) in the four unknowns
(c, tan(alpha), tan(beta), cos(phi)).  ``make derive`` reduces them by their symmetry to
(C, A, B, P, m) = (c^2, tan^2(alpha), tan^2(beta), cos^2(phi), tan(alpha) tan(beta) cos(phi))
and undoes the lean polynomial's one squaring: each frame keeps the unsquared (12*) with an
unknown s_i = C tan(alpha) tan(beta) sin(phi) sin(tau_i) of its own, so that nearly flat curves
and frames with c' near c are regular solutions, not near-double ones
(``generated/minimal_unsquared.py``, 9 equations in 9 unknowns; docs/derivation.md gives the
count, 104 for generic frames, its independent check and the symmetry).  It is solved once at
generic complex parameters; :func:`solve` tracks those 104 solutions to the given frames
(:mod:`curverecon.solvers.homotopy`), keeps the real ones that are shapes (C >= c'^2 in every
frame, A, B >= 0, 0 <= P <= 1), polishes each by Newton's method on that system in float64,
and solves every frame's pose for it (:func:`curverecon.solvers.pose.poses_from_shapes`).

Conventions: c in input units; alpha, beta in [0, pi/2] and phi in [0, pi], radians (one
representative per orbit: the signs of tan(alpha), tan(beta) only orient the tangent lines, and
the mirror image has the same cos(phi) up to that sign; CONTRACT.md).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cache

import numba
import numpy as np

from curverecon import jit_cache
from curverecon.errors import CurveReconError
from curverecon.generated import minimal_unsquared
from curverecon.model.observations import Observations, wrap_line_angle
from curverecon.options import MinimalOptions
from curverecon.solvers import homotopy
from curverecon.solvers.pose import poses_from_shapes

try:  # the system's straight-line kernels; absent only until `make derive` first writes them
    from curverecon.generated import minimal_unsquared_kernel
except ImportError:  # pragma: no cover
    minimal_unsquared_kernel = None

FRAMES = 4
REDUCED_UNKNOWNS = 5
REAL_TOLERANCE = 1e-6
"""Largest |imaginary part| / (1 + |value|) of a solution taken as real.  Tracked endpoints are
polished to about 1e-12; complex pairs of real data sit far above this (1e-3 lists the same
solutions: ``docs/options-audit.md``)."""
BOUND_TOLERANCE = 1e-6
"""Slack on C >= c'^2, A, B >= 0 and 0 <= P <= 1 (dimensionless, after scaling; 1e-3 lists the
same solutions)."""
"""(C, A, B, P, m) come first in ``minimal_unsquared.UNKNOWNS``."""


@dataclass
class MinimalResult:
    """Every real shape that fits four frames exactly, best first.

    ``shapes[k]`` is (c, alpha, beta, phi) (input units, radians), ``poses[k]`` the four frames'
    poses (delta, tau, theta, tx, ty) for it, ``residuals[k]`` the RMS tangent-angle misfit of
    those poses (radians; 0 up to rounding on exact data), ordered ascending.
    """

    shapes: np.ndarray
    poses: np.ndarray
    residuals: np.ndarray
    n_paths: int
    n_complex: int
    """Tracked solutions that are not real (pairs of complex conjugates)."""
    n_not_shapes: int
    """Real solutions outside the shape domain (C < c'^2, A < 0, B < 0 or P outside [0, 1])."""
    n_failed_paths: int
    """Paths that failed after every retry (counted, never dropped silently)."""
    failures: dict[str, int]
    retried_paths: int

    @property
    def n_real(self) -> int:
        return int(self.shapes.shape[0])


@numba.njit(cache=True, nogil=True)
def _track_kernels(q0, q1, d, x_start, opts, plan, x_end, status, steps, t_end):  # type: ignore[no-untyped-def]
    """The homotopy tracker on the generated straight-line kernels of the system
    (``generated/minimal_unsquared_kernel.py``): compiled and cached here, where the kernels
    are known by name (``homotopy.track_generated``).  numba's cache of this function is keyed
    on this file only; ``jit_cache.drop_stale`` below flushes it when ``homotopy.py`` or the
    kernels change (before, a stale cache kept running the old tracker)."""
    k = minimal_unsquared_kernel
    homotopy.track_generated(
        k.coefficients,
        k.coefficients_t,
        k.coefficient_rates,
        k.residual_jacobian,
        k.residual_jacobian_t,
        k.solve_pair,
        k.N_COEFFICIENTS,
        q0,
        q1,
        d,
        x_start,
        opts,
        plan,
        x_end,
        status,
        steps,
        t_end,
    )


@numba.njit(cache=True, nogil=True)
def _newton_kernels(xs, q, plan, iterations):  # type: ignore[no-untyped-def]
    """Newton's method on the generated kernels (``homotopy.newton_generated``)."""
    k = minimal_unsquared_kernel
    homotopy.newton_generated(
        k.coefficients, k.residual_jacobian, k.N_COEFFICIENTS, xs, q, plan, iterations
    )


# numba caches the two above on this file's source alone; the tracker and the kernels they
# compile in live elsewhere (curverecon.jit_cache)
if minimal_unsquared_kernel is not None:
    jit_cache.drop_stale((_track_kernels, _newton_kernels), (homotopy, minimal_unsquared_kernel))


@cache
def _system() -> homotopy.PolynomialSystem:
    """The tracked system: its tables, and the tracker on its generated kernels when the kernel
    module was generated from the same system (same unknowns, parameters and equations)."""
    k = minimal_unsquared_kernel
    same = k is not None and (k.UNKNOWNS, k.PARAMETERS, k.EQUATIONS) == (
        minimal_unsquared.UNKNOWNS,
        minimal_unsquared.PARAMETERS,
        minimal_unsquared.EQUATIONS,
    )
    # the 104 solutions are counted with C tan(alpha) tan(beta) != 0 (docs/derivation.md: the
    # unsaturated set adds the surfaces C = 0 and tan(alpha) = tan(beta) = 0)
    nonzero = ("C", "A", "B")
    tables = homotopy.PolynomialSystem.from_module(minimal_unsquared, nonzero=nonzero)
    # the kernels' linear solve is written out for one elimination plan: the tables' own
    if not same or not np.array_equal(getattr(k, "ELIMINATION", ()), tables.elimination):
        return tables
    return replace(tables, tracker=_track_kernels, newton=_newton_kernels)


def check_four_frames(obs: Observations, options: MinimalOptions | None = None) -> None:
    """Raise CurveReconError unless ``obs`` is four frames the minimal problem can use."""
    o = options or MinimalOptions()
    if obs.n_frames != FRAMES:
        raise CurveReconError(f"the minimal solver takes exactly 4 frames, got {obs.n_frames}")
    for name, rel in (("tangent_A", obs.rel_a), ("tangent_B", obs.rel_b)):
        limit = np.sin(np.radians(o.tangent_along_chord_deg))
        along = np.abs(np.sin(wrap_line_angle(rel))) <= limit
        if along.any():
            raise CurveReconError(
                f"frame {int(np.argmax(along))}: {name} lies along A'B', so the frame's "
                "tangent carries no depth information"
            )
    feats = np.column_stack([obs.cp, obs.dp, obs.ep]) / np.mean(obs.cp)
    for i in range(FRAMES):
        for j in range(i + 1, FRAMES):
            if np.max(np.abs(feats[i] - feats[j])) <= o.duplicate_frames * (
                1 + np.max(np.abs(feats[i]))
            ):
                raise CurveReconError(
                    f"frames {i} and {j} are the same view up to a rotation about the viewing "
                    "axis (equal c', d', e'): four different views are needed"
                )


def solve(obs: Observations, options: MinimalOptions | None = None) -> MinimalResult:
    """Every real shape (c, alpha, beta, phi) that fits the four frames of ``obs`` exactly."""
    o = options or MinimalOptions()
    check_four_frames(obs, o)
    scale = float(np.mean(obs.cp))
    cp, dp, ep = obs.cp / scale, obs.dp / scale, obs.ep / scale
    target = np.column_stack([cp, dp, ep]).ravel()
    tracked = homotopy.track(_system(), target, o.homotopy)
    x = tracked.solutions
    ok = np.all(np.isfinite(x), axis=1)
    real = ok & np.all(np.abs(x.imag) <= REAL_TOLERANCE * (1 + np.abs(x)), axis=1)
    # Newton's method in float64 on the tracked (unsquared) system at the frames' parameters;
    # real solutions stay real (real system, real start).  Not on the lean equations: where s_i
    # is near 0 (a nearly flat curve, c' near c) their root is near-double, and Newton's method
    # there moved a solution the unsquared system had to 1e-11 by 2e-4 (seed 300005, phi 178.7
    # degrees).
    xr = _system().polish(x[real], target, o.polish_iterations).real
    tol = BOUND_TOLERANCE
    c2, a2, b2, p2, m = xr[:, :REDUCED_UNKNOWNS].T if xr.size else np.zeros((REDUCED_UNKNOWNS, 0))
    inside = (
        (c2 >= np.max(cp) ** 2 * (1 - tol))
        & (a2 >= -tol)
        & (b2 >= -tol)
        & (p2 >= -tol)
        & (p2 <= 1 + tol)
    )
    rows = []
    for c2k, a2k, b2k, p2k, mk in zip(
        c2[inside], a2[inside], b2[inside], p2[inside], m[inside], strict=True
    ):
        ta, tb = np.sqrt(max(a2k, 0.0)), np.sqrt(max(b2k, 0.0))
        cos_phi = float(np.clip(mk / (ta * tb), -1.0, 1.0)) if ta * tb > 0 else 0.0
        # phi from (sin, cos): well conditioned near 0 and 180 degrees, where arccos is not
        rows.append(
            [
                np.sqrt(max(c2k, 0.0)) * scale,
                np.arctan(ta),
                np.arctan(tb),
                np.arctan2(np.sqrt(max(1.0 - p2k, 0.0)), cos_phi),
            ]
        )
    shapes = np.array(rows).reshape(-1, 4)
    # every shape's poses at once (3.7 ms a solve one shape at a time)
    poses, misfit = poses_from_shapes(obs, shapes)
    # one shape at a time, as before: on exact four-frame data every residual is rounding, so
    # its last bit orders the shapes, and the pipeline's four-frame samples follow that order
    # (np.mean along axis 1 changed one answer of tests/test_frame_samples.py)
    residuals = np.array([float(np.sqrt(np.mean(row**2))) for row in misfit])
    order = np.argsort(residuals, kind="stable")
    return MinimalResult(
        shapes=shapes[order],
        poses=poses.reshape(-1, FRAMES, 5)[order],
        residuals=residuals[order],
        n_paths=int(x.shape[0]),
        n_complex=int(np.sum(ok & ~real)),
        n_not_shapes=int(np.sum(~inside)),
        n_failed_paths=tracked.n_failed,
        failures=dict(tracked.failures),
        retried_paths=tracked.retried,
    )
