"""Shared pieces of the perspective minimal solvers (``persp_<row>.py``, ``stereo_free.py``).

Conventions (CONTRACT.md, "Configurations"; :mod:`curverecon.solvers.camera`): ``points`` are
pixel positions (F, P, 2), A first; rays are normalised image coordinates (x, y, 1); every
reconstructed point is in its frame's camera coordinates in units of A's depth in frame 0
(A_0 = m_A0, z = 1); rotations act on differences, X_f - A_f = R_f (X_0 - A_0), R_0 = I.  The
homotopy rows turn every ray by the fixed rotation G of ``generated/section2_perspective.py``
(``CHART_ROTATION``) before solving, so that the axis chart n = (n1, n2, 1) is generic for the
axes a real setup has (a turntable axis in the image plane).
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.generated import section2_perspective as gen
from curverecon.solvers import homotopy
from curverecon.solvers.camera import Camera
from curverecon.solvers.ortho_common import check_input
from curverecon.solvers.rigid_solutions import RigidSolutions

CHART = np.array(gen.CHART_ROTATION, dtype=float)
"""G: rays are solved as G m (an exact rational rotation; the fixed-axis solver turns them by a
complex rotation of its own)."""
REAL_TOLERANCE = 1e-6
"""Largest |imaginary part| / (1 + |value|) of a tracked solution taken as real (endpoints are
polished to about 1e-12; complex pairs of real data sit far above)."""


def rays_of(
    points: object, times: object, camera: object, frames: int, names: tuple[str, ...], row: str
) -> tuple[np.ndarray, np.ndarray]:
    """(rays (F, P, 3), times (F,)) of pixel ``points`` checked as the orthographic solvers do
    (shape, finite, increasing times), or a CurveReconError."""
    if not isinstance(camera, Camera):
        raise CurveReconError(f"{row}: the solver needs a Camera (focal_px, principal_point)")
    pts, t = check_input(points, times, frames, names, row)
    return camera.rays(pts), t


def homotopy_parameters(
    rays: np.ndarray, pairs: tuple[tuple[int, int], ...], chart: np.ndarray = CHART
) -> np.ndarray:
    """The homotopy rows' parameter vector: every ray turned by ``chart`` G; frame 0's rays,
    then per later frame the plane normals G m_P x G m_Q of ``pairs`` (indices into the
    points)."""
    turned = rays @ chart.T
    first, second = zip(*pairs, strict=True)
    a, b = turned[1:, list(first)], turned[1:, list(second)]  # (F - 1, pairs, 3)
    normals = np.stack(
        [
            a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
            a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
            a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0],
        ],
        axis=-1,
    )  # the cross products, written out (numpy's cross took 20 us a call)
    return np.concatenate([turned[0].reshape(-1), normals.reshape(-1)])


def cayley(k: np.ndarray) -> np.ndarray:
    """cayley(k) = ((1 - k.k) I + 2 [k]x + 2 k k^T) / (1 + k.k): the rotation about k / |k| by
    2 atan |k| (real k)."""
    kk = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return ((1 - k @ k) * np.eye(3) + 2 * kk + 2 * np.outer(k, k)) / (1 + k @ k)


def depths_from_difference(ma: np.ndarray, mb: np.ndarray, d: np.ndarray) -> np.ndarray:
    """(lambda_A, lambda_B) with lambda_B m_B - lambda_A m_A = D, least squares of the three
    components (exact when D lies in the plane of the rays m_A, m_B): the 2 x 2 normal
    equations by Cramer's rule (distinct rays; numpy's lstsq cost 60 us a call)."""
    aa, ab, bb = ma @ ma, ma @ mb, mb @ mb
    da, db = d @ ma, d @ mb
    det = aa * bb - ab * ab
    return np.array([(ab * db - bb * da) / det, (aa * db - ab * da) / det])


def place(rays: np.ndarray, rotations: np.ndarray, diffs0: np.ndarray) -> np.ndarray:
    """Every point in every frame (F, P, 3) from frame 0's differences X_P0 - A_0 (P - 1, 3)
    and the rotations: frame 0 is A_0 = m_A0 plus the differences; in frame f, D_f = R_f D_0
    fixes A's depth with the first difference (``depths_from_difference``) and the other
    points are A_f + R_f (X_P0 - A_0)."""
    frames, npts, _ = rays.shape
    out = np.empty((frames, npts, 3))
    out[0, 0] = rays[0, 0]
    out[0, 1:] = rays[0, 0] + diffs0
    for f in range(1, frames):
        moved = diffs0 @ rotations[f].T
        lam_a = depths_from_difference(rays[f, 0], rays[f, 1], moved[0])[0]
        out[f, 0] = lam_a * rays[f, 0]
        out[f, 1:] = out[f, 0] + moved
    return out


def real_solutions(
    system: homotopy.PolynomialSystem,
    target: np.ndarray,
    options: homotopy.HomotopyOptions | None = None,
) -> tuple[np.ndarray, int, int, int]:
    """Track every start solution of ``system`` to ``target``; (real rows polished by Newton's
    method, paths, complex endpoints, failed paths)."""
    tracked = homotopy.track(system, target, options)
    x = tracked.solutions
    ok = np.all(np.isfinite(x), axis=1)
    real = ok & np.all(np.abs(x.imag) <= REAL_TOLERANCE * (1 + np.abs(x)), axis=1)
    rows = system.polish(x[real], target, 4).real
    return rows, int(x.shape[0]), int(np.sum(ok & ~real)), tracked.n_failed


def solutions(
    points3: list[np.ndarray],
    rotations: list[np.ndarray],
    motion: list[dict],
    n_paths: int,
    n_complex: int,
    n_failed: int,
    shape: tuple[int, int],
) -> RigidSolutions:
    """A RigidSolutions of the listed solutions (``shape`` = (frames, points) when none)."""
    if not points3:
        out = RigidSolutions.empty(*shape)
    else:
        out = RigidSolutions(np.array(points3), np.array(rotations), motion)
    out.n_paths, out.n_complex, out.n_failed_paths = n_paths, n_complex, n_failed
    return out
