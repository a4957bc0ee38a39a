"""LO-RANSAC over minimal samples of frames: the perspective rotation-free and fixed-axis rows.

* Rotation-free (A, B): two-frame samples (below).
* Fixed axis (A, B, C): three-frame samples (``solvers/persp_fixed_axis_3pt.py``, about 0.4 s a
  sample), each solution extended to every frame by its angle about the axis
  (``rigid.pinhole_starts.extend_axis``); few samples (``AXIS_RANSAC``).  The all-frame starts
  include one sample of spread frames; when an outlier frame falls among them the
  weak-perspective starts alone decided, and on one scene in five (bench seed 0) they led to a
  wrong basin.

Every row keeps its all-frame starts (``rigid.pinhole_starts``) as the loop's initial models,
and the best-scoring unpolished sample models are polished after the loop
(``RansacOptions.final_refinements``): a sample's exact fit of a few noisy frames scores
worse unpolished than a polished start in a wrong basin.  The uniform rotation's five-frame
solver (``solvers/persp_uniform_rotation.py``) is not sampled: at 1 px its solutions of five
frames scored no better than the weak-perspective starts, and the one bench scene (seed 0) whose
answer missed while the oracle's did not went to the same wrong basin from a sample near the
truth (c within 1 %).

The rotation-free row's minimal solver (``solvers/persp_rotation_free.py``, closed form: one
linear solve of two frames) gives the body D_P = X_P - A (the same in every frame) with A's
depth in the sample's first frame as the unit; each other frame's A follows from its rays m_A,
m_B and D_B (``solvers.persp_common.depths_from_difference``), the whole model is rescaled to
A's depth in frame 0 = 1.  Every model is scored by the robust cost sum_f min(chi2_f, T) over
every frame (``rigid.hypotheses.FrameSampleEstimator``'s score), the best polished by the
consensus fit (``rigid.estimate.consensus_fit``).
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

AXIS_RANSAC = RansacOptions(
    max_iterations=6, min_iterations=4, success_prob=0.99, seed=0, final_refinements=2
)
"""Three-frame samples through the 0.4 s homotopy: at 20 % outlier frames one sample is clean
with probability 0.51, and all of 4 to 6 samples (the loop's adaptive count at that ratio is
above 6) miss with 0.014; the 2 best unpolished sample models polished after the loop."""


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


class FixedAxisEstimator(FrameSampleEstimator):
    """Three frames through the homotopy solver, extended by the axis angles (module
    docstring)."""

    def __init__(self, layout: Layout, data: RigidData, threshold: float, polish):
        from curverecon.solvers import persp_fixed_axis_3pt as solver

        super().__init__(layout, data, solver, threshold, polish)

    def generate_models(self, sample: np.ndarray) -> list[Hypothesis]:
        from curverecon.rigid.pinhole_starts import _solver_states

        return [Hypothesis(s) for s in _solver_states(self.layout, self.data, np.sort(sample))]


def sample_loop(layout: Layout, data: RigidData, threshold: float, initial: list, polish):
    """(fit over every frame, its consensus frames) of LO-RANSAC over the row's minimal
    samples with the all-frame starts ``initial`` as initial models; None where the row has
    no practical solver here (these points, too few frames) or nothing converged."""
    from curverecon.robust.ransac import lo_ransac

    names = tuple(layout.points)
    if layout.projection != "perspective" or layout.tangents:
        return None
    if layout.motion == "rotation-free":
        est, opts = RotationFreeEstimator(layout, data, threshold, polish), RANSAC
    elif layout.motion == "fixed-axis" and names == ("A", "B", "C") and data.n_frames > 3:
        est, opts = FixedAxisEstimator(layout, data, threshold, polish), AXIS_RANSAC
    else:
        return None
    model, _ = lo_ransac(est, opts, initial_models=initial)
    if model is not None and model.fit is None:
        model = est.refine_model(model)
    if model is None or model.fit is None:
        return None
    return model.fit, model.consensus


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
            if state is not None:
                out.append(Hypothesis(state))
        return out
