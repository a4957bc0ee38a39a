"""Every frame's pose searched again against a fixed curve (the starts of the poses).

:func:`_resect_starts`: a sweep over the poses that put A, B on the polyline's ends - the
wrong-branch poses that degree-off end tangents leave are beyond LM's reach - scored by the
projected curve's distance from the polyline; :func:`resect_all` refines the best starts of every
frame at once (``lm.lm_poses``).  :func:`regauge` re-expresses a state in frame 0's camera
coordinates when frame 0's own pose moved.
"""

from __future__ import annotations

import functools

import numpy as np

from curverecon.curve.bundle_kernel import (
    nearest_distances,
    sweep_distances,
)
from curverecon.curve.lm import lm_poses
from curverecon.curve.residuals import Problem
from curverecon.curve.spline import Basis

#: A swept pose is refined only if its grid score (mean squared distance) is below this multiple
#: of the current pose's (the grid is coarse: a pose near the right one can score several px^2).
RESECT_GAIN = 4.0


#: ... and not within this angle (degrees, the sweep's step) of the current pose: a start
#: there lies in the current pose's own basin, and its refinement returns there (1 px, 20
#: frames, seeds 1400, 1401, 2000, 2100, every family: of 480 such starts 99.2 % ended within
#: 2 degrees of the current pose and none elsewhere with a lower cost; 70 % of the refined
#: starts, so about half of the pose search's time).  The starts farther out (other branches,
#: other turns about AB) are refined as before.
RESECT_SAME_DEG = 10.0


def _rot_zyx(theta: float, tau: np.ndarray, delta: np.ndarray) -> np.ndarray:
    """(n, 3, 3) rotations ``Rz(theta) Ry(tau) Rx(delta)`` for n pairs (tau, delta)."""
    ct, st, cd, sd = np.cos(tau), np.sin(tau), np.cos(delta), np.sin(delta)
    ch, sh = np.cos(theta), np.sin(theta)
    n = len(tau)
    rz = np.array([[ch, -sh, 0.0], [sh, ch, 0.0], [0.0, 0.0, 1.0]])
    ry = np.zeros((n, 3, 3))
    ry[:, 0, 0], ry[:, 0, 2], ry[:, 1, 1], ry[:, 2, 0], ry[:, 2, 2] = ct, st, 1.0, -st, ct
    rx = np.zeros((n, 3, 3))
    rx[:, 0, 0], rx[:, 1, 1], rx[:, 1, 2], rx[:, 2, 1], rx[:, 2, 2] = 1.0, cd, -sd, sd, cd
    return rz @ ry @ rx


def _resect_starts(prob: Problem, ctrl: np.ndarray, mi: np.ndarray, bi: np.ndarray, i: int):
    """Best pose of frame i for the fixed curve: a sweep over the poses that put A, B on the
    polyline's ends (both signs of tau, rotation about AB in 10-degree steps), scored by the
    mean squared distance of the projected curve from the polyline.  The best two are refined
    by LM if they score below ``RESECT_GAIN`` times the current pose (a frame on the right
    branch scores near the noise level, far below any grid pose) and lie at least
    ``RESECT_SAME_DEG`` from it.  Returns the (m_i, b_i) to refine (:func:`resect_all`), none
    when no sweep pose beats the current one."""
    poly = prob.polys[i]
    a3 = ctrl[0]
    ab = ctrl[-1] - a3
    c = float(np.linalg.norm(ab))
    chord = poly[-1] - poly[0]
    cp = float(np.hypot(*chord))
    e1 = ab / c
    e2 = _cross3(e1, np.array([1.0, 0.0, 0.0] if abs(e1[0]) < 0.9 else [0.0, 1.0, 0.0]))
    e2 /= np.linalg.norm(e2)
    cmat = np.column_stack([e1, e2, _cross3(e1, e2)])
    tau_abs = float(np.arccos(min(cp / c, 1.0)))
    theta = float(np.arctan2(chord[1], chord[0]))
    pts = _sweep_basis(prob.k) @ ctrl - a3
    dense = prob.resampled(i)
    deltas = _SWEEP_DELTAS
    taus = np.array(sorted({tau_abs, -tau_abs}))
    mms = _rot_zyx(theta, np.repeat(taus, len(deltas)), np.tile(deltas, len(taus))) @ cmat.T
    current = float(np.mean(nearest_distances(dense, (pts + a3) @ mi[:2].T + bi[:2]) ** 2))
    # every sweep pose's projected curve in one query (the same distances as one by one); a
    # pose is measured only until its sum exceeds the refinement's limit (RESECT_GAIN times
    # the current score, with a margin for the order of the sums): such a pose is not refined
    # whatever its score, and the others keep theirs (the same starts as measuring them all)
    proj = pts @ np.transpose(mms[:, :2], (0, 2, 1)) + poly[0]
    bound = RESECT_GAIN * current * len(pts) * (1.0 + 1e-9)
    dist, over = sweep_distances(dense, proj.reshape(-1, 2), len(pts), bound)
    dist = dist.reshape(len(mms), len(pts))
    scores = np.mean(dist**2, axis=1)  # row by row: the same sums as one pose at a time
    scores[over] = np.inf
    best = np.argsort(scores, kind="stable")[:2]  # ties: the first pose (by score, index)
    # only sweep poses that beat the current one even on the coarse grid are refined
    # ... and only outside the current pose's own basin (RESECT_SAME_DEG)
    starts = [
        (mms[j], np.append(poly[0] - (mms[j] @ a3)[:2], 0.0))
        for j in best
        if float(scores[j]) < RESECT_GAIN * current
        and max_angle_deg(mms[j][None], mi[None]) > RESECT_SAME_DEG
    ]
    return starts


#: The pose sweep's rotations about AB (:func:`_resect_starts`), 10 degrees apart.
_SWEEP_DELTAS = np.radians(np.arange(0.0, 360.0, 10.0))
_SWEEP_DELTAS.flags.writeable = False


@functools.cache
def _sweep_basis(k: int) -> np.ndarray:
    """The basis values (40, k) of the pose sweep's curve samples (:func:`_resect_starts`)."""
    out = Basis(k).values(np.linspace(0.0, 1.0, 40))
    out.flags.writeable = False
    return out


def _cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.cross`` of two 3-vectors (its products and differences, without its dispatch)."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def resect_all(prob: Problem, ctrl: np.ndarray, m: np.ndarray, b: np.ndarray, frames):
    """:func:`_resect_starts` of the given frames, the starts refined by LM on their poses
    (at most 15 iterations), all at once.  Returns {frame: (m_i, b_i, cost) of its best
    refined pose} for the frames with a start."""
    owner, ms, bs = [], [], []
    for i in frames:
        for mm, bb in _resect_starts(prob, ctrl, m[i], b[i], i):
            owner.append(i)
            ms.append(mm)
            bs.append(bb)
    if not owner:
        return {}
    sub = prob.subset(owner)
    m2, b2, cost = lm_poses(sub, ctrl, np.array(ms), np.array(bs), 15, 1e-4)
    best: dict = {}
    for j, i in enumerate(owner):
        if i not in best or cost[j] < best[i][2]:
            best[i] = (m2[j], b2[j], float(cost[j]))
    return best


def max_angle_deg(m1: np.ndarray, m2: np.ndarray) -> float:
    """The largest rotation angle (degrees) between the frames' rotations m1[i] and m2[i]."""
    c = (np.einsum("nij,nij->n", m1, m2) - 1.0) / 2.0  # (trace(m1 m2^T) - 1) / 2
    return float(np.degrees(np.arccos(np.clip(c, -1.0, 1.0))).max())


def regauge(ctrl: np.ndarray, m: np.ndarray, b: np.ndarray):
    """Re-express the state in frame 0's (new) camera coordinates with A at depth 0."""
    m0, b0 = m[0].copy(), b[0].copy()
    ctrl = ctrl @ m0.T + b0
    m = np.einsum("nij,kj->nik", m, m0)  # m_i m_0^T
    b = b - np.einsum("nij,j->ni", m, b0)
    dz = ctrl[0, 2]
    ctrl = ctrl - [0.0, 0.0, dz]
    b = b + dz * m[:, :, 2]
    m[0], b[0] = np.eye(3), np.zeros(3)
    return ctrl, m, b
