"""LO-RANSAC over two-frame samples of the perspective rotation-free row.

The row's minimal solver (``solvers/persp_rotation_free.py``, closed form: one linear solve of
two frames) gives the body D_P = X_P - A (the same in every frame) with A's depth in the
sample's first frame as the unit; each other frame's A follows from its rays m_A, m_B and D_B
(``solvers.persp_common.depths_from_difference``), the whole model is rescaled to A's depth in
frame 0 = 1 and scored by the robust cost sum_f min(chi2_f, T) over every frame
(``rigid.hypotheses.FrameSampleEstimator``'s score), the best polished by the consensus fit
(``rigid.estimate.consensus_fit``).  The all-frame closed form enters as the loop's initial
model.
"""

from __future__ import annotations

import numpy as np

from curverecon.errors import CurveReconError
from curverecon.rigid.hypotheses import FrameSampleEstimator, Hypothesis
from curverecon.rigid.measurements import RigidData
from curverecon.rigid.model import Layout, RigidState
from curverecon.robust.ransac import RansacOptions

RANSAC = RansacOptions(max_iterations=60, min_iterations=20, success_prob=0.99, seed=0)
"""Two-frame samples at 20 % outlier frames need 5 draws for 0.99 (times 3); 20 at least."""


def extend_rotation_free(data: RigidData, body: np.ndarray) -> RigidState | None:
    """The rotation-free state over every frame from the body (P - 1, 3) relative to A: each
    frame's A on its ray at the depth that puts B - A = body[0] (least squares), rescaled so
    that A's depth in frame 0 is 1; None when frame 0's A is not in front of the camera."""
    m = data.camera.rays(data.points)  # (N, P, 3)
    a = np.stack([-m[:, 0], m[:, 1]], axis=-1)  # (N, 3, 2)
    ata = np.einsum("fki,fkj->fij", a, a)
    atb = np.einsum("fki,k->fi", a, body[0])
    depth = np.linalg.solve(ata, atb[..., None])[:, 0, 0]
    if not depth[0] > 0:
        return None
    state = RigidState(body=np.array(body, float), translations=depth[:, None] * m[:, 0])
    scale = 1.0 / depth[0]
    state.body, state.translations = state.body * scale, state.translations * scale
    return state


def with_tangents(layout: Layout, data: RigidData, state: RigidState) -> np.ndarray:
    """(2, 2) polar, azimuth of the body tangents at A and B of a rotation-free state from the
    frames' image angles (``pinhole_starts.tangent_planes``, every rotation the identity)."""
    from curverecon.rigid.pinhole_starts import tangent_planes

    body = np.concatenate([np.zeros((1, 3)), state.body])
    p3 = state.translations[:, None, :] + body[None]
    rots = np.broadcast_to(np.eye(3), (data.n_frames, 3, 3))
    return tangent_planes(layout, data, p3, rots)


class RotationFreeEstimator(FrameSampleEstimator):
    """Two-frame samples through the closed-form solver (module docstring)."""

    def __init__(self, layout: Layout, data: RigidData, threshold: float, polish):
        from curverecon.solvers import persp_rotation_free as solver

        super().__init__(layout, data, solver, threshold, polish)

    def generate_models(self, sample: np.ndarray) -> list[Hypothesis]:
        frames = np.sort(sample)
        try:
            sol = self.solver.solve(
                self.data.points[frames][:, :2], self.data.times[frames], self.data.camera
            )
        except (CurveReconError, np.linalg.LinAlgError, ValueError):
            return []
        out = []
        for s in range(sol.n_solutions):
            p3 = sol.points3[s]
            if len(self.layout.points) > 2:
                return []  # further points: the all-frame closed form alone
            state = extend_rotation_free(self.data, p3[0, 1:] - p3[0, :1])
            if state is not None and self.layout.tangents:
                state.directions = with_tangents(self.layout, self.data, state)
            if state is not None:
                out.append(Hypothesis(state))
        return out
