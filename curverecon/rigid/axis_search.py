"""A global search over the rotation axis and B's depth (``fixed-axis``, ``uniform-rotation``).

Under a rotation about the axis n the body vector V = B - A (frame 0's camera coordinates,
input units) sweeps a circle about n; its image is an ellipse through frame 0's image v_0,
so V = (v_0, z) and the pair (n, z) fixes the ellipse.  Each frame's angle free, the best
misfit of a frame is the distance d_f of its image v_f from that ellipse (the frame's shift
takes half of it: chi2_f = d_f^2 / (2 sigma^2)).  Every (n, z) of a grid (axes on the
hemisphere n_z >= 0, which the axis sign covers; z of either sign, which the mirror needs) is
scored by the trimmed sum of d_f^2 (the largest ``TRIM`` of the frames left out: outlier frames
do not decide), the ellipse drawn as a closed polygon of ``SAMPLES`` vertices (its sagitta about
0.4 % of the radius).  The best few distinct cells are starts: the angles from the nearest
point of the polygon, the rate by least squares on them (uniform rotation), further body points
by linear least squares given the axis and angles.

This is the exact likelihood of the frames' own parameters for a given body and axis, where the
algebraic invariants of ``rigid.starts.axis_starts`` weigh the frames unequally: with the axis
near the image plane (a flat ellipse) they prefer an axis near the viewing direction with a
depth of many body lengths (a large circle through a flat arc), which the data reject.
"""

from __future__ import annotations

import numpy as np

from curverecon.rigid.geometry import fit_rate, tangent_directions
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState, axis_angles, rodrigues
from curverecon.rigid.starts import TRIM

SAMPLES = 36
"""Vertices of an ellipse's polygon."""
N_AXES = 1200
"""Axes on the hemisphere (a Fibonacci lattice: about 4 degrees apart)."""
N_DEPTHS = 41
"""Depths of B in frame 0, from -3 to 3 times the longest image of B - A."""
KEEP = 300
"""Cells of the Sampson ranking measured again on the polygon."""


def fibonacci_hemisphere(count: int) -> np.ndarray:
    """(count, 3) unit axes spread evenly over the hemisphere z >= 0."""
    i = np.arange(count) + 0.5
    z = 1.0 - i / count
    r = np.sqrt(1.0 - z * z)
    phi = np.pi * (3.0 - np.sqrt(5.0)) * i
    return np.column_stack([r * np.cos(phi), r * np.sin(phi), z])


def _ellipses(axes: np.ndarray, body: np.ndarray) -> np.ndarray:
    """(H, S, 2) the image of Rot(n_h, a_s) V_h for H axes (H, 3) and bodies V_h (H, 3)."""
    a = np.linspace(-np.pi, np.pi, SAMPLES, endpoint=False)
    along = np.sum(axes * body, axis=1)[:, None] * axes
    perp, cross = body - along, np.cross(axes, body)
    pts = (
        along[:, None]
        + np.cos(a)[None, :, None] * perp[:, None]
        + np.sin(a)[None, :, None] * (cross[:, None])
    )
    return pts[..., :2]


def _distances(poly: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(squared distance (H, F), polygon parameter (H, F) in vertex units) of every image v
    (F, 2) from every closed polygon (H, S, 2)."""
    e = np.roll(poly, -1, axis=1) - poly  # (H, S, 2)
    d = v[None, :, None, :] - poly[:, None]  # (H, F, S, 2)
    ee = np.maximum(np.sum(e * e, axis=-1), 1e-300)[:, None]
    t = np.clip(np.sum(d * e[:, None], axis=-1) / ee, 0.0, 1.0)
    dist2 = np.sum((d - t[..., None] * e[:, None]) ** 2, axis=-1)  # (H, F, S)
    k = np.argmin(dist2, axis=2)
    best = np.take_along_axis(dist2, k[..., None], axis=2)[..., 0]
    frac = np.take_along_axis(t, k[..., None], axis=2)[..., 0]
    return best, k + frac


def _trimmed_sum(d2: np.ndarray) -> np.ndarray:
    keep = max(1, int(np.ceil((1.0 - TRIM) * d2.shape[1])))
    if keep >= d2.shape[1]:
        return np.sum(d2, axis=1)
    return np.sum(np.partition(d2, keep - 1, axis=1)[:, :keep], axis=1)


def _sampson(axes: np.ndarray, body: np.ndarray, v: np.ndarray) -> np.ndarray:
    """(H, F) first-order (Sampson) squared distance of every image v (F, 2) from the ellipse
    of every cell: with u = v - c_xy (c = (V.n) n the circle's centre, r its radius) the
    ellipse is n_z^2 |u|^2 + (u . n_xy)^2 = n_z^2 r^2."""
    along = np.sum(axes * body, axis=1)
    r2 = (np.sum(body * body, axis=1) - along**2)[:, None]
    nx, ny, nz2 = axes[:, :1], axes[:, 1:2], axes[:, 2:] ** 2
    ux = v[None, :, 0] - along[:, None] * nx  # (H, F)
    uy = v[None, :, 1] - along[:, None] * ny
    um = ux * nx + uy * ny
    q = nz2 * (ux * ux + uy * uy - r2) + um * um
    gx, gy = nz2 * ux + um * nx, nz2 * uy + um * ny
    return 0.25 * q * q / np.maximum(gx * gx + gy * gy, 1e-300)


def search_cells(v: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(axes (K, 3), depths (K,), trimmed misfit (K,)) of the grid's ``KEEP`` best cells for
    the images v (N, 2) of B - A: every cell scored by the Sampson distance, the best
    ``KEEP`` again by the distance from the ellipse's polygon."""
    axes = fibonacci_hemisphere(N_AXES)
    reach = 3.0 * float(np.max(np.linalg.norm(v, axis=1)))
    depths = np.linspace(-reach, reach, N_DEPTHS)
    nn = np.repeat(axes, len(depths), axis=0)
    zz = np.tile(depths, len(axes))
    body = np.column_stack([np.broadcast_to(v[0], (len(nn), 2)), zz])
    rough = _trimmed_sum(_sampson(nn, body, v))
    top = np.argsort(rough, kind="stable")[:KEEP]
    d2, _ = _distances(_ellipses(nn[top], body[top]), v)
    return nn[top], zz[top], _trimmed_sum(d2)


def ellipse_starts(layout: Layout, data: RigidData, count: int = 4) -> list[RigidState]:
    """Starts of the axis rows from the best ``count`` distinct cells (module docstring)."""
    vecs = data.points[:, 1:] - data.points[:, :1]  # (N, P-1, 2)
    v = vecs[:, 0]
    nn, zz, score = search_cells(v)
    reach = 3.0 * float(np.max(np.linalg.norm(v, axis=1)))
    chosen: list[int] = []
    for i in np.argsort(score, kind="stable"):
        if all(np.dot(nn[i], nn[j]) < 0.98 or abs(zz[i] - zz[j]) > 0.3 * reach for j in chosen):
            chosen.append(int(i))
        if len(chosen) == count:
            break
    return [_cell_state(layout, data, vecs, nn[i], zz[i]) for i in chosen]


def _cell_state(
    layout: Layout, data: RigidData, vecs: np.ndarray, n: np.ndarray, z: float
) -> RigidState:
    """The state of one cell: B = (v_0, z), angles from the nearest polygon points."""
    body_b = np.array([vecs[0, 0, 0], vecs[0, 0, 1], z])
    poly = _ellipses(n[None], body_b[None])
    _, where = _distances(poly, vecs[:, 0])
    step = 2.0 * np.pi / SAMPLES
    angles = -np.pi + where[0] * step
    angles = np.angle(np.exp(1j * (angles - angles[0])))
    if layout.motion == "uniform-rotation":
        rate = fit_rate(data.times, angles)
        angles = rate * (data.times - data.times[0])
    body = [body_b] + [_body_given(n, angles, vecs[:, k]) for k in range(1, vecs.shape[1])]
    state = RigidState(body=np.array(body), axis=axis_angles(n), shifts=data.points[:, 0].copy())
    if layout.motion == "uniform-rotation":
        state.rate = rate
    else:
        state.angles = angles
    if layout.tangents:
        state.directions = tangent_directions(data, rodrigues(np.outer(angles, n)))
    return state


def _body_given(n: np.ndarray, angles: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The body vector (3,) whose images under Rot(n, angles) fit v (N, 2) best (linear)."""
    rot = rodrigues(np.outer(angles, n))[:, :2, :]  # (N, 2, 3)
    return np.linalg.lstsq(rot.reshape(-1, 3), v.reshape(-1), rcond=None)[0]
