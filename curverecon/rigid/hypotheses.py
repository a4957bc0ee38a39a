"""LO-RANSAC over minimal samples of frames through the rows' minimal solvers.

The generic loop (``robust/ransac.py``) draws ``FRAMES`` frames, the row's solver
(``curverecon/solvers/ortho_<row>.py``, ``solve(points, times) -> RigidSolutions``) returns every
real solution, and each is extended to every frame (:func:`extend`): the uniform rotation by its
rate, the fixed axis by each frame's angle about the axis (linear least squares in its cosine
and sine), three free points by each frame's depths from the body's lengths and angle (the
triad aligned, ``rigid.starts.free_state``).  A model is scored by the robust cost
sum_f min(chi2_f, T) over every frame (T the outlier test's threshold) and polished by the
consensus fit (``rigid.estimate.consensus_fit``).  The all-frame starts (``rigid.starts``) enter
as the loop's initial models.  The force field has no practical minimal solver (its file says
why): its starts alone.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.model.configuration import SOLVER_MODULES
from curverecon.rigid.geometry import tangent_directions
from curverecon.rigid.measurements import RigidData, residuals
from curverecon.rigid.model import Layout, RigidState, axis_angles, frame_rotations, rodrigues
from curverecon.rigid.starts import free_state
from curverecon.robust.ransac import RansacOptions

RANSAC = RansacOptions(max_iterations=200, min_iterations=30, success_prob=0.99, seed=0)
"""The loop's options: at 20 % outlier frames and four-frame samples, 0.99 needs 9 samples
(times 3); 30 at least, as a guard; 200 at most (about 0.5 s of scoring)."""


@dataclass
class Hypothesis:
    """A state over every frame, with its consensus fit once polished."""

    state: RigidState
    cost: float | None = None
    consensus: np.ndarray | None = None
    fit: object | None = None


def solver_for(layout: Layout):
    """The row's minimal solver module, or None (no solver for this row or these points)."""
    key = (layout.motion, min(len(layout.points), 3 if layout.motion == "free" else 2))
    name = SOLVER_MODULES.get(key)
    if name is None or layout.tangents and layout.motion == "free" and len(layout.points) < 3:
        return None
    try:
        module = importlib.import_module(name)
    except ImportError:
        return None
    if not getattr(module, "PRACTICAL", True):  # the force field: its starts alone
        return None
    return module if tuple(getattr(module, "POINTS", ())) == layout.points[:3] else None


def _angles_about(n: np.ndarray, body: np.ndarray, vecs: np.ndarray) -> np.ndarray:
    """(N,) angle of every frame about n from the body (K, 3) to its image vectors (N, K, 2):
    [Rot(n, a) q]_xy = [(n.q) n + cos a q_perp + sin a (n x q)]_xy, least squares in
    (cos a, sin a)."""
    along = np.outer(body @ n, n)
    perp = body - along
    cross = np.cross(n, body)
    rhs = vecs - along[None, :, :2]
    a = np.stack([perp[:, :2].ravel(), cross[:, :2].ravel()], axis=1)
    cs = np.linalg.lstsq(a, rhs.reshape(len(vecs), -1).T, rcond=None)[0]
    return np.arctan2(cs[1], cs[0])


def extend(layout: Layout, data: RigidData, points3: np.ndarray, motion: dict, first: int):
    """A solution of the frames starting at ``first`` (its points3 (F, P, 3)) as a state over
    every frame (None where it does not extend)."""
    body_s = points3[0, 1:] - points3[0, :1]
    vecs = data.points[:, 1:] - data.points[:, :1]
    if layout.motion == "free":
        q1, q2 = body_s[0], body_s[1]
        v1, v2 = vecs[0, 0], vecs[0, 1]
        z1 = np.sqrt(max(q1 @ q1 - v1 @ v1, 0.0))
        z2 = (q1 @ q2 - v1 @ v2) / z1 if z1 > 1e-9 * np.linalg.norm(q1) else 0.0
        return free_state(layout, data, vecs, np.array([z1, z2]))
    n = np.asarray(motion["axis"], float)
    n = n / np.linalg.norm(n)
    state = RigidState(body=body_s.copy(), axis=axis_angles(n), shifts=data.points[:, 0].copy())
    if layout.motion == "uniform-rotation":
        state.rate = float(np.radians(motion["rate_deg"]))
        back = state.rate * (data.times[0] - data.times[first])
    else:
        ang = _angles_about(n, body_s, vecs)
        back = ang[0]
        state.angles = np.angle(np.exp(1j * (ang - ang[0])))
    state.body = body_s @ rodrigues(back * n).T
    if layout.tangents:
        state.directions = tangent_directions(data, frame_rotations(layout, state, data.times)[0])
    return state


class FrameSampleEstimator:
    """The row's estimator for ``robust.ransac.lo_ransac`` (frames are the data items)."""

    def __init__(self, layout: Layout, data: RigidData, solver, threshold: float, polish):
        self.layout, self.data, self.solver = layout, data, solver
        self.threshold, self.polish = threshold, polish
        self.sample_size = int(solver.FRAMES)
        self.num_data = data.n_frames

    def generate_models(self, sample: np.ndarray) -> list[Hypothesis]:
        try:
            sol = self.solver.solve(self.data.points[sample], self.data.times[sample])
        except (CurveReconError, np.linalg.LinAlgError, ValueError, ZeroDivisionError):
            return []
        out = []
        for s in range(sol.n_solutions):
            motion = sol.motion[s] if sol.motion else {}
            try:
                state = extend(self.layout, self.data, sol.points3[s], motion, int(sample[0]))
            except (KeyError, ValueError, np.linalg.LinAlgError):
                continue
            if state is not None:
                out.append(Hypothesis(state))
        return out

    def score_model(self, model: Hypothesis) -> tuple[float, int]:
        if model.cost is None:
            r = residuals(self.layout, model.state, self.data)
            chi2 = np.sum(r * r, axis=1)
            chi2 = np.where(np.isfinite(chi2), chi2, np.inf)
            model.cost = float(np.sum(np.minimum(chi2, self.threshold)))
            return model.cost, int(np.count_nonzero(chi2 <= self.threshold))
        return model.cost, int(np.count_nonzero(model.consensus))

    def refine_model(self, model: Hypothesis) -> Hypothesis:
        got = self.polish(self.layout, self.data, model.state, self.threshold)
        if got is None:
            return model
        fit, cons, cost = got
        return Hypothesis(fit.state, cost, cons, fit)
