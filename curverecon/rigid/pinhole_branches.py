"""Every frame's root pair of the perspective force field with A and B, chosen again.

Given the globals (the mass centre's parabola G(t), the body's vectors a = A - G, b = B - G
in frame 0), a frame's rays meet the spheres |A - G| = |a| and |B - G| = |b| in up to two
points each: four root pairs (``pinhole_force_field.branches``), each a triangle A, B, G and
so a rotation (``rigid.starts.kabsch``).  With noise each frame's rotation has a local minimum
near every pair that nearly fits, and a fit over every frame moves each frame only locally:
where a ray nearly grazes a sphere the truth-started fit itself stays on the other pair (bench
seed 0, accuracy scene 2 at 1 px: chi2 23.6 started at the truth, 13.9 after the frames'
pairs were chosen again, every parameter within 0.9 of its bound).

:func:`choose_pairs` refits every frame's rotation from each pair with the globals held and
keeps, per frame, the least chi2 (frame 0: the body from that frame's pair, every other
rotation carried along); :func:`settle` alternates it with the fit over every frame until no
frame changes.  :func:`walk` moves a settled fit along its weakest direction (the mass centre
inside the body, every rotation with it), where the likelihood has minima of tiny residual
apart from the truth.  The valleys settled in are remembered (:func:`remember`) and
:func:`force_field_valleys` lists those that fit the answer's frames about as well.  At 1 px
several valleys fit within the noise and the lowest is often not the truth's
(docs/accuracy.md).  Lengths in the fit's gauge (g0_z = 1), chi2 in units of the stated noise.
"""

from __future__ import annotations

import numpy as np

from curverecon.rigid.measurements import RigidData, residuals
from curverecon.rigid.model import Layout, RigidState
from curverecon.rigid.refinement import RigidFit, refine
from curverecon.rigid.starts import kabsch

PAIR_ITERATIONS = 30
"""Levenberg-Marquardt iterations of every frame's own rotation per root pair (globals held)."""
ROUNDS = 4
"""Rounds of :func:`settle` at most (the pair choice, then the fit over every frame)."""
GAIN = 1e-6
"""A frame changes its pair when its chi2 falls by more than this."""


def row_of(state: RigidState) -> np.ndarray:
    """The search's parameter row (11,) of a force-field state: g0_x, g0_y, g1, g2, |a|^2,
    |b|^2, a.b (``pinhole_force_field``; g0_z = 1 assumed)."""
    p = np.asarray(state.parabola, float)
    a, b = np.asarray(state.body, float)[:2]
    return np.concatenate([p[0, :2], p[1], p[2], [a @ a, b @ b, a @ b]])


def _triangles(data: RigidData, state: RigidState) -> np.ndarray:
    """(4, N, 3, 3) every frame's triangle (A - G, B - G, their cross product) per root pair."""
    from curverecon.rigid.pinhole_force_field import branches

    cam = data.camera
    u = (data.points - np.asarray(cam.principal_point, float)) / float(cam.focal_px)
    pts, g, _ = branches(u, data.times, row_of(state))
    a, b = pts[:, :, 0] - g, pts[:, :, 1] - g
    return np.stack([a, b, np.cross(a, b)], axis=2)


def _frame0_body(layout: Layout, data: RigidData, state: RigidState, tri: np.ndarray):
    """The state with frame 0 on its best root pair: the body from that pair's triangle and
    every rotation carried along (R_f Q, Q the body's turn), when frame 0's chi2 falls."""
    a, b = state.body[0], state.body[1]
    ref = np.stack([a, b, np.cross(a, b)])
    r0 = residuals(layout, state, data)[0]
    best, best_chi2 = state, float(r0 @ r0)
    for k in range(len(tri)):
        if not np.all(np.isfinite(tri[k, 0])):
            continue
        q = kabsch(tri[k, 0], ref[None])[0]  # q tri_k0 ~ ref
        cand = state.copy()
        cand.body = tri[k, 0, :2].copy()
        cand.rotations = np.einsum("fij,jk->fik", state.rotations, q)
        cand.rotations[0] = np.eye(3)
        r = residuals(layout, cand, data)[0]
        chi2 = float(r @ r)
        if np.isfinite(chi2) and chi2 < best_chi2 - GAIN:
            best, best_chi2 = cand, chi2
    return best


def choose_pairs(
    layout: Layout, data: RigidData, state: RigidState, frame_chi2: np.ndarray | None = None
) -> tuple[RigidState, int]:
    """(the state with every frame on its best root pair, the frames changed): each pair's
    rotation refitted with the globals held; a frame keeps its own rotation unless a pair's
    chi2 is lower by ``GAIN``.  ``frame_chi2``: the state's own per-frame chi2 (refitted with
    the globals held when None)."""
    tri = _triangles(data, state)
    moved = _frame0_body(layout, data, state, tri)
    if moved is not state:
        state, frame_chi2 = moved, None
        tri = _triangles(data, state)
    if frame_chi2 is None:
        base = refine(layout, state, data, max_iter=PAIR_ITERATIONS, covariance=False,
                      fix_globals=True)  # fmt: skip
        state, frame_chi2 = base.state, base.frame_chi2
    best = np.where(np.isfinite(frame_chi2), frame_chi2, np.inf)
    rots = np.array(state.rotations, float)
    a, b = state.body[0], state.body[1]
    ref = np.stack([a, b, np.cross(a, b)])
    changed = np.zeros(len(best), bool)
    for k in range(len(tri)):
        ok = np.all(np.isfinite(tri[k]), axis=(1, 2))
        cand = state.copy()
        cand.rotations = np.where(ok[:, None, None], kabsch(ref, np.nan_to_num(tri[k])), rots)
        cand.rotations[0] = np.eye(3)
        try:
            fit = refine(layout, cand, data, max_iter=PAIR_ITERATIONS, covariance=False,
                         fix_globals=True)  # fmt: skip
        except (np.linalg.LinAlgError, ValueError, FloatingPointError):
            continue
        chi2 = np.where(np.isfinite(fit.frame_chi2), fit.frame_chi2, np.inf)
        take = ok & (chi2 < best - GAIN)
        take[0] = False
        best = np.where(take, chi2, best)
        rots[take] = fit.state.rotations[take]
        changed |= take
    out = state.copy()
    out.rotations = rots
    return out, int(np.count_nonzero(changed)) + (moved is not state)


def settle(
    layout: Layout, data: RigidData, state: RigidState, max_iter: int = 200, rounds: int = ROUNDS
) -> RigidFit:
    """The fit over every frame, then rounds of :func:`choose_pairs` and the fit again while a
    frame changes its pair and chi2 falls (module docstring)."""
    fit = refine(layout, state, data, max_iter=max_iter, covariance=False)
    for _ in range(rounds):
        try:
            moved, changed = choose_pairs(layout, data, fit.state, fit.frame_chi2)
            if not changed:
                break
            new = refine(layout, moved, data, max_iter=max_iter, covariance=False)
        except (np.linalg.LinAlgError, ValueError, FloatingPointError):
            break
        if not np.isfinite(new.chi2) or new.chi2 >= fit.chi2:
            break
        fit = new
    return fit


ALTERNATIVE_DCHI2 = 4.0
"""A valley of the search is an alternative when its chi2 on the answer's frames is at most
this above the answer's (as ``pinhole_search.ALTERNATIVE_DCHI2``)."""
VALLEYS = 6
"""Settled valleys of the search (least trimmed chi2 first) refitted on the answer's frames."""
_CACHE: dict[bytes, list[RigidState]] = {}
_CACHE_SIZE = 8


def _key(data: RigidData) -> bytes:
    return np.asarray(data.points, float).tobytes() + np.asarray(data.times, float).tobytes()


def remember(data: RigidData, states: list[RigidState]) -> None:
    """Keep the search's settled valleys (every frame, least trimmed chi2 first; one of each)
    for :func:`force_field_valleys`."""
    if len(_CACHE) >= _CACHE_SIZE:
        _CACHE.pop(next(iter(_CACHE)))
    kept: list[RigidState] = []
    for s in states:
        scale = 1e-4 * float(np.linalg.norm(s.body))
        if all(np.max(np.abs(_globals(s) - _globals(k))) > scale for k in kept):
            kept.append(s.copy())
    _CACHE[_key(data)] = kept[:VALLEYS]


def force_field_valleys(layout: Layout, data: RigidData, fit: RigidFit, idx: np.ndarray):
    """(the answer's fit, the alternatives' fits) on the inlier frames ``idx`` of ``data``
    (every frame): each valley the search settled in (:func:`remember`) refitted on those
    frames with its covariance; one of lower chi2 becomes the answer (its ``full_state`` the
    valley's over every frame), the others within ``ALTERNATIVE_DCHI2`` whose globals differ
    from the answer's by more than its std are alternatives (``pinhole_search
    .widened_covariance`` widens the std to reach them)."""
    from curverecon.rigid.estimate import expand_state
    from curverecon.rigid.model import with_frames

    stored = _CACHE.get(_key(data), [])
    if fit.covariance is None or not stored:
        return fit, []
    sub = data.subset(idx)
    fits = [fit]
    for state in stored:
        try:
            with np.errstate(all="ignore"):
                alt = refine(layout, with_frames(state, idx), sub, max_iter=200)
        except (np.linalg.LinAlgError, FloatingPointError, ValueError):
            continue
        if alt.covariance is None or not np.isfinite(alt.chi2):
            continue
        alt.full_state = expand_state(layout, alt.state, idx, state)
        fits.append(alt)
    best = min(fits, key=lambda f: f.chi2)
    sd = np.sqrt(np.maximum(np.diag(best.covariance), 0.0))
    out: list[RigidFit] = []
    for other in fits:
        if other is best or other.chi2 - best.chi2 > ALTERNATIVE_DCHI2:
            continue
        d = np.abs(_globals(other.state) - _globals(best.state))
        if np.any(d > sd) and not any(np.allclose(_globals(other.state), _globals(o.state),
                                                  atol=1e-6) for o in out):  # fmt: skip
            out.append(other)
    return best, out


def _globals(state: RigidState) -> np.ndarray:
    """The force field's globals in the fit's order: the body, then the parabola."""
    return np.concatenate([np.ravel(state.body), np.ravel(state.parabola)])


STEPS = (-0.3, -0.1, 0.1, 0.3)
"""Steps of :func:`walk` along the weakest direction, in units of the body's norm (noise-free
bench seed 1, scene 0: the truth 0.18 away from a minimum of chi2 3.5e-7 px^2 along it)."""


def admit(layout: Layout, data: RigidData, fit: RigidFit) -> list:
    """[(singular, trimmed chi2, state, the globals' covariance or None)] of a settled fit, or
    [] when a point is behind the camera (a pinhole images X and -X alike).  A singular
    information (the answer would be refused) ranks after every regular fit: on scenes that
    hardly determine the body (a small turn) it may be all there is."""
    from curverecon.rigid.model import points3
    from curverecon.rigid.refinement import information_inverse
    from curverecon.rigid.starts import trimmed_sum

    if not np.isfinite(fit.chi2):
        return []
    if np.min(points3(layout, fit.state, data.times)[..., 2]) <= 0.0:
        return []
    cov = information_inverse(layout, fit.state, data)[0]
    chi2 = np.where(np.isfinite(fit.frame_chi2), fit.frame_chi2, np.inf)
    return [(cov is None, float(trimmed_sum(chi2)), fit.state, cov)]


def walk(layout: Layout, data: RigidData, state: RigidState, cov: np.ndarray) -> list[RigidFit]:
    """Fits settled from ``state`` moved along its weakest direction (the globals' covariance
    scaled to unit diagonal, its largest eigenvector) by each of ``STEPS`` times the body's
    norm.  The force field's weak direction moves the mass centre inside the body and every
    rotation with it; along it the likelihood has minima of tiny residual apart from the truth
    (docs/accuracy.md), which a local fit does not leave.  Not on a fit whose c's std is above
    ``rigid.answer.UNDETERMINED_FRACTION`` of c (a small turn): its weak direction leads into
    fits the information no longer determines (bench test scene: 180-300 degrees, c's std 300
    times c, the walked fit refused as singular)."""
    from curverecon.rigid.answer import UNDETERMINED_FRACTION, chord_std
    from curverecon.rigid.measurements import apply_step
    from curverecon.rigid.model import body_vectors

    q = body_vectors(layout, state)
    c = float(np.linalg.norm(q[1] - q[0]))
    if not chord_std(layout, state, cov) <= UNDETERMINED_FRACTION * c:
        return []

    d = np.sqrt(np.maximum(np.diag(cov), 1e-300))
    v = np.linalg.eigh(cov / np.outer(d, d))[1][:, -1] * d
    n = np.asarray(state.body).size
    v = v / max(float(np.linalg.norm(v[:n])), 1e-300) * float(np.linalg.norm(state.body))
    locals0 = np.zeros((data.n_frames, layout.n_local))
    out = []
    for s in STEPS:
        try:
            with np.errstate(all="ignore"):
                moved = apply_step(layout, state, s * v, locals0, data.times)
                out.append(settle(layout, data, moved))
        except (np.linalg.LinAlgError, ValueError, FloatingPointError):
            continue
    return out


__all__ = ["admit", "choose_pairs", "force_field_valleys", "remember", "row_of", "settle", "walk"]
