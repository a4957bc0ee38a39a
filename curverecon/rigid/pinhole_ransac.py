"""Minimal samples of frames for the perspective rotation-free and fixed-axis rows.

* Rotation-free (A, B): LO-RANSAC over two-frame samples (below).
* Fixed axis (A, B, C), more than three frames (:func:`axis_samples`): the all-frame starts
  (``rigid.pinhole_starts``: the minimal solver on three spread frames 0, N // 3, 2N // 3 and
  weak perspective) polished by the consensus fit; when one of those spread frames is outside
  the best consensus (an outlier frame among them: then weak perspective alone decided, and on
  one scene in five, bench seed 0, it led to a wrong basin), ``AXIS_SAMPLES`` more triples,
  one frame drawn from each third of the consensus frames (of every frame when the consensus
  holds fewer than half), go through the solver (``solvers/persp_fixed_axis_3pt.py``, a
  homotopy, about 0.4 s a sample on a quiet core), each solution extended to every frame by
  its angle about the axis (``rigid.pinhole_starts.extend_axis``); each sample's
  ``AXIS_POLISHED`` solutions of least robust cost are polished, the lowest robust cost of all
  kept; the draws stop once a sample leads to a new best whose consensus holds its frames.
  A sample's exact fit of three noisy frames scores worse unpolished than a polished start in
  a wrong basin, and its best unpolished solution is not always the one that polishes into
  the scene's basin (bench seed 0), hence two polished per sample.  Scenes whose spread frames
  agree draw no sample.

The uniform rotation's five-frame solver (``solvers/persp_uniform_rotation.py``) is not
sampled: at 1 px its solutions of five frames scored no better than the weak-perspective
starts.  Its starts and the free row's (:func:`graduated_loop`) are polished by the consensus
fit, and the ``REPOLISHED`` best again through a wider consensus when a frame outside theirs
misfits by less than ``GRADUATED`` times the threshold: a consensus fit that left out good
frames at the end of the sequence (the rate slightly off, their misfit growing with time)
stays where it is, since the frames it left out no longer pull; the wider consensus takes them
in, and the fit at the threshold from there reaches the scene's basin (bench seed 0, uniform
rotation, scene 17: robust cost 88.5 -> 64.6 against a wrong basin's 73.9, c 25 % off before).

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

AXIS_SAMPLES = 4
"""Triples drawn when a spread frame is outside the consensus: drawn from every frame at 20 %
outlier frames each is clean with probability 0.51 and all 4 miss with 0.06; drawn from the
consensus frames, rarely."""

AXIS_POLISHED = 2
"""Solutions of each sample polished (least unpolished robust cost first)."""

GRADUATED = 4.0
"""The wider consensus's threshold, in units of the threshold (module docstring): bench seed 0,
uniform rotation, scene 17, two good frames left out at chi2 46 and 52 against 13.8; 2 times
stayed, 4 and 8 reached the basin."""

REPOLISHED = 2
"""Polished starts of least robust cost that go through the wider consensus too."""


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


def _spread_triple(rng: np.random.Generator, pool: np.ndarray) -> np.ndarray:
    """One frame drawn from each third of ``pool`` (sorted frame indices, at least three)."""
    return np.array([rng.choice(part) for part in np.array_split(pool, 3)])


def axis_samples(layout: Layout, data: RigidData, threshold: float, initial: list, polish):
    """(fit over every frame, its consensus frames) of the fixed-axis row (module docstring);
    None when nothing converged."""
    from curverecon.rigid.pinhole_starts import solver_states
    from curverecon.solvers import persp_fixed_axis_3pt as solver

    n = data.n_frames
    best = None
    for h in initial:
        got = polish(layout, data, h.state, threshold)
        if got is not None and (best is None or got[2] < best[2]):
            best = got
    spread = np.array([0, n // 3, 2 * n // 3])
    if best is not None and np.all(best[1][spread]):
        return best[:2]
    pool = np.arange(n)
    if best is not None and np.count_nonzero(best[1]) >= max(n / 2, 3):
        pool = np.flatnonzero(best[1])
    est = FrameSampleEstimator(layout, data, solver, threshold, polish)
    rng = np.random.default_rng(0)
    for _ in range(AXIS_SAMPLES):
        triple = _spread_triple(rng, pool)
        states = solver_states(layout, data, triple)
        models = [Hypothesis(st) for st in states]
        improved = False
        for h in sorted(models, key=lambda h: est.score_model(h)[0])[:AXIS_POLISHED]:
            got = polish(layout, data, h.state, threshold)
            if got is not None and (best is None or got[2] < best[2]):
                best, improved = got, True
        if improved and np.all(best[1][triple]):
            break  # the sample led to the best consensus and agrees with it
    return None if best is None else best[:2]


def graduated_loop(layout: Layout, data: RigidData, threshold: float, initial: list, polish):
    """(fit over every frame, its consensus frames) of least robust cost from the all-frame
    starts ``initial``, the best ``REPOLISHED`` polished again through a consensus at
    ``GRADUATED`` times the threshold (module docstring); None when nothing converged."""
    got = [polish(layout, data, h.state, threshold) for h in initial]
    got = sorted((g for g in got if g is not None), key=lambda g: g[2])
    if not got:
        return None
    best = got[0]
    wide_threshold = GRADUATED * threshold
    for fit, cons, _ in got[:REPOLISHED]:
        if not np.any(~cons & (fit.frame_chi2 <= wide_threshold)):
            continue  # every frame left out misfits by far: the wider consensus is the same
        wide = polish(layout, data, fit.state, wide_threshold)
        again = None if wide is None else polish(layout, data, wide[0].state, threshold)
        if again is not None and again[2] < best[2]:
            best = again
    return best[:2]


def sample_loop(layout: Layout, data: RigidData, threshold: float, initial: list, polish):
    """(fit over every frame, its consensus frames) from the row's minimal samples with the
    all-frame starts ``initial``; None where the row has no practical solver here (these
    points, too few frames) or nothing converged."""
    from curverecon.robust.ransac import lo_ransac

    if layout.projection != "perspective":
        return None
    if layout.tangents and layout.motion != "rotation-free":
        return None
    if layout.motion == "fixed-axis" and tuple(layout.points) == ("A", "B", "C"):
        return axis_samples(layout, data, threshold, initial, polish) if data.n_frames > 3 else None
    if layout.motion in ("uniform-rotation", "free"):
        return graduated_loop(layout, data, threshold, initial, polish)
    if layout.motion != "rotation-free":
        return None
    est = RotationFreeEstimator(layout, data, threshold, polish)
    model, _ = lo_ransac(est, RANSAC, initial_models=initial)
    if model is not None and model.fit is None:
        model = est.refine_model(model)
    if model is None or model.fit is None:
        return None
    return model.fit, model.consensus


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
