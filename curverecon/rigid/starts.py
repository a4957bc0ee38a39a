"""Start states for the rows' maximum likelihood from all frames at once (robust scores).

* Rotation about a fixed axis (``fixed-axis``, ``uniform-rotation``): a body vector V = X - A
  keeps its component along the axis n and its length, so with v_f its image in frame f and
  a_f = n_xy . v_f: z_f = (h - a_f) / n_z and |v_f|^2 + z_f^2 = L^2, i.e.
  2 a_f h + K = a_f^2 + n_z^2 |v_f|^2 with K = n_z^2 L^2 - h^2: linear in (h, K) for a given
  axis.  Every axis of a grid on the hemisphere is scored by these equations' residuals
  (each divided by its gradient in v_f, about pixels; the largest fifth trimmed so that outlier
  frames do not decide), the best few axes give the depths, the angles about the axis
  (and the rate by least squares), and each is a start.
* Free motion with three points or more: the depths z_1, z_2 of B - A and C - A in frame 0 fix
  the body's lengths and angle; frame f needs |z_1f| |z_2f| = |D.E - v_1f . v_2f| with
  z_kf^2 = |V_k|^2 - |v_kf|^2.  A grid over (z_1 >= 0, z_2) scored by the trimmed residuals
  gives the body; each frame's rotation follows by aligning the body's triad (Kabsch), on the
  depth sign (Necker reversal) whose tangents fit better where tangents are given.
* Force field: the distinct minima of the parabola search (``rigid.parabola``: the mass
  centre's image and the body's invariants from every frame's equation); frame 0's depths from
  the invariants, each frame's rotation aligning the body with the images.
"""

from __future__ import annotations

import numpy as np

from curverecon.rigid.geometry import fit_rate, tangent_directions
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState, axis_angles, rodrigues

TRIM = 0.2
"""Fraction of frames left out of a start's score (outlier frames)."""


def trimmed_sum(res2: np.ndarray, axis: int = -1) -> np.ndarray:
    """Sum of the smallest (1 - TRIM) of the squared residuals along ``axis``."""
    n = res2.shape[axis]
    keep = max(1, int(np.ceil((1.0 - TRIM) * n)))
    return np.sum(np.sort(res2, axis=axis).take(np.arange(keep), axis=axis), axis=axis)


def hemisphere(n_polar: int = 30, n_azimuth: int = 60) -> np.ndarray:
    """(K, 3) axes on the hemisphere z > 0 (the mirror and the axis sign cover the rest)."""
    k = np.linspace(0.04, np.pi / 2 - 0.002, n_polar)
    lam = np.linspace(0.0, 2 * np.pi, n_azimuth, endpoint=False)
    kk, ll = np.meshgrid(k, lam, indexing="ij")
    kk, ll = kk.ravel(), ll.ravel()
    return np.column_stack([np.sin(kk) * np.cos(ll), np.sin(kk) * np.sin(ll), np.cos(kk)])


def _axis_fit(axes: np.ndarray, v: np.ndarray):
    """For every axis (K, 3) and body vector images v (N, 2): (h, K) (K,), residuals (K, N)."""
    a = np.einsum("kd,fd->kf", axes[:, :2], v)
    nz2 = axes[:, 2:3] ** 2
    rhs = a * a + nz2 * np.sum(v * v, axis=1)[None]
    # least squares of 2 a h + K = rhs per axis
    sa, saa, n = a.sum(1), (a * a).sum(1), a.shape[1]
    sr, sar = rhs.sum(1), (a * rhs).sum(1)
    det = 2 * saa * n - 2 * sa * sa
    det = np.where(np.abs(det) < 1e-300, 1e-300, det)
    h = (n * sar - sa * sr) / det
    kk = (2 * saa * sr - 2 * sa * sar) / det
    res = 2 * a * h[:, None] + kk[:, None] - rhs
    grad = 2 * (a - h[:, None])[..., None] * axes[:, None, :2] + 2 * nz2[..., None] * v[None]
    return h, kk, res / np.maximum(np.linalg.norm(grad, axis=2), 1e-9)


def _rotations_about(n: np.ndarray, angles: np.ndarray) -> np.ndarray:
    return rodrigues(np.outer(angles, n))


def axis_starts(layout: Layout, data: RigidData, count: int = 4) -> list[RigidState]:
    """Starts of the fixed-axis and uniform-rotation rows (see the module docstring)."""
    axes = hemisphere()
    vecs = data.points[:, 1:] - data.points[:, :1]  # (N, P-1, 2)
    score = np.zeros(len(axes))
    fits = []
    for k in range(vecs.shape[1]):
        h, kk, res = _axis_fit(axes, vecs[:, k])
        fits.append((h, kk))
        score += trimmed_sum(res * res)
    order = np.argsort(score)
    chosen: list[int] = []
    for i in order:
        if all(np.dot(axes[i], axes[j]) < 0.98 for j in chosen):
            chosen.append(int(i))
        if len(chosen) == count:
            break
    return [_axis_state(layout, data, axes[i], [(h[i], kk[i]) for h, kk in fits]) for i in chosen]


def _axis_state(layout: Layout, data: RigidData, n: np.ndarray, hk) -> RigidState:
    vecs = data.points[:, 1:] - data.points[:, :1]
    scale = 3.0 * float(np.max(np.linalg.norm(vecs, axis=-1)))
    full = []
    for k, (h, _) in enumerate(hk):
        v = vecs[:, k]
        z = np.clip((h - v @ n[:2]) / n[2], -scale, scale)
        full.append(np.column_stack([v, z]))
    full = np.array(full)  # (P-1, N, 3)
    perp = full - np.einsum("knd,d->kn", full, n)[..., None] * n
    cross = np.einsum("d,knd->kn", n, np.cross(perp[:, :1], perp))
    dot = np.einsum("knd,knd->kn", perp[:, :1], perp)
    angles = np.arctan2(cross.sum(0), dot.sum(0))
    state = RigidState(body=full[:, 0].copy(), axis=axis_angles(n))
    state.shifts = data.points[:, 0].copy()
    if layout.motion == "uniform-rotation":
        state.rate = fit_rate(data.times, angles)
        angles = state.rate * (data.times - data.times[0])
    else:
        state.angles = angles
    if layout.tangents:
        state.directions = tangent_directions(data, _rotations_about(n, angles))
    return state


def kabsch(src: np.ndarray, dst: np.ndarray) -> np.ndarray:
    """(N, 3, 3) rotations R minimising sum |R src_k - dst_fk|^2 (src (K, 3), dst (N, K, 3))."""
    h = np.einsum("kd,fke->fde", src, dst)
    u, _, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(np.einsum("fij,fjk->fik", u, vt)))
    fix = np.ones((len(dst), 3))
    fix[:, 2] = d
    return np.einsum("fji,fj,fkj->fik", vt, fix, u)


def _triad(vectors: np.ndarray) -> np.ndarray:
    """Body vectors (..., K, 3) with the cross product of the first two appended."""
    return np.concatenate([vectors, np.cross(vectors[..., :1, :], vectors[..., 1:2, :])], axis=-2)


def _depth_score(v1, v2, z1, z2):
    """Trimmed residual (pixels squared) of the free three-point invariants, grid (G,)."""
    len1 = np.sum(v1[0] ** 2) + z1**2
    len2 = np.sum(v2[0] ** 2) + z2**2
    dot = v1[0] @ v2[0] + z1 * z2
    a = len1[:, None] - np.sum(v1 * v1, axis=1)[None]
    b = len2[:, None] - np.sum(v2 * v2, axis=1)[None]
    rhs = np.abs(dot[:, None] - np.sum(v1 * v2, axis=1)[None])
    prod = np.sqrt(np.maximum(a, 0) * np.maximum(b, 0))
    scale = np.sqrt(len1 + len2)[:, None]
    res = (prod - rhs) / scale + (np.minimum(a, 0) + np.minimum(b, 0)) / scale
    return trimmed_sum(res * res)


def free_starts(layout: Layout, data: RigidData, count: int = 3) -> list[RigidState]:
    """Starts of the free row with three points or more (see the module docstring)."""
    vecs = data.points[:, 1:] - data.points[:, :1]
    v1, v2 = vecs[:, 0], vecs[:, 1]
    r = 2.5 * float(np.max(np.linalg.norm(vecs, axis=-1)))
    z1, z2 = np.meshgrid(np.linspace(0.0, r, 41), np.linspace(-r, r, 81), indexing="ij")
    z1, z2 = z1.ravel(), z2.ravel()
    score = _depth_score(v1, v2, z1, z2)
    out = []
    for i in np.argsort(score)[: 4 * count]:
        if any(abs(z1[i] - s.body[0, 2]) + abs(z2[i] - s.body[1, 2]) < 0.1 * r for s in out):
            continue
        out.append(free_state(layout, data, vecs, np.array([z1[i], z2[i]])))
        if len(out) == count:
            break
    return out


def align_rotations(body: np.ndarray, img: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every frame's rotation of two body vectors (2, 3) onto their images (N, 2, 2): the depths
    from the vectors' lengths and their dot product, then the triads aligned (Kabsch).  Returns
    (rotations (N, 3, 3), the depth-reversed ones (N, 3, 3))."""
    lengths2 = np.sum(body**2, axis=1)
    z = np.sqrt(np.maximum(lengths2[None] - np.sum(img**2, axis=2), 0.0))
    sign = np.sign(body[0] @ body[1] - np.sum(img[:, 0] * img[:, 1], axis=1))
    z[:, 1] *= np.where(sign == 0, 1.0, sign)
    dst = np.concatenate([img, z[..., None]], axis=2)
    rots = kabsch(_triad(body), _triad(dst))
    other = kabsch(_triad(body), _triad(dst * np.array([1.0, 1.0, -1.0])))
    return rots, other


def free_state(layout: Layout, data: RigidData, vecs: np.ndarray, z0: np.ndarray) -> RigidState:
    """The free row's state from frame 0's depths ``z0`` of B - A and C - A (further points at
    depth 0), every frame's rotation aligned (:func:`align_rotations`)."""
    body = np.column_stack([vecs[0, :2], np.zeros(2)])
    body[:, 2] = z0
    body = np.vstack([body, np.column_stack([vecs[0, 2:], np.zeros(len(vecs[0]) - 2)])])
    rots, other = align_rotations(body[:2], vecs[:, :2])
    if layout.tangents:
        rots = _better_tangents(data, rots, other)
    rots = np.einsum("fij,kj->fik", rots, rots[0])  # relative to frame 0
    body = np.einsum("ij,kj->ki", rots[0], body)
    state = RigidState(body=body, rotations=rots, shifts=data.points[:, 0].copy())
    if layout.tangents:
        state.directions = tangent_directions(data, rots)
    return state


def reset_rotations(layout: Layout, state: RigidState, data: RigidData) -> RigidState:
    """The state with every frame's free rotation (but frame 0's) aligned again from its images
    (:func:`align_rotations`, on the depth branch the further points or else the tangents
    prefer where given): a frame left
    on a poor local minimum of its own parameters starts again from the closed form."""
    if not layout.free_rotations:
        return state
    from curverecon.rigid.model import body_vectors, frame_shifts

    q = body_vectors(layout, state)
    ref = frame_shifts(layout, state, data.times)
    img = data.points - ref[:, None, :]
    if not layout.centred:
        q, img = q[1:], img[:, 1:]
    rots, other = align_rotations(q[:2], img[:, :2])
    if len(q) > 2:  # a body off one plane: the further points choose each frame's branch
        worse = _extra_misfit(other, q[2:], img[:, 2:]) < _extra_misfit(rots, q[2:], img[:, 2:])
        rots = np.where(worse[:, None, None], other, rots)
    elif layout.tangents and state.directions is not None:
        rots = _better_tangents(data, rots, other)
    out = state.copy()
    out.rotations[1:] = rots[1:]
    return out


def _better_tangents(data: RigidData, rots: np.ndarray, other: np.ndarray) -> np.ndarray:
    """Per frame the rotation (of the Necker pair) whose tangent planes fit a common body
    direction better."""
    out = rots.copy()
    for _ in range(2):
        d = tangent_directions(data, out)
        u = np.column_stack([np.sin(d[:, 0]) * np.cos(d[:, 1]), np.sin(d[:, 0]) * np.sin(d[:, 1])])
        u = np.column_stack([u, np.cos(d[:, 0])])
        normals = np.stack([-np.sin(data.angles), np.cos(data.angles), 0 * data.angles], axis=2)

        e_other = np.sum(np.einsum("fjd,fde,je->fj", normals, other, u) ** 2, axis=1)
        e_out = np.sum(np.einsum("fjd,fde,je->fj", normals, out, u) ** 2, axis=1)
        out = np.where((e_other < e_out)[:, None, None], other, out)
    return out


def force_field_starts(layout: Layout, data: RigidData, count: int = 3) -> list[RigidState]:
    """Starts of the force-field row: the distinct minima of the parabola search
    (``rigid.parabola``) as states (see the module docstring)."""
    from curverecon.rigid.parabola import search

    return [
        force_field_state(layout, data, par, inv)
        for par, inv, _ in search(data.points[:, :2], data.times, TRIM, count)
    ]


def force_field_state(
    layout: Layout, data: RigidData, parabola: np.ndarray, inv: np.ndarray
) -> RigidState:
    """The force field's state from the mass centre's parabola (3, 2) and the invariants
    (|a|^2, |b|^2, a.b) of a = A - G, b = B - G: frame 0's depths from them, every frame's
    rotation aligned (:func:`align_rotations`); further points by linear least squares over
    the frames, each frame on the depth branch they fit better."""
    t = data.times
    centre = np.column_stack([np.ones_like(t), t, 0.5 * t * t]) @ parabola
    img = data.points - centre[:, None]
    p0, q0 = img[0, 0], img[0, 1]
    za = np.sqrt(max(inv[0] - p0 @ p0, 0.0))
    zb = np.sqrt(max(inv[1] - q0 @ q0, 0.0)) * (1.0 if inv[2] - p0 @ q0 >= 0 else -1.0)
    ab = np.array([[*p0, za], [*q0, zb]])
    rots, other = align_rotations(ab, img[:, :2])
    extra = np.zeros((0, 3))
    for _ in range(3 if img.shape[1] > 2 else 0):
        extra = _extra_points(rots, img[:, 2:])
        worse = _extra_misfit(other, extra, img[:, 2:]) < _extra_misfit(rots, extra, img[:, 2:])
        rots, other = (
            np.where(worse[:, None, None], other, rots),
            np.where(worse[:, None, None], rots, other),
        )
    if img.shape[1] > 2:
        extra = _extra_points(rots, img[:, 2:])
    if layout.tangents:
        rots = _better_tangents(data, rots, other)
    body = np.vstack([ab, extra])
    rots = np.einsum("fij,kj->fik", rots, rots[0])
    state = RigidState(body=np.einsum("ij,kj->ki", rots[0], body), rotations=rots)
    state.parabola = np.array(parabola, float)
    if layout.tangents:
        state.directions = tangent_directions(data, rots)
    return state


def _extra_points(rots: np.ndarray, img: np.ndarray) -> np.ndarray:
    """(K, 3) body vectors X with [R_f X]_xy = img_fk by least squares over the frames."""
    a = rots[:, :2].reshape(-1, 3)
    return np.linalg.lstsq(a, img.transpose(0, 2, 1).reshape(-1, img.shape[1]), rcond=None)[0].T


def _extra_misfit(rots: np.ndarray, extra: np.ndarray, img: np.ndarray) -> np.ndarray:
    return np.sum((np.einsum("fij,kj->fki", rots[:, :2], extra) - img) ** 2, axis=(1, 2))


def starts(layout: Layout, data: RigidData) -> list[RigidState]:
    """Start states of a row from all of its frames."""
    if layout.motion in ("uniform-rotation", "fixed-axis"):
        return axis_starts(layout, data)
    if layout.motion == "free":
        return free_starts(layout, data)
    return force_field_starts(layout, data)
